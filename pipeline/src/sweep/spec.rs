//! The sweep file as written: a base scene, fixed overrides, axes, and what to record.
//!
//! Like scenes, every table denies unknown keys, so a misspelt key is an error naming its
//! path (`axis[1].linspce`) instead of a silently ignored line. The shape is checked here; the
//! rules between values (one generator per axis, equal lengths when zipped, known summary
//! keys) are checked in `expand.rs`, all at once, before anything runs.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::output::format::TableFormat;

/// A whole sweep file.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SweepFile {
    /// One line saying what question the sweep answers.
    #[serde(default)]
    pub description: Option<String>,
    /// The base scene: a built-in name or a file (relative to the sweep file's folder).
    pub scene: String,
    /// Overrides applied to every point before the axes: `[set] run.t_end = 10.0`.
    #[serde(default)]
    pub set: BTreeMap<String, toml::Table>,
    /// How the axes combine: every combination (`grid`, default) or side by side (`zip`).
    #[serde(default)]
    pub combine: Combine,
    /// The axes, in order (the first varies slowest in a grid).
    #[serde(default, rename = "axis")]
    pub axes: Vec<AxisSpec>,
    /// The summary keys written to `sweep.csv` (default: every scalar key).
    #[serde(default)]
    pub keys: Option<Vec<String>>,
    /// What each run keeps besides its row (default `none`).
    #[serde(default)]
    pub keep: Keep,
    /// Runs at once, unless `--jobs` says otherwise (default: the number of cores). A sweep
    /// that measures CPU time sets 1: `cpu_s` is then each run's own.
    #[serde(default)]
    pub jobs: Option<usize>,
    /// A run still going after this many seconds of wall time is stopped and recorded as a
    /// `timeout` row.
    #[serde(default)]
    pub timeout_s: Option<f64>,
    /// Error columns against a reference run.
    #[serde(default)]
    pub error: Option<ErrorSpec>,
    /// Which figures to draw.
    #[serde(default)]
    pub figures: FiguresSpec,
}

/// How the axes combine into points.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Combine {
    /// Every combination of the axes' values.
    #[default]
    Grid,
    /// The i-th value of every axis together (all axes equally long).
    Zip,
}

/// What a run keeps on disk besides its row, in `runs/<id>/`.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Keep {
    /// Nothing: the row is the result.
    #[default]
    None,
    /// `summary.json`.
    Summary,
    /// `summary.json` and the events (`events.csv` or `.parquet`).
    Events,
    /// Everything `eulerdisk run` writes, figures included.
    All,
}

impl Keep {
    /// The files of a run's folder this keeps, its tables in `format` (`None`: the whole
    /// folder goes).
    pub fn files(self, format: TableFormat) -> Vec<String> {
        let tables: &[&str] = match self {
            Keep::None => return Vec::new(),
            Keep::Summary => &[],
            Keep::Events => &["events"],
            Keep::All => &["events", "trajectory"],
        };
        let mut files = vec!["summary.json".to_string()];
        files.extend(tables.iter().map(|stem| format.file(stem)));
        files
    }
}

/// One axis: a scene key and how its values are made (exactly one of the generators).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AxisSpec {
    /// The scene key, `table.key` (as in `--set`).
    pub key: String,
    /// Explicit values (numbers, words such as integrator names, booleans, lists such as
    /// `["rolling"]` for `modes.allowed`).
    #[serde(default)]
    pub values: Option<Vec<toml::Value>>,
    /// `num` evenly spaced values from `from` to `to`, both included.
    #[serde(default)]
    pub linspace: Option<Span>,
    /// `num` geometrically spaced values from `from` to `to`, both included (both > 0).
    #[serde(default)]
    pub logspace: Option<Span>,
    /// `num` seeded random values.
    #[serde(default)]
    pub random: Option<RandomSpec>,
}

/// A span of values.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Span {
    /// The first value.
    pub from: f64,
    /// The last value.
    pub to: f64,
    /// How many values (≥ 1; 1 gives `from`).
    pub num: u32,
}

/// Seeded random samples, uniform in `[min, max]` (or log-uniform).
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RandomSpec {
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// How many values.
    pub num: u32,
    /// The seed: the same seed gives the same values on every machine.
    pub seed: u64,
    /// Uniform in `log(value)` instead (both bounds > 0).
    #[serde(default)]
    pub log: bool,
}

