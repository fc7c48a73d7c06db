//! The sound's two figures: its spectrogram, and the knock rate against the paper's numbers.
//!
//! The rate figure is an ordinary line chart and is drawn by the shared chart code; the
//! spectrogram is an image (one coloured cell per pixel), which that code does not draw, so
//! it is drawn here with the same size, font and margins.

use std::f64::consts::TAU;
use std::path::Path;
use std::sync::OnceLock;

use plotters::prelude::*;

use super::peaks::Peak;
use super::rate::PeakRate;
use super::spectrogram::Spectrogram;
use super::trace::TimeSpan;
use crate::figures::chart::{colors, render, Chart, Line, SIZE};
use crate::output::atomic::{produce_atomic, WriteError};

/// The font of all figures (DejaVu Sans, see `assets/`).
const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");
/// The family name the figures ask for.
const FAMILY: &str = "sans-serif";
/// The paper's knock "frequency" in the first second (angular, s⁻¹; period 0.14 s).
pub const PAPER_FIRST_SECOND: f64 = 44.0;
/// The paper's knock "frequency" in the last second of its 100 s run (angular, s⁻¹).
pub const PAPER_LAST_SECOND: f64 = 149.0;
/// The paper's figure for the recording of the real toy (s⁻¹).
pub const RECORDED: f64 = 154.0;
/// The quietest level shown (dB below the loudest cell).
pub const SHOWN_DB: f64 = 80.0;

fn register_font() {
    static DONE: OnceLock<()> = OnceLock::new();
    DONE.get_or_init(|| {
        for style in [FontStyle::Normal, FontStyle::Bold] {
            if plotters::style::register_font(FAMILY, style, FONT).is_err() {
                eprintln!("warning: the embedded font could not be loaded; figures lack text");
            }
        }
    });
}

/// The chart of the knock rate over the run (angular, to compare with the paper).
pub fn rate_chart(rates: &[PeakRate], peaks: &[Peak], span: TimeSpan, window: f64) -> Chart {
    let windowed: Vec<(f64, f64)> = rates
        .iter()
        .filter_map(|r| Some((r.centre(), r.angular()?)))
        .collect();
    let intervals: Vec<(f64, f64)> = peaks
        .windows(2)
        .map(|w| (0.5 * (w[0].t + w[1].t), TAU / (w[1].t - w[0].t)))
        .collect();
    let level = |label: String, value: f64, color| {
        Line::new(label, vec![(span.start, value), (span.end, value)], color).thin()
    };
    Chart {
        stem: "sound_peak_rate".into(),
        title: "Rate of the major peaks of N (the knocks)".into(),
        x_label: "t (s)".into(),
        y_label: "2π · peaks per second (1/s)".into(),
        y2_label: None,
        log_y: false,
        lines: vec![
            Line::new("2π / interval between peaks", intervals, colors::GREEN).dots(),
            Line::new(
                format!("2π · rate in {window} s windows"),
                windowed,
                colors::BLUE,
            ),
            level(
                format!("paper, first second: {PAPER_FIRST_SECOND}"),
                PAPER_FIRST_SECOND,
                colors::RED,
            ),
            level(
                format!("paper, last second: {PAPER_LAST_SECOND}"),
                PAPER_LAST_SECOND,
                colors::PURPLE,
            ),
            level(format!("recorded toy: {RECORDED}"), RECORDED, colors::BLACK),
        ],
    }
}

/// Draws the rate chart to `dir` (PNG and SVG).
pub fn write_rate_chart(chart: &Chart, dir: &Path) -> Result<(), WriteError> {
    render(chart, dir)
}

/// Colour of a level in [0, 1] (dark blue → green → yellow, perceptually ordered).
fn heat(level: f64) -> RGBColor {
    const STOPS: [(f64, [f64; 3]); 5] = [
        (0.00, [13.0, 8.0, 35.0]),
        (0.30, [59.0, 48.0, 143.0]),
        (0.55, [33.0, 145.0, 140.0]),
        (0.80, [94.0, 201.0, 98.0]),
        (1.00, [253.0, 231.0, 37.0]),
    ];
    let x = level.clamp(0.0, 1.0);
    let k = STOPS
        .iter()
        .rposition(|s| s.0 <= x)
        .unwrap_or(0)
        .min(STOPS.len() - 2);
    let (x0, c0) = STOPS[k];
    let (x1, c1) = STOPS[k + 1];
    let f = (x - x0) / (x1 - x0);
    let mix = |i: usize| (c0[i] + f * (c1[i] - c0[i])).round() as u8;
    RGBColor(mix(0), mix(1), mix(2))
}

