//! A compiled model run by the interpreter as a runtime [`System`].
//!
//! A file's model has its size only when the file is read, so it is a system of the runtime's
//! run-time size [`Dyn`]: its states are vectors of exactly its own `n` components, integrated
//! by the same integrators, error norm and drivers as a model compiled by `model!` (which run
//! on fixed-size arrays). There is no padding and no limit on the number of states, and the
//! tolerance is the request's own.
//!
//! The runtime's [`ModelInfo`] and [`EvalError`] carry [`Name`]s, which a compiled model
//! borrows from its constants and an interpreted one owns: its names live as long as the
//! model being solved ([`Labels`]), so a long-lived process solving many models keeps none.

use crate::engine::Engine;
use crate::error::{PointError, SolveFailure};
use model_algebra::{CompiledModel, EvalFailure};
use model_runtime::{
    Dyn, EvalError, ModelInfo, Name, Names, Rhs, System, SystemOutputs, Tolerance,
};

/// The request's tolerance for the `n` states of a model.
pub(crate) fn tolerance(n: usize, rtol: f64, atol: f64) -> Tolerance<Dyn> {
    Tolerance::scalar_in(Dyn(n), rtol, atol)
}

/// `model`'s failure at `t` as a failed solve.
pub(crate) fn failure_at(model: &CompiledModel, t: f64, failure: EvalFailure) -> SolveFailure {
    SolveFailure::Eval {
        t,
        failure: PointError::Interpreter {
            model: model.name.clone(),
            failure,
        },
    }
}

/// What the runtime calls an interpreted model and its parts: its [`ModelInfo`] and the
/// `der(x)` name of each state, owned (the model was read at run time), made once per model
/// solved and dropped with it.
pub(crate) struct Labels {
    info: ModelInfo,
    /// `der(x)` for each state, for `NonFinite` errors.
    der_names: Vec<Name>,
}

impl Labels {
    pub(crate) fn of(model: &CompiledModel) -> Self {
        Labels {
            info: ModelInfo {
                name: Name::Owned(model.name.clone()),
                state_names: model.states.iter().cloned().collect(),
                param_names: model.params.iter().map(|(name, _)| name.clone()).collect(),
                output_names: Names::EMPTY,
                rhs_ops: model.rhs.ops(),
                jacobian_ops: model.jacobian.ops(),
                outputs_ops: model.outputs_program.ops(),
                pivots: (model.pivots.iter().chain(&model.numeric_blocks))
                    .cloned()
                    .collect(),
                numeric_blocks: Names::EMPTY,
            },
            der_names: (model.states.iter())
                .map(|s| Name::Owned(format!("der({s})")))
                .collect(),
        }
    }
}

/// A compiled model run by the interpreter, in its own number of states.
pub(crate) struct Interpreted<'a> {
    model: &'a CompiledModel,
    params: &'a [f64],
    labels: &'a Labels,
    engine: &'a Engine,
}

impl<'a> Interpreted<'a> {
    /// `model` reading `params`, named by `labels` (made by [`Labels::of`] from `model`) and
    /// evaluated by `engine` (made from `model`).
    pub(crate) fn new(
        model: &'a CompiledModel,
        params: &'a [f64],
        labels: &'a Labels,
        engine: &'a Engine,
    ) -> Self {
        Interpreted {
            model,
            params,
            labels,
            engine,
        }
    }

    /// The engine that evaluates it.
    pub(crate) fn engine(&self) -> &'a Engine {
        self.engine
    }

    /// An interpreter failure as the runtime's error, naming the pivot.
    pub(crate) fn error(&self, failure: EvalFailure) -> EvalError {
        let model = self.labels.info.name.clone();
        match failure {
            EvalFailure::SingularPivot { text, value } => EvalError::SingularPivot {
                model,
                pivot: Name::Owned(text),
                value,
            },
            EvalFailure::BadOperand(operand) => EvalError::NonFinite {
                model,
                quantity: Name::Owned(format!("{operand:?} (a compiler bug)")),
                value: f64::NAN,
            },
        }
    }
}

impl Rhs<Dyn> for Interpreted<'_> {
    fn rhs(&self, t: f64, y: &Vec<f64>, dy: &mut Vec<f64>) -> Result<(), EvalError> {
        (self.engine.rhs(t, y, self.params, dy)).map_err(|e| self.error(e))?;
        if let Some(k) = dy.iter().position(|v| !v.is_finite()) {
            return Err(EvalError::NonFinite {
                model: self.labels.info.name.clone(),
                quantity: self.labels.der_names[k].clone(),
                value: dy[k],
            });
        }
        Ok(())
    }

    fn jacobian(&self, t: f64, y: &Vec<f64>, jac: &mut Vec<Vec<f64>>) -> Result<(), EvalError> {
        (self.engine.jacobian(t, y, self.params, jac)).map_err(|e| self.error(e))
    }
}

impl System<Dyn> for Interpreted<'_> {
    fn info(&self) -> &ModelInfo {
        &self.labels.info
    }

    fn dim(&self) -> Dyn {
        Dyn(self.model.states.len())
    }
}

/// The outputs are evaluated by the interpreter at the recorded points (`Tables::row`), not by the
/// runtime.
impl SystemOutputs<Dyn, 0> for Interpreted<'_> {
    fn outputs(
        &self,
        _t: f64,
        _y: &Vec<f64>,
        _dy: &Vec<f64>,
        _out: &mut [f64; 0],
    ) -> Result<(), EvalError> {
        Ok(())
    }
}
