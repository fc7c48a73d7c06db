//! Scenes: TOML files that say which disk, which start, which solver and which outputs.
//!
//! Loading is a pipeline: text -> TOML tree -> command-line overrides applied to the tree ->
//! the program's own entries (`description`, `[output]`) split off -> typed tables (unknown
//! keys and wrong types rejected with the key's path), the disk's read straight into the
//! equations crate's [`SceneSettings`] -> rules between values (all collected; the disk's are
//! the equations crate's, [`SceneSettings::resolve`]) -> a validated [`Scene`]. Overrides act
//! on the tree, before any checking, so `--set` and `--rtol` are held to exactly the rules the
//! file is.
//!
//! The scenes shipped in `scenes/` are compiled into the binary, so `eulerdisk run
//! tangent-toy` works from any directory.

pub mod schema;
mod validate;

use std::path::{Path, PathBuf};

use equations::{Issue, Rule, SceneSettings};

pub use schema::{CliTables, OutputTable, SceneFile};
pub use validate::Scene;

/// The scenes shipped with the program: (name, TOML text).
pub const BUILTIN: &[(&str, &str)] = &[
    (
        "tangent-toy",
        include_str!("../../../scenes/tangent-toy.toml"),
    ),
    (
        "tangent-toy-pruned",
        include_str!("../../../scenes/tangent-toy-pruned.toml"),
    ),
    (
        "pure-rolling",
        include_str!("../../../scenes/pure-rolling.toml"),
    ),
    (
        "spinning-in-place",
        include_str!("../../../scenes/spinning-in-place.toml"),
    ),
    (
        "steady-circle",
        include_str!("../../../scenes/steady-circle.toml"),
    ),
    (
        "upright-stable",
        include_str!("../../../scenes/upright-stable.toml"),
    ),
    (
        "upright-unstable",
        include_str!("../../../scenes/upright-unstable.toml"),
    ),
    (
        "high-friction",
        include_str!("../../../scenes/high-friction.toml"),
    ),
];

/// The scene run when none is named.
pub const DEFAULT_SCENE: &str = "tangent-toy";

/// Why a scene could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// Neither a readable file nor a built-in scene.
    #[error("scene `{name}` is neither a file nor a built-in scene (built-in: {builtin})")]
    NotFound {
        /// What was asked for.
        name: String,
        /// The built-in names, comma separated.
        builtin: String,
    },
    /// The file exists but could not be read.
    #[error("cannot read scene file {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Not valid TOML.
    #[error("scene `{name}` is not valid TOML: {message}")]
    Syntax {
        /// The scene.
        name: String,
        /// The parser's message (with line and column).
        message: String,
    },
    /// A `--set` argument is malformed.
    #[error("--set `{spec}`: {problem}")]
    Override {
        /// The argument as given.
        spec: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A key is unknown, missing, or of the wrong type.
    #[error("scene `{name}`, key `{key}`: {message}")]
    Key {
        /// The scene.
        name: String,
        /// The key's path (`table.key`).
        key: String,
        /// What is wrong.
        message: String,
    },
    /// One or more rules are broken.
    #[error("scene `{name}` is invalid:\n  {}", listed(issues))]
    Invalid {
        /// The scene.
        name: String,
        /// Every broken rule.
        issues: Vec<Issue>,
    },
}

/// The most issues an invalid scene lists; the rest are counted (a scene repeating one bad
/// entry millions of times must not print a line for each).
pub const MAX_LISTED_ISSUES: usize = 50;

/// The issues one per line, the first [`MAX_LISTED_ISSUES`] of them, then how many more.
fn listed(issues: &[Issue]) -> String {
    let mut lines: Vec<String> = (issues.iter().take(MAX_LISTED_ISSUES))
        .map(Issue::to_string)
        .collect();
    if issues.len() > MAX_LISTED_ISSUES {
        lines.push(format!(
            "... and {} more issues",
            issues.len() - MAX_LISTED_ISSUES
        ));
    }
    lines.join("\n  ")
}

impl SceneError {
    /// The keys this error is about (empty when it is about no key).
    pub fn keys(&self) -> Vec<&str> {
        match self {
            SceneError::Key { key, .. } => vec![key],
            SceneError::Invalid { issues, .. } => issues.iter().map(|i| i.key.as_str()).collect(),
            SceneError::Override { spec, .. } => vec![spec],
            _ => vec![],
        }
    }
}

