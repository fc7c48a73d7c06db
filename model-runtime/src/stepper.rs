//! The one interface every method implements, so the drivers (plain integration, events, the
//! hybrid driver) are written once.
//!
//! A stepper only knows how to *attempt* one step and how to interpolate inside the last
//! accepted one; step-size control, end times, events and observers live in the driver. All
//! buffers are fixed-size arrays inside the stepper, so stepping allocates nothing.

use crate::dense::DenseOutput;
use crate::dim::{Const, Dim, Matrix, Vector};
use crate::error::{EvalError, SolveError};
use crate::stats::Stats;
use crate::tolerance::{ErrorEstimate, Tolerance};

/// A first-order system `dy/dt = f(t, y)` as the steppers see it.
///
/// Every [`crate::System`] is one (so every [`crate::Model`]); the hybrid driver presents "the
/// system in its current mode" as one.
pub trait Rhs<D: Dim> {
    /// `dy = f(t, y)`.
    fn rhs(&self, t: f64, y: &Vector<D>, dy: &mut Vector<D>) -> Result<(), EvalError>;
    /// `jac[i][j] = ∂f_i/∂y_j`.
    fn jacobian(&self, t: f64, y: &Vector<D>, jac: &mut Matrix<D>) -> Result<(), EvalError>;
}

/// Evaluates `f`, counting the call and attaching `t` to a failure.
#[inline]
pub(crate) fn eval<F: Rhs<D>, D: Dim>(
    sys: &F,
    t: f64,
    y: &Vector<D>,
    dy: &mut Vector<D>,
    stats: &mut Stats,
) -> Result<(), SolveError> {
    stats.rhs_evals += 1;
    sys.rhs(t, y, dy).map_err(crate::error::at(t))
}

/// The start of a step: `(t0, y0)` with `f0 = f(t0, y0)` already known (first same as last).
#[derive(Clone, Copy, Debug)]
pub struct StepStart<'a, D: Dim> {
    /// Time at the start.
    pub t: f64,
    /// State at the start.
    pub y: &'a Vector<D>,
    /// Derivative at the start.
    pub f: &'a Vector<D>,
}

/// Where an attempted step writes its result.
#[derive(Debug)]
pub struct StepEnd<'a, D: Dim> {
    /// The new state `y(t0 + h)`.
    pub y: &'a mut Vector<D>,
    /// `f(t0 + h, y)`, which becomes the next step's `f0`.
    pub f: &'a mut Vector<D>,
}

/// A set of components of a state: which ones a partial interpolation fills.
///
/// Kept both as a mask and as the list of its indices: the list lets a partial interpolation
/// visit only the chosen components (a handful of twelve, for the disk's guards), and both are
/// built together, so every index is valid for the size by construction. For a size known at
/// compile time the sets are `const` ([`Components::of`]) and live in arrays.
#[derive(Clone, Debug, PartialEq)]
pub struct Components<D: Dim> {
    mask: D::Array<bool>,
    /// The indices in the set, increasing, in `list[..len]`; the rest is zero.
    list: D::Array<usize>,
    len: usize,
}

impl<const N: usize> Components<Const<N>> {
    /// Every component.
    pub const ALL: Self = Self::from_mask([true; N]);
    /// No component.
    pub const NONE: Self = Self::from_mask([false; N]);

    /// The set with this mask.
    const fn from_mask(mask: [bool; N]) -> Self {
        let mut list = [0; N];
        let mut len = 0;
        let mut i = 0;
        while i < N {
            if mask[i] {
                list[len] = i;
                len += 1;
            }
            i += 1;
        }
        Components { mask, list, len }
    }

    /// The components at `indices` (repetitions are harmless). A `const fn`, so that a
    /// constant set is checked when it compiles.
    ///
    /// # Panics
    ///
    /// If an index is `N` or more (at compile time for a constant).
    pub const fn of(indices: &[usize]) -> Self {
        let mut mask = [false; N];
        let mut k = 0;
        while k < indices.len() {
            assert!(indices[k] < N, "component index out of range");
            mask[indices[k]] = true;
            k += 1;
        }
        Self::from_mask(mask)
    }

