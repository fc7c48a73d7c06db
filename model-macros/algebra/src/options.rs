//! The compiler's knobs, settable per model (the DSL's `options { .. }`).

/// Knobs of the compiler.
#[derive(Clone, Debug, PartialEq)]
pub struct CompileOptions {
    /// The most operations a block's symbolic solution may cost (beyond computing its
    /// coefficients) before the block is solved numerically at run time instead.
    pub swell_bound: usize,
    /// A checked pivot is singular when one of its sums has cancelled to at most this fraction
    /// of the sum of its terms' magnitudes (see [`PIVOT_TOLERANCE`]); `0` tests exact zero only.
    pub pivot_tolerance: f64,
}

/// The default [`CompileOptions::pivot_tolerance`]. A sum of `n` terms, each a few rounded
/// operations, is computed with an error of about `(n + k)·ε·Σ|terms|` (`ε = 1.1e-16`, `k` the
/// operations per term): for models like the disk's, ~`1e-15·Σ|terms|`. A pivot below
/// `1e-12·Σ|terms|` has therefore at most ~3 correct digits left, and every value divided by it
/// is amplified by ~`1e12` beyond its ordinary size: not an answer to integrate. A genuine
/// pivot that is merely small (a small parameter, a product of small factors) has no
/// cancelling sum and is never flagged, whatever its size.
pub const PIVOT_TOLERANCE: f64 = 1e-12;

impl Default for CompileOptions {
    fn default() -> Self {
        CompileOptions {
            swell_bound: 600,
            pivot_tolerance: PIVOT_TOLERANCE,
        }
    }
}
