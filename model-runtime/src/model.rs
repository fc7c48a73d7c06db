//! The contract between the equation compiler and the runtime.
//!
//! The compiler (`model-macros`) emits one type per model that implements [`Model`] and
//! [`WithOutputs`]; hand-written models (test problems, the disk's reference) implement the
//! same traits, so every integrator, event locator and driver runs on either without change.
//! States live in fixed-size arrays so that a step allocates nothing. A model whose size is
//! known only at run time implements the general [`System`] of [`crate::Dyn`] instead; every
//! [`Model`] is a [`System`] of [`Const`], so the drivers are written once, over [`System`].

use crate::dim::{Const, Dim, Vector};
use crate::error::EvalError;
use crate::jacobian::{finite_difference_jacobian, FD_MODEL};
use crate::stepper::Rhs;

/// Operation counts of one emitted function, after common-subexpression elimination.
///
/// Counted on the straight-line code the compiler emits: every `+`/`-` is an add, every `*` a
/// mul, every `/` a div; `sqrt`, the trigonometric functions (`sin cos tan atan2`) and the
/// transcendental ones (`exp ln`, real powers) are counted apart because they cost far more.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCounts {
    /// Additions and subtractions (including negations).
    pub add: u32,
    /// Multiplications (integer powers count as the multiplications they expand to).
    pub mul: u32,
    /// Divisions.
    pub div: u32,
    /// Square roots.
    pub sqrt: u32,
    /// Trigonometric calls (`sin`, `cos`, `tan`, `atan2`); a shared `sin_cos` counts once.
    pub trig: u32,
    /// Other transcendental calls (`exp`, `ln`, `powf`, `abs` is not counted here).
    pub transcendental: u32,
}

impl OpCounts {
    /// All operations, weighted equally.
    pub fn total(&self) -> u32 {
        self.add + self.mul + self.div + self.sqrt + self.trig + self.transcendental
    }
}

/// What a model says about itself: names, sizes and the cost of its emitted code.
#[derive(Clone, Copy, Debug)]
pub struct ModelInfo {
    /// The model's name (the module name in the DSL).
    pub name: &'static str,
    /// State names, in index order.
    pub state_names: &'static [&'static str],
    /// Parameter names, in index order.
    pub param_names: &'static [&'static str],
    /// Output names, in index order.
    pub output_names: &'static [&'static str],
    /// Operation counts of `rhs`.
    pub rhs_ops: OpCounts,
    /// Operation counts of `jacobian` (zero for hand-written models without one).
    pub jacobian_ops: OpCounts,
    /// Operation counts of `outputs`.
    pub outputs_ops: OpCounts,
    /// Pivots checked at run time, as they read in the user's terms (e.g. `sin(theta)`).
    pub pivots: &'static [&'static str],
    /// Blocks the compiler solved numerically instead of symbolically (each named by its
    /// derivatives, e.g. `der(V_X), der(V_Y)`), because the symbolic solution would swell.
    pub numeric_blocks: &'static [&'static str],
}

/// An explicit first-order system `dy/dt = f(t, y)` of any [`Dim`]: what every integrator
/// and driver runs.
///
/// A model of a size fixed at compile time implements the more convenient [`Model`] (arrays
/// of `N`) and is a `System<Const<N>>` through the blanket implementation; a model whose size
/// is known only at run time (the DSL interpreter's) implements `System<Dyn>` itself. The
/// right-hand side and the Jacobian are its [`Rhs`] (the steppers need no more).
pub trait System<D: Dim>: Rhs<D> {
    /// Names, sizes and costs.
    fn info(&self) -> &ModelInfo;

    /// The number of states.
    fn dim(&self) -> D;
}

impl<M: Model<N>, const N: usize> System<Const<N>> for M {
    #[inline]
    fn info(&self) -> &ModelInfo {
        Model::info(self)
    }

    #[inline(always)]
    fn dim(&self) -> Const<N> {
        Const
    }
}

