//! One line chart, drawn the same way to PNG and SVG.
//!
//! Every figure of the paper is a few lines over time (or one quantity against another),
//! sometimes with a second y axis. Describing a figure as data ([`Chart`]) and drawing it
//! with one generic function keeps the ten figures consistent and each one a few lines.
//! Text is drawn with the font shipped in `assets/` (no system font lookup).
//!
//! Lines are drawn in the order the chart lists them, so a figure decides what lies on top
//! (Fig. 8 puts the force spikes over θ). The legend has its own strip above the plot
//! (`figures/legend.rs`), and a chart with nothing to draw says so in the picture
//! ([`Chart::empty_note`]) instead of showing an empty box.

use std::ops::Range;
use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::axes::{data_range, padded_range, tick_label, usable_span};
use super::legend;
use super::line::{marker_at, Axis, Line, Stroke, FAMILY};
use crate::output::atomic::{produce_atomic, write_bytes_atomic, WriteError};

/// The shipped font (DejaVu Sans, Bitstream Vera licence, see `assets/`).
const FONT: &[u8] = include_bytes!("../../../assets/DejaVuSans.ttf");
/// Pixel size of every figure.
pub const SIZE: (u32, u32) = (1200, 720);
/// Most points drawn per line: longer series are reduced to their min/max per bucket, which
/// looks the same at this size.
pub const MAX_POINTS: usize = 4000;

/// Registers the shipped font with plotters (once per process); every figure calls it first.
pub fn register_font() {
    static DONE: OnceLock<()> = OnceLock::new();
    DONE.get_or_init(|| {
        for style in [FontStyle::Normal, FontStyle::Bold] {
            // The bytes are a valid TrueType font compiled into the binary; a failure here
            // would be a broken build, and text would then silently be missing.
            if plotters::style::register_font(FAMILY, style, FONT).is_err() {
                eprintln!("warning: the embedded font could not be loaded; figures lack text");
            }
        }
    });
}

/// A figure described as data.
#[derive(Clone, Debug)]
pub struct Chart {
    /// File name without extension (`fig01a_theta_first_second`).
    pub stem: String,
    /// Title.
    pub title: String,
    /// x-axis label, with unit.
    pub x_label: String,
    /// Left y-axis label, with unit.
    pub y_label: String,
    /// Right y-axis label, when a line uses it.
    pub y2_label: Option<String>,
    /// Logarithmic left axis, if the data span a decade ([`Chart::log_scales`]).
    pub log_y: bool,
    /// Logarithmic x axis (for a quantity spanning decades, like θ in Fig. 9), as for `log_y`.
    pub log_x: bool,
    /// The lines, drawn in this order (later ones on top).
    pub lines: Vec<Line>,
    /// The x range to show (a time axis: the time the figure covers); `None` for the extent
    /// of the data.
    pub x_range: Option<Range<f64>>,
    /// What the picture says when no data line has a point to draw (why it is empty).
    pub empty_note: String,
}

impl Chart {
    /// A chart of `lines` against time on linear axes, covering the data's time span, with a
    /// generic note for when it is empty.
    pub fn over_time(stem: &str, title: String, y_label: &str, lines: Vec<Line>) -> Chart {
        Chart {
            stem: stem.to_string(),
            title,
            x_label: "time t (s)".to_string(),
            y_label: y_label.to_string(),
            y2_label: None,
            log_y: false,
            log_x: false,
            lines,
            x_range: None,
            empty_note: "no samples to show".to_string(),
        }
    }

    /// The points of `line` this chart can draw: finite, and positive on a logarithmic axis.
    pub fn drawable(&self, line: &Line) -> Vec<(f64, f64)> {
        let log_y = self.log_y && line.axis == Axis::Left;
        line.points
            .iter()
            .copied()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .filter(|p| (!self.log_x || p.0 > 0.0) && (!log_y || p.1 > 0.0))
            .collect()
    }