    /// The components in either set.
    pub const fn union(self, other: Self) -> Self {
        let mut mask = self.mask;
        let mut i = 0;
        while i < N {
            mask[i] |= other.mask[i];
            i += 1;
        }
        Self::from_mask(mask)
    }
}

impl<D: Dim> Components<D> {
    /// The set with this mask, of any size.
    fn masked(dim: D, mask: D::Array<bool>) -> Self {
        let mut list = dim.filled(0);
        let mut len = 0;
        for i in 0..dim.size() {
            if mask[i] {
                list[len] = i;
                len += 1;
            }
        }
        Components { mask, list, len }
    }

    /// Every component of a state of size `dim`.
    pub fn all(dim: D) -> Self {
        Self::masked(dim, dim.filled(true))
    }

    /// No component of a state of size `dim`.
    pub fn none(dim: D) -> Self {
        Self::masked(dim, dim.filled(false))
    }

    /// The components at `indices` of a state of size `dim` (repetitions are harmless), or
    /// `None` if an index is `dim` or more.
    pub fn at(dim: D, indices: &[usize]) -> Option<Self> {
        let mut mask = dim.filled(false);
        for &i in indices {
            *mask.as_mut().get_mut(i)? = true;
        }
        Some(Self::masked(dim, mask))
    }

    /// The components in either set (of the same size).
    pub fn either(&self, other: &Self) -> Self {
        let dim = D::of(&self.mask);
        Self::masked(dim, dim.tabulate(|i| self.mask[i] || other.mask[i]))
    }

    /// Whether component `i` is in the set (false for `i` past the size).
    #[inline]
    pub fn contains(&self, i: usize) -> bool {
        self.mask.as_ref().get(i).copied().unwrap_or(false)
    }

    /// Whether the set holds every component.
    pub fn is_all(&self) -> bool {
        self.len == self.mask.as_ref().len()
    }

    /// The indices in the set, increasing.
    #[inline]
    pub fn indices(&self) -> &[usize] {
        &self.list.as_ref()[..self.len]
    }

    /// Copies the components in the set from `from` to `to`, leaving the others of `to`.
    #[inline]
    pub fn copy(&self, from: &Vector<D>, to: &mut Vector<D>) {
        self.fill(to, |i| from[i]);
    }

    /// Sets each component `i` in the set of `out` to `value(i)`, leaving the others: how an
    /// interpolant evaluated component by component fills a full or a partial state.
    #[inline]
    pub fn fill(&self, out: &mut Vector<D>, mut value: impl FnMut(usize) -> f64) {
        for &i in self.indices() {
            out[i] = value(i);
        }
    }
}

impl<const N: usize> Copy for Components<Const<N>> {}

impl<const N: usize> Default for Components<Const<N>> {
    /// Every component: the safe choice for a caller that does not know what it needs.
    fn default() -> Self {
        Self::ALL
    }
}

/// Sets every component `i` of `out` to `value(i)`: a full interpolation.
#[inline(always)]
pub(crate) fn fill_all<D: Dim>(out: &mut Vector<D>, mut value: impl FnMut(usize) -> f64) {
    for (i, o) in out.as_mut().iter_mut().enumerate() {
        *o = value(i);
    }
}

/// The spacing in `theta` of [`Stepper::interpolate_derivative`]'s default central difference.
const DIFFERENCE_STEP: f64 = 1.0 / 1024.0;

/// The central difference in `theta` of `interpolate` over a step `h`, in the components
/// `out`: the default derivative of an interpolant.
pub(crate) fn central_difference<D: Dim>(
    interpolate: impl Fn(f64, &mut Vector<D>),
    theta: f64,
    h: f64,
    out: &mut Vector<D>,
) {
    let mut below = D::of(out).zeros();
    interpolate(theta - DIFFERENCE_STEP, &mut below);
    interpolate(theta + DIFFERENCE_STEP, out);
    let scale = 1.0 / (2.0 * DIFFERENCE_STEP * h);
    for (o, b) in out.as_mut().iter_mut().zip(below.as_ref()) {
        *o = (*o - b) * scale;
    }
}

