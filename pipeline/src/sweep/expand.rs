//! From a sweep file to a plan: the axes' values, the points, and every point's scene,
//! validated before anything runs.
//!
//! Each point's scene is loaded exactly as `eulerdisk run SCENE --set table.key=value ...`
//! loads it — the same resolver, the same overrides on the TOML tree, the same validation —
//! with the sweep's `[set]` first, then the command line's `--set`, then the axis values. So
//! a point is as strict as `run`, and its numbers are `run`'s. A sweep with one bad point
//! does not start: the error lists the bad points with their values and the broken rule.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::axes::{self, as_number, AxisIssue, AxisValues};
use super::columns::{summary_keys, ERROR_PREFIX, FIXED_COLUMNS, TIMING_COLUMNS};
use super::spec::{Combine, LoadedSweep, SpecError, SweepFile};
use crate::output::format::TableFormat;
use crate::output::tables::number;
use crate::scene::{self, Override, Scene, SceneError};

/// The scene key of the tables' format, which no axis may vary.
pub const FORMAT_KEY: &str = "output.format";
/// Most points a sweep may have.
pub const MAX_POINTS: usize = 1_000_000;
/// How many bad points an error lists (the rest are counted).
pub const LISTED_FAILURES: usize = 5;

/// Everything that defines a sweep's rows: two sweeps with equal definitions make the same
/// rows, so a folder (resume) or a shard (merge) is accepted only under an equal one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Definition {
    /// The sweep's name.
    pub name: String,
    /// The sweep file as written.
    pub file: SweepFile,
    /// The base scene's name.
    pub scene_name: String,
    /// The base scene's text (a changed scene file is a different sweep).
    pub scene_text: String,
    /// `--set` overrides from the command line, applied to every point after `[set]`.
    pub cli_sets: Vec<String>,
    /// The axes with their values.
    pub axes: Vec<AxisValues>,
    /// The points: per point, one value per axis.
    pub points: Vec<Vec<toml::Value>>,
    /// The summary keys written to the table.
    pub columns: Vec<String>,
    /// The format of the table and of the runs' tables: the points' `output.format` (one
    /// for the whole sweep: `[set]` or `-f/--format`, never an axis).
    #[serde(default)]
    pub format: TableFormat,
}

impl Definition {
    /// The definition without its `timeout_s`: what the rows depend on. A finished run's row
    /// is the same under any timeout, so a folder (or a shard) made under another timeout is
    /// the same sweep, and its timed-out runs can be run again with more time.
    pub fn rows_defined(&self) -> Definition {
        let mut d = self.clone();
        d.file.timeout_s = None;
        d
    }

    /// Whether this definition gives runs more time than `earlier` did (no timeout, or a
    /// longer one), so that runs that timed out under `earlier` are worth running again.
    pub fn allows_longer_than(&self, earlier: &Definition) -> bool {
        match (self.file.timeout_s, earlier.file.timeout_s) {
            (_, None) => false,
            (None, Some(_)) => true,
            (Some(now), Some(then)) => now > then,
        }
    }
}

/// One point of a sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct PointId(pub usize);

impl PointId {
    /// The run's name in files and folders (`r000042`).
    pub fn name(self) -> String {
        format!("r{:06}", self.0)
    }
}

/// A definition with every point's validated scene.
#[derive(Clone, Debug)]
pub struct Plan {
    /// What defines the rows.
    pub definition: Definition,
    /// The scene of every point, in point order.
    pub scenes: Vec<Scene>,
}

/// A point whose scene does not validate.
#[derive(Debug)]
pub struct PointFailure {
    /// The point.
    pub point: PointId,
    /// Its axis values, as `key = value`.
    pub values: String,
    /// Why its scene is rejected.
    pub error: SceneError,
}

