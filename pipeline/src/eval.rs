//! `eulerdisk eval` and `eulerdisk model eval rolling|sliding|sliding-cartesian`: one
//! evaluation of a disk model at a state, printed as JSON.
//!
//! This is the shortest path from a state to the equations, for checking a model by hand or
//! from another program: derivatives (`der(theta)`, as `model eval` of a DSL file names
//! them) and outputs are keyed by the paper's names and printed so they parse back to the same bits. Which implementation answers (generated or the
//! hand-written reference) is decided in [`evaluate`] only.

use equations::{models, reference};
use equations::{DiskParams, ParamError};
use model_interpreted::NamedValues;
use model_runtime::{EvalError, Name, Names, Readable, WithOutputs};

use crate::model_show::ModelName;
use crate::named_numbers::{parse_assignments, NamedNumbersError};
use equations::Mode;

/// Number of states of every disk model.
const N: usize = equations::DIM;

/// Which implementation of the equations answers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// The models generated from the DSL at compile time.
    Generated,
    /// The hand-written reference (independent road to the same physics).
    Reference,
}

/// The models the front ends run unless asked for the reference (`--reference`): the one
/// line to switch.
pub const DEFAULT_BACKEND: Backend = Backend::Generated;

/// Why an evaluation failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EvalCommandError {
    /// `--state` or `--set` is malformed.
    #[error(transparent)]
    Input(#[from] NamedNumbersError),
    /// A parameter breaks a rule.
    #[error("--set: key `{key}`: {source}")]
    Param {
        /// The parameter's name.
        key: &'static str,
        /// The rule it breaks.
        source: ParamError,
    },
    /// The model is singular at the state.
    #[error("--state: the {mode} equations are singular here (key `{key}` = {}): {source}", Readable(*value))]
    Singular {
        /// The mode evaluated.
        mode: Mode,
        /// The state key the singular pivot depends on.
        key: String,
        /// Its value.
        value: f64,
        /// The model's error.
        source: EvalError,
    },
    /// The hand-written reference has no model in Cartesian slip components.
    #[error(
        "--reference: the hand-written reference has no `sliding-cartesian` model (use `sliding`)"
    )]
    NoReference,
    /// A derivative or output is not finite at the state.
    #[error("--state: {mode}: `{quantity}` is not finite ({value}) at this state")]
    NonFinite {
        /// The mode evaluated.
        mode: Mode,
        /// The quantity.
        quantity: String,
        /// Its value.
        value: f64,
    },
}

impl EvalCommandError {
    /// The key the error is about, if any.
    pub fn key(&self) -> Option<&str> {
        match self {
            EvalCommandError::Input(e) => e.key(),
            EvalCommandError::Param { key, .. } => Some(key),
            EvalCommandError::Singular { key, .. } => Some(key),
            EvalCommandError::NonFinite { quantity, .. } => Some(quantity),
            EvalCommandError::NoReference => None,
        }
    }
}

/// The result of one evaluation.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Evaluation {
    /// The mode evaluated.
    pub mode: Mode,
    /// The model that answered (its name in the DSL or the reference).
    pub model: Name,
    /// `der(name)` for every state, keyed `der(name)` as `model eval` and the DSL write it.
    pub derivatives: NamedValues,
    /// Every output of the model, keyed by name.
    pub outputs: NamedValues,
}

/// The state names of a disk model, in the models' index order.
pub fn model_state_names(model: ModelName) -> &'static [&'static str; N] {
    match model {
        ModelName::Rolling => &models::rolling::STATE_NAMES,
        ModelName::Sliding => &models::sliding::STATE_NAMES,
        ModelName::SlidingCartesian => &models::sliding_cartesian::STATE_NAMES,
    }
}

/// The model `eval --mode` evaluates for a mode.
fn model_of(mode: Mode) -> ModelName {
    match mode {
        Mode::Rolling => ModelName::Rolling,
        Mode::Sliding => ModelName::Sliding,
    }
}

