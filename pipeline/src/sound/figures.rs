//! The sound's two figures: its spectrogram, and the knock rate against the paper's numbers.
//!
//! Both are drawn here with the shared charts' size, font, colours and margins: the
//! spectrogram is an image (one coloured cell per pixel) and the rate figure needs a second
//! axis tied to the first (peaks per second = angular / 2π) and its legend away from the
//! curve's end, which the shared line chart does not offer.

use std::f64::consts::TAU;
use std::path::{Path, PathBuf};

use equations::paper;
use plotters::prelude::*;

use super::peaks::Peak;
use super::rate::PeakRate;
use super::spectrogram::Spectrogram;
use super::trace::TimeSpan;
use crate::figures::chart::{colors, register_font, SIZE};
use crate::figures::line::FAMILY;
use crate::output::atomic::{produce_atomic, WriteError};

/// The paper's knock "frequency" in the first second (angular, s⁻¹; period 0.14 s).
pub const PAPER_FIRST_SECOND: f64 = paper::THETA_OMEGA_FIRST;
/// The paper's knock "frequency" in the last second of its 100 s run (angular, s⁻¹).
pub const PAPER_LAST_SECOND: f64 = paper::THETA_OMEGA_LAST;
/// The paper's figure for the recording of the real toy (s⁻¹).
pub const RECORDED: f64 = paper::RECORDED_OMEGA;
/// The quietest level shown (dB below the loudest cell).
pub const SHOWN_DB: f64 = 80.0;

/// A labelled series of the rate figure.
struct Series {
    label: String,
    points: Vec<(f64, f64)>,
    color: RGBColor,
}

/// The series of the knock rate figure (angular, to compare with the paper): the rate from
/// each interval, the windowed rate, and, for the paper's scene only (`paper`), the paper's
/// three numbers as levels.
fn rate_series(
    rates: &[PeakRate],
    peaks: &[Peak],
    span: TimeSpan,
    window: f64,
    paper: bool,
) -> Vec<Series> {
    let windowed: Vec<(f64, f64)> = rates
        .iter()
        .filter_map(|r| Some((r.centre(), r.angular()?)))
        .collect();
    let intervals: Vec<(f64, f64)> = peaks
        .windows(2)
        .map(|w| (0.5 * (w[0].t + w[1].t), TAU / (w[1].t - w[0].t)))
        .collect();
    let level = |label: String, value: f64, color| Series {
        label,
        points: vec![(span.start, value), (span.end, value)],
        color,
    };
    let ours = [
        Series {
            label: "2π / interval between peaks".into(),
            points: intervals,
            color: colors::GREEN,
        },
        Series {
            label: format!("2π · rate in {window} s windows"),
            points: windowed,
            color: colors::BLUE,
        },
    ];
    let papers = [
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
    ];
    let shown = if paper { papers.len() } else { 0 };
    ours.into_iter()
        .chain(papers.into_iter().take(shown))
        .collect()
}

fn draw_rate_on<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    series: &[Series],
    span: TimeSpan,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let top = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .filter(|v| v.is_finite())
        .fold(1.0, f64::max)
        * 1.08;
    let x_end = span.end.max(span.start + 1e-9);
    let mut chart = ChartBuilder::on(root)
        .caption(
            "Rate of the major peaks of N (the knocks)",
            (FAMILY, 30).into_font().style(FontStyle::Bold),
        )
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(100)
        .right_y_label_area_size(100)
        .build_cartesian_2d(span.start..x_end, 0.0..top)?
        .set_secondary_coord(span.start..x_end, 0.0..top / TAU);
    chart
        .configure_mesh()
        .x_desc("t (s)")
        .y_desc("angular: 2π · peaks per second (1/s)")
        .y_label_formatter(&|v| format!("{v:.0}"))
        .axis_desc_style((FAMILY, 22).into_font())
        .label_style((FAMILY, 18).into_font())
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(200, 200, 200))
        .draw()?;
    chart
        .configure_secondary_axes()
        .y_desc("peaks per second")
        .y_label_formatter(&|v| format!("{v:.0}"))
        .axis_desc_style((FAMILY, 22).into_font())
        .label_style((FAMILY, 18).into_font())
        .draw()?;
    for s in series {
        let color = s.color;
        chart
            .draw_series(LineSeries::new(
                s.points.iter().copied(),
                color.stroke_width(2),
            ))?
            .label(s.label.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(3))
            });
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .label_font((FAMILY, 20).into_font())
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(160, 160, 160))
        .draw()?;
    root.present()
}

/// Draws the knock rate (against the paper's numbers when `paper`: the scene is the
/// paper's) to `dir/sound_peak_rate.png`, atomically; returns the path.
pub fn write_rate_figure(
    rates: &[PeakRate],
    peaks: &[Peak],
    span: TimeSpan,
    window: f64,
    paper: bool,
    dir: &Path,
) -> Result<PathBuf, WriteError> {
    register_font();
    let path = dir.join("sound_peak_rate.png");
    let series = rate_series(rates, peaks, span, window, paper);
    produce_atomic(&path, |tmp| {
        let root = BitMapBackend::new(tmp, SIZE).into_drawing_area();
        draw_rate_on(&root, &series, span).map_err(|e| e.to_string())
    })?;
    Ok(path)
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

/// One panel of the spectrogram figure: a window of simulated time.
struct Panel<'a> {
    caption: String,
    from: f64,
    to: f64,
    spec: &'a Spectrogram,
    view: &'a SpectrogramView,
}

