//! The legend of a chart, drawn in its own strip between the title and the plot.
//!
//! A legend inside the plotting area covers data whenever the data reach the corner it was
//! put in (the first second of θ, the ν of the last second, the spikes of N); no corner is
//! free on every scene. Outside the plot it can cover nothing. Each entry shows the mark its
//! series is drawn with: a line for a line, a dot for dots, a few small dots for a cloud.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::line::{marker_at, Line, Stroke, FAMILY};

/// Height of the legend strip (pixels).
pub const HEIGHT: u32 = 34;
/// Width of an entry's mark (pixels).
const MARK: i32 = 26;
/// Space between a mark and its text, and between entries (pixels).
const GAP: i32 = 8;
const ENTRY_GAP: i32 = 30;
/// Legend text size (pixels).
const FONT_SIZE: u32 = 20;

/// Draws one entry per line into `area`, left to right from `left` pixels in, vertically
/// centred.
pub fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    lines: &[Line],
    left: i32,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let font = (FAMILY, FONT_SIZE).into_font();
    let style = font.color(&BLACK).pos(Pos::new(HPos::Left, VPos::Center));
    let y = HEIGHT as i32 / 2;
    let mut x = left;
    for line in lines {
        draw_mark(area, line, (x, y))?;
        let text_x = x + MARK + GAP;
        area.draw_text(&line.label, &style, (text_x, y))?;
        let (width, _) = area.estimate_text_size(&line.label, &style)?;
        x = text_x + width as i32 + ENTRY_GAP;
    }
    Ok(())
}

/// The mark of `line`, its left end at `at`.
fn draw_mark<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    line: &Line,
    (x, y): (i32, i32),
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let color = line.color;
    match line.stroke {
        Stroke::Line => area.draw(&PathElement::new(
            vec![(x, y), (x + MARK, y)],
            color.stroke_width(3),
        )),
        Stroke::Thin => area.draw(&PathElement::new(
            vec![(x, y), (x + MARK, y)],
            color.mix(0.6).stroke_width(2),
        )),
        Stroke::Dots => area.draw(&Circle::new((x + MARK / 2, y), 4, color.filled())),
        Stroke::Marked(marker) => {
            area.draw(&PathElement::new(
                vec![(x, y), (x + MARK, y)],
                color.stroke_width(1),
            ))?;
            area.draw(&marker_at(marker, (x + MARK / 2, y), color))
        }
        Stroke::Cloud => {
            for (dx, dy) in [(4, 3), (10, -4), (15, 2), (21, -2)] {
                area.draw(&Circle::new((x + dx, y + dy), 2, color.filled()))?;
            }
            Ok(())
        }
    }
}