/// A one-step method with an interpolant over its last accepted step.
pub trait Stepper<D: Dim> {
    /// The method's name, for reports.
    const NAME: &'static str;
    /// Order of the error estimate (the lower order of the embedded pair); the controller uses
    /// the exponent `1 / (ERROR_ORDER + 1)`.
    const ERROR_ORDER: u32;
    /// Order of the interpolant inside a step.
    const DENSE_ORDER: u32;
    /// The coefficients of its interpolant over one step (what [`Stepper::interpolate`]
    /// evaluates), which a caller may copy and keep ([`crate::StoredInterpolant`]).
    type Dense: DenseOutput<D>;

    /// The interpolant of the last prepared step ([`Stepper::prepare_dense`]).
    fn dense_output(&self) -> &Self::Dense;

    /// The size of the states it steps.
    fn dim(&self) -> D;

    /// The step size of a method without error control; `None` for adaptive methods.
    fn fixed_step(&self) -> Option<f64> {
        None
    }

    /// Attempts a step of size `h` from `start`, writes the candidate end point into `end` and
    /// returns the scaled local error estimate ([`ErrorEstimate::NONE`] for fixed-step methods).
    ///
    /// The stepper keeps its stages, so that after the driver accepts the step it may call
    /// [`Stepper::prepare_dense`] and [`Stepper::interpolate`].
    fn attempt<F: Rhs<D>>(
        &mut self,
        sys: &F,
        start: StepStart<'_, D>,
        h: f64,
        tol: &Tolerance<D>,
        end: StepEnd<'_, D>,
        stats: &mut Stats,
    ) -> Result<ErrorEstimate, SolveError>;

    /// Builds the interpolant of the last accepted step (some methods need extra evaluations).
    /// `start` and `end` are that step's end points (`end.f` is `f` at its end).
    fn prepare_dense<F: Rhs<D>>(
        &mut self,
        sys: &F,
        start: StepStart<'_, D>,
        end_y: &Vector<D>,
        end_f: &Vector<D>,
        h: f64,
        stats: &mut Stats,
    ) -> Result<(), SolveError>;

    /// The interpolated state at `t0 + theta * h` of the last prepared step, `theta ∈ [0, 1]`.
    fn interpolate(&self, theta: f64, out: &mut Vector<D>);

    /// The time derivative of the interpolant at `t0 + theta * h` (not a model evaluation).
    ///
    /// The default differentiates [`Stepper::interpolate`] by a central difference in `theta`
    /// with spacing `2⁻¹⁰`: exact for the quadratic part of the polynomial, within
    /// `δ²/6 · |P'''|` (≈ 1.6e-7 relative) for the rest. That is ample for its one use,
    /// estimating guard values between the points where they are evaluated exactly.
    fn interpolate_derivative(&self, theta: f64, h: f64, out: &mut Vector<D>) {
        central_difference::<D>(|s, o| self.interpolate(s, o), theta, h, out);
    }

    /// [`Stepper::interpolate`] in the components `which` of `out` only; the others are left
    /// as they are, so a caller that filled them with NaN sees NaN there.
    ///
    /// The default interpolates every component into a scratch vector and copies the chosen
    /// ones: correct for any method, and no faster. Methods whose interpolant is evaluated
    /// component by component override it to skip the rest (bit for bit the same values).
    fn interpolate_components(&self, theta: f64, which: &Components<D>, out: &mut Vector<D>) {
        let mut full = D::of(out).zeros();
        self.interpolate(theta, &mut full);
        which.copy(&full, out);
    }

    /// Component `i` of [`Stepper::interpolate`] (the same bits). The default interpolates
    /// every component; methods evaluated component by component override it.
    fn interpolate_component(&self, theta: f64, i: usize) -> f64 {
        let mut full = self.dim().zeros();
        self.interpolate(theta, &mut full);
        full[i]
    }

    /// [`Stepper::interpolate_derivative`] in the components `which` of `out` only; the others
    /// are left as they are. The default, like [`Stepper::interpolate_components`], computes
    /// every component and copies the chosen ones.
    fn interpolate_derivative_components(
        &self,
        theta: f64,
        h: f64,
        which: &Components<D>,
        out: &mut Vector<D>,
    ) {
        let mut full = D::of(out).zeros();
        self.interpolate_derivative(theta, h, &mut full);
        which.copy(&full, out);
    }
}
