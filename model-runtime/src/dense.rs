//! A step's interpolant ([`Interpolant`], what the drivers lend an observer), and one that
//! outlives the step: what an observer keeps when it wants to sample
//! a stretch of the run only after the run has decided where that stretch is (the last second
//! before a stop nobody could foresee).
//!
//! While a run goes, an observer is lent the step's interpolant ([`Interpolant`]), a
//! view into the stepper's buffers that the next step overwrites. [`Interpolant::stored`]
//! copies what the view reads — the method's dense-output coefficients ([`DenseOutput`], the
//! same code the stepper evaluates, so a stored step gives the same bits) and the step's ends
//! — into a [`StoredInterpolant`]. Only an observer that asks pays for the copy; the drivers
//! never make one.

use std::fmt::Debug;
use std::sync::Arc;

use crate::dim::{Array, Dim, Vector};

/// Evaluation of the interpolant of one accepted step.
pub trait Interpolant<D: Dim> {
    /// The size of the states it interpolates.
    fn dim(&self) -> D;

    /// The interpolated state at `t` inside the step (clamped to it; end points exact).
    fn at(&self, t: f64, out: &mut Vector<D>);

    /// Component `i` of [`Interpolant::at`] alone (the same value; a root search on one
    /// component need not interpolate the others).
    fn component_at(&self, t: f64, i: usize) -> f64 {
        let mut out = self.dim().zeros();
        self.at(t, &mut out);
        out[i]
    }

    /// The state at `t` as the run samples its grid there: [`Interpolant::at`], except in
    /// regularised time, where a sample finds the clock's root from the step's ends (and
    /// [`Interpolant::at`] by a faster iteration that agrees to a few ulps of the clock). A
    /// sample taken later from a stored step ([`Interpolant::stored`]) is then the sample the
    /// run took, bit for bit.
    fn sample_at(&self, t: f64, out: &mut Vector<D>) {
        self.at(t, out)
    }

    /// The point a fraction `u ∈ [0, 1]` of the way from `t0` to `t1` (times in the step,
    /// `t0 < t1`) measured in the variable the run integrates in (the time itself, or
    /// regularised time's `τ`): its state in `out`, its time returned. The time rises with
    /// `u`. Where the run's variable is not the time, this is how a scan of a step reads it
    /// cheaply: [`Interpolant::at`] first finds where the clock reads `t`, this reads the clock
    /// where it is (at the step's reported ends `t0` and `t1` the run's variable is known).
    fn at_fraction(&self, (t0, t1): (f64, f64), u: f64, out: &mut Vector<D>) -> f64 {
        let t = t0 + u * (t1 - t0);
        self.at(t, out);
        t
    }

    /// An owned copy that outlives the step and evaluates to the same bits
    /// ([`StoredInterpolant`]): it copies the method's coefficients, so ask only for the steps
    /// kept.
    fn stored(&self) -> StoredInterpolant<D>;
}

impl<D: Dim, I: Interpolant<D> + ?Sized> Interpolant<D> for &I {
    fn dim(&self) -> D {
        (**self).dim()
    }

    fn at(&self, t: f64, out: &mut Vector<D>) {
        (**self).at(t, out)
    }

    fn component_at(&self, t: f64, i: usize) -> f64 {
        (**self).component_at(t, i)
    }

    fn sample_at(&self, t: f64, out: &mut Vector<D>) {
        (**self).sample_at(t, out)
    }

    fn at_fraction(&self, span: (f64, f64), u: f64, out: &mut Vector<D>) -> f64 {
        (**self).at_fraction(span, u, out)
    }

    fn stored(&self) -> StoredInterpolant<D> {
        (**self).stored()
    }
}