    /// Whether no data line (reference lines, drawn `Stroke::Thin`, do not count) has a
    /// point to draw.
    pub fn is_empty(&self) -> bool {
        self.lines
            .iter()
            .filter(|l| l.stroke != Stroke::Thin)
            .all(|l| self.drawable(l).is_empty())
    }

    /// Whether the x and the left y axis are drawn logarithmic: asked for, and the drawable
    /// values span at least a decade (or there are none). Over less than a decade a logarithmic
    /// axis carries one tick label or none, so a short run's data get a linear one.
    pub fn log_scales(&self) -> (bool, bool) {
        let spans_decades = |values: &mut dyn Iterator<Item = f64>| {
            let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(l, h), v| (l.min(v), h.max(v)));
            !lo.is_finite() || hi >= LOG_MIN_RATIO * lo
        };
        let mut xs = self.xs();
        let mut ys =
            series_of(self, Axis::Left).flat_map(|l| self.drawable(l).into_iter().map(|p| p.1));
        (
            self.log_x && spans_decades(&mut xs),
            self.log_y && spans_decades(&mut ys),
        )
    }

    /// The x values of every drawable point.
    fn xs(&self) -> impl Iterator<Item = f64> + '_ {
        self.lines
            .iter()
            .flat_map(|l| self.drawable(l).into_iter().map(|p| p.0))
    }

    /// The x range drawn: the chart's own (a time span) or the extent of the drawable points.
    pub fn x_axis(&self) -> Range<f64> {
        let xs = || self.xs();
        match (&self.x_range, self.log_scales().0) {
            (Some(r), false) => usable_span(r.start, r.end),
            (Some(r), true) if r.start > 0.0 => usable_span(r.start, r.end),
            (_, true) => padded_range(xs(), true),
            (None, false) => data_range(xs()).unwrap_or(0.0..1.0),
        }
    }
}

/// The colours used by the figures (colour-blind safe, after Okabe & Ito).
pub mod colors {
    use plotters::style::RGBColor;
    /// Blue.
    pub const BLUE: RGBColor = RGBColor(0, 114, 178);
    /// Vermillion.
    pub const RED: RGBColor = RGBColor(213, 94, 0);
    /// Bluish green.
    pub const GREEN: RGBColor = RGBColor(0, 158, 115);
    /// Reddish purple.
    pub const PURPLE: RGBColor = RGBColor(204, 121, 167);
    /// Black.
    pub const BLACK: RGBColor = RGBColor(0, 0, 0);
}

/// Reduces a long series to at most about `max` points by keeping, per bucket of consecutive
/// points, the first, the smallest and the largest (in order): peaks survive.
pub fn decimate(points: &[(f64, f64)], max: usize) -> Vec<(f64, f64)> {
    if points.len() <= max || max < 3 {
        return points.to_vec();
    }
    let buckets = max / 3;
    let size = points.len().div_ceil(buckets);
    let mut out = Vec::with_capacity(3 * buckets + 1);
    for chunk in points.chunks(size) {
        let (mut lo, mut hi) = (0, 0);
        for (i, p) in chunk.iter().enumerate() {
            if p.1 < chunk[lo].1 {
                lo = i;
            }
            if p.1 > chunk[hi].1 {
                hi = i;
            }
        }
        let mut idx = [0, lo, hi];
        idx.sort_unstable();
        for (k, &i) in idx.iter().enumerate() {
            if k == 0 || idx[k - 1] != i {
                out.push(chunk[i]);
            }
        }
    }
    out
}

/// What drawing on a backend returns.
pub type DrawResult<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

fn series_of(chart: &Chart, axis: Axis) -> impl Iterator<Item = &Line> {
    chart.lines.iter().filter(move |l| l.axis == axis)
}

/// A logarithmic axis needs its values to span at least this ratio (one decade).
const LOG_MIN_RATIO: f64 = 10.0;

/// Left edge of the plotting area inside the chart's area (margin plus y label area).
const PLOT_LEFT: i32 = MARGIN as i32 + Y_LABEL_AREA as i32;
const MARGIN: u32 = 20;
const Y_LABEL_AREA: u32 = 100;