/// Parses the parameters (`NAME=VALUE` items; missing ones take the paper's values) and
/// validates the result. `what` names the flag in errors (`--set`).
pub fn parse_params(what: &str, items: &[String]) -> Result<DiskParams, EvalCommandError> {
    let mut p = DiskParams::paper();
    for (k, v) in parse_assignments(what, items, &DiskParams::NAMES)? {
        match k.as_str() {
            "m" => p.m = v,
            "a" => p.a = v,
            "g" => p.g = v,
            "mu_d" => p.mu_d = v,
            "mu_st" => p.mu_st = v,
            "mu_a" => p.mu_a = v,
            "w_z" => p.w_z = v,
            _ => unreachable!("parse_assignments admits only DiskParams::NAMES"),
        }
    }
    p.validate().map_err(param_error)?;
    Ok(p)
}

/// A parameter error, named by the parameter it is about.
fn param_error(source: ParamError) -> EvalCommandError {
    let key = match source {
        ParamError::NotPositive { name, .. }
        | ParamError::NotFinite { name, .. }
        | ParamError::Negative { name, .. }
        | ParamError::Overflow { name, .. } => name,
        ParamError::DynamicAboveStatic { .. } => "mu_d",
    };
    EvalCommandError::Param { key, source }
}

/// Parses `--state` items (`NAME=VALUE`) for `mode` (missing entries are 0) into the model's
/// state array.
pub fn parse_state(mode: Mode, items: &[String]) -> Result<[f64; N], EvalCommandError> {
    parse_model_state(model_of(mode), items)
}

/// [`parse_state`] for any disk model, the Cartesian slip chart included.
pub fn parse_model_state(model: ModelName, items: &[String]) -> Result<[f64; N], EvalCommandError> {
    let names = model_state_names(model);
    let given = parse_assignments("--state", items, names)?;
    Ok(std::array::from_fn(|i| {
        given.get(names[i]).copied().unwrap_or(0.0)
    }))
}

/// Evaluates the `mode` equations of `backend` at `y`. Switching the CLI's default backend
/// is the one line in the `args` module (`DEFAULT_BACKEND`) that names it.
pub fn evaluate(
    backend: Backend,
    mode: Mode,
    params: &DiskParams,
    y: &[f64; N],
) -> Result<Evaluation, EvalCommandError> {
    evaluate_model(backend, model_of(mode), params, 0.0, y)
}

/// Evaluates a disk model (`model eval rolling`) at `(t, y)`. The hand-written reference has
/// no Cartesian slip chart: asking for it is an input error.
pub fn evaluate_model(
    backend: Backend,
    model: ModelName,
    params: &DiskParams,
    t: f64,
    y: &[f64; N],
) -> Result<Evaluation, EvalCommandError> {
    let p = *params;
    let (rolling, sliding) = (Mode::Rolling, Mode::Sliding);
    match (backend, model) {
        (Backend::Generated, ModelName::Rolling) => {
            run(rolling, &models::rolling::Model::new(p.to_array()), t, y)
        }
        (Backend::Generated, ModelName::Sliding) => {
            run(sliding, &models::sliding::Model::new(p.to_array()), t, y)
        }
        (Backend::Generated, ModelName::SlidingCartesian) => run(
            sliding,
            &models::sliding_cartesian::Model::new(p.to_array()),
            t,
            y,
        ),
        (Backend::Reference, ModelName::Rolling) => run(
            rolling,
            &reference::RollingReference::new(p).map_err(param_error)?,
            t,
            y,
        ),
        (Backend::Reference, ModelName::Sliding) => run(
            sliding,
            &reference::SlidingPolarReference::new(p).map_err(param_error)?,
            t,
            y,
        ),
        (Backend::Reference, ModelName::SlidingCartesian) => Err(EvalCommandError::NoReference),
    }
}

fn run<M: WithOutputs<N, K>, const K: usize>(
    mode: Mode,
    model: &M,
    t: f64,
    y: &[f64; N],
) -> Result<Evaluation, EvalCommandError> {
    let info = model.info();
    let fail = |e: EvalError| to_command_error(mode, &info.state_names, y, e);
    let mut dy = [0.0; N];
    model.rhs(t, y, &mut dy).map_err(fail)?;
    let mut out = [0.0; K];
    model.outputs(t, y, &dy, &mut out).map_err(fail)?;
    let derivatives: Vec<_> = (info.state_names.iter().map(|n| format!("der({n})")))
        .zip(dy)
        .collect();
    let outputs: Vec<_> = (info.output_names.iter().map(|n| n.to_string()))
        .zip(out)
        .collect();
    if let Some((name, value)) = derivatives
        .iter()
        .chain(&outputs)
        .find(|(_, v)| !v.is_finite())
    {
        return Err(EvalCommandError::NonFinite {
            mode,
            quantity: name.clone(),
            value: *value,
        });
    }
    Ok(Evaluation {
        mode,
        model: info.name.clone(),
        derivatives: NamedValues(derivatives),
        outputs: NamedValues(outputs),
    })
}