/// Why a sweep cannot start.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// The file cannot be read or has the wrong shape.
    #[error(transparent)]
    Spec(#[from] SpecError),
    /// Rules of the sweep file are broken.
    #[error("sweep `{name}` is invalid:\n  {}", issues.iter().map(|i| format!("`{}`: {}", i.key, i.message)).collect::<Vec<_>>().join("\n  "))]
    Rules {
        /// The sweep.
        name: String,
        /// Every broken rule, by key.
        issues: Vec<AxisIssue>,
    },
    /// The base scene cannot be loaded, or a `--set` is malformed.
    #[error("sweep `{name}`: {source}")]
    Scene {
        /// The sweep.
        name: String,
        /// The scene's error.
        source: SceneError,
    },
    /// Points whose scenes do not validate.
    #[error("sweep `{name}`: {} of {total} points are invalid, nothing was run:\n  {}{}",
        failures.len(),
        failures.iter().take(LISTED_FAILURES).map(|f| format!("point {} ({}): {}", f.point.0, f.values, f.error)).collect::<Vec<_>>().join("\n  "),
        if failures.len() > LISTED_FAILURES { format!("\n  ... and {} more", failures.len() - LISTED_FAILURES) } else { String::new() })]
    Points {
        /// The sweep.
        name: String,
        /// How many points the sweep has.
        total: usize,
        /// Every bad point.
        failures: Vec<PointFailure>,
    },
}

impl PlanError {
    /// The keys this error is about: sweep-file keys, or the scene keys a bad point breaks.
    pub fn keys(&self) -> Vec<String> {
        match self {
            PlanError::Spec(SpecError::Key { key, .. }) => vec![key.clone()],
            PlanError::Rules { issues, .. } => issues.iter().map(|i| i.key.clone()).collect(),
            PlanError::Scene { source, .. } => {
                source.keys().iter().map(|k| k.to_string()).collect()
            }
            PlanError::Points { failures, .. } => failures
                .iter()
                .flat_map(|f| f.error.keys().into_iter().map(str::to_string))
                .collect(),
            PlanError::Spec(_) => vec![],
        }
    }
}

/// Makes the plan of `sweep` with the command line's `--set` overrides `cli_sets`.
pub fn plan(sweep: &LoadedSweep, cli_sets: &[String]) -> Result<Plan, PlanError> {
    let name = sweep.name.clone();
    let file = &sweep.file;
    let scene_err = |source| PlanError::Scene {
        name: name.clone(),
        source,
    };
    let base = base_overrides(file, cli_sets).map_err(scene_err)?;
    // The base scene is not validated alone: an axis may supply or correct what it lacks
    // (`--set solver.rtol=...` under an rtol axis); every point is validated below.
    let (scene_name, scene_text) = resolve_scene(sweep).map_err(scene_err)?;

    let mut issues = Vec::new();
    let axes: Vec<AxisValues> = file
        .axes
        .iter()
        .enumerate()
        .filter_map(|(i, a)| axes::values(i, a).map_err(|e| issues.push(e)).ok())
        .collect();
    check_rules(file, &axes, &mut issues);
    let points = if issues.is_empty() {
        combine(file.combine, &axes, &mut issues)
    } else {
        Vec::new()
    };
    let columns = match &file.keys {
        Some(keys) => keys.clone(),
        None => summary_keys(),
    }
    .into_iter()
    .filter(|k| !FIXED_COLUMNS.contains(&k.as_str()))
    .collect();
    if !issues.is_empty() {
        return Err(PlanError::Rules { name, issues });
    }
    // The base scene's text is read once; each point overrides a copy of its tree (reading
    // the text again for each of up to a million points was most of the plan's time).
    let tree = scene::parse_tree(&scene_name, &scene_text);
    let scenes: Vec<Result<Scene, PointFailure>> = points
        .par_iter()
        .enumerate()
        .map(|(i, values)| {
            let overrides = point_overrides(&base, &axes, values);
            let scene = match &tree {
                Ok(tree) => scene::from_tree(&scene_name, tree.clone(), &overrides),
                Err(_) => scene::parse(&scene_name, &scene_text, &overrides),
            };
            scene.map_err(|error| PointFailure {
                point: PointId(i),
                values: describe(&axes, values),
                error,
            })
        })
        .collect();
    let (good, bad): (Vec<_>, Vec<_>) = scenes.into_iter().partition(Result::is_ok);
    let failures: Vec<PointFailure> = bad.into_iter().filter_map(Result::err).collect();
    if !failures.is_empty() {
        return Err(PlanError::Points {
            name,
            total: points.len(),
            failures,
        });
    }
    let scenes: Vec<Scene> = good.into_iter().filter_map(Result::ok).collect();
    let format = scenes
        .first()
        .map(|s| s.file.cli.output.format)
        .unwrap_or_default();
    Ok(Plan {
        scenes,
        definition: Definition {
            name,
            file: file.clone(),
            scene_name,
            scene_text,
            cli_sets: cli_sets.to_vec(),
            axes,
            points,
            columns,
            format,
        },
    })
}

