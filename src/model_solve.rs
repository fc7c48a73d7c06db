//! `eulerdisk model solve FILE.dsl`: a model read from a file, integrated by the runtime's
//! `Problem` API with its programs run by the compiler's interpreter, into a CSV.
//!
//! The runtime's models have a state dimension fixed at compile time; a file's model has its
//! own. Rather than instantiating the integrators once per dimension, the interpreted model is
//! embedded in [`MAX_STATES`] components: the components past the model's states have zero
//! derivatives and stay zero. The error norm is a root mean square over all components, so
//! each component's tolerances are scaled by `sqrt(n / MAX_STATES)`, which makes the norm, and
//! with it every step-size decision, exactly that of the model's `n` states alone.

use crate::model_file::{describe, ModelFileError};
use model_algebra::{CompiledModel, EvalFailure, Inputs, Ops};
use model_runtime::{
    EvalError, Method, Model, ModelInfo, OpCounts, Output, Problem, Stats, Termination, Tolerance,
    WithOutputs,
};
use std::io::Write;

/// The most states a model file may have for `model solve`.
pub const MAX_STATES: usize = 32;

/// How to integrate.
#[derive(Clone, Debug, PartialEq)]
pub struct SolveSettings {
    /// Start time.
    pub t0: f64,
    /// End time.
    pub t_end: f64,
    /// The integration method.
    pub method: Method,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// Record every `dt` from `t0` (and at `t_end`); `None`: at every accepted step.
    pub dt: Option<f64>,
}

/// A trajectory of a file's model: a table of `t`, the states and the outputs.
#[derive(Clone, Debug)]
pub struct FileTrajectory {
    /// Column names: `t`, the states, the outputs.
    pub header: Vec<String>,
    /// One row per recorded time.
    pub rows: Vec<Vec<f64>>,
    /// Why the run ended.
    pub stop: Termination,
    /// The work done.
    pub stats: Stats,
}

impl FileTrajectory {
    /// Writes the table as CSV, numbers in Rust's shortest round-trip form.
    pub fn write_csv(&self, mut out: impl Write) -> std::io::Result<()> {
        writeln!(out, "{}", self.header.join(","))?;
        for row in &self.rows {
            let cells: Vec<String> = row.iter().map(f64::to_string).collect();
            writeln!(out, "{}", cells.join(","))?;
        }
        Ok(())
    }
}

/// Integrates `model` from `y0` with `params`; the outputs are evaluated at every recorded
/// point. Errors name the state, the pivot or the time, as the runtime does for compiled
/// models.
pub fn solve(
    model: &CompiledModel,
    params: &[f64],
    y0: &[f64],
    settings: &SolveSettings,
) -> Result<FileTrajectory, ModelFileError> {
    let n = model.states.len();
    if n > MAX_STATES {
        return Err(ModelFileError::Eval(format!(
            "`{}` has {n} states; `model solve` integrates at most {MAX_STATES} (compile the model with `model!` instead)",
            model.name
        )));
    }
    let interpreted = Interpreted::new(model, params);
    let mut start = [0.0; MAX_STATES];
    start[..n].copy_from_slice(y0);
    let scale = (n as f64 / MAX_STATES as f64).sqrt();
    let tolerance = Tolerance::per_component(
        [settings.rtol * scale; MAX_STATES],
        [settings.atol * scale; MAX_STATES],
    );
    let output = match settings.dt {
        Some(dt) => Output::Times(sample_times(settings.t0, settings.t_end, dt)?),
        None => Output::Steps,
    };
    let solved = Problem::new(&interpreted, start, (settings.t0, settings.t_end))
        .method(settings.method)
        .tolerance(tolerance)
        .output(output)
        .solve::<0>()
        .map_err(|failure| ModelFileError::Eval(failure.to_string()))?;
    let mut header = vec!["t".to_string()];
    header.extend(model.states.iter().cloned());
    header.extend(model.outputs.iter().cloned());
    let mut rows = Vec::with_capacity(solved.t.len());
    for (&t, y) in solved.t.iter().zip(&solved.y) {
        let y = &y[..n];
        let at_t =
            |e: EvalFailure| ModelFileError::Eval(format!("at t = {t}: {}", describe(model, &e)));
        let der = model.derivatives(t, y, params).map_err(at_t)?;
        let outputs = model.outputs_at(t, y, &der, params).map_err(at_t)?;
        let mut row = vec![t];
        row.extend_from_slice(y);
        row.extend(outputs);
        rows.push(row);
    }
    Ok(FileTrajectory {
        header,
        rows,
        stop: solved.stop,
        stats: solved.stats,
    })
}

