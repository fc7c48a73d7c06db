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
use crate::name::{Name, Names};
use crate::stepper::Rhs;
pub use model_ops::OpCounts;

/// What a model says about itself: names, sizes and the cost of its emitted code.
#[derive(Clone, Debug)]
pub struct ModelInfo {
    /// The model's name (the module name in the DSL).
    pub name: Name,
    /// State names, in index order.
    pub state_names: Names,
    /// Parameter names, in index order.
    pub param_names: Names,
    /// Output names, in index order.
    pub output_names: Names,
    /// Operation counts of `rhs`.
    pub rhs_ops: OpCounts,
    /// Operation counts of `jacobian` (zero for hand-written models without one).
    pub jacobian_ops: OpCounts,
    /// Operation counts of `outputs`.
    pub outputs_ops: OpCounts,
    /// Pivots checked at run time, as they read in the user's terms (e.g. `sin(theta)`).
    pub pivots: Names,
    /// Blocks the compiler solved numerically instead of symbolically (each named by its
    /// derivatives, e.g. `der(V_X), der(V_Y)`), because the symbolic solution would swell.
    pub numeric_blocks: Names,
}

impl ModelInfo {
    /// The info of a hand-written model: its names, no operation counts (it was not
    /// compiled), no checked pivots and no numeric blocks.
    ///
    /// ```
    /// use model_runtime::ModelInfo;
    /// static INFO: ModelInfo = ModelInfo::of("ball", &["h", "v"], &["g"], &["energy"]);
    /// assert_eq!(INFO.state_names.position("v"), Some(1));
    /// ```
    pub const fn of(
        name: &'static str,
        state_names: &'static [&'static str],
        param_names: &'static [&'static str],
        output_names: &'static [&'static str],
    ) -> ModelInfo {
        ModelInfo {
            name: Name::Borrowed(name),
            state_names: Names::Static(state_names),
            param_names: Names::Static(param_names),
            output_names: Names::Static(output_names),
            rhs_ops: OpCounts::NONE,
            jacobian_ops: OpCounts::NONE,
            outputs_ops: OpCounts::NONE,
            pivots: Names::EMPTY,
            numeric_blocks: Names::EMPTY,
        }
    }
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
                    model,
                    quantity,
                    value,
                } if model == FD_MODEL => EvalError::NonFinite {
                    model: Model::info(self).name.clone(),
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
