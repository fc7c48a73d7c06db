//! The peak tables, as CSV or Parquet (the scene's `output.format`): plain enough to re-plot
//! or to check against another detector.
//!
//! `peaks` has one row per knock: its time, its height `N/mg`, its rise above the baseline
//! (`prominence`, N/mg), its amplitude in the WAV (a fraction of full scale,
//! [`Sound::knock_amplitude`]) and whether the peak is a located extremum (`1`) or a sample
//! refined by a parabola (`0`).

use std::path::{Path, PathBuf};

use super::render::Sound;
use super::PeakAnalysis;
use crate::output::atomic::WriteError;
use crate::output::cells::{Cell, Table};
use crate::output::files::write_table;
use crate::output::format::TableFormat;

/// Writes `peaks.<format>` (one row per major peak) and `peak_rate.<format>` (one row per
/// window with at least two peaks); returns their paths.
pub fn write_tables(
    analysis: &PeakAnalysis,
    sound: &Sound,
    dir: &Path,
    format: TableFormat,
) -> Result<Vec<PathBuf>, WriteError> {
    let mut peaks = Table::new(["t_s", "N_over_mg", "prominence", "amplitude", "located"]);
    peaks.rows = analysis
        .peaks
        .iter()
        .map(|p| {
            vec![
                Cell::Float(p.t),
                Cell::Float(p.n_over_mg),
                Cell::Float(p.prominence),
                Cell::Float(sound.knock_amplitude(p.prominence)),
                Cell::Int(i64::from(u8::from(p.located))),
            ]
        })
        .collect();
    let mut rates = Table::new([
        "t_centre_s",
        "window_s",
        "peaks",
        "rate_per_s",
        "angular_per_s",
    ]);
    rates.rows = analysis
        .rates
        .iter()
        .filter_map(|r| {
            let (rate, angular) = (r.per_second?, r.angular()?);
            Some(vec![
                Cell::Float(r.centre()),
                Cell::Float(r.to - r.from),
                Cell::Int(i64::try_from(r.peaks).unwrap_or(i64::MAX)),
                Cell::Float(rate),
                Cell::Float(angular),
            ])
        })
        .collect();
    Ok(vec![
        write_table(&peaks, dir, "peaks", format)?,
        write_table(&rates, dir, "peak_rate", format)?,
    ])
}
