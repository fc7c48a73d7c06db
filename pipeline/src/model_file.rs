//! `eulerdisk model show|eval|solve FILE.dsl`: a model of one's own, without compiling Rust.
//!
//! The file holds what goes inside `model! { .. }`. The library `model-interpreted` reads it
//! with the same front end and compiles it with the same equation compiler as the macro, and
//! runs its programs in the compiler's interpreter (the reference the emitted Rust is tested
//! against); this module is the command line's side of it: the `NAME=VALUE` and
//! `NAME[:up|:down][:stop]` arguments, the library's typed errors said with the flag and the
//! argument they came from, and `show`'s text. A mistake in the file is reported as
//! `file:line:col: message` with the line and a caret under the token, never a panic.

use crate::model_show::Format;
use model_dsl::{switching_latex, switching_markdown, CompiledSwitched};
use model_interpreted::{
    EventRequest, LoadError, ModelCache, ModelFile, Named, PointError, RequestError, SolveFailure,
    ValueError,
};
use model_runtime::Direction;
use std::path::Path;

/// Why a model file could not be shown, evaluated or solved.
#[derive(Debug, thiserror::Error)]
pub enum ModelFileError {
    /// The file cannot be read or compiled, or names no such chart.
    #[error(transparent)]
    Load(#[from] LoadError),
    /// An argument is malformed or names nothing.
    #[error("{flag} `{text}`: {problem}")]
    Assignment {
        /// The flag (`--state`, `--set`, `--event`).
        flag: &'static str,
        /// The argument as given.
        text: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A parameter without a default in the file was not set.
    #[error("parameter `{0}` has no default in the file: give it with `--set {0}=VALUE`")]
    MissingParam(String),
    /// The model cannot be evaluated at the point given.
    #[error(transparent)]
    Point(#[from] PointError),
    /// A setting of `model solve` is unusable (an empty or non-finite time span, a sampling
    /// step or a tolerance): an input error, found before any
    /// integration.
    #[error(transparent)]
    Setting(RequestError),
    /// The run failed (or the model's modes do not form a graph).
    #[error(transparent)]
    Failed(SolveFailure),
}

impl ModelFileError {
    /// Whether the error is the user's input (exit 2) rather than a failed run (exit 1).
    pub fn is_input(&self) -> bool {
        !matches!(self, ModelFileError::Failed(_))
    }
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

/// The file at `path` compiled, through the user's cache of compiled models unless
/// `no_cache` (or there is no cache directory: then compiled).
pub fn read(path: &Path, no_cache: bool) -> Result<ModelFile, ModelFileError> {
    let cache = (!no_cache).then(ModelCache::user).flatten();
    Ok(ModelFile::read_with(path, cache.as_ref())?)
}

/// The solved equations of every model of the file (the model, then its charts).
pub fn show(path: &Path, format: Format, no_cache: bool) -> Result<String, ModelFileError> {
    let models = match read(path, no_cache)? {
        ModelFile::Smooth(models) => models,
        ModelFile::Switched(model) => {
            // What the model says that is legal but likely not meant, beside its text.
            for warning in &model.warnings {
                eprintln!("{warning}");
            }
            return Ok(show_switched(&model, format));
        }
    };
    let texts: Vec<String> = (models.iter().map(|m| &m.compiled.explanation))
        .map(|explanation| match format {
            Format::Markdown => explanation.markdown.clone(),
            Format::Latex => explanation.latex.clone(),
        })
        .collect();
    Ok(texts.join("\n"))
}

/// The `NAME=VALUE` arguments of `flag`, read; the names are checked against the model by the
/// library ([`value_error`] says its errors with the argument).
pub fn named(flag: &'static str, arguments: &[String]) -> Result<Vec<Named>, ModelFileError> {
    (arguments.iter())
        .map(|text| {
            let problem = |problem: String| ModelFileError::Assignment {
                flag,
                text: text.clone(),
                problem,
            };
            let (name, value) = text
                .split_once('=')
                .ok_or_else(|| problem("expected NAME=VALUE".into()))?;
            let (name, value) = (name.trim(), value.trim());
            match value.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok((name.to_string(), v)),
                _ => Err(problem(format!("`{value}` is not a finite number"))),
            }
        })
        .collect()
}

/// The library's complaint about a value, with the flag and the argument it came from.
pub fn value_error(flag: &'static str, arguments: &[String], error: ValueError) -> ModelFileError {
    match error {
        ValueError::Missing { name } => ModelFileError::MissingParam(name),
        error => ModelFileError::Assignment {
            flag,
            text: (error.index().and_then(|k| arguments.get(k)).cloned()).unwrap_or_default(),
            problem: error.to_string(),
        },
    }
}

/// The form of `--event`, said in every error about it.
const EVENT_FORM: &str = "expected NAME[:up|:down][:stop]";

/// Reads `NAME[:up|:down][:stop]`; an empty name, an unknown word or a word given twice is an
/// [`ModelFileError::Assignment`] naming the flag, the spec and the problem (whether the name
/// is a state or an output of the model, the library checks).
pub fn event_spec(text: &str) -> Result<EventRequest, ModelFileError> {
    let problem = |problem: String| ModelFileError::Assignment {
        flag: "--event",
        text: text.to_string(),
        problem,
    };
    let mut words = text.split(':').map(str::trim);
    let name = words.next().unwrap_or_default();
    if name.is_empty() {
        return Err(problem(format!("the name is empty; {EVENT_FORM}")));
    }
    let (mut direction, mut stop) = (None, false);
    for word in words {
        let twice = match word {
            "up" => direction.replace(Direction::Up).is_some(),
            "down" => direction.replace(Direction::Down).is_some(),
            "stop" => std::mem::replace(&mut stop, true),
            _ => {
                return Err(problem(format!(
                    "`{word}` is neither a direction (`up`, `down`) nor `stop`; {EVENT_FORM}"
                )))
            }
        };
        if twice {
            return Err(problem(format!(
                "`{word}` comes after another direction or twice; {EVENT_FORM}"
            )));
        }
    }
    Ok(EventRequest {
        name: name.to_string(),
        direction: direction.unwrap_or(Direction::Both),
        stop,
    })
}

/// The arguments a request was built from, to say the library's errors with them.
pub struct Arguments<'a> {
    /// `--set`.
    pub set: &'a [String],
    /// `--state`.
    pub state: &'a [String],
    /// `--event`.
    pub event: &'a [String],
}

impl Arguments<'_> {
    /// A failed solve, with the flag and argument an input error came from.
    pub fn solve_error(&self, failure: SolveFailure) -> ModelFileError {
        match failure {
            SolveFailure::Request(RequestError::Params(error)) => {
                value_error("--set", self.set, error)
            }
            SolveFailure::Request(RequestError::State(error)) => {
                value_error("--state", self.state, error)
            }
            SolveFailure::Request(RequestError::UnknownEvent(unknown)) => {
                ModelFileError::Assignment {
                    flag: "--event",
                    text: self.event.get(unknown.index).cloned().unwrap_or_default(),
                    problem: unknown.to_string(),
                }
            }
            SolveFailure::Request(error) => ModelFileError::Setting(error),
            failure => ModelFileError::Failed(failure),
        }
    }
}
