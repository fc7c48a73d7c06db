//! Figures: a generic chart drawn to PNG and SVG, and the paper's ten figures built with it.

pub mod chart;
pub mod paper;
