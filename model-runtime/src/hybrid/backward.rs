//! Runs backward in time: a run from `t0` to `t_end < t0` is the forward run of the
//! time-reversed system in `τ = −t`, `dy/dτ = −f(−τ, y)`, read back in `t`.
//!
//! Why a reversal rather than negative steps: every piece of the driver (the step loop, the
//! step-size controller, the guard tracker, the root finder, the samples, the chattering
//! window) is written for time that grows, and each would need a signed variant. The reversal
//! reuses all of them unchanged, and it is exact, not an approximation of a backward run:
//!
//! * Negation is exact in floating point, and rounding to nearest is symmetric
//!   (`fl(−a) = −fl(a)`, `fl(−a · b) = −fl(a · b)`, `fl(−a − b) = −fl(a + b)`). A step of the
//!   reversed system from `τ0 = −t0` with `H = −h > 0` evaluates the model at
//!   `−(τ0 + c_i H) = t0 + c_i h` and at the stage states `y0 + H Σ a_ij K_j` with
//!   `K_j = −k_j`, the very numbers an explicit method stepping `h < 0` in `t` would compute;
//!   its error estimate is the same norm of the same numbers. Rosenbrock's
//!   `I/(γH) − ∂(−f)/∂y` is the negated matrix of `I/(γh) − ∂f/∂y`, whose LU with partial
//!   pivoting picks the same pivots; the one difference is RODAS4's `∂f/∂t` of a model that
//!   reads `t`, a forward difference in `τ`, so taken on the other side of `t` (both are
//!   first-order differences over `√ε·|t|`).
//! * The guards see the model's own `t` and `dy/dt` ([`HybridSystem::guard_values`] is
//!   called at `t = −τ` with the derivative negated back), the transition map gets the event
//!   in `t`, and the observer every step, sample, event and transition in `t`: its steps go
//!   from `t0` to `t1 < t0`, its samples are due at `t0 − k / rate`, and a step's interpolant
//!   is evaluated at `t` ([`Interpolant::at`] reflects it).
//! * A guard's [`crate::Direction`] keeps its meaning along the run: `Up` fires where the
//!   guard goes from negative to positive *as the run proceeds*, here as `t` decreases. This
//!   is SciPy's `solve_ivp` rule (`direction > 0` fires on a value that was negative at the
//!   previous step and is positive at the next one, whichever way the integration goes).
//!
//! What has no backward meaning is left to the system: a transition map still maps the state
//! before an event (now the later one) to the state after it. A system whose resets are
//! meant forward (a bounce that loses energy) is not a system to run backward, and a caller
//! that knows its maps are forward-only refuses a backward run (as the model interpreter
//! does for a switched model).

use super::{HybridError, HybridOutcome, HybridSystem, TransitionOf};
use crate::dense::{Interpolant, StoredInterpolant};
use crate::dim::{Dim, Matrix, Vector};
use crate::error::{EvalError, SolveError};
use crate::events::{EventHit, GuardInputs, GuardSpec};
use crate::observer::{Observed, Observer, Sample, StepView, TransitionRecord};
use crate::stepper::Rhs;
use std::cell::RefCell;
use std::ops::ControlFlow;

/// `v ← −v`.
fn negate<D: Dim>(v: &mut Vector<D>) {
    for x in v.as_mut() {
        *x = -*x;
    }
}

/// `−v`.
fn negated<D: Dim>(v: &Vector<D>) -> Vector<D> {
    let mut out = v.clone();
    negate::<D>(&mut out);
    out
}

/// An event of the reversed run as it happened in `t`.
fn hit_in_t<D: Dim, G: Copy>(hit: &EventHit<D, G>) -> EventHit<D, G> {
    EventHit {
        guard: hit.guard,
        index: hit.index,
        t: -hit.t,
        before: -hit.before,
        y: hit.y.clone(),
        dy: negated::<D>(&hit.dy),
        value: hit.value,
        direction: hit.direction,
    }
}