/// What a key of an override must look like.
const KEY_SHAPE: &str = "the key must be `table.key`, e.g. `friction.mu_d`";

/// A command-line override `table.key=value`.
#[derive(Clone, Debug, PartialEq)]
pub struct Override {
    /// The table.
    pub table: String,
    /// The key in the table.
    pub key: String,
    /// The new value.
    pub value: toml::Value,
}

impl Override {
    /// Parses `table.key=value`; the value is read as a TOML value (`0.2`, `true`,
    /// `["rolling"]`), or as a string when it is not one (`dop853`).
    pub fn parse(spec: &str) -> Result<Override, SceneError> {
        let bad = |problem: &str| SceneError::Override {
            spec: spec.to_string(),
            problem: problem.to_string(),
        };
        let (path, text) = spec
            .split_once('=')
            .ok_or_else(|| bad("expected `table.key=value`"))?;
        let text = text.trim();
        let value = match toml::from_str::<toml::Table>(&format!("v = {text}")) {
            Ok(mut t) => t.remove("v").ok_or_else(|| bad("no value"))?,
            Err(_) => toml::Value::String(text.to_string()),
        };
        Override::at(path.trim(), value).map_err(|_| bad(KEY_SHAPE))
    }

    /// An override of the key at `path` (`table.key`, as in `--set`) with `value`; a path
    /// that is not of that shape is an error naming it.
    pub fn at(path: &str, value: toml::Value) -> Result<Override, SceneError> {
        let is_name = |s: &str| {
            !s.is_empty()
                && s.chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        };
        match path.split_once('.') {
            Some((table, key)) if is_name(table) && is_name(key) => Ok(Override {
                table: table.to_string(),
                key: key.to_string(),
                value,
            }),
            _ => Err(SceneError::Override {
                spec: path.to_string(),
                problem: KEY_SHAPE.to_string(),
            }),
        }
    }

    /// The key's path, `table.key`.
    pub fn path(&self) -> String {
        format!("{}.{}", self.table, self.key)
    }

    /// An override for a key from a dedicated flag (`--rtol` -> `solver.rtol`).
    pub fn new(table: &str, key: &str, value: impl Into<toml::Value>) -> Override {
        Override {
            table: table.to_string(),
            key: key.to_string(),
            value: value.into(),
        }
    }
}

/// Finds the scene text: a readable file first, else a built-in scene by name.
/// When `name_or_path` is an existing file: its name (the file stem) and text, or the path and
/// the I/O error; `None` when it names no file (a built-in name, say). Scenes and sweeps are
/// both given this way.
pub fn read_file_by_path(
    name_or_path: &str,
) -> Option<Result<(String, String), (std::path::PathBuf, std::io::Error)>> {
    let path = Path::new(name_or_path);
    if !path.is_file() {
        return None;
    }
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| name_or_path.to_string());
    Some(
        std::fs::read_to_string(path)
            .map(|text| (name, text))
            .map_err(|source| (path.to_path_buf(), source)),
    )
}

