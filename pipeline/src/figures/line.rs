//! What a chart draws: lines, how each is stroked, which axis it uses, and the font family
//! of its text. Shared by the chart and its legend, which both draw lines.

use plotters::prelude::*;

/// The family name the charts ask for.
pub const FAMILY: &str = "sans-serif";
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
    /// A continuous line with a marker at every point, so that lines lying on each other
    /// stay apart (a sweep's series).
    Marked(Marker),
}

/// The marker of a [`Stroke::Marked`] line; successive series take successive shapes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    /// A hollow circle.
    Circle,
    /// A filled triangle.
    Triangle,
    /// A cross.
    Cross,
}

impl Marker {
    /// The shapes in the order series take them.
    pub const ALL: [Marker; 3] = [Marker::Circle, Marker::Triangle, Marker::Cross];
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

    /// The same line with `marker` at every point.
    pub fn marked(mut self, marker: Marker) -> Line {
        self.stroke = Stroke::Marked(marker);
        self
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

/// `marker` at `p` in `color`: the same shape on a chart (data coordinates) and in its
/// legend (pixels).
pub fn marker_at<C, DB: DrawingBackend>(
    marker: Marker,
    p: C,
    color: RGBColor,
) -> DynElement<'static, DB, C>
where
    C: Clone + 'static,
{
    match marker {
        Marker::Circle => Circle::new(p, 6, color.stroke_width(2)).into_dyn(),
        Marker::Triangle => TriangleMarker::new(p, 6, color.filled()).into_dyn(),
        Marker::Cross => Cross::new(p, 5, color.stroke_width(2)).into_dyn(),
    }
}