/// A right-hand side in `τ = −t`: `dy/dτ = −f(−τ, y)`, its Jacobian `−∂f/∂y`.
pub(crate) struct ReversedRhs<'a, F>(pub(crate) &'a F);

impl<D: Dim, F: Rhs<D>> Rhs<D> for ReversedRhs<'_, F> {
    #[inline]
    fn rhs(&self, tau: f64, y: &Vector<D>, dy: &mut Vector<D>) -> Result<(), EvalError> {
        self.0.rhs(-tau, y, dy)?;
        negate::<D>(dy);
        Ok(())
    }

    fn jacobian(&self, tau: f64, y: &Vector<D>, jac: &mut Matrix<D>) -> Result<(), EvalError> {
        self.0.jacobian(-tau, y, jac)?;
        for row in jac.as_mut() {
            negate::<D>(row);
        }
        Ok(())
    }
}

/// A hybrid system in `τ = −t`.
pub(super) struct Reversed<'a, H, D: Dim> {
    sys: &'a mut H,
    /// `dy/dt` for the guards (the driver hands them `dy/dτ`).
    rates: RefCell<Vector<D>>,
}

impl<'a, H, D: Dim> Reversed<'a, H, D> {
    pub(super) fn new(sys: &'a mut H, dim: D) -> Self {
        Reversed {
            sys,
            rates: RefCell::new(dim.zeros()),
        }
    }
}

impl<D: Dim, H: HybridSystem<D>> HybridSystem<D> for Reversed<'_, H, D> {
    type Mode = H::Mode;
    type Guard = H::Guard;
    type Stop = H::Stop;
    type Note = H::Note;

    #[inline]
    fn rhs(
        &self,
        mode: H::Mode,
        tau: f64,
        y: &Vector<D>,
        dy: &mut Vector<D>,
    ) -> Result<(), EvalError> {
        self.sys.rhs(mode, -tau, y, dy)?;
        negate::<D>(dy);
        Ok(())
    }

    fn jacobian(
        &self,
        mode: H::Mode,
        tau: f64,
        y: &Vector<D>,
        jac: &mut Matrix<D>,
    ) -> Result<(), EvalError> {
        self.sys.jacobian(mode, -tau, y, jac)?;
        for row in jac.as_mut() {
            negate::<D>(row);
        }
        Ok(())
    }

    fn guards(&self, mode: H::Mode) -> &[GuardSpec<H::Guard>] {
        self.sys.guards(mode)
    }

    fn guard_values(
        &self,
        mode: H::Mode,
        tau: f64,
        y: &Vector<D>,
        dy: &Vector<D>,
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        let mut rates = self.rates.borrow_mut();
        // A screening estimate fills only the guards' inputs, NaN elsewhere: negated, NaN
        // stays NaN, so the guard sees what it would forward.
        for (r, d) in rates.as_mut().iter_mut().zip(dy.as_ref()) {
            *r = -*d;
        }
        self.sys.guard_values(mode, -tau, y, &rates, values)
    }

    fn guard_inputs(&self, mode: H::Mode) -> Option<GuardInputs<D>> {
        self.sys.guard_inputs(mode)
    }

    fn on_event(
        &mut self,
        mode: H::Mode,
        hit: &EventHit<D, H::Guard>,
    ) -> Result<TransitionOf<D, H>, EvalError> {
        self.sys.on_event(mode, &hit_in_t(hit))
    }

    fn first_step(&self, mode: H::Mode, tau: f64, y: &Vector<D>) -> Option<f64> {
        self.sys.first_step(mode, -tau, y)
    }

    fn fires_on_entry(&self) -> bool {
        self.sys.fires_on_entry()
    }

    fn project(&self, mode: H::Mode, tau: f64, y: &mut Vector<D>) -> bool {
        self.sys.project(mode, -tau, y)
    }
}

/// An interpolant in `τ` (a live step's, or a stored one), evaluated at `t`.
struct Reflected<I>(I);

impl<D: Dim, I: Interpolant<D>> Interpolant<D> for Reflected<I> {
    fn dim(&self) -> D {
        self.0.dim()
    }

