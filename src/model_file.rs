//! `eulerdisk model show|eval|solve FILE.dsl`: a model of one's own, without compiling Rust.
//!
//! The file holds what goes inside `model! { .. }`. It is read by the same front end and
//! compiled by the same equation compiler as the macro, so `show` prints what `model!` would
//! emit as `SOLVED_MARKDOWN`/`SOLVED_LATEX`, and `eval`/`solve` run the compiled programs in
//! the compiler's interpreter (the reference the emitted Rust is tested against). Editing an
//! equation and rerunning takes well under a second. A mistake in the file is reported as
//! `file:line:col: message` with the line and a caret under the token, never a panic.

use crate::model_show::Format;
use model_algebra::{CompiledModel, EvalFailure};
use model_dsl::{
    switching_latex, switching_markdown, CompiledSwitched, LocatedErrors, Source, TextModel,
};
use serde::ser::{Serialize, SerializeMap, Serializer};
use std::path::{Path, PathBuf};

/// Why a model file could not be shown, evaluated or solved.
#[derive(Debug, thiserror::Error)]
pub enum ModelFileError {
    /// The file could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The model has errors (each located in the file).
    #[error("{0}")]
    Dsl(LocatedErrors),
    /// `--chart` names no chart of the model.
    #[error("`{name}` is not a chart of the model; the file defines {available}")]
    NoSuchChart {
        /// The name asked for.
        name: String,
        /// The models the file defines, quoted.
        available: String,
    },
    /// A `NAME=VALUE` argument is malformed or names nothing.
    #[error("{flag} `{text}`: {problem}")]
    Assignment {
        /// The flag (`--state`, `--set`).
        flag: &'static str,
        /// The argument as given.
        text: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A parameter without a default in the file was not set.
    #[error("parameter `{0}` has no default in the file: give it with `--set {0}=VALUE`")]
    MissingParam(String),
    /// The model cannot be evaluated or integrated (a singular pivot, a non-finite value, a
    /// failed integration), said in the model's terms.
    #[error("{0}")]
    Eval(String),
    /// A setting of `model solve` is unusable (an empty or non-finite time span, a sampling
    /// step, a tolerance, a model with too many states): an input error, found before any
    /// integration.
    #[error("{0}")]
    Setting(String),
}

/// A model file, compiled: the model, then each of its charts.
pub fn load(path: &Path) -> Result<Vec<TextModel>, ModelFileError> {
    match load_any(path)? {
        Loaded::Smooth(models) => Ok(models),
        Loaded::Switched(model) => Err(ModelFileError::Eval(format!(
            "`{}` is a switched model (it has modes or events): use `model show` or `model solve`",
            model.name
        ))),
    }
}

/// A model file as compiled: a smooth model (with its charts) or a switched one.
pub enum Loaded {
    /// The model, then each of its charts.
    Smooth(Vec<TextModel>),
    /// A model with modes and events.
    Switched(CompiledSwitched),
}

/// Reads and compiles a model file of either kind.
pub fn load_any(path: &Path) -> Result<Loaded, ModelFileError> {
    let source = Source::read(path).map_err(|source| ModelFileError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    load_source(&source)
}

/// Compiles a model given as text (its name is the one shown in messages), of either kind.
pub fn load_source(source: &Source) -> Result<Loaded, ModelFileError> {
    let ast = source.parse().map_err(ModelFileError::Dsl)?;
    if ast.is_switched() {
        let model = source.compile_switched().map_err(ModelFileError::Dsl)?;
        return Ok(Loaded::Switched(model));
    }
    source
        .compile()
        .map(Loaded::Smooth)
        .map_err(ModelFileError::Dsl)
}

/// The modes and events of a switched model, then each mode's solved equations.
pub fn show_switched(model: &CompiledSwitched, format: Format) -> String {
    let mut text = match format {
        Format::Markdown => switching_markdown(model),
        Format::Latex => switching_latex(model),
    };
    for mode in &model.modes {
        text.push('\n');
        text.push_str(match format {
            Format::Markdown => &mode.model.explanation.markdown,
            Format::Latex => &mode.model.explanation.latex,
        });
    }
    text
}

/// The model called `chart` among `models` (`None`: the model itself, the first).
pub fn select<'a>(
    models: &'a [TextModel],
    chart: Option<&str>,
) -> Result<&'a CompiledModel, ModelFileError> {
    let found = match chart {
        None => models.first(),
        Some(name) => models.iter().find(|m| m.compiled.name == name),
    };
    found.map(|m| &m.compiled).ok_or_else(|| {
        let names: Vec<String> = models
            .iter()
            .map(|m| format!("`{}`", m.compiled.name))
            .collect();
        ModelFileError::NoSuchChart {
            name: chart.unwrap_or_default().to_string(),
            available: names.join(", "),
        }
    })
}

