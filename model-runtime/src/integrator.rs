//! The adaptive stepping loop, shared by plain integration and the hybrid driver.
//!
//! [`Integrator`] owns a [`Stepper`], the current point `(t, y, f)` and the previous one, and
//! advances by one *accepted* step at a time; the caller decides what happens between steps
//! (events, samples, projections, restarts). Keeping this loop in one place means every method
//! gets the same rejection logic, end-time handling and collapse detection.

use crate::control::{initial_step, min_step, Controller, StepOptions};
use crate::dense::{place_in_step, Interpolant, OwnedStep, StoredInterpolant};
use crate::dim::{Array, Const, Dim, Vector};
use crate::error::{InputError, SolveError};
use crate::hybrid::backward::{solve_error_in_t, ReversedRhs};
use crate::stats::Stats;
use crate::stepper::{eval, Components, Rhs, StepEnd, StepStart, Stepper};
use crate::tolerance::{LimitingComponent, Tolerance};

/// Where a time falls in the last accepted step.
enum InStep {
    /// At or after its end.
    End,
    /// At or before its start.
    Start,
    /// Inside, at the fraction `theta` of the step.
    Inside { theta: f64 },
}

/// A stepper plus its step-size control and the current and previous accepted points.
#[derive(Clone, Debug)]
pub struct Integrator<S, D: Dim> {
    stepper: S,
    tol: Tolerance<D>,
    opts: StepOptions,
    ctrl: Controller,
    t: f64,
    y: Vector<D>,
    f: Vector<D>,
    t_prev: f64,
    y_prev: Vector<D>,
    f_prev: Vector<D>,
    h: f64,
    has_step: bool,
    dense_ready: bool,
    attempts: u64,
    stats: Stats,
}

impl<S: Stepper<D>, D: Dim> Integrator<S, D> {
    /// An integrator; call [`Integrator::restart`] before the first step.
    pub fn new(stepper: S, tol: Tolerance<D>, opts: StepOptions) -> Result<Self, InputError> {
        tol.validate()?;
        let dim = stepper.dim();
        if tol.dim() != dim {
            return Err(InputError::Size {
                what: "tolerance",
                expected: dim.size(),
                found: tol.dim().size(),
            });
        }
        for h in [stepper.fixed_step(), opts.h_initial].into_iter().flatten() {
            if !(h.is_finite() && h > 0.0) {
                return Err(InputError::StepSize { h });
            }
        }
        if opts.h_max.is_nan() || opts.h_max <= 0.0 || opts.h_min.is_nan() || opts.h_min < 0.0 {
            return Err(InputError::StepSize {
                h: if opts.h_max.is_nan() || opts.h_max <= 0.0 {
                    opts.h_max
                } else {
                    opts.h_min
                },
            });
        }
        Ok(Integrator {
            stepper,
            tol,
            opts,
            ctrl: Controller::new(S::ERROR_ORDER, opts.control),
            t: 0.0,
            y: dim.zeros(),
            f: dim.zeros(),
            t_prev: 0.0,
            y_prev: dim.zeros(),
            f_prev: dim.zeros(),
            h: 0.0,
            has_step: false,
            dense_ready: false,
            attempts: 0,
            stats: Stats::default(),
        })
    }

    /// Starts afresh at `(t, y)`: evaluates `f`, forgets the previous step (no first-same-as-last
    /// reuse across a restart, no error history) and chooses a new initial step size.
    pub fn restart<F: Rhs<D>>(&mut self, sys: &F, t: f64, y: &Vector<D>) -> Result<(), SolveError> {
        self.restart_with_step(sys, t, y, None)
    }

    /// Like [`Integrator::restart`], trying `first_step` (if given, positive and finite) as the
    /// first step of an adaptive method instead of the configured or automatic one.
    pub fn restart_with_step<F: Rhs<D>>(
        &mut self,
        sys: &F,
        t: f64,
        y: &Vector<D>,
        first_step: Option<f64>,
    ) -> Result<(), SolveError> {
        if !t.is_finite() {
            return Err(InputError::TimeSpan { t0: t, t_end: t }.into());
        }
        if y.as_ref().len() != self.y.as_ref().len() {
            return Err(InputError::Size {
                what: "initial state",
                expected: self.y.as_ref().len(),
                found: y.as_ref().len(),
            }
            .into());
        }
        if let Some(i) = y.as_ref().iter().position(|v| !v.is_finite()) {
            return Err(InputError::InitialState {
                component: i,
                value: y[i],
            }
            .into());
        }
        self.t = t;
        self.y.assign(y);
        eval(sys, t, &self.y, &mut self.f, &mut self.stats)?;
        self.ctrl.reset();
        self.has_step = false;
        self.dense_ready = false;
        let hint = first_step.filter(|h| h.is_finite() && *h > 0.0);
        self.h = match (self.stepper.fixed_step(), hint.or(self.opts.h_initial)) {
            (Some(h), _) | (None, Some(h)) => h,
            (None, None) => initial_step(
                sys,
                StepStart {
                    t,
                    y: &self.y,
                    f: &self.f,
                },
                S::ERROR_ORDER,
                &self.tol,
                self.opts.h_max,
                &mut self.stats,
            )?,
        };
        Ok(())
    }

