//! A scene whose every rule holds.
//!
//! The disk's rules (physics, numerics, the initial state, the allowed modes) are the
//! equations crate's, applied by [`SceneSettings::resolve`]; this program adds only the rules
//! of its own table, `[output]` (its quantities and its fine-sampling windows). Every rule is checked even after one fails, so the user sees
//! all the problems of a scene in one go.

use equations::{DiskConfig, DiskParams, InitialState, Issue, Number, Rule, STATE_NAMES};

use super::schema::SceneFile;
use crate::output::format::{TableFormat, PARQUET_UNAVAILABLE};
use crate::output::parquet::parquet_writer;
use crate::run::plan::{SamplePlan, MAX_GRID_POINTS, MIN_RATE_WITH_WINDOWS};
use equations::record::Quantity;

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
    check_windows(&mut issues, &file);
    check_format(&mut issues, &file);
    if let Ok(disk) = &resolved {
        check_energy(&mut issues, &disk.initial, &disk.params);
    }
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

/// The start's energy is finite (every backend writes it; a velocity of 1e300 m/s squares
/// to infinity): else an issue naming the largest of the components it is made of.
fn check_energy(issues: &mut Vec<Issue>, initial: &InitialState, params: &DiskParams) {
    let energy = initial.state.energy(params);
    if energy.is_finite() {
        return;
    }
    let parts = Quantity::Energy.reads();
    let largest = (STATE_NAMES.iter().zip(initial.state.y))
        .filter(|(name, _)| parts.contains(name))
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()));
    if let Some((name, value)) = largest {
        issues.push(Issue::new(
            format!("initial.{name}"),
            Rule::Incompatible {
                value: Number(value).to_string(),
                reason: "gives the disk a non-finite energy at the start",
            },
        ));
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

/// `output.format` names a writer this front end has: without a Parquet writer installed
/// (`output::parquet`), Parquet is refused here, before any file is written.
fn check_format(issues: &mut Vec<Issue>, file: &SceneFile) {
    let format = file.cli.output.format;
    if format == TableFormat::Parquet && parquet_writer().is_none() {
        issues.push(Issue::new(
            "output.format",
            Rule::Incompatible {
                value: format.name().to_string(),
                reason: PARQUET_UNAVAILABLE,
            },
        ));
    }
}

/// The rules of `output.windows`: each inside the run, `from` before `to`, its rate positive
/// and a whole multiple of `run.sample_rate`, and the common grid they make not too fine.
fn check_windows(issues: &mut Vec<Issue>, file: &SceneFile) {
    let run = &file.settings.run;
    let windows = &file.cli.output.windows;
    for (i, w) in windows.iter().enumerate() {
        let key = |k: &str| format!("output.windows[{i}].{k}");
        let mut in_range = |k: &str, value: f64, min: f64| {
            if !value.is_finite() {
                issues.push(Issue::new(key(k), Rule::NotFinite { value }));
            } else if !(min..=run.t_end).contains(&value) {
                let (max, open) = (run.t_end, false);
                issues.push(Issue::new(
                    key(k),
                    Rule::OutOfRange {
                        value,
                        min,
                        max,
                        open,
                    },
                ));
            }
        };
        in_range("from", w.from, 0.0);
        in_range("to", w.to, w.from.max(0.0));
        let rate = w.sample_rate;
        if !(rate.is_finite() && rate > 0.0) {
            issues.push(Issue::new(
                key("sample_rate"),
                Rule::NotPositive { value: rate },
            ));
        } else if SamplePlan::multiple(rate, run.sample_rate).is_none() {
            issues.push(Issue::new(
                key("sample_rate"),
                Rule::Incompatible {
                    value: Number(rate).to_string(),
                    reason: "must be a whole multiple of `run.sample_rate` (the windows' samples \
                             lie on the trajectory's grid)",
                },
            ));
        }
    }
    let rate = run.sample_rate;
    if !windows.is_empty() && rate.is_finite() && rate > 0.0 && rate < MIN_RATE_WITH_WINDOWS {
        issues.push(Issue::new(
            "run.sample_rate",
            Rule::Incompatible {
                value: Number(rate).to_string(),
                reason: "is too low for `output.windows` to refine (at least 2e-8 samples per \
                         second: the windows' grid would hold more than 1e12 points per \
                         trajectory point)",
            },
        ));
        return;
    }
    let clean = issues.iter().all(|i| !i.key.starts_with("output.windows"));
    if clean && !windows.is_empty() && run.sample_rate > 0.0 && run.t_end > 0.0 {
        let plan = SamplePlan::new(0.0, run.t_end, run.sample_rate).with_windows(windows);
        let points = plan.fine_rate() * run.t_end;
        if points > MAX_GRID_POINTS {
            issues.push(Issue::new(
                "output.windows",
                Rule::Incompatible {
                    value: format!("{} grid points", Number(points)),
                    reason: "the windows' rates make the sampling grid too fine (at most 1e9 \
                             points over the run): lower a window's `sample_rate`",
                },
            ));
        }
    }
}
