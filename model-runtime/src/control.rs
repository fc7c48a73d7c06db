//! Step-size selection: a PI controller with Gustafsson's predictive limit, and Hairer's
//! automatic initial step.
//!
//! The controller is shared by all adaptive methods (only the error order differs), so two
//! methods compared on the same problem differ only in their formulas.

use crate::dim::{Dim, Vector};
use crate::error::{parse_word, ParseSettingError, SolveError};
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
    /// How the step size follows the error estimates.
    pub control: StepControl,
}

/// The gains of the step-size controller: how strongly the next step follows the last error
/// (`integral`) and the change from the error before it (`proportional`), in units of
/// `1/(q+1)` for an error estimate of order `q`. All three keep Gustafsson's predictive
/// limit and retry a rejected step with the full exponent.
///
/// The choice matters where the time scale of the solution changes by a constant factor from
/// step to step, as when the slip of a disk grows from zero or runs into it: there the smooth
/// PI controllers grow the step by only ~1.5× per step while the error stays at a few percent
/// of the tolerance, and the integral controller takes ~20% fewer steps. But the steps it
/// saves are the ones that kept the error well below the tolerance: at equal accuracy none of
/// the three is cheaper on the disk (BENCHMARKS.md §3), so the default stays the smoothest.
/// (SciPy's explicit methods use the integral controller.)
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum StepControl {
    /// The elementary controller `h·0.9·err^(-1/(q+1))` (integral gain 1, no proportional part).
    Integral,
    /// Hairer's DOPRI5 defaults (integral gain 0.65, proportional 0.2; β = 0.04 for q = 4).
    PiHairer,
    /// Gustafsson's PI.3.4 (integral gain 0.3, proportional 0.4): the smoothest step sequence.
    #[default]
    PiGustafsson,
}

impl StepControl {
    /// The (integral, proportional) gains in units of `1/(q+1)`.
    fn gains(self) -> (f64, f64) {
        match self {
            StepControl::Integral => (1.0, 0.0),
            StepControl::PiHairer => (0.65, 0.2),
            StepControl::PiGustafsson => (0.3, 0.4),
        }
    }
}

/// Spelled `integral`, `pi-hairer` or `pi-gustafsson`, as in scene files and command lines.
impl std::fmt::Display for StepControl {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            StepControl::Integral => "integral",
            StepControl::PiHairer => "pi-hairer",
            StepControl::PiGustafsson => "pi-gustafsson",
        })
    }
}

impl std::str::FromStr for StepControl {
    type Err = ParseSettingError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        parse_word(
            s,
            &[
                StepControl::Integral,
                StepControl::PiHairer,
                StepControl::PiGustafsson,
            ],
            "step control",
            "integral, pi-hairer or pi-gustafsson",
        )
    }
}

impl Default for StepOptions {
    fn default() -> Self {
        StepOptions {
            h_initial: None,
            h_max: f64::INFINITY,
            h_min: 0.0,
            max_steps: 100_000_000,
            control: StepControl::default(),
        }
    }
}

/// Step-size control: a proportional-integral controller, `h * safety * err^(-alpha) *
/// err_prev^(beta)` with `alpha = (k_I + k_P)/k`, `beta = k_P/k` ([`StepControl`]), limited by Gustafsson's predictive factor `safety * (h / h_prev) *
/// (err_prev / err²)^(1/k)` (which sees an error that grows from step to step, as on the way
/// into a near-singular region, and shrinks the step before it is rejected), clamped to
/// `[fac_min, fac_max]` times `h`. A rejected step is retried with the full exponent `1/k`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Controller {
    /// `1 / (q + 1)` for an error estimate of order `q`.
    inv_k: f64,
    alpha: f64,
    beta: f64,
    /// `beta * ln(err_prev)` of the last accepted step. The controller works with logarithms
    /// of the errors: one `ln` and two `exp` per step instead of three `powf`, which cost
    /// 5% of a run whose steps are cheap.
    beta_ln_err_prev: f64,
    /// Step size and `ln(error)` of the last accepted step, for the predictive factor.
    last_accepted: Option<(f64, f64)>,
    rejected_last: bool,
}