impl<M: Model<N>, const N: usize> Rhs<Const<N>> for M {
    #[inline(always)]
    fn rhs(&self, t: f64, y: &[f64; N], dy: &mut [f64; N]) -> Result<(), EvalError> {
        Model::rhs(self, t, y, dy)
    }
    #[inline(always)]
    fn jacobian(&self, t: f64, y: &[f64; N], jac: &mut [[f64; N]; N]) -> Result<(), EvalError> {
        Model::jacobian(self, t, y, jac)
    }
}

/// An explicit first-order system `dy/dt = f(t, y)` with a number `N` of states fixed at
/// compile time: what `model-macros` emits and hand-written models implement. Every such model
/// is a [`System`] of [`Const<N>`].
///
/// The parameters are part of the value implementing the trait.
pub trait Model<const N: usize> {
    /// Names, sizes and costs.
    fn info(&self) -> &'static ModelInfo;

    /// Evaluates the right-hand side: `dy = f(t, y)`.
    fn rhs(&self, t: f64, y: &[f64; N], dy: &mut [f64; N]) -> Result<(), EvalError>;

    /// The Jacobian `jac[i][j] = ∂f_i/∂y_j`. The default uses central finite differences;
    /// emitted models override it with the symbolic derivative of the solved system.
    fn jacobian(&self, t: f64, y: &[f64; N], jac: &mut [[f64; N]; N]) -> Result<(), EvalError> {
        finite_difference_jacobian::<Const<N>>(|y, dy| Model::rhs(self, t, y, dy), y, jac).map_err(
            |e| match e {
                // A non-finite entry is the model's, named as such.
                EvalError::NonFinite {
                    model: FD_MODEL,
                    quantity,
                    value,
                } => EvalError::NonFinite {
                    model: Model::info(self).name,
                    quantity,
                    value,
                },
                e => e,
            },
        )
    }
}

/// A model with `M` secondary outputs (contact forces, energy, constraint residuals, ...),
/// computed after the solve from the state and its derivative.
pub trait WithOutputs<const N: usize, const M: usize>: Model<N> {
    /// Evaluates the outputs at `(t, y)` given `dy = f(t, y)`.
    fn outputs(
        &self,
        t: f64,
        y: &[f64; N],
        dy: &[f64; N],
        out: &mut [f64; M],
    ) -> Result<(), EvalError>;

    /// The derivatives and the outputs at `(t, y)` in one call.
    fn evaluate(&self, t: f64, y: &[f64; N]) -> Result<Evaluation<N, M>, EvalError> {
        let mut der = [0.0; N];
        Model::rhs(self, t, y, &mut der)?;
        let mut outputs = [0.0; M];
        WithOutputs::outputs(self, t, y, &der, &mut outputs)?;
        Ok(Evaluation { der, outputs })
    }
}

/// A [`System`] with `M` secondary outputs, of any [`Dim`]: what [`crate::Problem`] records.
/// Every [`WithOutputs`] is one.
pub trait SystemOutputs<D: Dim, const M: usize>: System<D> {
    /// Evaluates the outputs at `(t, y)` given `dy = f(t, y)`.
    fn outputs(
        &self,
        t: f64,
        y: &Vector<D>,
        dy: &Vector<D>,
        out: &mut [f64; M],
    ) -> Result<(), EvalError>;
}

impl<W: WithOutputs<N, M>, const N: usize, const M: usize> SystemOutputs<Const<N>, M> for W {
    #[inline]
    fn outputs(
        &self,
        t: f64,
        y: &[f64; N],
        dy: &[f64; N],
        out: &mut [f64; M],
    ) -> Result<(), EvalError> {
        WithOutputs::outputs(self, t, y, dy, out)
    }
}

/// The derivatives and the outputs of a model at one point ([`WithOutputs::evaluate`]); an
/// emitted model names them with its `State::from(ev.der)` and `Outputs::from(ev.outputs)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Evaluation<const N: usize, const M: usize> {
    /// `dy/dt`, indexed like the state.
    pub der: [f64; N],
    /// The outputs, in index order.
    pub outputs: [f64; M],
}