/// Returns (scene name, text).
pub fn resolve(name_or_path: &str) -> Result<(String, String), SceneError> {
    if let Some(read) = read_file_by_path(name_or_path) {
        return read.map_err(|(path, source)| SceneError::Read { path, source });
    }
    let stem = name_or_path.strip_suffix(".toml").unwrap_or(name_or_path);
    let stem = stem.strip_prefix("scenes/").unwrap_or(stem);
    BUILTIN
        .iter()
        .find(|(n, _)| *n == stem)
        .map(|(n, text)| (n.to_string(), text.to_string()))
        .ok_or_else(|| SceneError::NotFound {
            name: name_or_path.to_string(),
            builtin: BUILTIN
                .iter()
                .map(|(n, _)| *n)
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// Parses, overrides and validates a scene's text.
pub fn parse(name: &str, text: &str, overrides: &[Override]) -> Result<Scene, SceneError> {
    from_tree(name, parse_tree(name, text)?, overrides)
}

/// A scene's text as a TOML tree (the first stage of [`parse`]; a sweep reads its base scene
/// once and gives each point a copy of the tree).
pub fn parse_tree(name: &str, text: &str) -> Result<toml::Table, SceneError> {
    toml::from_str(text).map_err(|e| SceneError::Syntax {
        name: name.to_string(),
        message: e.to_string().trim_end().to_string(),
    })
}

/// Overrides and validates a scene's TOML tree (the rest of [`parse`]).
pub fn from_tree(
    name: &str,
    mut tree: toml::Table,
    overrides: &[Override],
) -> Result<Scene, SceneError> {
    for o in overrides {
        let entry = tree
            .entry(o.table.clone())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        match entry {
            toml::Value::Table(t) => {
                t.insert(o.key.clone(), o.value.clone());
            }
            _ => {
                return Err(SceneError::Key {
                    name: name.to_string(),
                    key: o.table.clone(),
                    message: "is not a table, so it cannot take an override".into(),
                })
            }
        }
    }
    // The program's own entries are split off; the rest is the disk's, read straight into
    // the equations crate's settings.
    let cli_tree: toml::Table = schema::CLI_KEYS
        .iter()
        .filter_map(|k| tree.remove(*k).map(|v| (k.to_string(), v)))
        .collect();
    let cli: CliTables = serde_path_to_error::deserialize(toml::Value::Table(cli_tree))
        .map_err(|e| key_error(name, e))?;
    let missing = missing_required(&tree);
    let settings: SceneSettings = serde_path_to_error::deserialize(toml::Value::Table(tree))
        .map_err(|e| match e.inner().message().starts_with("missing field") {
            // The reader stops at the first missing key: name them all instead.
            true if !missing.is_empty() => SceneError::Invalid {
                name: name.to_string(),
                issues: missing,
            },
            _ => key_error(name, e),
        })?;
    let file = SceneFile { cli, settings };
    validate::validate(name, file).map_err(|issues| SceneError::Invalid {
        name: name.to_string(),
        issues,
    })
}

/// The keys every scene must give (all others have defaults). `initial.theta` is the one
/// required key of `[initial]`; the tables of the others are required with them.
pub const REQUIRED_KEYS: [&str; 7] = [
    "disk.m",
    "disk.a",
    "disk.g",
    "friction.mu_d",
    "friction.mu_st",
    "initial.theta",
    "run.t_end",
];

/// Every required key the scene's tree lacks, each as a "missing" issue: all of them at once,
/// where reading the tree stops at the first (`disk`, then `disk.g`, then `run`). Used when
/// the reader finds a key missing, so an unknown or mistyped key keeps its own message. A
/// table that is there but not a table is left to the reader, which names it.
fn missing_required(tree: &toml::Table) -> Vec<Issue> {
    REQUIRED_KEYS
        .iter()
        .filter(|path| {
            let (table, key) = path.split_once('.').expect("REQUIRED_KEYS are `table.key`");
            match tree.get(table) {
                None => true,
                Some(toml::Value::Table(t)) => !t.contains_key(key),
                Some(_) => false,
            }
        })
        .map(|path| Issue::new(*path, Rule::Missing))
        .collect()
}

/// Turns a typed-deserialisation error into one naming the key: the path serde was at, plus
/// the field named in "missing field `x`" / "unknown field `x`" messages.
fn key_error(name: &str, e: serde_path_to_error::Error<toml::de::Error>) -> SceneError {
    let (key, message) = error_key(&e);
    SceneError::Key {
        name: name.to_string(),
        key,
        message,
    }
}

/// The key a typed-deserialisation error is about (`table.key`, or `table.field` for a
/// missing or unknown field) and the deserialiser's message; shared by every TOML file the
/// program reads (scenes, sweeps).
pub fn error_key(e: &serde_path_to_error::Error<toml::de::Error>) -> (String, String) {
    let path = e.path().to_string();
    let message = e.inner().message().trim_end().to_string();
    let field = ["missing field `", "unknown field `"]
        .iter()
        .find_map(|prefix| message.strip_prefix(prefix))
        .and_then(|rest| rest.split('`').next());
    let base = if path == "." { String::new() } else { path };
    let key = match field {
        Some(field) if !base.ends_with(field) => {
            if base.is_empty() {
                field.to_string()
            } else {
                format!("{base}.{field}")
            }
        }
        _ => base,
    };
    (key, message)
}

/// Loads a scene by file path or built-in name and applies the overrides.
pub fn load(name_or_path: &str, overrides: &[Override]) -> Result<Scene, SceneError> {
    let (name, text) = resolve(name_or_path)?;
    parse(&name, &text, overrides)
}
