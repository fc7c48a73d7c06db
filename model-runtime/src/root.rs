//! Bracketing root finder for guard crossings.
//!
//! Event times must be exact to a few ulps, and the state at the event must be on the far side
//! of the crossing, so that restarting there cannot fire the same guard again. The finder
//! therefore keeps a bracket `[lo, hi]` with `lo` strictly on the starting side and `hi` on the
//! far side (or exactly at zero), and returns `hi` once the bracket is a few ulps wide.
//! Illinois (modified regula falsi) steps give superlinear convergence; a bisection is forced
//! whenever the bracket fails to halve, so the iteration count is bounded by the bits of `t`.

/// A located crossing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// The first point found on the far side of the crossing (or where the function is zero).
    pub t: f64,
    /// The last point on the starting side; `t - before` is a few ulps at most.
    pub before: f64,
    /// The function's value at `t`.
    pub value: f64,
    /// Function evaluations used.
    pub evaluations: u32,
}

/// Width below which a search in `[lo, hi]` counts as converged: a few ulps of the larger end
/// (near `t = 0` the ulps of the search interval's scale, not of zero itself).
pub fn converged_width(lo: f64, hi: f64) -> f64 {
    4.0 * f64::EPSILON * lo.abs().max(hi.abs()).max(f64::MIN_POSITIVE / f64::EPSILON)
}

/// Finds where `f` leaves the sign `start_sign` (±1) inside `[lo, hi]`.
///
/// Requires `f(lo) = f_lo` to have sign `start_sign` and `f(hi) = f_hi` to be zero or of the
/// opposite sign. Errors from `f` are passed through.
pub fn find_crossing<E>(
    mut lo: f64,
    mut f_lo: f64,
    mut hi: f64,
    mut f_hi: f64,
    start_sign: f64,
    mut f: impl FnMut(f64) -> Result<f64, E>,
) -> Result<Crossing, E> {
    let on_start_side = |v: f64| v * start_sign > 0.0;
    debug_assert!(on_start_side(f_lo) && !on_start_side(f_hi));
    let mut evaluations = 0;
    // Which end was kept last time (for the Illinois halving): -1 lo, +1 hi, 0 none.
    let mut kept = 0i32;
    let mut width_before = hi - lo;
    let mut since_halving = 0;
    let tol = converged_width(lo, hi);
    while f_hi != 0.0 && hi - lo > tol && evaluations < 400 {
        let bisect = since_halving >= 2;
        let mut t = if bisect {
            0.5 * (lo + hi)
        } else {
            // Secant through (lo, f_lo), (hi, f_hi).
            hi - f_hi * (hi - lo) / (f_hi - f_lo)
        };
        if !(t > lo && t < hi) {
            t = 0.5 * (lo + hi);
        }
        if !(t > lo && t < hi) {
            break; // lo and hi are adjacent floats.
        }
        let v = f(t)?;
        evaluations += 1;
        if on_start_side(v) {
            lo = t;
            f_lo = v;
            if kept == 1 {
                f_hi *= 0.5;
            }
            kept = 1;
        } else {
            hi = t;
            f_hi = v;
            if kept == -1 {
                f_lo *= 0.5;
            }
            kept = -1;
        }
        let width = hi - lo;
        if width <= 0.5 * width_before {
            width_before = width;
            since_halving = 0;
        } else {
            since_halving += 1;
        }
    }
    // f_hi may have been halved by the Illinois rule; report the true value's sign only.
    Ok(Crossing {
        t: hi,
        before: lo,
        value: f_hi,
        evaluations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::cell::Cell;

    thread_local!(static WIDTH: Cell<f64> = const { Cell::new(0.0) });
    fn width() -> f64 {
        WIDTH.with(|w| w.get())
    }

    fn solve(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> Crossing {
        let s = f(lo).signum();
        WIDTH.with(|w| w.set(converged_width(lo, hi)));
        find_crossing::<()>(lo, f(lo), hi, f(hi), s, |t| Ok(f(t))).unwrap()
    }

    #[test]
    fn finds_simple_roots_to_a_few_ulps() {
        let c = solve(|t| t * t - 2.0, 0.0, 3.0);
        assert!((c.t - 2f64.sqrt()).abs() <= 4.0 * f64::EPSILON * 2.0);
        assert!(c.t * c.t - 2.0 >= 0.0);
        assert!(c.before * c.before - 2.0 < 0.0);
        assert!(c.evaluations < 60, "{c:?}");
    }

    #[test]
    fn a_root_at_the_upper_end_is_returned_exactly() {
        let c = solve(|t| t - 1.0, 0.0, 1.0);
        assert_eq!(c.t, 1.0);
        assert_eq!(c.evaluations, 0);
    }

    #[test]
    fn flat_functions_converge_by_bisection() {
        // (t-1)^9 is flat near the root: regula falsi alone would crawl.
        let c = solve(|t| (t - 1.0).powi(9), 0.3, 2.0);
        assert!(c.t - c.before <= width());
        assert!((c.t - 1.0).abs() < 1e-2, "{c:?}");
        assert!(c.evaluations < 400);
    }

    proptest! {
        #[test]
        fn crossing_brackets_the_root(root in -1e3f64..1e3, slope in 0.01f64..100.0, a in 0.1f64..10.0, b in 0.1f64..10.0) {
            let f = |t: f64| slope * (t - root) + 0.1 * (t - root).powi(3);
            let c = solve(f, root - a, root + b);
            prop_assert!(f(c.t) >= 0.0);
            prop_assert!(f(c.before) < 0.0);
            prop_assert!(c.t - c.before <= width() || f(c.t) == 0.0, "{:?}", c);
            prop_assert!((c.t - root).abs() <= 1e-12 * root.abs().max(1.0));
        }
    }
}
