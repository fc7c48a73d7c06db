//! The peak tables, as CSV: plain enough to re-plot or to check against another detector.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::PeakAnalysis;
use crate::output::atomic::{write_atomic, WriteError};

/// Writes `peaks.csv` (one row per major peak) and `peak_rate.csv` (one row per window with
/// at least two peaks); returns their paths.
pub fn write_tables(analysis: &PeakAnalysis, dir: &Path) -> Result<Vec<PathBuf>, WriteError> {
    let peaks = dir.join("peaks.csv");
    write_atomic(&peaks, |w| {
        writeln!(w, "t_s,N_over_mg,prominence")?;
        for p in &analysis.peaks {
            writeln!(w, "{},{},{}", p.t, p.n_over_mg, p.prominence)?;
        }
        Ok(())
    })?;
    let rates = dir.join("peak_rate.csv");
    write_atomic(&rates, |w| {
        writeln!(w, "t_centre_s,window_s,peaks,rate_per_s,angular_per_s")?;
        for r in &analysis.rates {
            if let (Some(rate), Some(angular)) = (r.per_second, r.angular()) {
                writeln!(
                    w,
                    "{},{},{},{rate},{angular}",
                    r.centre(),
                    r.to - r.from,
                    r.peaks
                )?;
            }
        }
        Ok(())
    })?;
    Ok(vec![peaks, rates])
}