/// Relative error columns `err_<key>` against the reference run: the run with the smallest
/// value of the axis `against` (the first such run when several have it).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ErrorSpec {
    /// The axis whose smallest value marks the reference (e.g. `solver.rtol`).
    pub against: String,
    /// The numeric summary keys compared.
    pub keys: Vec<String>,
}

/// The figures of a sweep: each key against the axis `x`, one line per value of the axis
/// `series`, and a heat map over the first two axes when they form a grid.
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FiguresSpec {
    /// The summary (or error) keys drawn; none by default.
    #[serde(default)]
    pub keys: Vec<String>,
    /// The x axis (default the first axis).
    #[serde(default)]
    pub x: Option<String>,
    /// The axis drawn as one line per value (default the second axis, if any).
    #[serde(default)]
    pub series: Option<String>,
}

/// Why a sweep file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum SpecError {
    /// Neither a readable file nor a built-in sweep.
    #[error("sweep `{name}` is neither a file nor a built-in sweep (built-in: {builtin})")]
    NotFound {
        /// What was asked for.
        name: String,
        /// The built-in names.
        builtin: String,
    },
    /// The file exists but could not be read.
    #[error("cannot read sweep file {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Not valid TOML.
    #[error("sweep `{name}` is not valid TOML: {message}")]
    Syntax {
        /// The sweep.
        name: String,
        /// The parser's message.
        message: String,
    },
    /// A key is unknown, missing, of the wrong type, or breaks a rule.
    #[error("sweep `{name}`, key `{key}`: {message}")]
    Key {
        /// The sweep.
        name: String,
        /// The key's path in the sweep file (`axis[0].linspace.num`).
        key: String,
        /// What is wrong.
        message: String,
    },
}

/// The sweeps shipped with the program: (name, TOML text).
pub const BUILTIN: &[(&str, &str)] = &[
    (
        "speed-accuracy",
        include_str!("../../../sweeps/speed-accuracy.toml"),
    ),
    (
        "paper-friction",
        include_str!("../../../sweeps/paper-friction.toml"),
    ),
];

/// A sweep file read and parsed, with where relative scene paths start.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadedSweep {
    /// The sweep's name (file stem or built-in name).
    pub name: String,
    /// The folder relative scene paths start from (`None` for a built-in sweep).
    pub folder: Option<PathBuf>,
    /// The parsed file.
    pub file: SweepFile,
}

/// Reads a sweep by file path or built-in name.
pub fn load(name_or_path: &str) -> Result<LoadedSweep, SpecError> {
    if let Some(read) = crate::scene::read_file_by_path(name_or_path) {
        let (name, text) = read.map_err(|(path, source)| SpecError::Read { path, source })?;
        let folder = Path::new(name_or_path).parent().map(Path::to_path_buf);
        return parse(&name, &text).map(|file| LoadedSweep { name, folder, file });
    }
    let stem = name_or_path.strip_suffix(".toml").unwrap_or(name_or_path);
    let stem = stem.strip_prefix("sweeps/").unwrap_or(stem);
    match BUILTIN.iter().find(|(n, _)| *n == stem) {
        Some((name, text)) => parse(name, text).map(|file| LoadedSweep {
            name: name.to_string(),
            folder: None,
            file,
        }),
        None => Err(SpecError::NotFound {
            name: name_or_path.to_string(),
            builtin: BUILTIN
                .iter()
                .map(|(n, _)| *n)
                .collect::<Vec<_>>()
                .join(", "),
        }),
    }
}

/// Parses a sweep file's text (shape only; `expand` checks the rules).
pub fn parse(name: &str, text: &str) -> Result<SweepFile, SpecError> {
    let tree: toml::Table = toml::from_str(text).map_err(|e| SpecError::Syntax {
        name: name.to_string(),
        message: e.to_string().trim_end().to_string(),
    })?;
    serde_path_to_error::deserialize(toml::Value::Table(tree)).map_err(|e| {
        let (key, message) = crate::scene::error_key(&e);
        SpecError::Key {
            name: name.to_string(),
            key,
            message,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_sweeps_parse() {
        for (name, text) in BUILTIN {
            parse(name, text).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }

    #[test]
    fn a_misspelt_generator_is_named_by_its_path() {
        let text = "scene = \"tangent-toy\"\n[[axis]]\nkey = \"friction.mu_d\"\nlinspce = { from = 0.1, to = 0.2, num = 3 }\n";
        let err = parse("s", text).unwrap_err();
        assert!(err.to_string().contains("axis[0].linspce"), "{err}");
    }
}
