//! The scene file as written: the program's own tables beside the disk's.
//!
//! A scene file is the equations crate's [`SceneSettings`] (disk, friction, air, initial
//! state, modes, solver, run) plus two entries only this program reads: a `description` and
//! the `[output]` quantities. The loader splits those off the TOML tree and reads each part
//! into its own type, so every table keeps `deny_unknown_fields` and its defaults live in one
//! place (`equations`).

use equations::SceneSettings;
use serde::{Deserialize, Serialize};

use crate::output::format::TableFormat;
use equations::record::Quantity;

/// The top-level keys of a scene file that belong to this program, not to the disk.
pub const CLI_KEYS: [&str; 2] = ["description", "output"];

/// The program's own entries of a scene file.
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CliTables {
    /// One line saying what the scene shows.
    #[serde(default)]
    pub description: Option<String>,
    /// What goes into `trajectory.csv`.
    #[serde(default)]
    pub output: OutputTable,
}

/// A whole scene file, as written (after command-line overrides); serialised flat, as the
/// file is, into a run's provenance.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct SceneFile {
    /// The program's own entries.
    #[serde(flatten)]
    pub cli: CliTables,
    /// The disk's tables.
    #[serde(flatten)]
    pub settings: SceneSettings,
}

/// `[output]`: the quantities written to the trajectory, and the format of the tables. The
/// quantities also decide the models that run: when none of them (nor the figures) needs a state the pruned variants drop (`X`, `Y`,
/// `Z`, `phi`, hence `energy`, `residual_Z`) and the air is still, the pruned 8-state models
/// run (`crate::run::model`).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct OutputTable {
    /// Quantity names (see `eulerdisk quantities`); default all (also in an `[output]` table
    /// that does not name them).
    #[serde(default = "all_quantities")]
    pub quantities: Vec<String>,
    /// The format of the trajectory, events and extrema (and of a sweep's table): `csv`
    /// (default) or `parquet`; `-f/--format` on the command line.
    #[serde(default)]
    pub format: TableFormat,
    /// Stretches of the run sampled finer than `run.sample_rate` in the trajectory file
    /// (`windows = [{ from = 99.0, to = 100.0, sample_rate = 200000 }]`); none by default.
    #[serde(default)]
    pub windows: Vec<SampleWindow>,
}

/// `[output] windows`: one stretch of the run whose trajectory is sampled at its own rate, a
/// whole multiple of `run.sample_rate` (all samples lie on one grid).
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SampleWindow {
    /// Where it starts (s).
    pub from: f64,
    /// Where it ends (s), included.
    pub to: f64,
    /// Samples per second inside it.
    pub sample_rate: f64,
}

/// Every quantity: what `output.quantities` is when not given.
fn all_quantities() -> Vec<String> {
    Quantity::ALL.iter().map(|q| q.name().to_string()).collect()
}

impl Default for OutputTable {
    fn default() -> Self {
        OutputTable {
            quantities: all_quantities(),
            format: TableFormat::default(),
            windows: Vec::new(),
        }
    }
}
