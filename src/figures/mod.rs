//! Figures: a generic chart drawn to PNG and SVG, and the paper's ten figures built with it.

pub mod axes;
pub mod chart;
mod legend;
pub mod paper;