/// What the spectrogram figure shows.
#[derive(Clone, Debug, PartialEq)]
pub struct SpectrogramView {
    /// Title.
    pub title: String,
    /// Highest frequency shown (Hz).
    pub max_hz: f64,
    /// Simulated time at the sound's start (s).
    pub t_start: f64,
    /// Simulated seconds per second of sound.
    pub speed: f64,
}

fn draw_spectrogram_on<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    spec: &Spectrogram,
    view: &SpectrogramView,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let (main, bar) = root.split_horizontally(SIZE.0 - 150);
    let frames = spec.power_db.len();
    let t_of = |sound_s: f64| view.t_start + sound_s * view.speed;
    let t0 = t_of(spec.frame_time(0));
    let t1 = t_of(spec.frame_time(frames.saturating_sub(1))).max(t0 + 1e-9);
    let max_hz = view.max_hz.min(0.5 * spec.sample_rate);
    let mut chart = ChartBuilder::on(&main)
        .caption(&view.title, (FAMILY, 30).into_font().style(FontStyle::Bold))
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(100)
        .build_cartesian_2d(t0..t1, 0.0..max_hz)?;
    let x_desc = if view.speed == 1.0 {
        "t (s)".to_string()
    } else {
        format!("t (s), played {}× faster", view.speed)
    };
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(x_desc)
        .y_desc("frequency (Hz)")
        .axis_desc_style((FAMILY, 22).into_font())
        .label_style((FAMILY, 18).into_font())
        .draw()?;
    let area = chart.plotting_area().strip_coord_spec();
    let (w, h) = area.dim_in_pixel();
    let bin_hz = spec.bin_hz();
    for px in 0..w {
        // Frames whose centres fall in this column (at least the nearest one).
        let frame_at = |x: f64| {
            let sound_s = (t0 + x / f64::from(w) * (t1 - t0) - view.t_start) / view.speed;
            let f = (sound_s - spec.frame_time(0)) * spec.sample_rate / spec.settings.hop as f64;
            (f.max(0.0) as usize).min(frames - 1)
        };
        let (fa, fb) = (frame_at(f64::from(px)), frame_at(f64::from(px + 1)));
        for py in 0..h {
            let hz_at = |y: f64| (1.0 - y / f64::from(h)) * max_hz;
            let hi = (hz_at(f64::from(py)) / bin_hz).round() as usize;
            let lo = (hz_at(f64::from(py + 1)) / bin_hz).round() as usize;
            let mut db = f64::NEG_INFINITY;
            for row in &spec.power_db[fa..=fb.max(fa)] {
                for &v in &row[lo.min(row.len() - 1)..=hi.min(row.len() - 1)] {
                    db = db.max(f64::from(v));
                }
            }
            let color = heat((db + SHOWN_DB) / SHOWN_DB);
            area.draw_pixel((px as i32, py as i32), &color)?;
        }
    }
    let mut scale = ChartBuilder::on(&bar)
        .margin_top(70)
        .margin_bottom(80)
        .margin_right(10)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..1.0, -SHOWN_DB..0.0)?;
    scale
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc("dB")
        .axis_desc_style((FAMILY, 20).into_font())
        .label_style((FAMILY, 16).into_font())
        .draw()?;
    let steps = 160;
    scale.draw_series((0..steps).map(|k| {
        let a = -SHOWN_DB + SHOWN_DB * k as f64 / steps as f64;
        let b = a + SHOWN_DB / steps as f64;
        Rectangle::new([(0.0, a), (1.0, b)], heat(k as f64 / steps as f64).filled())
    }))?;
    root.present()
}

/// Draws the spectrogram to `path` (PNG), atomically.
pub fn write_spectrogram(
    spec: &Spectrogram,
    view: &SpectrogramView,
    path: &Path,
) -> Result<(), WriteError> {
    register_font();
    produce_atomic(path, |tmp| {
        if spec.power_db.is_empty() {
            return Err("the spectrogram has no frames".to_string());
        }
        let root = BitMapBackend::new(tmp, SIZE).into_drawing_area();
        draw_spectrogram_on(&root, spec, view).map_err(|e| e.to_string())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heat_runs_from_dark_to_bright() {
        let lum = |c: RGBColor| {
            0.2126 * f64::from(c.0) + 0.7152 * f64::from(c.1) + 0.0722 * f64::from(c.2)
        };
        let levels: Vec<f64> = (0..=20).map(|k| lum(heat(k as f64 / 20.0))).collect();
        assert!(levels.windows(2).all(|w| w[1] > w[0]), "{levels:?}");
        assert_eq!(heat(-1.0), heat(0.0));
        assert_eq!(heat(2.0), RGBColor(253, 231, 37));
    }
}