    /// Takes one accepted step, never beyond `t_end` (the last step lands on it exactly).
    /// Does nothing when `t >= t_end`.
    ///
    /// A model error at a trial stage of an adaptive method, or a singular iteration matrix of
    /// an implicit one, rejects the attempt (a shorter step may stay clear of the singular
    /// region); it is returned, with its time, once the step cannot shrink any further.
    /// Fixed-step methods return it at once.
    pub fn step<F: Rhs<D>>(&mut self, sys: &F, t_end: f64) -> Result<(), SolveError> {
        if self.t >= t_end {
            return Ok(());
        }
        let fixed = self.stepper.fixed_step();
        let mut h = self.h.min(self.opts.h_max);
        loop {
            if self.attempts >= self.opts.max_steps {
                return Err(SolveError::MaxSteps {
                    t: self.t,
                    steps: self.attempts,
                });
            }
            let h_min = min_step(self.t, self.opts.h_min);
            if fixed.is_none() {
                h = h.max(h_min);
            }
            let remaining = t_end - self.t;
            // A fixed-step method lands on `t_end` with its last full step despite the
            // round-off accumulated in `t`; an adaptive one stretches a step by up to 1 %.
            let stretch = if fixed.is_some() { 1.0 + 1e-9 } else { 1.01 };
            let last = stretch * h >= remaining;
            if last {
                h = remaining;
            }
            self.attempts += 1;
            let dim = self.dim();
            let mut y1 = dim.zeros();
            let mut f1 = dim.zeros();
            let attempt = self.stepper.attempt(
                sys,
                StepStart {
                    t: self.t,
                    y: &self.y,
                    f: &self.f,
                },
                h,
                &self.tol,
                StepEnd {
                    y: &mut y1,
                    f: &mut f1,
                },
                &mut self.stats,
            );
            let est = match attempt {
                Ok(est) => est,
                // A model that cannot be evaluated at a trial stage (the step overshot into a
                // region where it is singular) is treated as a rejection: a shorter step may
                // stay clear of it. Only when the step cannot shrink further is it an error.
                Err(SolveError::Eval { .. } | SolveError::SingularIterationMatrix { .. })
                    if fixed.is_none() && h > h_min =>
                {
                    self.stats.rejected += 1;
                    h = self.ctrl.rejected(h, f64::INFINITY);
                    continue;
                }
                Err(e) => return Err(e),
            };
            if est.norm <= 1.0 {
                self.stats.steps += 1;
                if fixed.is_none() && self.tol.limiting() == LimitingComponent::Tracked {
                    self.stats.limiting.record(est.worst);
                }
                self.t_prev = self.t;
                self.y_prev.assign(&self.y);
                self.f_prev.assign(&self.f);
                self.t = if last { t_end } else { self.t + h };
                self.y = y1;
                self.f = f1;
                self.has_step = true;
                self.dense_ready = false;
                self.h = match fixed {
                    Some(hf) => hf,
                    None => self.ctrl.accepted(h, est.norm),
                };
                return Ok(());
            }
            self.stats.rejected += 1;
            if h <= h_min {
                return Err(SolveError::StepSizeCollapse {
                    t: self.t,
                    h,
                    h_min,
                    component: est.worst,
                    error_norm: est.norm,
                });
            }
            h = self.ctrl.rejected(h, est.norm);
        }
    }

    /// Builds the interpolant of the last accepted step if it is not built yet.
    pub fn ensure_dense<F: Rhs<D>>(&mut self, sys: &F) -> Result<(), SolveError> {
        if self.has_step && !self.dense_ready {
            self.stepper.prepare_dense(
                sys,
                StepStart {
                    t: self.t_prev,
                    y: &self.y_prev,
                    f: &self.f_prev,
                },
                &self.y,
                &self.f,
                self.t - self.t_prev,
                &mut self.stats,
            )?;
            self.dense_ready = true;
        }
        Ok(())
    }

