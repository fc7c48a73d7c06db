//! Figures: a generic chart drawn to PNG and SVG, and the paper's ten figures built with it.

pub mod axes;
pub mod chart;
mod legend;
pub mod line;
pub mod paper;

use equations::record::Quantity;

/// Every quantity the figures plot (besides time): a run that draws them must compute these.
pub const FIGURE_QUANTITIES: [Quantity; 6] = [
    Quantity::Theta,
    Quantity::ThetaDot,
    Quantity::PsiDot,
    Quantity::Nu,
    Quantity::V_C,
    Quantity::NOverMg,
];