    fn at(&self, t: f64, out: &mut Vector<D>) {
        self.0.at(-t, out)
    }

    fn component_at(&self, t: f64, i: usize) -> f64 {
        self.0.component_at(-t, i)
    }

    fn sample_at(&self, t: f64, out: &mut Vector<D>) {
        self.0.sample_at(-t, out)
    }

    fn at_fraction(&self, (t0, t1): (f64, f64), u: f64, out: &mut Vector<D>) -> f64 {
        -self.0.at_fraction((-t0, -t1), u, out)
    }

    fn stored(&self) -> StoredInterpolant<D> {
        StoredInterpolant::new(Reflected(self.0.stored()))
    }
}

/// The caller's observer, handed the reversed run's output in `t`.
pub(super) struct InCallersTime<'a, O, D: Dim> {
    obs: &'a mut O,
    /// `dy/dt` at a step's start.
    f0: Vector<D>,
}

impl<'a, O, D: Dim> InCallersTime<'a, O, D> {
    pub(super) fn new(obs: &'a mut O, dim: D) -> Self {
        InCallersTime {
            obs,
            f0: dim.zeros(),
        }
    }
}

impl<D: Dim, Md: Copy, G: Copy, Nt, O: Observer<D, Md, G, Nt>> Observer<D, Md, G, Nt>
    for InCallersTime<'_, O, D>
{
    fn wants_dense(&self) -> bool {
        self.obs.wants_dense()
    }

    fn on_step(&mut self, step: &StepView<'_, D, Md>) -> Observed {
        for (f, d) in self.f0.as_mut().iter_mut().zip(step.f0.as_ref()) {
            *f = -*d;
        }
        let dense = step.dense.map(Reflected);
        self.obs.on_step(&StepView {
            mode: step.mode,
            t0: -step.t0,
            t1: -step.t1,
            y0: step.y0,
            y1: step.y1,
            f0: &self.f0,
            dense: dense.as_ref().map(|d| d as &dyn Interpolant<D>),
        })
    }

    fn wants_sample(&self, tau: f64) -> bool {
        self.obs.wants_sample(-tau)
    }

    fn on_sample(&mut self, sample: &Sample<'_, D, Md>) -> Observed {
        self.obs.on_sample(&Sample {
            t: -sample.t,
            mode: sample.mode,
            y: sample.y,
        })
    }

    fn proceed(&mut self) -> ControlFlow<()> {
        self.obs.proceed()
    }

    fn on_transition(&mut self, record: TransitionRecord<D, Md, G, Nt>) -> Observed {
        self.obs.on_transition(TransitionRecord {
            hit: hit_in_t(&record.hit),
            from: record.from,
            kind: record.kind,
            y_after: record.y_after,
            note: record.note,
        })
    }
}

/// The reversed run's outcome in `t`.
pub(super) fn outcome_in_t<D: Dim, Md, R>(
    mut outcome: HybridOutcome<D, Md, R>,
) -> HybridOutcome<D, Md, R> {
    outcome.t = -outcome.t;
    outcome
}

/// The reversed run's failure dated in `t` (an observer's is already: it reports the times
/// it was handed).
pub(super) fn error_in_t<Md>(error: HybridError<Md>) -> HybridError<Md> {
    match error {
        HybridError::Solve { mode, error } => HybridError::Solve {
            mode,
            error: match error.time() {
                Some(tau) => error.at_time(-tau),
                None => error,
            },
        },
        HybridError::Transition { mode, t, source } => HybridError::Transition {
            mode,
            t: -t,
            source,
        },
        HybridError::Chattering {
            t,
            transitions,
            window,
            modes,
        } => HybridError::Chattering {
            t: -t,
            transitions,
            window,
            modes,
        },
        observer @ HybridError::Observer { .. } => observer,
    }
}

/// `SolveError` in `τ`, dated in `t` (for a plain integration).
pub(crate) fn solve_error_in_t(error: SolveError) -> SolveError {
    match error.time() {
        Some(tau) => error.at_time(-tau),
        None => error,
    }
}