const SAFETY: f64 = 0.9;
const FAC_MIN: f64 = 0.2;
const FAC_MAX: f64 = 10.0;
/// `ln(1e-4)`: the previous error in the PI factor is at least `1e-4`.
const LN_ERR_PREV_MIN: f64 = -9.210_340_371_976_184;
/// `ln(1e-2)`: the previous error in the predictive factor is at least `1e-2`.
const LN_ERR_PREDICTIVE_MIN: f64 = -4.605_170_185_988_091;

impl Controller {
    /// A controller for an error estimate of order `q` with the gains of `control`.
    pub(crate) fn new(error_order: u32, control: StepControl) -> Self {
        let k = (error_order + 1) as f64;
        let (integral, proportional) = control.gains();
        Controller {
            inv_k: 1.0 / k,
            alpha: (integral + proportional) / k,
            beta: proportional / k,
            beta_ln_err_prev: 0.0,
            last_accepted: None,
            rejected_last: false,
        }
    }

    /// Forgets the error history (after a restart).
    pub(crate) fn reset(&mut self) {
        self.beta_ln_err_prev = 0.0;
        self.last_accepted = None;
        self.rejected_last = false;
    }

    /// The next step size after an accepted step with scaled error `err <= 1`.
    pub(crate) fn accepted(&mut self, h: f64, err: f64) -> f64 {
        let ln_err = err.max(1e-10).ln();
        let mut fac = SAFETY * (self.beta_ln_err_prev - self.alpha * ln_err).exp();
        if let Some((h_prev, ln_err_prev)) = self.last_accepted {
            let predictive =
                SAFETY * (h / h_prev) * ((ln_err_prev - 2.0 * ln_err) * self.inv_k).exp();
            fac = fac.min(predictive);
        }
        fac = fac.clamp(FAC_MIN, FAC_MAX);
        if self.rejected_last {
            fac = fac.min(1.0);
        }
        self.beta_ln_err_prev = self.beta * ln_err.max(LN_ERR_PREV_MIN);
        self.last_accepted = Some((h, ln_err.max(LN_ERR_PREDICTIVE_MIN)));
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
pub(crate) fn initial_step<F: Rhs<D>, D: Dim>(
    sys: &F,
    start: StepStart<'_, D>,
    order: u32,
    tol: &Tolerance<D>,
    h_max: f64,
    stats: &mut Stats,
) -> Result<f64, SolveError> {
    let (t, y, f) = (start.t, start.y, start.f);
    let dim = D::of(y);
    let scales = tol.scales(y, &dim.zeros());
    let norm = |v: &Vector<D>| -> f64 {
        if dim.size() == 0 {
            return 0.0;
        }
        let mut s = 0.0;
        for i in 0..dim.size() {
            let x = v[i] / scales[i];
            s += x * x;
        }
        (s / dim.size() as f64).sqrt()
    };
    let d0 = norm(y);
    let d1 = norm(f);
    let mut h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    h0 = h0.min(h_max);
    let mut y1 = dim.zeros();
    for i in 0..dim.size() {
        y1[i] = y[i] + h0 * f[i];
    }
    let mut f1 = dim.zeros();
    eval(sys, t + h0, &y1, &mut f1, stats)?;
    let mut diff = dim.zeros();
    for i in 0..dim.size() {
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

    const ALL: [StepControl; 3] = [
        StepControl::Integral,
        StepControl::PiHairer,
        StepControl::PiGustafsson,
    ];

    /// The controller's formulas as written in its docs, in powers.
    fn by_powers(c: StepControl, h: f64, err: f64, prev: Option<(f64, f64)>, k: f64) -> f64 {
        let (ki, kp) = c.gains();
        let err = err.max(1e-10);
        let pi = |ep: f64| SAFETY * err.powf(-(ki + kp) / k) * ep.max(1e-4).powf(kp / k);
        match prev {
            None => pi(1.0).clamp(FAC_MIN, FAC_MAX) * h,
            Some((h_prev, ep)) => {
                let predictive = SAFETY * (h / h_prev) * (ep.max(1e-2) / (err * err)).powf(1.0 / k);
                pi(ep).min(predictive).clamp(FAC_MIN, FAC_MAX) * h
            }
        }
    }

    #[test]
    fn logarithms_give_the_factors_of_the_powers() {
        // A sequence of accepted steps with errors over ten decades, for both error orders in
        // use and every gain set: each proposed step is the one of the formula in powers.
        for control in ALL {
            for order in [4, 7] {
                let k = (order + 1) as f64;
                let mut c = Controller::new(order, control);
                let mut prev = None;
                let mut h = 1e-3;
                for i in 0..200 {
                    let err = 10f64.powf(-10.0 + 10.0 * ((i * 37 % 101) as f64 / 100.0));
                    let expected = by_powers(control, h, err, prev, k);
                    let got = c.accepted(h, err);
                    assert!(
                        (got - expected).abs() <= 1e-13 * expected,
                        "{control}: {got} vs {expected}"
                    );
                    prev = Some((h, err));
                    h = got;
                }
            }
        }
    }

    /// Steps from `t = 1e-10` to `1e-5` when the solution's time scale is the time `t` since
    /// a singularity (the error of a step is `(h/t)^5`, as near a slip of zero).
    fn steps_out_of_a_singularity(control: StepControl) -> u32 {
        let mut c = Controller::new(4, control);
        let (mut t, mut h, mut steps): (f64, f64, u32) = (1e-10, 1e-11, 0);
        while t < 1e-5 {
            let err = (h / t).powi(5) * 10.0;
            if err <= 1.0 {
                t += h;
                h = c.accepted(h, err);
                steps += 1;
            } else {
                h = c.rejected(h, err);
            }
            assert!(steps < 10_000);
        }
        steps
    }

    #[test]
    fn the_integral_controller_leaves_a_singularity_in_fewer_steps() {
        let [integral, hairer, gustafsson] = ALL.map(steps_out_of_a_singularity);
        println!("steps: integral {integral}, pi-hairer {hairer}, pi-gustafsson {gustafsson}");
        assert!(
            integral < hairer && hairer < gustafsson,
            "{integral} {hairer} {gustafsson}"
        );
        // At best every step is the largest the tolerance admits, h = 10^(-1/5)·t, with the
        // safety factor h ≈ 0.57 t: ln(1e5)/ln(1.57) ≈ 26 steps. Within 1.5× of that:
        assert!(integral <= 39, "{integral}");
    }

    #[test]
    fn step_controls_are_spelled_and_read_back() {
        for c in ALL {
            assert_eq!(c.to_string().parse::<StepControl>(), Ok(c));
        }
        let e = "pid".parse::<StepControl>().unwrap_err();
        assert!(e.to_string().contains("\"pid\""), "{e}");
    }

    #[test]
    fn a_rejection_shrinks_by_the_full_error_exponent() {
        let mut c = Controller::new(4, StepControl::default());
        // err = 32 with k = 5: the step that would have met the tolerance is h / 2.
        let h = c.rejected(1.0, 32.0);
        assert!((h - 0.45).abs() < 1e-12, "{h}");
        assert_eq!(c.rejected(1.0, f64::INFINITY), FAC_MIN);
        assert_eq!(c.rejected(1.0, 1e30), FAC_MIN);
    }

    #[test]
    fn steps_grow_on_small_errors_but_not_right_after_a_rejection() {
        let mut c = Controller::new(4, StepControl::default());
        assert_eq!(c.accepted(1.0, 1e-12), FAC_MAX);
        c.reset();
        c.rejected(1.0, 2.0);
        assert!(c.accepted(1.0, 1e-6) <= 1.0);
    }

    #[test]
    fn a_growing_error_shrinks_the_step_before_it_is_rejected() {
        // Errors tripling from step to step at a constant step size: the predictive factor
        // proposes a smaller step than the proportional-integral one alone would.
        for control in ALL {
            let mut c = Controller::new(4, control);
            c.accepted(1.0, 0.1);
            let with_history = c.accepted(1.0, 0.3);
            let mut fresh = Controller::new(4, control);
            let without = fresh.accepted(1.0, 0.3);
            assert!(
                with_history < without,
                "{control}: {with_history} vs {without}"
            );
            assert!(with_history < 1.0, "{control}");
        }
    }
}