/// The solved equations of every model of the file (the model, then its charts).
pub fn show(path: &Path, format: Format) -> Result<String, ModelFileError> {
    let models = match load_any(path)? {
        Loaded::Smooth(models) => models,
        Loaded::Switched(model) => return Ok(show_switched(&model, format)),
    };
    let texts: Vec<String> = (models.iter().map(|m| &m.compiled.explanation))
        .map(|explanation| match format {
            Format::Markdown => explanation.markdown.clone(),
            Format::Latex => explanation.latex.clone(),
        })
        .collect();
    Ok(texts.join("\n"))
}

/// Values by name: the model's `names` in order, each from `NAME=VALUE` arguments or its
/// default (`None`: required).
pub fn assign(
    flag: &'static str,
    names: &[String],
    defaults: impl Fn(usize) -> Option<f64>,
    arguments: &[String],
) -> Result<Vec<f64>, ModelFileError> {
    let mut values: Vec<Option<f64>> = (0..names.len()).map(&defaults).collect();
    let mut given = vec![false; names.len()];
    for text in arguments {
        let problem = |problem: String| ModelFileError::Assignment {
            flag,
            text: text.clone(),
            problem,
        };
        let (name, value) = text
            .split_once('=')
            .ok_or_else(|| problem("expected NAME=VALUE".into()))?;
        let (name, value) = (name.trim(), value.trim());
        let Some(k) = names.iter().position(|n| n == name) else {
            let quoted: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
            return Err(problem(format!(
                "the model has no `{name}`; the names are {}",
                quoted.join(", ")
            )));
        };
        if std::mem::replace(&mut given[k], true) {
            return Err(problem(format!("`{name}` is given twice")));
        }
        match value.parse::<f64>() {
            Ok(v) if v.is_finite() => values[k] = Some(v),
            _ => return Err(problem(format!("`{value}` is not a finite number"))),
        }
    }
    (values.into_iter().zip(names))
        .map(|(value, name)| value.ok_or_else(|| ModelFileError::MissingParam(name.clone())))
        .collect()
}

/// The parameter values of `model`: the file's defaults, overridden by `--set NAME=VALUE`.
pub fn params(model: &CompiledModel, set: &[String]) -> Result<Vec<f64>, ModelFileError> {
    let names: Vec<String> = model.params.iter().map(|(n, _)| n.clone()).collect();
    assign("--set", &names, |k| model.params[k].1, set)
}

/// The state of `model` from `--state NAME=VALUE` (unnamed states are zero).
pub fn state(model: &CompiledModel, state: &[String]) -> Result<Vec<f64>, ModelFileError> {
    assign("--state", &model.states, |_| Some(0.0), state)
}

/// The initial state of a switched model from `--state NAME=VALUE`: states not given start
/// at the value the file writes on them, or zero.
pub fn initial_state(
    model: &CompiledSwitched,
    state: &[String],
) -> Result<Vec<f64>, ModelFileError> {
    let initial = |k: usize| Some(model.initial[k].unwrap_or(0.0));
    assign("--state", model.states(), initial, state)
}

/// Numbers under names, in the model's order (serialised as a JSON object in that order).
#[derive(Clone, Debug, PartialEq)]
pub struct NamedValues(pub Vec<(String, f64)>);

impl Serialize for NamedValues {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (name, value) in &self.0 {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

/// What `model eval` prints.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FileEvaluation {
    /// The model's (or chart's) name.
    pub model: String,
    /// The time.
    pub t: f64,
    /// `der(state)` by state name.
    pub derivatives: NamedValues,
    /// The outputs by name.
    pub outputs: NamedValues,
}

/// The derivatives and outputs of `model` at `(t, y)`; a singular pivot or a non-finite value
/// is an error naming it.
pub fn evaluate(
    model: &CompiledModel,
    t: f64,
    y: &[f64],
    params: &[f64],
) -> Result<FileEvaluation, ModelFileError> {
    let failure = |e: EvalFailure| ModelFileError::Eval(describe(model, &e));
    let der = model.derivatives(t, y, params).map_err(failure)?;
    let outputs = model.outputs_at(t, y, &der, params).map_err(failure)?;
    let derivatives = (model.states.iter().map(|s| format!("der({s})"))).zip(der);
    let derivatives = NamedValues(derivatives.collect());
    let outputs = NamedValues(model.outputs.iter().cloned().zip(outputs).collect());
    let all = derivatives.0.iter().chain(&outputs.0);
    if let Some((name, value)) = all.into_iter().find(|(_, v)| !v.is_finite()) {
        return Err(ModelFileError::Eval(format!(
            "`{}`: {name} = {value} is not finite at this state",
            model.name
        )));
    }
    Ok(FileEvaluation {
        model: model.name.clone(),
        t,
        derivatives,
        outputs,
    })
}

/// An interpreter failure in the model's terms.
pub fn describe(model: &CompiledModel, failure: &EvalFailure) -> String {
    match failure {
        EvalFailure::SingularPivot { text, value } => format!(
            "`{}`: the pivot `{text}` is {value} at this state: the equations cannot be solved for the derivatives here",
            model.name
        ),
        EvalFailure::BadOperand(operand) => format!(
            "`{}`: the compiled program reads {operand:?}, which does not exist (a compiler bug)",
            model.name
        ),
    }
}
