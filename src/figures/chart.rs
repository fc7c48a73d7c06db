//! One line chart, drawn the same way to PNG and SVG.
//!
//! Every figure of the paper is a few lines over time (or one quantity against another),
//! sometimes with a second y axis. Describing a figure as data ([`Chart`]) and drawing it
//! with one generic function keeps the ten figures consistent and each one a few lines.
//! Text is drawn with the font shipped in `assets/` (no system font lookup).

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::output::atomic::{produce_atomic, write_bytes_atomic, WriteError};

/// The shipped font (DejaVu Sans, Bitstream Vera licence, see `assets/`).
const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");
/// The family name the charts ask for.
pub const FAMILY: &str = "sans-serif";
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

/// How a line is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stroke {
    /// A continuous line.
    Line,
    /// A thin continuous line (reference values).
    Thin,
    /// Small unconnected dots (a cloud of many points).
    Cloud,
    /// Unconnected dots.
    Dots,
}

/// Which y axis a line uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// The left axis.
    Left,
    /// The right axis.
    Right,
}

/// One line of a chart.
#[derive(Clone, Debug)]
pub struct Line {
    /// Legend text.
    pub label: String,
    /// Points (x, y).
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub color: RGBColor,
    /// Line or dots.
    pub stroke: Stroke,
    /// Which y axis.
    pub axis: Axis,
}

impl Line {
    /// A continuous line on the left axis.
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, color: RGBColor) -> Line {
        Line {
            label: label.into(),
            points,
            color,
            stroke: Stroke::Line,
            axis: Axis::Left,
        }
    }

    /// The same line drawn as dots.
    pub fn dots(mut self) -> Line {
        self.stroke = Stroke::Dots;
        self
    }

    /// The same line drawn as a cloud of small dots.
    pub fn cloud(mut self) -> Line {
        self.stroke = Stroke::Cloud;
        self
    }

    /// The same line drawn thin.
    pub fn thin(mut self) -> Line {
        self.stroke = Stroke::Thin;
        self
    }

    /// The same line on the right axis.
    pub fn right(mut self) -> Line {
        self.axis = Axis::Right;
        self
    }
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
    /// Logarithmic left axis.
    pub log_y: bool,
    /// Logarithmic x axis (for a quantity spanning decades, like θ in Fig. 9).
    pub log_x: bool,
    /// The lines.
    pub lines: Vec<Line>,
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

/// The range of the finite values of `values`, padded by 5% (or by 1 when flat).
fn padded_range(values: impl Iterator<Item = f64>, log: bool) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
    if !lo.is_finite() {
        return if log { 1e-6..1.0 } else { 0.0..1.0 };
    }
    if log {
        return lo / 1.5..hi * 1.5;
    }
    let pad = if hi > lo {
        0.05 * (hi - lo)
    } else {
        1.0f64.max(hi.abs() * 0.1)
    };
    lo - pad..hi + pad
}