fn draw_on<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, chart: &Chart) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let body = root.margin(12, 0, 0, 0).titled(
        &chart.title,
        (FAMILY, 30).into_font().style(FontStyle::Bold),
    )?;
    let (legend_strip, plot) = body.split_vertically(legend::HEIGHT);
    legend::draw(&legend_strip, &chart.lines, PLOT_LEFT)?;
    let x_range = chart.x_axis();
    let (log_x, log_y) = chart.log_scales();
    let left = padded_range(
        series_of(chart, Axis::Left).flat_map(|l| chart.drawable(l).into_iter().map(|p| p.1)),
        log_y,
    );
    let described = |label: &str, log: bool| {
        if log {
            format!("{label}, logarithmic")
        } else {
            label.to_string()
        }
    };
    let (x_desc, y_desc) = (
        described(&chart.x_label, log_x),
        described(&chart.y_label, log_y),
    );
    let right = padded_range(
        series_of(chart, Axis::Right).flat_map(|l| chart.drawable(l).into_iter().map(|p| p.1)),
        false,
    );
    let (x_span, left_span, right_span) = (
        x_range.end - x_range.start,
        left.end - left.start,
        right.end - right.start,
    );
    let has_right = series_of(chart, Axis::Right).next().is_some();
    let mut builder = ChartBuilder::on(&plot);
    builder
        .margin(MARGIN)
        .margin_top(8)
        .margin_right(if has_right { MARGIN } else { 45 })
        .x_label_area_size(60)
        .y_label_area_size(Y_LABEL_AREA)
        .right_y_label_area_size(if has_right { Y_LABEL_AREA } else { 0 });
    let label_font = (FAMILY, 22).into_font();
    let tick_font = (FAMILY, 18).into_font();
    macro_rules! line_elements {
        ($line:expr, $ctx:ident . $method:ident) => {{
            let line: &Line = $line;
            let max = if line.stroke == Stroke::Cloud {
                4 * MAX_POINTS
            } else {
                MAX_POINTS
            };
            let points = decimate(&chart.drawable(line), max);
            let color = line.color;
            match line.stroke {
                // Width 1: wider polylines are drawn with mitred joins, which spike far out of
                // the plot where a dense series reverses (every peak of N).
                Stroke::Line => {
                    $ctx.$method(LineSeries::new(points, color.stroke_width(1)))?;
                }
                Stroke::Thin => {
                    $ctx.$method(LineSeries::new(points, color.mix(0.6)))?;
                }
                Stroke::Dots => {
                    $ctx.$method(
                        points
                            .into_iter()
                            .map(move |p| Circle::new(p, 3, color.filled())),
                    )?;
                }
                Stroke::Marked(marker) => {
                    $ctx.$method(LineSeries::new(points.clone(), color.stroke_width(1)))?;
                    $ctx.$method(points.into_iter().map(move |p| marker_at(marker, p, color)))?;
                }
                Stroke::Cloud => {
                    $ctx.$method(
                        points
                            .into_iter()
                            .map(move |p| Circle::new(p, 1, color.mix(0.5).filled())),
                    )?;
                }
            }
        }};
    }
    macro_rules! mesh {
        ($ctx:expr) => {
            $ctx.configure_mesh()
                .x_label_formatter(&|v: &f64| tick_label(*v, log_x, x_span))
                .y_label_formatter(&|v: &f64| tick_label(*v, log_y, left_span))
                .x_desc(x_desc.as_str())
                .y_desc(y_desc.as_str())
                .axis_desc_style(label_font.clone())
                .label_style(tick_font.clone())
                .light_line_style(RGBColor(235, 235, 235))
                .bold_line_style(RGBColor(200, 200, 200))
                .draw()?
        };
    }
    macro_rules! finish {
        ($ctx:expr, $x:expr) => {{
            let ctx = $ctx;
            let area = if has_right {
                // The secondary axis must take the right label area before the primary
                // mesh is drawn, or the primary labels are drawn there too.
                let mut ctx = ctx.set_secondary_coord($x, right.clone());
                mesh!(ctx);
                ctx.configure_secondary_axes()
                    .y_label_formatter(&|v: &f64| tick_label(*v, false, right_span))
                    .y_desc(chart.y2_label.as_deref().unwrap_or(""))
                    .axis_desc_style(label_font.clone())
                    .label_style(tick_font.clone())
                    .draw()?;
                for line in &chart.lines {
                    match line.axis {
                        Axis::Left => line_elements!(line, ctx.draw_series),
                        Axis::Right => line_elements!(line, ctx.draw_secondary_series),
                    }
                }
                ctx.plotting_area().get_pixel_range()
            } else {
                let mut ctx = ctx;
                mesh!(ctx);
                for line in &chart.lines {
                    line_elements!(line, ctx.draw_series);
                }
                ctx.plotting_area().get_pixel_range()
            };
            if chart.is_empty() {
                draw_empty_note(root, &chart.empty_note, area)?;
            }
        }};
    }
    let x = || x_range.clone();
    match (log_x, log_y) {
        (false, false) => finish!(builder.build_cartesian_2d(x(), left)?, x()),
        (false, true) => finish!(builder.build_cartesian_2d(x(), left.log_scale())?, x()),
        (true, false) => finish!(
            builder.build_cartesian_2d(x().log_scale(), left)?,
            x().log_scale()
        ),
        (true, true) => finish!(
            builder.build_cartesian_2d(x().log_scale(), left.log_scale())?,
            x().log_scale()
        ),
    }
    root.present()
}

