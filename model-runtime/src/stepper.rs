//! The one interface every method implements, so the drivers (plain integration, events, the
//! hybrid driver) are written once.
//!
//! A stepper only knows how to *attempt* one step and how to interpolate inside the last
//! accepted one; step-size control, end times, events and observers live in the driver. All
//! buffers are fixed-size arrays inside the stepper, so stepping allocates nothing.

use crate::error::SolveError;
use crate::model::{EvalError, Model};
use crate::stats::Stats;
use crate::tolerance::{ErrorEstimate, Tolerance};

/// A first-order system `dy/dt = f(t, y)` as the steppers see it.
///
/// Every [`Model`] is one; the hybrid driver presents "the system in its current mode" as one.
pub trait Rhs<const N: usize> {
    /// `dy = f(t, y)`.
    fn rhs(&self, t: f64, y: &[f64; N], dy: &mut [f64; N]) -> Result<(), EvalError>;
    /// `jac[i][j] = ∂f_i/∂y_j`.
    fn jacobian(&self, t: f64, y: &[f64; N], jac: &mut [[f64; N]; N]) -> Result<(), EvalError>;
}

impl<M: Model<N>, const N: usize> Rhs<N> for M {
    #[inline]
    fn rhs(&self, t: f64, y: &[f64; N], dy: &mut [f64; N]) -> Result<(), EvalError> {
        Model::rhs(self, t, y, dy)
    }
    #[inline]
    fn jacobian(&self, t: f64, y: &[f64; N], jac: &mut [[f64; N]; N]) -> Result<(), EvalError> {
        Model::jacobian(self, t, y, jac)
    }
}

/// Evaluates `f`, counting the call and attaching `t` to a failure.
#[inline]
pub(crate) fn eval<F: Rhs<N>, const N: usize>(
    sys: &F,
    t: f64,
    y: &[f64; N],
    dy: &mut [f64; N],
    stats: &mut Stats,
) -> Result<(), SolveError> {
    stats.rhs_evals += 1;
    sys.rhs(t, y, dy).map_err(crate::error::at(t))
}

/// The start of a step: `(t0, y0)` with `f0 = f(t0, y0)` already known (first same as last).
#[derive(Clone, Copy, Debug)]
pub struct StepStart<'a, const N: usize> {
    /// Time at the start.
    pub t: f64,
    /// State at the start.
    pub y: &'a [f64; N],
    /// Derivative at the start.
    pub f: &'a [f64; N],
}

/// Where an attempted step writes its result.
#[derive(Debug)]
pub struct StepEnd<'a, const N: usize> {
    /// The new state `y(t0 + h)`.
    pub y: &'a mut [f64; N],
    /// `f(t0 + h, y)`, which becomes the next step's `f0`.
    pub f: &'a mut [f64; N],
}

/// A one-step method with an interpolant over its last accepted step.
pub trait Stepper<const N: usize> {
    /// The method's name, for reports.
    const NAME: &'static str;
    /// Order of the error estimate (the lower order of the embedded pair); the controller uses
    /// the exponent `1 / (ERROR_ORDER + 1)`.
    const ERROR_ORDER: u32;
    /// Order of the interpolant inside a step.
    const DENSE_ORDER: u32;

    /// The step size of a method without error control; `None` for adaptive methods.
    fn fixed_step(&self) -> Option<f64> {
        None
    }

    /// Attempts a step of size `h` from `start`, writes the candidate end point into `end` and
    /// returns the scaled local error estimate ([`ErrorEstimate::NONE`] for fixed-step methods).
    ///
    /// The stepper keeps its stages, so that after the driver accepts the step it may call
    /// [`Stepper::prepare_dense`] and [`Stepper::interpolate`].
    fn attempt<F: Rhs<N>>(
        &mut self,
        sys: &F,
        start: StepStart<'_, N>,
        h: f64,
        tol: &Tolerance<N>,
        end: StepEnd<'_, N>,
        stats: &mut Stats,
    ) -> Result<ErrorEstimate, SolveError>;

    /// Builds the interpolant of the last accepted step (some methods need extra evaluations).
    /// `start` and `end` are that step's end points (`end.f` is `f` at its end).
    fn prepare_dense<F: Rhs<N>>(
        &mut self,
        sys: &F,
        start: StepStart<'_, N>,
        end_y: &[f64; N],
        end_f: &[f64; N],
        h: f64,
        stats: &mut Stats,
    ) -> Result<(), SolveError>;

    /// The interpolated state at `t0 + theta * h` of the last prepared step, `theta ∈ [0, 1]`.
    fn interpolate(&self, theta: f64, out: &mut [f64; N]);

    /// The time derivative of the interpolant at `t0 + theta * h` (not a model evaluation).
    ///
    /// The default differentiates [`Stepper::interpolate`] by a central difference in `theta`
    /// with spacing `2⁻¹⁰`: exact for the quadratic part of the polynomial, within
    /// `δ²/6 · |P'''|` (≈ 1.6e-7 relative) for the rest. That is ample for its one use,
    /// estimating guard values between the points where they are evaluated exactly.
    fn interpolate_derivative(&self, theta: f64, h: f64, out: &mut [f64; N]) {
        const DELTA: f64 = 1.0 / 1024.0;
        let mut below = [0.0; N];
        self.interpolate(theta - DELTA, &mut below);
        self.interpolate(theta + DELTA, out);
        let scale = 1.0 / (2.0 * DELTA * h);
        for (o, b) in out.iter_mut().zip(&below) {
            *o = (*o - b) * scale;
        }
    }
}
