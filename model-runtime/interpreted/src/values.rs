//! Named values to the model's order, and one point evaluated: the parameters and the initial
//! state a front end gives by name become the vectors the interpreter reads, with every
//! mistake (an unknown name, a name twice, a value that is not finite, a parameter without a
//! default) located by its position in what was given.

use crate::error::{PointError, ValueError};
use crate::load::{quoted, ModelRef};
use model_algebra::CompiledModel;
use serde::ser::{Serialize, SerializeMap, Serializer};

/// A value given by name (`("theta", 0.5)`).
pub type Named = (String, f64);

/// Values for `names`, in their order: each from `given` or its default (`None`: required).
pub fn resolve(
    names: &[String],
    defaults: impl Fn(usize) -> Option<f64>,
    given: &[Named],
) -> Result<Vec<f64>, ValueError> {
    let mut values: Vec<Option<f64>> = (0..names.len()).map(&defaults).collect();
    let mut set = vec![false; names.len()];
    for (index, (name, value)) in given.iter().enumerate() {
        let Some(k) = names.iter().position(|n| n == name) else {
            return Err(ValueError::Unknown {
                index,
                name: name.clone(),
                names: quoted(names),
            });
        };
        if std::mem::replace(&mut set[k], true) {
            return Err(ValueError::Twice {
                index,
                name: name.clone(),
            });
        }
        if !value.is_finite() {
            return Err(ValueError::NotFinite {
                index,
                name: name.clone(),
                value: *value,
            });
        }
        values[k] = Some(*value);
    }
    (values.into_iter().zip(names))
        .map(|(value, name)| value.ok_or_else(|| ValueError::Missing { name: name.clone() }))
        .collect()
}

/// The parameter values of `model`: the file's defaults, overridden by `given`.
pub fn params(model: ModelRef<'_>, given: &[Named]) -> Result<Vec<f64>, ValueError> {
    let params = model.params();
    let names: Vec<String> = params.iter().map(|(n, _)| n.clone()).collect();
    resolve(&names, |k| params[k].1, given)
}

/// The initial state of `model` from `given`: a state not given starts at the value the file
/// writes on it (`states { x = 2 }`, smooth or switched alike), or zero.
pub fn initial_state(model: ModelRef<'_>, given: &[Named]) -> Result<Vec<f64>, ValueError> {
    let written = match model {
        ModelRef::Smooth(model) => &model.initial,
        ModelRef::Switched(model) => &model.initial,
    };
    let initial = |k: usize| Some(written.get(k).copied().flatten().unwrap_or(0.0));
    resolve(model.states(), initial, given)
}

/// Numbers under names, in the model's order (serialised as a JSON object in that order):
/// what `model eval` and the disk's `eulerdisk eval` print.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedValues(pub Vec<(String, f64)>);

impl NamedValues {
    /// The value called `name`.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.0.iter().find(|(n, _)| n == name).map(|&(_, v)| v)
    }
}

impl Serialize for NamedValues {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (name, value) in &self.0 {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

/// The derivatives and outputs of a model at one point, by name.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PointValues {
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
) -> Result<PointValues, PointError> {
    let failure = |failure| PointError::Interpreter {
        model: model.name.clone(),
        failure,
    };
    let der = model.derivatives(t, y, params).map_err(failure)?;
    let outputs = model.outputs_at(t, y, &der, params).map_err(failure)?;
    let derivatives = (model.states.iter().map(|s| format!("der({s})"))).zip(der);
    let derivatives = NamedValues(derivatives.collect());
    let outputs = NamedValues(model.outputs.iter().cloned().zip(outputs).collect());
    let all = derivatives.0.iter().chain(&outputs.0);
    if let Some((name, value)) = all.into_iter().find(|(_, v)| !v.is_finite()) {
        return Err(PointError::NonFinite {
            model: model.name.clone(),
            name: name.clone(),
            value: *value,
        });
    }
    Ok(PointValues {
        model: model.name.clone(),
        t,
        derivatives,
        outputs,
    })
}