/// Writes `note` in the middle of the plotting area `(xs, ys)` (pixels of `root`).
fn draw_empty_note<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    note: &str,
    (xs, ys): (Range<i32>, Range<i32>),
) -> DrawResult<DB> {
    let style = (FAMILY, 26)
        .into_font()
        .color(&RGBColor(90, 90, 90))
        .pos(Pos::new(HPos::Center, VPos::Center));
    let centre = ((xs.start + xs.end) / 2, (ys.start + ys.end) / 2);
    root.draw_text(note, &style, centre)
}

/// A figure that draws itself on any plotters backend, so one [`render`] writes every kind
/// (line charts, the sweeps' heat maps) to PNG and SVG alike.
pub trait Figure {
    /// File name without extension.
    fn stem(&self) -> &str;
    /// Draws the figure on `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB>;
}

impl Figure for Chart {
    fn stem(&self) -> &str {
        &self.stem
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        draw_on(root, self)
    }
}

/// Draws `figure` to `dir/<stem>.png` and `dir/<stem>.svg`, each written atomically.
pub fn render<F: Figure>(figure: &F, dir: &Path) -> Result<(), WriteError> {
    register_font();
    let png = dir.join(format!("{}.png", figure.stem()));
    produce_atomic(&png, |tmp| {
        let root = BitMapBackend::new(tmp, SIZE).into_drawing_area();
        figure.draw(&root).map_err(|e| e.to_string())
    })?;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        figure.draw(&root).map_err(|e| WriteError {
            path: dir.join(format!("{}.svg", figure.stem())),
            source: std::io::Error::other(e.to_string()),
        })?;
    }
    write_bytes_atomic(&dir.join(format!("{}.svg", figure.stem())), svg.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimation_keeps_peaks_and_order() {
        let points: Vec<(f64, f64)> = (0..100_000)
            .map(|i| {
                (
                    i as f64,
                    if i == 54_321 {
                        10.0
                    } else {
                        (i as f64 * 0.01).sin()
                    },
                )
            })
            .collect();
        let d = decimate(&points, 3000);
        assert!(d.len() <= 3100, "{}", d.len());
        assert!(d.contains(&(54_321.0, 10.0)));
        assert!(d.windows(2).all(|w| w[0].0 < w[1].0));
        let min = d.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        assert!(min < -0.9999);
    }

    fn chart_of(lines: Vec<Line>, log_y: bool) -> Chart {
        let mut c = Chart::over_time("t", "test".into(), "y (1)", lines);
        c.log_y = log_y;
        c
    }

    #[test]
    fn a_chart_is_empty_when_no_data_line_can_be_drawn() {
        let zeros = Line::new("z", vec![(0.0, 0.0), (1.0, 0.0)], colors::BLUE);
        // Zeros are data on a linear axis, nothing on a logarithmic one.
        assert!(!chart_of(vec![zeros.clone()], false).is_empty());
        assert!(chart_of(vec![zeros.clone()], true).is_empty());
        // Non-finite points never count; reference lines do not make a chart non-empty.
        let nan = Line::new(
            "n",
            vec![(0.0, f64::NAN), (f64::INFINITY, 1.0)],
            colors::RED,
        );
        let reference = Line::new("μ", vec![(0.0, 0.2), (1.0, 0.2)], colors::RED).thin();
        assert!(chart_of(vec![nan, reference], false).is_empty());
        assert!(chart_of(Vec::new(), false).is_empty());
    }

    #[test]
    fn the_x_axis_is_the_charts_time_span_or_the_datas() {
        let line = Line::new("y", vec![(0.25, 1.0), (0.75, 2.0)], colors::BLUE);
        let mut c = chart_of(vec![line], false);
        assert_eq!(c.x_axis(), 0.25..0.75);
        c.x_range = Some(0.0..2.0);
        assert_eq!(c.x_axis(), 0.0..2.0);
        // A reversed span (a run shorter than the window) still gives a usable axis.
        c.x_range = Some(1.0..0.5);
        assert_eq!(c.x_axis(), 0.5..1.5);
        c.lines.clear();
        c.x_range = None;
        assert_eq!(c.x_axis(), 0.0..1.0);
    }

    #[test]
    fn a_logarithmic_axis_needs_a_decade_of_data() {
        let narrow = Line::new("n", vec![(0.0, 0.1), (1.0, 0.15)], colors::BLUE);
        let wide = Line::new("w", vec![(0.0, 1e-4), (1.0, 0.15)], colors::BLUE);
        assert_eq!(
            chart_of(vec![narrow.clone()], true).log_scales(),
            (false, false)
        );
        assert_eq!(chart_of(vec![wide], true).log_scales(), (false, true));
        // Not asked for, never logarithmic; no data, as asked.
        assert_eq!(chart_of(vec![narrow], false).log_scales(), (false, false));
        assert_eq!(chart_of(Vec::new(), true).log_scales(), (false, true));
        // A narrow logarithmic x axis falls back to the data's extent.
        let mut c = chart_of(
            vec![Line::new("x", vec![(0.2, 1.0), (0.5, 2.0)], colors::BLUE)],
            false,
        );
        c.log_x = true;
        assert_eq!(c.log_scales(), (false, false));
        assert_eq!(c.x_axis(), 0.2..0.5);
    }

    /// `friction.mu_st = 1.7976931348623157e308` put that value on the ν axis, and drawing
    /// never finished.
    #[test]
    fn a_reference_line_at_the_largest_float_is_drawn() {
        let data = Line::new("ν", vec![(0.0, 0.1), (1.0, 0.115)], colors::BLUE);
        let reference = Line::new("μ_st", vec![(0.0, f64::MAX), (1.0, f64::MAX)], colors::RED);
        let c = chart_of(vec![reference.thin(), data], false);
        let dir = tempfile::tempdir().unwrap();
        render(&c, dir.path()).unwrap();
        assert!(std::fs::metadata(dir.path().join("t.png")).unwrap().len() > 1000);
    }

    #[test]
    fn an_empty_chart_is_drawn_with_its_note() {
        let mut c = chart_of(Vec::new(), true);
        c.empty_note = "nothing here: a test".into();
        let dir = tempfile::tempdir().unwrap();
        render(&c, dir.path()).unwrap();
        let svg = std::fs::read_to_string(dir.path().join("t.svg")).unwrap();
        assert!(
            svg.contains("nothing here: a test"),
            "the note is in the picture"
        );
        assert!(std::fs::metadata(dir.path().join("t.png")).unwrap().len() > 1000);
    }
}
