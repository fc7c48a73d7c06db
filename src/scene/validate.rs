//! A scene whose every rule holds.
//!
//! The disk's rules (physics, numerics, the initial state, the allowed modes) are the
//! equations crate's, applied by [`SceneSettings::resolve`]; this program adds only the rules
//! of its own table, `[output]`. Every rule is checked even after one fails, so the user sees
//! all the problems of a scene in one go.

use equations::{DiskConfig, DiskParams, InitialState, Issue, Rule};

use super::schema::SceneFile;
use crate::quantity::Quantity;

/// A scene whose every rule holds, with its derived values.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The scene's name (file stem).
    pub name: String,
    /// The tables as written, after command-line overrides.
    pub file: SceneFile,
    /// The disk's parameters.
    pub params: DiskParams,
    /// The run's settings; samples at the scene's `run.sample_rate`.
    pub config: DiskConfig,
    /// The completed initial state.
    pub initial: InitialState,
    /// The quantities written to `trajectory.csv`, in the scene's order.
    pub quantities: Vec<Quantity>,
}

/// Checks every rule of `file`; on success returns the scene, else every issue found.
pub fn validate(name: &str, file: SceneFile) -> Result<Scene, Vec<Issue>> {
    let resolved = file.settings.resolve();
    let mut issues = resolved.as_ref().err().cloned().unwrap_or_default();
    let quantities = check_quantities(&mut issues, &file.cli.output.quantities);
    match resolved {
        Ok(disk) if issues.is_empty() => Ok(Scene {
            name: name.to_string(),
            file,
            params: disk.params,
            config: disk.config,
            initial: disk.initial,
            quantities,
        }),
        _ => Err(issues),
    }
}

fn check_quantities(issues: &mut Vec<Issue>, names: &[String]) -> Vec<Quantity> {
    const KEY: &str = "output.quantities";
    if names.is_empty() {
        issues.push(Issue::new(KEY, Rule::Empty));
    }
    let mut out = Vec::new();
    for name in names {
        match Quantity::from_name(name) {
            None => issues.push(Issue::new(
                KEY,
                Rule::Unknown {
                    name: name.clone(),
                    expected: Quantity::ALL.map(|q| q.name()).join(", "),
                },
            )),
            Some(q) if out.contains(&q) => {
                issues.push(Issue::new(KEY, Rule::Duplicate { name: name.clone() }))
            }
            Some(q) => out.push(q),
        }
    }
    out
}
