//! A compiled model run by the interpreter as a runtime [`System`].
//!
//! A file's model has its size only when the file is read, so it is a system of the runtime's
//! run-time size [`Dyn`]: its states are vectors of exactly its own `n` components, integrated
//! by the same integrators, error norm and drivers as a model compiled by `model!` (which run
//! on fixed-size arrays). There is no padding and no limit on the number of states, and the
//! tolerance is the request's own.
//!
//! The runtime's [`ModelInfo`] and [`EvalError`] name things with `'static` strings (a
//! compiled model's are constants), so an interpreted model's names are leaked once per model
//! solved.

use crate::error::{PointError, SolveFailure};
use model_algebra::{CompiledModel, EvalFailure, Inputs, Ops};
use model_runtime::{Dyn, EvalError, ModelInfo, OpCounts, Rhs, System, SystemOutputs, Tolerance};

/// The request's tolerance for the `n` states of a model.
pub(crate) fn tolerance(n: usize, rtol: f64, atol: f64) -> Tolerance<Dyn> {
    Tolerance::scalar_in(Dyn(n), rtol, atol)
}

/// `t`, the states and the outputs of `model` at `(t, y)`, as a trajectory row.
pub(crate) fn row(
    model: &CompiledModel,
    params: &[f64],
    t: f64,
    y: &[f64],
) -> Result<Vec<f64>, SolveFailure> {
    let at_t = |failure: EvalFailure| SolveFailure::Eval {
        t,
        failure: PointError::Interpreter {
            model: model.name.clone(),
            failure,
        },
    };
    let der = model.derivatives(t, y, params).map_err(at_t)?;
    let outputs = model.outputs_at(t, y, &der, params).map_err(at_t)?;
    let mut row = vec![t];
    row.extend_from_slice(y);
    row.extend(outputs);
    Ok(row)
}

/// A compiled model run by the interpreter, in its own number of states.
pub(crate) struct Interpreted<'a> {
    model: &'a CompiledModel,
    params: &'a [f64],
    /// The runtime's names for the model: leaked once per model solved, as a compiled
    /// model's are `static`.
    info: &'static ModelInfo,
    /// `der(x)` for each state, for `NonFinite` errors.
    der_names: &'static [&'static str],
    /// The pivots and numeric blocks, for `SingularPivot` errors.
    pivots: &'static [&'static str],
}

fn leak(text: String) -> &'static str {
    Box::leak(text.into_boxed_str())
}

fn leak_all(texts: impl Iterator<Item = String>) -> &'static [&'static str] {
    Box::leak(texts.map(leak).collect::<Vec<_>>().into_boxed_slice())
}

fn op_counts(ops: Ops) -> OpCounts {
    OpCounts {
        add: ops.add,
        mul: ops.mul,
        div: ops.div,
        sqrt: ops.sqrt,
        trig: ops.trig,
        transcendental: ops.transcendental,
    }
}

impl<'a> Interpreted<'a> {
    pub(crate) fn new(model: &'a CompiledModel, params: &'a [f64]) -> Self {
        let pivots = leak_all(model.pivots.iter().chain(&model.numeric_blocks).cloned());
        let info = Box::leak(Box::new(ModelInfo {
            name: leak(model.name.clone()),
            state_names: leak_all(model.states.iter().cloned()),
            param_names: leak_all(model.params.iter().map(|(name, _)| name.clone())),
            output_names: &[],
            rhs_ops: op_counts(model.rhs.ops()),
            jacobian_ops: op_counts(model.jacobian.ops()),
            outputs_ops: op_counts(model.outputs_program.ops()),
            pivots,
            numeric_blocks: &[],
        }));
        Interpreted {
            model,
            params,
            info,
            der_names: leak_all(model.states.iter().map(|s| format!("der({s})"))),
            pivots,
        }
    }

    /// The same model reading other parameter values (a switched model's discrete values,
    /// which follow its parameters, change at events).
    pub(crate) fn reading<'b>(&self, params: &'b [f64]) -> Interpreted<'b>
    where
        'a: 'b,
    {
        Interpreted {
            model: self.model,
            params,
            info: self.info,
            der_names: self.der_names,
            pivots: self.pivots,
        }
    }

    /// An interpreter failure as the runtime's error, naming the pivot.
    pub(crate) fn error(&self, failure: EvalFailure) -> EvalError {
        match failure {
            EvalFailure::SingularPivot { text, value } => EvalError::SingularPivot {
                model: self.info.name,
                pivot: (self.pivots.iter().find(|p| **p == text).copied())
                    .unwrap_or_else(|| leak(text)),
                value,
            },
            EvalFailure::BadOperand(operand) => EvalError::NonFinite {
                model: self.info.name,
                quantity: leak(format!("{operand:?} (a compiler bug)")),
                value: f64::NAN,
            },
        }
    }
}

impl Rhs<Dyn> for Interpreted<'_> {
    fn rhs(&self, t: f64, y: &Vec<f64>, dy: &mut Vec<f64>) -> Result<(), EvalError> {
        let der = (self.model.derivatives(t, y, self.params)).map_err(|e| self.error(e))?;
        if let Some(k) = der.iter().position(|v| !v.is_finite()) {
            return Err(EvalError::NonFinite {
                model: self.info.name,
                quantity: self.der_names[k],
                value: der[k],
            });
        }
        dy.copy_from_slice(&der);
        Ok(())
    }

    fn jacobian(&self, t: f64, y: &Vec<f64>, jac: &mut Vec<Vec<f64>>) -> Result<(), EvalError> {
        let inputs = Inputs {
            t,
            states: y,
            params: self.params,
            ders: &[],
        };
        let stores = (self.model.jacobian.eval(&inputs)).map_err(|e| self.error(e))?;
        for (row, values) in jac.iter_mut().zip(stores.jacobian(y.len())) {
            row.copy_from_slice(&values);
        }
        Ok(())
    }
}

impl System<Dyn> for Interpreted<'_> {
    fn info(&self) -> &ModelInfo {
        self.info
    }

    fn dim(&self) -> Dyn {
        Dyn(self.model.states.len())
    }
}

/// The outputs are evaluated by the interpreter at the recorded points ([`row`]), not by the
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