/// Names the state key behind a model error: the state named in the pivot (`sin(theta)` ->
/// `theta`), else the one whose value is not finite, else the quantity itself.
fn to_command_error(mode: Mode, names: &Names, y: &[f64; N], e: EvalError) -> EvalCommandError {
    match &e {
        EvalError::SingularPivot { pivot, .. } => {
            let named = (names.iter().enumerate())
                .filter(|(_, n)| mentions(pivot, n))
                .max_by_key(|(_, n)| n.len());
            let (i, key) = match named {
                Some((i, n)) => (i, n.to_string()),
                None => {
                    let i = (0..N).find(|&i| !y[i].is_finite()).unwrap_or(0);
                    (i, format!("{} (pivot `{pivot}`)", &names[i]))
                }
            };
            EvalCommandError::Singular {
                mode,
                key,
                value: y[i],
                source: e,
            }
        }
        EvalError::NonFinite {
            quantity, value, ..
        } => EvalCommandError::NonFinite {
            mode,
            quantity: quantity.to_string(),
            value: *value,
        },
        // The disk's equations have no resets; named all the same.
        EvalError::ResetNotFinite { event, value, .. } => EvalCommandError::NonFinite {
            mode,
            quantity: format!("reset of {event}"),
            value: *value,
        },
        EvalError::Undecided { event, mode: next } => EvalCommandError::NonFinite {
            mode,
            quantity: format!("decision of {event}"),
            value: next.map_or(f64::NAN, |k| k as f64),
        },
    }
}

/// Whether `text` mentions the identifier `name` as a whole word.
fn mentions(text: &str, name: &str) -> bool {
    let ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    text.match_indices(name).any(|(i, _)| {
        let before = text[..i].chars().next_back();
        let after = text[i + name.len()..].chars().next();
        !before.is_some_and(ident) && !after.is_some_and(ident)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_and_reference_agree_at_the_papers_start() {
        let theta0 = std::f64::consts::FRAC_PI_2 - 1.0;
        let items = [
            format!("theta={theta0}"),
            "Omega_x=1".to_string(),
            format!("Z={}", 0.03755 * theta0.sin()),
        ];
        let y = parse_state(Mode::Rolling, &items).unwrap();
        let p = parse_params("--set", &[]).unwrap();
        let g = evaluate(Backend::Generated, Mode::Rolling, &p, &y).unwrap();
        let r = evaluate(Backend::Reference, Mode::Rolling, &p, &y).unwrap();
        for (a, b) in g.derivatives.0.iter().zip(&r.derivatives.0) {
            assert_eq!(a.0, b.0);
            assert!((a.1 - b.1).abs() <= 1e-9 * (1.0 + b.1.abs()), "{a:?} {b:?}");
        }
        let nu = g.outputs.0.iter().find(|(n, _)| *n == "nu").unwrap().1;
        // docs/physics.md §11: rolling would need nu = 0.8355 at t = 0.
        assert!((nu - 0.8355).abs() < 5e-4, "{nu}");
    }

    #[test]
    fn flat_disk_is_singular_and_names_theta() {
        let p = parse_params("--set", &[]).unwrap();
        for backend in [Backend::Generated, Backend::Reference] {
            for mode in [Mode::Rolling, Mode::Sliding] {
                let slip = ["v_C=0.1".to_string()];
                let items = if mode == Mode::Sliding {
                    &slip[..]
                } else {
                    &[]
                };
                let y = parse_state(mode, items).unwrap();
                let err = evaluate(backend, mode, &p, &y).unwrap_err();
                assert_eq!(err.key(), Some("theta"), "{backend:?} {mode}: {err}");
            }
        }
    }

    #[test]
    fn mentions_whole_words_only() {
        assert!(mentions("sin(theta)", "theta"));
        assert!(!mentions("sin(theta_2)", "theta"));
        assert!(mentions("v_C", "v_C"));
        assert!(!mentions("v_Cx", "v_C"));
    }
}