/// `key = value, ...` of a point.
pub fn describe(axes: &[AxisValues], values: &[toml::Value]) -> String {
    axes.iter()
        .zip(values)
        .map(|(a, v)| format!("{} = {v}", a.key))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The sweep's `[set]` then the command line's `--set`, as overrides.
fn base_overrides(file: &SweepFile, cli_sets: &[String]) -> Result<Vec<Override>, SceneError> {
    let mut out = Vec::new();
    for (table, keys) in &file.set {
        for (key, value) in keys {
            out.push(Override::at(&format!("{table}.{key}"), value.clone())?);
        }
    }
    for spec in cli_sets {
        out.push(Override::parse(spec)?);
    }
    Ok(out)
}

/// The overrides of one point: the base ones, then its axis values.
pub fn point_overrides(
    base: &[Override],
    axes: &[AxisValues],
    values: &[toml::Value],
) -> Vec<Override> {
    let mut out = base.to_vec();
    for (a, v) in axes.iter().zip(values) {
        // The key's shape was checked with the rules.
        if let Ok(o) = Override::at(&a.key, v.clone()) {
            out.push(o);
        }
    }
    out
}

/// The `--set` arguments that make `eulerdisk run` build the same scene as point `values`
/// (the sweep's `[set]` and the command line's are included).
pub fn run_arguments(d: &Definition, values: &[toml::Value]) -> Vec<String> {
    let base = base_overrides(&d.file, &d.cli_sets).unwrap_or_default();
    point_overrides(&base, &d.axes, values)
        .iter()
        .map(|o| match &o.value {
            toml::Value::Float(f) => format!("{}={}", o.path(), number(*f)),
            v => format!("{}={v}", o.path()),
        })
        .collect()
}

/// The base scene's name and text: a file relative to the sweep's folder first, then
/// whatever `eulerdisk run` would find under that name.
fn resolve_scene(sweep: &LoadedSweep) -> Result<(String, String), SceneError> {
    let beside = sweep.folder.as_ref().map(|f| f.join(&sweep.file.scene));
    match beside.filter(|p| p.is_file()) {
        Some(path) => scene::resolve(&path.to_string_lossy()),
        None => scene::resolve(&sweep.file.scene),
    }
}

fn issue(key: impl Into<String>, message: String) -> AxisIssue {
    AxisIssue {
        key: key.into(),
        message,
    }
}

/// The rules between the sweep file's values.
fn check_rules(file: &SweepFile, axes: &[AxisValues], issues: &mut Vec<AxisIssue>) {
    for (i, a) in file.axes.iter().enumerate() {
        if let Err(e) = Override::at(&a.key, toml::Value::Boolean(false)) {
            issues.push(issue(format!("axis[{i}].key"), format!("`{}`: {e}", a.key)));
        }
        if a.key == FORMAT_KEY {
            issues.push(issue(
                format!("axis[{i}].key"),
                format!("`{FORMAT_KEY}` is one for the whole sweep: give it in `[set]` or with -f/--format"),
            ));
        }
        if file.axes[..i].iter().any(|b| b.key == a.key) {
            issues.push(issue(
                format!("axis[{i}].key"),
                format!("`{}` is already an axis", a.key),
            ));
        }
    }
    let known = summary_keys();
    let known_list = known.join(", ");
    if let Some(keys) = &file.keys {
        for k in keys.iter().filter(|k| !known.contains(k)) {
            issues.push(issue(
                "keys",
                format!("unknown summary key `{k}` (expected one of: {known_list})"),
            ));
        }
    }
    if let Some(t) = file.timeout_s {
        if !(t.is_finite() && t > 0.0) {
            issues.push(issue("timeout_s", format!("must be > 0 s, got {t}")));
        }
    }
    if file.jobs == Some(0) {
        issues.push(issue("jobs", "must be at least 1, got 0".into()));
    }
    let is_axis = |k: &str| file.axes.iter().any(|a| a.key == k);
    let mut drawable = known.clone();
    drawable.extend(TIMING_COLUMNS.iter().map(|k| k.to_string()));
    if let Some(e) = &file.error {
        match axes.iter().find(|a| a.key == e.against) {
            None if !is_axis(&e.against) => issues.push(issue(
                "error.against",
                format!("`{}` is not an axis", e.against),
            )),
            Some(a) if a.numbers().is_none() => issues.push(issue(
                "error.against",
                format!("axis `{}` has values that are not numbers", e.against),
            )),
            _ => {}
        }
        for k in &e.keys {
            if known.contains(k) {
                drawable.push(format!("{ERROR_PREFIX}{k}"));
            } else {
                issues.push(issue(
                    "error.keys",
                    format!("unknown summary key `{k}` (expected one of: {known_list})"),
                ));
            }
        }
    }
    let f = &file.figures;
    for (field, axis) in [("figures.x", &f.x), ("figures.series", &f.series)] {
        if let Some(k) = axis.as_ref().filter(|k| !is_axis(k)) {
            issues.push(issue(field, format!("`{k}` is not an axis")));
        }
    }
    for k in f.keys.iter().filter(|k| !drawable.contains(k)) {
        issues.push(issue(
            "figures.keys",
            format!(
                "`{k}` is neither a summary key nor an error column (expected one of: {})",
                drawable.join(", ")
            ),
        ));
    }
    if !f.keys.is_empty() && file.axes.is_empty() {
        issues.push(issue(
            "figures.keys",
            "figures need at least one axis".into(),
        ));
    }
}

/// The points of `axes` combined as `how` says.
fn combine(
    how: Combine,
    axes: &[AxisValues],
    issues: &mut Vec<AxisIssue>,
) -> Vec<Vec<toml::Value>> {
    if axes.is_empty() {
        return vec![Vec::new()];
    }
    match how {
        Combine::Zip => {
            let n = axes[0].values.len();
            for (i, a) in axes.iter().enumerate().skip(1) {
                if a.values.len() != n {
                    issues.push(issue(
                        format!("axis[{i}]"),
                        format!(
                            "zipped axes must be equally long: `{}` has {} values, `{}` has {n}",
                            a.key,
                            a.values.len(),
                            axes[0].key
                        ),
                    ));
                }
            }
            if !issues.is_empty() {
                return Vec::new();
            }
            (0..n)
                .map(|k| axes.iter().map(|a| a.values[k].clone()).collect())
                .collect()
        }
        Combine::Grid => {
            let total = axes
                .iter()
                .try_fold(1usize, |acc, a| acc.checked_mul(a.values.len()));
            match total {
                Some(t) if t <= MAX_POINTS => {}
                _ => {
                    issues.push(issue(
                        "axis",
                        format!("the grid has more than {MAX_POINTS} points"),
                    ));
                    return Vec::new();
                }
            }
            let mut points = vec![Vec::new()];
            for a in axes {
                points = points
                    .into_iter()
                    .flat_map(|p: Vec<toml::Value>| {
                        a.values.iter().map(move |v| {
                            let mut q = p.clone();
                            q.push(v.clone());
                            q
                        })
                    })
                    .collect();
            }
            points
        }
    }
}

/// The numeric value of axis `key` at point `values`, if it is a number.
pub fn axis_number(d: &Definition, key: &str, values: &[toml::Value]) -> Option<f64> {
    let i = d.axes.iter().position(|a| a.key == key)?;
    values.get(i).and_then(as_number)
}