/// `t0, t0 + dt, ...` up to and including `t_end`.
fn sample_times(t0: f64, t_end: f64, dt: f64) -> Result<Vec<f64>, ModelFileError> {
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(ModelFileError::Eval(format!(
            "--dt {dt}: the sampling step must be positive and finite"
        )));
    }
    let count = ((t_end - t0) / dt).floor();
    if !(0.0..1e8).contains(&count) {
        return Err(ModelFileError::Eval(format!(
            "--dt {dt} from {t0} to {t_end}: gives no samples or too many (at most 1e8)"
        )));
    }
    let mut times: Vec<f64> = (0..=count as u64).map(|k| t0 + k as f64 * dt).collect();
    if times.last().is_some_and(|&t| t < t_end) {
        times.push(t_end);
    }
    Ok(times)
}

/// A compiled model run by the interpreter, in [`MAX_STATES`] components.
struct Interpreted<'a> {
    model: &'a CompiledModel,
    params: &'a [f64],
    /// The runtime's names for the model: leaked once per command, as a compiled model's are
    /// `static`.
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
    fn new(model: &'a CompiledModel, params: &'a [f64]) -> Self {
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

    fn error(&self, failure: EvalFailure) -> EvalError {
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

    fn rhs(
        &self,
        t: f64,
        y: &[f64; MAX_STATES],
        dy: &mut [f64; MAX_STATES],
    ) -> Result<(), EvalError> {
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
        y: &[f64; MAX_STATES],
        jac: &mut [[f64; MAX_STATES]; MAX_STATES],
    ) -> Result<(), EvalError> {
        let n = self.model.states.len();
        let inputs = Inputs {
            t,
            states: &y[..n],
            params: self.params,
            ders: &[],
        };
        let stores = self
            .model
            .jacobian
            .eval(&inputs)
            .map_err(|e| self.error(e))?;
        *jac = [[0.0; MAX_STATES]; MAX_STATES];
        for (row, values) in jac.iter_mut().zip(stores.jacobian(n)) {
            row[..n].copy_from_slice(&values);
        }
        Ok(())
    }
}

impl WithOutputs<MAX_STATES, 0> for Interpreted<'_> {
    fn outputs(
        &self,
        _t: f64,
        _y: &[f64; MAX_STATES],
        _dy: &[f64; MAX_STATES],
        _out: &mut [f64; 0],
    ) -> Result<(), EvalError> {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use equations::models::rolling;
    use equations::DiskParams;
    use equations::InitialState;
    use model_dsl::Source;

    /// The rolling disk from its own source file, interpreted and embedded, against the same
    /// model compiled by `model!`: the same steps (the scaled tolerances make the error norm
    /// the model's own) and the same trajectory.
    #[test]
    fn the_embedded_interpreted_model_steps_like_the_compiled_one() {
        let file = include_str!("../equations/src/models/box1_rolling.rs");
        let models = Source::rust("box1_rolling.rs", file).compile().unwrap();
        let interpreted = &models[0].compiled;
        let p = DiskParams::paper();
        let y0 = InitialState::paper(&p).state.y;
        let params = p.to_array();
        for method in [Method::Dopri5, Method::Dop853, Method::Rodas4] {
            let settings = SolveSettings {
                t0: 0.0,
                t_end: 0.3,
                method,
                rtol: 1e-9,
                atol: 1e-11,
                dt: None,
            };
            let file = solve(interpreted, &params, &y0, &settings).unwrap();
            let model = rolling::Model::new(params);
            let compiled = Problem::new(&model, y0, (0.0, 0.3))
                .method(method)
                .tolerances(1e-9, 1e-11)
                .solve::<{ rolling::N_OUTPUTS }>()
                .unwrap();
            assert_eq!(file.stats.steps, compiled.stats.steps, "{method:?}");
            assert_eq!(file.stats.rejected, compiled.stats.rejected, "{method:?}");
            let last = file.rows.last().unwrap();
            let want = compiled.last().unwrap();
            for (k, (got, want)) in last[1..=12].iter().zip(want).enumerate() {
                assert!(
                    (got - want).abs() <= 1e-9 * want.abs().max(1.0),
                    "{method:?} {}: {got} vs {want}",
                    rolling::STATE_NAMES[k]
                );
            }
            assert_eq!(file.header.len(), 1 + 12 + rolling::N_OUTPUTS);
        }
    }
}
