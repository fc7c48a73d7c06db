//! The peak tables, as CSV: plain enough to re-plot or to check against another detector.
//!
//! `peaks.csv` has one row per knock: its time, its height `N/mg`, its rise above the
//! baseline (`prominence`, N/mg), its amplitude in the WAV (a fraction of full scale,
//! [`Sound::knock_amplitude`]) and whether the peak is a located extremum (`1`) or a sample
//! refined by a parabola (`0`).

use std::io::Write;
use std::path::{Path, PathBuf};

use super::render::Sound;
use super::PeakAnalysis;
use crate::output::atomic::{write_atomic, WriteError};

/// Writes `peaks.csv` (one row per major peak) and `peak_rate.csv` (one row per window with
/// at least two peaks); returns their paths.
pub fn write_tables(
    analysis: &PeakAnalysis,
    sound: &Sound,
    dir: &Path,
) -> Result<Vec<PathBuf>, WriteError> {
    let peaks = dir.join("peaks.csv");
    write_atomic(&peaks, |w| {
        writeln!(w, "t_s,N_over_mg,prominence,amplitude,located")?;
        for p in &analysis.peaks {
            writeln!(
                w,
                "{},{},{},{},{}",
                p.t,
                p.n_over_mg,
                p.prominence,
                sound.knock_amplitude(p.prominence),
                u8::from(p.located)
            )?;
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