impl Panel<'_> {
    /// The frame whose centre is nearest to simulated time `t`.
    fn frame_at(&self, t: f64) -> usize {
        let sound_s = (t - self.view.t_start) / self.view.speed;
        let f = (sound_s - self.spec.frame_time(0)) * self.spec.sample_rate
            / self.spec.settings.hop as f64;
        (f.round().max(0.0) as usize).min(self.spec.power_db.len() - 1)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let (spec, view) = (self.spec, self.view);
        let max_hz = view.max_hz.min(0.5 * spec.sample_rate);
        let span = self.to - self.from;
        let decimals = if span > 10.0 { 0 } else { 2 };
        let mut chart = ChartBuilder::on(area)
            .caption(
                &self.caption,
                (FAMILY, 22).into_font().style(FontStyle::Bold),
            )
            .margin(12)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d(self.from..self.to, 0.0..max_hz)?;
        let x_desc = if view.speed == 1.0 {
            "t (s)".to_string()
        } else {
            format!("simulated t (s), played {}x faster", view.speed)
        };
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(x_desc)
            .y_desc("frequency (Hz)")
            .x_labels(6)
            .x_label_formatter(&|v| format!("{v:.decimals$}"))
            .y_label_formatter(&|v| format!("{v:.0}"))
            .axis_desc_style((FAMILY, 18).into_font())
            .label_style((FAMILY, 15).into_font())
            .draw()?;
        let pixels = chart.plotting_area().strip_coord_spec();
        let (w, h) = pixels.dim_in_pixel();
        let bin_hz = spec.bin_hz();
        let bins = spec.bins();
        for px in 0..w {
            // The loudest cell among the frames of this column (at least the nearest one).
            let t_at = |x: u32| self.from + f64::from(x) / f64::from(w) * span;
            let (fa, fb) = (self.frame_at(t_at(px)), self.frame_at(t_at(px + 1)));
            for py in 0..h {
                let hz_at = |y: u32| (1.0 - f64::from(y) / f64::from(h)) * max_hz;
                let hi = ((hz_at(py) / bin_hz).round() as usize).min(bins - 1);
                let lo = ((hz_at(py + 1) / bin_hz).round() as usize).min(hi);
                let db = spec.power_db[fa..=fb.max(fa)]
                    .iter()
                    .flat_map(|row| &row[lo..=hi])
                    .fold(f64::NEG_INFINITY, |m, &v| m.max(f64::from(v)));
                let color = heat((db + SHOWN_DB) / SHOWN_DB);
                pixels.draw_pixel((px as i32, py as i32), &color)?;
            }
        }
        Ok(())
    }
}

fn draw_scale<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let mut scale = ChartBuilder::on(area)
        .margin_top(60)
        .margin_bottom(60)
        .margin_right(10)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..1.0, -SHOWN_DB..0.0)?;
    scale
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc("dB below the loudest")
        .y_label_formatter(&|v| format!("{v:.0}"))
        .axis_desc_style((FAMILY, 18).into_font())
        .label_style((FAMILY, 15).into_font())
        .draw()?;
    let steps = 160;
    scale.draw_series((0..steps).map(|k| {
        let a = -SHOWN_DB + SHOWN_DB * k as f64 / steps as f64;
        let b = a + SHOWN_DB / steps as f64;
        Rectangle::new([(0.0, a), (1.0, b)], heat(k as f64 / steps as f64).filled())
    }))?;
    Ok(())
}

/// Three panels: the whole sound, its first and its last second (where single knocks show).
fn draw_spectrogram_on<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    spec: &Spectrogram,
    view: &SpectrogramView,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let (main, bar) = root.split_horizontally(SIZE.0 - 130);
    let (top, bottom) = main.split_vertically(SIZE.1 / 2);
    let (left, right) = bottom.split_horizontally((SIZE.0 - 130) / 2);
    let frames = spec.power_db.len();
    let t_of = |sound_s: f64| view.t_start + sound_s * view.speed;
    let t0 = t_of(spec.frame_time(0));
    let t1 = t_of(spec.frame_time(frames - 1)).max(t0 + 1e-9);
    let second = (t1 - t0).min(1.0);
    let panel = |caption: String, from: f64, to: f64| Panel {
        caption,
        from,
        to,
        spec,
        view,
    };
    panel(view.title.clone(), t0, t1).draw(&top)?;
    panel("first second".into(), t0, t0 + second).draw(&left)?;
    panel("last second".into(), t1 - second, t1).draw(&right)?;
    draw_scale(&bar)?;
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
    fn the_papers_levels_only_for_the_papers_scene() {
        let span = TimeSpan {
            start: 0.0,
            end: 2.0,
        };
        let peaks: Vec<Peak> = (0..8)
            .map(|k| Peak {
                t: 0.25 * f64::from(k),
                n_over_mg: 2.0,
                prominence: 1.0,
                located: true,
            })
            .collect();
        let labels = |paper| -> Vec<String> {
            rate_series(&[], &peaks, span, 1.0, paper)
                .into_iter()
                .map(|s| s.label)
                .collect()
        };
        let (with, without) = (labels(true), labels(false));
        assert_eq!(with.len(), 5);
        assert_eq!(without, with[..2]);
        assert!(without
            .iter()
            .all(|l| !l.contains("paper") && !l.contains("recorded")));
    }

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