    /// Where `t` falls in the last accepted step (clamped to it), the interpolant built when
    /// `t` is inside.
    fn place<F: Rhs<D>>(&mut self, sys: &F, t: f64) -> Result<InStep, SolveError> {
        if !self.has_step || t >= self.t {
            return Ok(InStep::End);
        }
        if t <= self.t_prev {
            return Ok(InStep::Start);
        }
        self.ensure_dense(sys)?;
        Ok(InStep::Inside {
            theta: (t - self.t_prev) / (self.t - self.t_prev),
        })
    }

    /// The interpolated state at `t` inside the last accepted step (`t` is clamped to it).
    /// The end points are returned exactly.
    pub fn interpolate<F: Rhs<D>>(
        &mut self,
        sys: &F,
        t: f64,
        out: &mut Vector<D>,
    ) -> Result<(), SolveError> {
        match self.place(sys, t)? {
            InStep::End => out.assign(&self.y),
            InStep::Start => out.assign(&self.y_prev),
            InStep::Inside { theta } => self.stepper.interpolate(theta, out),
        }
        Ok(())
    }

    /// The interpolated state at `t` inside the last accepted step and the time derivative of
    /// the interpolant there ([`Stepper::interpolate_derivative`]: an estimate of `f`, not a
    /// model evaluation). At the step's end points both are exact.
    pub fn interpolate_with_derivative<F: Rhs<D>>(
        &mut self,
        sys: &F,
        t: f64,
        y: &mut Vector<D>,
        dy: &mut Vector<D>,
    ) -> Result<(), SolveError> {
        let all = Components::all(self.dim());
        self.interpolate_components(sys, t, &all, &all, y, dy)
    }

    /// [`Integrator::interpolate_with_derivative`] in the components `state` of `y` and
    /// `rates` of `dy` only; the other components are left as they are (at the step's end
    /// points too), so that a caller that filled them with NaN sees NaN there.
    #[inline]
    pub fn interpolate_components<F: Rhs<D>>(
        &mut self,
        sys: &F,
        t: f64,
        state: &Components<D>,
        rates: &Components<D>,
        y: &mut Vector<D>,
        dy: &mut Vector<D>,
    ) -> Result<(), SolveError> {
        match self.place(sys, t)? {
            InStep::End => {
                state.copy(&self.y, y);
                rates.copy(&self.f, dy);
            }
            InStep::Start => {
                state.copy(&self.y_prev, y);
                rates.copy(&self.f_prev, dy);
            }
            InStep::Inside { theta } => {
                self.stepper.interpolate_components(theta, state, y);
                self.stepper.interpolate_derivative_components(
                    theta,
                    self.t - self.t_prev,
                    rates,
                    dy,
                );
            }
        }
        Ok(())
    }

    /// The interpolant of the last step, if it has been built (see [`Integrator::ensure_dense`]).
    pub fn dense(&self) -> Option<DenseStep<'_, S, D>> {
        (self.has_step && self.dense_ready).then_some(DenseStep {
            stepper: &self.stepper,
            t0: self.t_prev,
            t1: self.t,
            y0: &self.y_prev,
            y1: &self.y,
        })
    }

    /// Replaces the current state (e.g. by a projection onto constraints) and re-evaluates `f`.
    /// The interpolant of the last step is left as it was.
    pub fn replace_state<F: Rhs<D>>(&mut self, sys: &F, y: &Vector<D>) -> Result<(), SolveError> {
        self.y.assign(y);
        eval(sys, self.t, &self.y, &mut self.f, &mut self.stats)
    }

    /// The size of the states it integrates.
    #[inline(always)]
    pub fn dim(&self) -> D {
        self.stepper.dim()
    }

    /// Zeroes the work counters and the step budget (at the start of a run).
    pub fn reset_counters(&mut self) {
        self.stats = Stats::default();
        self.attempts = 0;
    }

    /// Current time.
    pub fn t(&self) -> f64 {
        self.t
    }
    /// Current state.
    pub fn y(&self) -> &Vector<D> {
        &self.y
    }
    /// `f(t, y)` at the current point.
    pub fn f(&self) -> &Vector<D> {
        &self.f
    }
    /// Start time of the last accepted step (equals [`Integrator::t`] before the first step).
    pub fn t_prev(&self) -> f64 {
        if self.has_step {
            self.t_prev
        } else {
            self.t
        }
    }
    /// State at the start of the last accepted step.
    pub fn y_prev(&self) -> &Vector<D> {
        if self.has_step {
            &self.y_prev
        } else {
            &self.y
        }
    }
    /// `f` at the start of the last accepted step.
    pub fn f_prev(&self) -> &Vector<D> {
        if self.has_step {
            &self.f_prev
        } else {
            &self.f
        }
    }
    /// The step size the controller proposes next.
    pub fn next_step_size(&self) -> f64 {
        self.h
    }
    /// Work done so far.
    pub fn stats(&self) -> &Stats {
        &self.stats
    }
    /// Mutable work counters (for drivers that evaluate the model themselves).
    pub fn stats_mut(&mut self) -> &mut Stats {
        &mut self.stats
    }
    /// The tolerances.
    pub fn tolerance(&self) -> &Tolerance<D> {
        &self.tol
    }
}

