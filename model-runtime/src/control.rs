//! Step-size selection: a PI controller with Gustafsson's predictive limit, and Hairer's
//! automatic initial step.
//!
//! The controller is shared by all adaptive methods (only the error order differs), so two
//! methods compared on the same problem differ only in their formulas.

use crate::error::SolveError;
use crate::stats::Stats;
use crate::stepper::{eval, Rhs, StepStart};
use crate::tolerance::Tolerance;

/// Limits and initial values for step-size selection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepOptions {
    /// First step size of every segment (a run's start and each restart after a transition);
    /// `None` chooses it automatically each time (Hairer's algorithm).
    pub h_initial: Option<f64>,
    /// Largest step size.
    pub h_max: f64,
    /// Smallest step size; a step that must be smaller is a
    /// [`SolveError::StepSizeCollapse`]. The solver also never goes below a few ulps of `t`.
    pub h_min: f64,
    /// Budget of step attempts (accepted and rejected) for one run.
    pub max_steps: u64,
}

impl Default for StepOptions {
    fn default() -> Self {
        StepOptions {
            h_initial: None,
            h_max: f64::INFINITY,
            h_min: 0.0,
            max_steps: 100_000_000,
        }
    }
}

/// Step-size control: a proportional-integral controller, `h * safety * err^(-alpha) *
/// err_prev^(beta)`, limited by Gustafsson's predictive factor `safety * (h / h_prev) *
/// (err_prev / err²)^(1/k)` (which sees an error that grows from step to step, as on the way
/// into a near-singular region, and shrinks the step before it is rejected), clamped to
/// `[fac_min, fac_max]` times `h`. A rejected step is retried with the full exponent `1/k`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Controller {
    /// `1 / (q + 1)` for an error estimate of order `q`.
    inv_k: f64,
    alpha: f64,
    beta: f64,
    /// `err_prev^beta` of the last accepted step (kept raised, to save a `powf` per step).
    err_prev_beta: f64,
    /// Step size and error of the last accepted step, for the predictive factor.
    last_accepted: Option<(f64, f64)>,
    rejected_last: bool,
}

const SAFETY: f64 = 0.9;
const FAC_MIN: f64 = 0.2;
const FAC_MAX: f64 = 10.0;

impl Controller {
    /// A controller for an error estimate of order `q` (exponents `0.7/(q+1)` and `0.4/(q+1)`).
    pub(crate) fn new(error_order: u32) -> Self {
        let k = (error_order + 1) as f64;
        Controller {
            inv_k: 1.0 / k,
            alpha: 0.7 / k,
            beta: 0.4 / k,
            err_prev_beta: 1.0,
            last_accepted: None,
            rejected_last: false,
        }
    }

    /// Forgets the error history (after a restart).
    pub(crate) fn reset(&mut self) {
        self.err_prev_beta = 1.0;
        self.last_accepted = None;
        self.rejected_last = false;
    }

    /// The next step size after an accepted step with scaled error `err <= 1`.
    pub(crate) fn accepted(&mut self, h: f64, err: f64) -> f64 {
        let err = err.max(1e-10);
        let mut fac = SAFETY * err.powf(-self.alpha) * self.err_prev_beta;
        if let Some((h_prev, err_prev)) = self.last_accepted {
            let predictive = SAFETY * (h / h_prev) * (err_prev / (err * err)).powf(self.inv_k);
            fac = fac.min(predictive);
        }
        fac = fac.clamp(FAC_MIN, FAC_MAX);
        if self.rejected_last {
            fac = fac.min(1.0);
        }
        self.err_prev_beta = err.max(1e-4).powf(self.beta);
        self.last_accepted = Some((h, err.max(1e-2)));
        self.rejected_last = false;
        h * fac
    }

    /// The retry step size after a rejected step with scaled error `err > 1` (possibly infinite).
    pub(crate) fn rejected(&mut self, h: f64, err: f64) -> f64 {
        self.rejected_last = true;
        let fac = if err.is_finite() {
            (SAFETY * err.powf(-self.inv_k)).clamp(FAC_MIN, 1.0)
        } else {
            FAC_MIN
        };
        h * fac
    }
}

/// Hairer's initial step-size guess (HNW I, II.4): balances `h*|f0|` against the state and
/// estimates the second derivative with one explicit Euler step.
pub(crate) fn initial_step<F: Rhs<N>, const N: usize>(
    sys: &F,
    start: StepStart<'_, N>,
    order: u32,
    tol: &Tolerance<N>,
    h_max: f64,
    stats: &mut Stats,
) -> Result<f64, SolveError> {
    let (t, y, f) = (start.t, start.y, start.f);
    let scales = tol.scales(y, &[0.0; N]);
    let norm = |v: &[f64; N]| -> f64 {
        if N == 0 {
            return 0.0;
        }
        let mut s = 0.0;
        for i in 0..N {
            let x = v[i] / scales[i];
            s += x * x;
        }
        (s / N as f64).sqrt()
    };
    let d0 = norm(y);
    let d1 = norm(f);
    let mut h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    h0 = h0.min(h_max);
    let mut y1 = [0.0; N];
    for i in 0..N {
        y1[i] = y[i] + h0 * f[i];
    }
    let mut f1 = [0.0; N];
    eval(sys, t + h0, &y1, &mut f1, stats)?;
    let mut diff = [0.0; N];
    for i in 0..N {
        diff[i] = f1[i] - f[i];
    }
    let d2 = norm(&diff) / h0;
    let dm = d1.max(d2);
    let h1 = if dm.is_nan() || dm <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / dm).powf(1.0 / (order as f64 + 1.0))
    };
    let h = (100.0 * h0).min(h1).min(h_max);
    Ok(if h.is_finite() && h > 0.0 { h } else { h0 })
}

/// The smallest step the solver may take at time `t`: the user's floor, but never below a few
/// ulps of `t` (a smaller step would not advance time).
pub(crate) fn min_step(t: f64, h_min: f64) -> f64 {
    h_min
        .max(8.0 * f64::EPSILON * t.abs())
        .max(f64::MIN_POSITIVE)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rejection_shrinks_by_the_full_error_exponent() {
        let mut c = Controller::new(4);
        // err = 32 with k = 5: the step that would have met the tolerance is h / 2.
        let h = c.rejected(1.0, 32.0);
        assert!((h - 0.45).abs() < 1e-12, "{h}");
        assert_eq!(c.rejected(1.0, f64::INFINITY), FAC_MIN);
        assert_eq!(c.rejected(1.0, 1e30), FAC_MIN);
    }

    #[test]
    fn steps_grow_on_small_errors_but_not_right_after_a_rejection() {
        let mut c = Controller::new(4);
        assert_eq!(c.accepted(1.0, 1e-12), FAC_MAX);
        c.reset();
        c.rejected(1.0, 2.0);
        assert!(c.accepted(1.0, 1e-6) <= 1.0);
    }

    #[test]
    fn a_growing_error_shrinks_the_step_before_it_is_rejected() {
        // Errors tripling from step to step at a constant step size: the predictive factor
        // proposes a smaller step than the proportional-integral one alone would.
        let mut c = Controller::new(4);
        c.accepted(1.0, 0.1);
        let with_history = c.accepted(1.0, 0.3);
        let mut fresh = Controller::new(4);
        let without = fresh.accepted(1.0, 0.3);
        assert!(with_history < without, "{with_history} vs {without}");
        assert!(with_history < 1.0);
    }
}