/// The coefficients of one step's interpolant in `θ ∈ [0, 1]`, apart from the method's stages:
/// what [`crate::Stepper::interpolate`] evaluates. Each method keeps its dense output in one of
/// these and evaluates it through it, so a copy evaluates to the same bits.
pub trait DenseOutput<D: Dim>: Clone + Debug + Send + Sync + 'static {
    /// The size of the states it interpolates.
    fn dim(&self) -> D;
    /// The interpolated state at `θ`.
    fn value(&self, theta: f64, out: &mut Vector<D>);
    /// Component `i` of [`DenseOutput::value`] (the same bits).
    fn component(&self, theta: f64, i: usize) -> f64 {
        let mut out = self.dim().zeros();
        self.value(theta, &mut out);
        out[i]
    }
}

/// Where `t` falls in a step `[t0, t1]`: `Err(true)` at or past its end, `Err(false)` at or
/// before its start, else `Ok(θ)`. The one rule of the live and the stored interpolants.
#[inline(always)]
pub(crate) fn place_in_step(t: f64, t0: f64, t1: f64) -> Result<f64, bool> {
    if t <= t0 {
        Err(false)
    } else if t >= t1 {
        Err(true)
    } else {
        Ok((t - t0) / (t1 - t0))
    }
}

/// One step's interpolant, owned: its ends and its method's coefficients.
#[derive(Clone, Debug)]
pub(crate) struct OwnedStep<C, D: Dim> {
    /// Start and end time of the step (the whole step, also when an event cut its report).
    pub(crate) t: (f64, f64),
    pub(crate) y0: Vector<D>,
    pub(crate) y1: Vector<D>,
    pub(crate) coefficients: C,
}

impl<C: DenseOutput<D>, D: Dim> Interpolant<D> for OwnedStep<C, D> {
    fn dim(&self) -> D {
        D::of(&self.y0)
    }

    fn at(&self, t: f64, out: &mut Vector<D>) {
        match place_in_step(t, self.t.0, self.t.1) {
            Ok(theta) => self.coefficients.value(theta, out),
            Err(true) => out.assign(&self.y1),
            Err(false) => out.assign(&self.y0),
        }
    }

    fn component_at(&self, t: f64, i: usize) -> f64 {
        match place_in_step(t, self.t.0, self.t.1) {
            Ok(theta) => self.coefficients.component(theta, i),
            Err(true) => self.y1[i],
            Err(false) => self.y0[i],
        }
    }

    fn stored(&self) -> StoredInterpolant<D> {
        StoredInterpolant::new(self.clone())
    }
}

/// A step's interpolant kept after the step ([`Interpolant::stored`]): cheap to clone (shared),
/// safe to send to another thread, evaluated exactly as the live one was.
#[derive(Clone)]
pub struct StoredInterpolant<D: Dim>(Arc<dyn Interpolant<D> + Send + Sync>);

impl<D: Dim> StoredInterpolant<D> {
    /// Keeps `interpolant` (which owns everything it reads).
    pub fn new(interpolant: impl Interpolant<D> + Send + Sync + 'static) -> Self {
        StoredInterpolant(Arc::new(interpolant))
    }
}

impl<D: Dim> Debug for StoredInterpolant<D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StoredInterpolant")
            .field("dim", &self.0.dim())
            .finish_non_exhaustive()
    }
}

impl<D: Dim> Interpolant<D> for StoredInterpolant<D> {
    fn dim(&self) -> D {
        self.0.dim()
    }

    fn at(&self, t: f64, out: &mut Vector<D>) {
        self.0.at(t, out)
    }

    fn component_at(&self, t: f64, i: usize) -> f64 {
        self.0.component_at(t, i)
    }

    fn sample_at(&self, t: f64, out: &mut Vector<D>) {
        self.0.sample_at(t, out)
    }

    fn at_fraction(&self, span: (f64, f64), u: f64, out: &mut Vector<D>) -> f64 {
        self.0.at_fraction(span, u, out)
    }

    fn stored(&self) -> StoredInterpolant<D> {
        self.clone()
    }
}