/// Read access to the interpolant of one accepted step.
#[derive(Clone, Copy, Debug)]
pub struct DenseStep<'a, S, D: Dim> {
    stepper: &'a S,
    /// Start time of the step.
    pub t0: f64,
    /// End time of the step.
    pub t1: f64,
    pub(crate) y0: &'a Vector<D>,
    y1: &'a Vector<D>,
}

impl<S: Stepper<D>, D: Dim> DenseStep<'_, S, D> {
    /// The interpolated state at `t ∈ [t0, t1]` (clamped; end points are exact).
    pub fn at(&self, t: f64, out: &mut Vector<D>) {
        match place_in_step(t, self.t0, self.t1) {
            Ok(theta) => self.stepper.interpolate(theta, out),
            Err(true) => out.assign(self.y1),
            Err(false) => out.assign(self.y0),
        }
    }

    /// Component `i` of [`DenseStep::at`], interpolating that component only.
    pub fn component_at(&self, t: f64, i: usize) -> f64 {
        match place_in_step(t, self.t0, self.t1) {
            Ok(theta) => self.stepper.interpolate_component(theta, i),
            Err(true) => self.y1[i],
            Err(false) => self.y0[i],
        }
    }

    /// The step with a copy of its method's coefficients (for a stored interpolant).
    pub(crate) fn to_owned_step(&self) -> OwnedStep<S::Dense, D> {
        OwnedStep {
            t: (self.t0, self.t1),
            y0: self.y0.clone(),
            y1: self.y1.clone(),
            coefficients: self.stepper.dense_output().clone(),
        }
    }
}

impl<S: Stepper<D>, D: Dim> Interpolant<D> for DenseStep<'_, S, D> {
    fn dim(&self) -> D {
        D::of(self.y0)
    }

    fn at(&self, t: f64, out: &mut Vector<D>) {
        DenseStep::at(self, t, out)
    }

    fn component_at(&self, t: f64, i: usize) -> f64 {
        DenseStep::component_at(self, t, i)
    }

    fn stored(&self) -> StoredInterpolant<D> {
        StoredInterpolant::new(DenseStep::to_owned_step(self))
    }
}

/// The end of a plain integration.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution<D: Dim> {
    /// Final time (the requested end time).
    pub t: f64,
    /// Final state.
    pub y: Vector<D>,
    /// Work done.
    pub stats: Stats,
}

impl<const N: usize> Copy for Solution<Const<N>> {}

/// Integrates `model` from `(t0, y0)` to `t_end` without events; a `t_end` before `t0`
/// integrates backward in time (exactly as [`crate::HybridSolver::run`] does: the forward
/// run in `τ = −t`, its failure dated in `t`).
pub fn integrate<M: Rhs<D>, S: Stepper<D>, D: Dim>(
    model: &M,
    stepper: S,
    tol: Tolerance<D>,
    opts: StepOptions,
    t0: f64,
    y0: &Vector<D>,
    t_end: f64,
) -> Result<Solution<D>, SolveError> {
    if !(t0.is_finite() && t_end.is_finite()) {
        return Err(InputError::TimeSpan { t0, t_end }.into());
    }
    if t_end < t0 {
        let reversed = ReversedRhs(model);
        let end =
            forward(&reversed, stepper, tol, opts, -t0, y0, -t_end).map_err(solve_error_in_t)?;
        return Ok(Solution { t: -end.t, ..end });
    }
    forward(model, stepper, tol, opts, t0, y0, t_end)
}

/// [`integrate`] for `t_end >= t0`.
fn forward<M: Rhs<D>, S: Stepper<D>, D: Dim>(
    model: &M,
    stepper: S,
    tol: Tolerance<D>,
    opts: StepOptions,
    t0: f64,
    y0: &Vector<D>,
    t_end: f64,
) -> Result<Solution<D>, SolveError> {
    let mut it = Integrator::new(stepper, tol, opts)?;
    it.restart(model, t0, y0)?;
    while it.t() < t_end {
        it.step(model, t_end)?;
    }
    Ok(Solution {
        t: it.t(),
        y: it.y().clone(),
        stats: *it.stats(),
    })
}
