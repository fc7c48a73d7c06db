//! A compiled model run by the interpreter as a runtime [`Model`].
//!
//! The runtime's models have a state dimension fixed at compile time; a file's model has its
//! own. Rather than instantiating the integrators once per dimension, the interpreted model is
//! embedded in [`MAX_STATES`] components: the components past the model's states have zero
//! derivatives and stay zero. The error norm is a root mean square over all components, so
//! each component's tolerances are scaled by `sqrt(n / MAX_STATES)` ([`tolerance`]), which
//! makes the norm, and with it every step-size decision, exactly that of the model's `n`
//! states alone. The runtime's [`ModelInfo`] is `'static` (a compiled model's is a constant),
//! so an interpreted model's names are leaked once per model solved.

use crate::error::{PointError, RequestError, SolveFailure};
use model_algebra::{CompiledModel, EvalFailure, Inputs, Ops};
use model_runtime::{EvalError, Model, ModelInfo, OpCounts, Tolerance, WithOutputs};

/// The most states an interpreted model may have.
pub const MAX_STATES: usize = 32;

/// A state of [`MAX_STATES`] components.
pub(crate) type Padded = [f64; MAX_STATES];

/// Refuses a model of more than [`MAX_STATES`] states.
pub(crate) fn check_size(model: &str, states: usize) -> Result<(), RequestError> {
    if states > MAX_STATES {
        return Err(RequestError::TooManyStates {
            model: model.to_string(),
            states,
            max: MAX_STATES,
        });
    }
    Ok(())
}

/// `y` in [`MAX_STATES`] components, zero past its own.
pub(crate) fn pad(y: &[f64]) -> Padded {
    let mut padded = [0.0; MAX_STATES];
    padded[..y.len()].copy_from_slice(y);
    padded
}

/// The tolerance of `n` states embedded in [`MAX_STATES`]: the same error norm.
pub(crate) fn tolerance(n: usize, rtol: f64, atol: f64) -> Tolerance<MAX_STATES> {
    let scale = (n as f64 / MAX_STATES as f64).sqrt();
    Tolerance::per_component([rtol * scale; MAX_STATES], [atol * scale; MAX_STATES])
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

/// A compiled model run by the interpreter, in [`MAX_STATES`] components.
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
        let n = model.states.len();
        let padding = (n..MAX_STATES).map(|k| format!("(unused {k})"));
        let pivots = leak_all(model.pivots.iter().chain(&model.numeric_blocks).cloned());
        let info = Box::leak(Box::new(ModelInfo {
            name: leak(model.name.clone()),
            state_names: leak_all(model.states.iter().cloned().chain(padding)),
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

impl Model<MAX_STATES> for Interpreted<'_> {
    fn info(&self) -> &'static ModelInfo {
        self.info
    }

    fn rhs(&self, t: f64, y: &Padded, dy: &mut Padded) -> Result<(), EvalError> {
        let n = self.model.states.len();
        let der = (self.model.derivatives(t, &y[..n], self.params)).map_err(|e| self.error(e))?;
        if let Some(k) = der.iter().position(|v| !v.is_finite()) {
            return Err(EvalError::NonFinite {
                model: self.info.name,
                quantity: self.der_names[k],
                value: der[k],
            });
        }
        dy[..n].copy_from_slice(&der);
        dy[n..].fill(0.0);
        Ok(())
    }

    fn jacobian(
        &self,
        t: f64,
        y: &Padded,
        jac: &mut [Padded; MAX_STATES],
    ) -> Result<(), EvalError> {
        let n = self.model.states.len();
        let inputs = Inputs {
            t,
            states: &y[..n],
            params: self.params,
            ders: &[],
        };
        let stores = (self.model.jacobian.eval(&inputs)).map_err(|e| self.error(e))?;
        *jac = [[0.0; MAX_STATES]; MAX_STATES];
        for (row, values) in jac.iter_mut().zip(stores.jacobian(n)) {
            row[..n].copy_from_slice(&values);
        }
        Ok(())
    }
}

/// The outputs are evaluated by the interpreter at the recorded points ([`row`]), not by the
/// runtime.
impl WithOutputs<MAX_STATES, 0> for Interpreted<'_> {
    fn outputs(
        &self,
        _t: f64,
        _y: &Padded,
        _dy: &Padded,
        _out: &mut [f64; 0],
    ) -> Result<(), EvalError> {
        Ok(())
    }
}
