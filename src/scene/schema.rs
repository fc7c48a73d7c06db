//! The scene file as written: the program's own tables beside the disk's.
//!
//! A scene file is the equations crate's [`SceneSettings`] (disk, friction, air, initial
//! state, modes, solver, run) plus two entries only this program reads: a `description` and
//! the `[output]` quantities. The loader splits those off the TOML tree and reads each part
//! into its own type, so every table keeps `deny_unknown_fields` and its defaults live in one
//! place (`equations`).

use equations::SceneSettings;
use serde::{Deserialize, Serialize};

use crate::quantity::Quantity;

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

/// `[output]`: the quantities written to `trajectory.csv`. They also decide the models that
/// run: when none of them (nor the figures) needs a state the pruned variants drop (`X`, `Y`,
/// `Z`, `phi`, hence `energy`, `residual_Z`) and the air is still, the pruned 8-state models
/// run (`crate::run::model`).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct OutputTable {
    /// Quantity names (see `eulerdisk quantities`); default all (also in an `[output]` table
    /// that does not name them).
    #[serde(default = "all_quantities")]
    pub quantities: Vec<String>,
}

/// Every quantity: what `output.quantities` is when not given.
fn all_quantities() -> Vec<String> {
    Quantity::ALL.iter().map(|q| q.name().to_string()).collect()
}

impl Default for OutputTable {
    fn default() -> Self {
        OutputTable {
            quantities: all_quantities(),
        }
    }
}