/// A tick label: exponent notation on a logarithmic axis and for extreme magnitudes, the
/// shortest plain form otherwise (no `0.30000000000000004`).
pub fn tick_label(v: f64, log: bool) -> String {
    let a = v.abs();
    if v == 0.0 {
        "0".to_string()
    } else if log || !(1e-3..1e5).contains(&a) {
        let text = format!("{v:.1e}");
        text.replace(".0e", "e")
    } else {
        let text = format!("{v:.6}");
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// What drawing on a backend returns.
pub type DrawResult<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

fn series_of(chart: &Chart, axis: Axis) -> impl Iterator<Item = &Line> {
    chart.lines.iter().filter(move |l| l.axis == axis)
}

fn draw_on<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, chart: &Chart) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let xs = chart
        .lines
        .iter()
        .flat_map(|l| l.points.iter().map(|p| p.0));
    let x_range = if chart.log_x {
        padded_range(xs, true)
    } else {
        let r = padded_range(xs, false);
        let span = r.end - r.start;
        // Time axes start and end at the data: remove the padding on x.
        r.start + span / 22.0..r.end - span / 22.0
    };
    let left = padded_range(
        series_of(chart, Axis::Left).flat_map(|l| l.points.iter().map(|p| p.1)),
        chart.log_y,
    );
    let right = padded_range(
        series_of(chart, Axis::Right).flat_map(|l| l.points.iter().map(|p| p.1)),
        false,
    );
    let has_right = series_of(chart, Axis::Right).next().is_some();
    let mut builder = ChartBuilder::on(root);
    builder
        .caption(
            &chart.title,
            (FAMILY, 30).into_font().style(FontStyle::Bold),
        )
        .margin(20)
        .margin_right(if has_right { 20 } else { 45 })
        .x_label_area_size(60)
        .y_label_area_size(100)
        .right_y_label_area_size(if has_right { 100 } else { 0 });
    let label_font = (FAMILY, 22).into_font();
    let tick_font = (FAMILY, 18).into_font();
    macro_rules! line_elements {
        ($line:expr, $ctx:ident . $method:ident) => {{
            let line: &Line = $line;
            let finite: Vec<(f64, f64)> = line
                .points
                .iter()
                .copied()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .filter(|p| (!chart.log_x || p.0 > 0.0) && (!chart.log_y || p.1 > 0.0))
                .collect();
            let max = if line.stroke == Stroke::Cloud {
                4 * MAX_POINTS
            } else {
                MAX_POINTS
            };
            let points = decimate(&finite, max);
            let color = line.color;
            let anno = match line.stroke {
                // Width 1: wider polylines are drawn with mitred joins, which spike far out of
                // the plot where a dense series reverses (every peak of N).
                Stroke::Line => $ctx.$method(LineSeries::new(points, color.stroke_width(1)))?,
                Stroke::Thin => $ctx.$method(LineSeries::new(points, color.mix(0.6)))?,
                Stroke::Dots => $ctx.$method(
                    points
                        .into_iter()
                        .map(move |p| Circle::new(p, 3, color.filled())),
                )?,
                Stroke::Cloud => $ctx.$method(
                    points
                        .into_iter()
                        .map(move |p| Circle::new(p, 1, color.mix(0.5).filled())),
                )?,
            };
            anno.label(line.label.as_str()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(3))
            });
        }};
    }
    macro_rules! mesh {
        ($ctx:expr) => {
            $ctx.configure_mesh()
                .x_label_formatter(&|v: &f64| tick_label(*v, chart.log_x))
                .y_label_formatter(&|v: &f64| tick_label(*v, chart.log_y))
                .x_desc(chart.x_label.as_str())
                .y_desc(chart.y_label.as_str())
                .axis_desc_style(label_font.clone())
                .label_style(tick_font.clone())
                .light_line_style(RGBColor(235, 235, 235))
                .bold_line_style(RGBColor(200, 200, 200))
                .draw()?
        };
    }
    macro_rules! legend {
        ($ctx:expr) => {
            $ctx.configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .label_font((FAMILY, 20).into_font())
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(160, 160, 160))
                .draw()?
        };
    }
    macro_rules! finish {
        ($ctx:expr, $x:expr) => {{
            let ctx = $ctx;
            if has_right {
                // The secondary axis must take the right label area before the primary
                // mesh is drawn, or the primary labels are drawn there too.
                let mut ctx = ctx.set_secondary_coord($x, right.clone());
                mesh!(ctx);
                for line in series_of(chart, Axis::Left) {
                    line_elements!(line, ctx.draw_series);
                }
                ctx.configure_secondary_axes()
                    .y_desc(chart.y2_label.as_deref().unwrap_or(""))
                    .axis_desc_style(label_font.clone())
                    .label_style(tick_font.clone())
                    .draw()?;
                for line in series_of(chart, Axis::Right) {
                    line_elements!(line, ctx.draw_secondary_series);
                }
                legend!(ctx);
            } else {
                let mut ctx = ctx;
                mesh!(ctx);
                for line in series_of(chart, Axis::Left) {
                    line_elements!(line, ctx.draw_series);
                }
                legend!(ctx);
            }
        }};
    }
    let x = || x_range.clone();
    match (chart.log_x, chart.log_y) {
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
    fn tick_labels_are_short() {
        assert_eq!(tick_label(9.999999999e-6, true), "1e-5");
        assert_eq!(tick_label(3e-5, true), "3e-5");
        assert_eq!(tick_label(0.30000000000000004, false), "0.3");
        assert_eq!(tick_label(1400.0, false), "1400");
        assert_eq!(tick_label(2.5e6, false), "2.5e6");
        assert_eq!(tick_label(0.0, false), "0");
    }

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
}
