//! A sweep's folder: its definition, one file per finished run, and the table.
//!
//! ```text
//! DIR/sweep.json        the definition (format, program version, shard), written first
//! DIR/rows/r000042.json one finished run, written atomically the moment it finishes
//! DIR/sweep.csv         the table, rebuilt atomically from rows/ as runs finish
//!                       (`sweep.parquet` when the sweep's `output.format` is Parquet)
//! DIR/runs/r000042/     what a run keeps (`keep`), if anything
//! ```
//!
//! A row file appears whole or not at all (temporary name, flush, rename), so a sweep killed
//! at any instant leaves complete rows and, at worst, a hidden temporary file that the next
//! start removes. The rows on disk are the truth: resuming runs exactly the points without a
//! row, and a folder holding another sweep's definition is refused rather than mixed.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::expand::{Definition, PointId};
use super::row::{belongs, table, Row};
use super::shard::Shard;
use super::spec::Keep;
use crate::output::atomic::{write_bytes_atomic, WriteError};
use crate::output::files::write_table;

/// The definition file.
pub const DEFINITION_FILE: &str = "sweep.json";
/// The table's stem: `sweep.csv`, or `sweep.parquet` in a sweep whose format is Parquet.
pub const TABLE_STEM: &str = "sweep";
/// The table in the default format.
pub const TABLE_FILE: &str = "sweep.csv";
/// The folder of row files.
pub const ROWS_DIR: &str = "rows";
/// The folder of what runs keep.
pub const RUNS_DIR: &str = "runs";
/// Where runs that keep nothing write while they run.
pub const SCRATCH_DIR: &str = ".scratch";
/// The format of `sweep.json` and the row files.
pub const FORMAT: u32 = 1;
/// Prefix of the temporary files of atomic writes (`output::atomic`).
const PARTIAL_PREFIX: &str = ".partial-";

/// `sweep.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// The file format.
    pub format: u32,
    /// The program version that wrote it.
    pub program: String,
    /// The shard this folder holds (`None`: the whole sweep).
    pub shard: Option<Shard>,
    /// The sweep.
    pub definition: Definition,
}

impl Manifest {
    /// The manifest of `definition` (or its `shard`) written by this program.
    pub fn new(definition: Definition, shard: Option<Shard>) -> Manifest {
        Manifest {
            format: FORMAT,
            program: env!("CARGO_PKG_VERSION").to_string(),
            shard,
            definition,
        }
    }
}

/// Why a sweep folder cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    /// A file or folder cannot be read or created.
    #[error("{}: {source}", path.display())]
    Io {
        /// The path.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A file cannot be written.
    #[error(transparent)]
    Write(#[from] WriteError),
    /// A file is not what this program writes.
    #[error("{}: not a sweep file of format {FORMAT}: {message}", path.display())]
    Unreadable {
        /// The file.
        path: PathBuf,
        /// The parser's message.
        message: String,
    },
    /// The folder holds another sweep (or another shard).
    #[error("{} holds {what}; choose another --out, or delete it to start over", dir.display())]
    Foreign {
        /// The folder.
        dir: PathBuf,
        /// What differs.
        what: String,
    },
}

/// An open sweep folder.
#[derive(Clone, Debug)]
pub struct Store {
    dir: PathBuf,
    rerun_timeouts: bool,
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> StoreError + '_ {
    move |source| StoreError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Reads `dir/sweep.json`, if there is one.
pub fn read_manifest(dir: &Path) -> Result<Option<Manifest>, StoreError> {
    let path = dir.join(DEFINITION_FILE);
    if !path.is_file() {
        return Ok(None);
    }
    let text = fs::read_to_string(&path).map_err(io(&path))?;
    let m: Manifest = serde_json::from_str(&text).map_err(|e| StoreError::Unreadable {
        path: path.clone(),
        message: e.to_string(),
    })?;
    if m.format != FORMAT {
        return Err(StoreError::Unreadable {
            path,
            message: format!("format {}", m.format),
        });
    }
    Ok(Some(m))
}

impl Store {
    /// Opens (or creates) `dir` for `manifest`: a folder that already holds a different
    /// sweep or shard is refused (a different `timeout_s` alone is the same sweep: with a
    /// longer one, its timed-out runs are run again); leftovers of interrupted writes are
    /// removed.
    pub fn open(dir: &Path, manifest: &Manifest) -> Result<Store, StoreError> {
        let rows = dir.join(ROWS_DIR);
        fs::create_dir_all(&rows).map_err(io(&rows))?;
        let mut rerun_timeouts = false;
        if let Some(old) = read_manifest(dir)? {
            rerun_timeouts = manifest.definition.allows_longer_than(&old.definition);
            let what = if old.definition.rows_defined() != manifest.definition.rows_defined() {
                Some(format!("another sweep (`{}`, or the same with other axes, keys, settings or base scene)", old.definition.name))
            } else if old.shard != manifest.shard {
                Some(format!("shard {}", Shard::label(old.shard)))
            } else {
                None
            };
            if let Some(what) = what {
                return Err(StoreError::Foreign {
                    dir: dir.to_path_buf(),
                    what,
                });
            }
        }
        let json = serde_json::to_string_pretty(manifest).map_err(|e| StoreError::Unreadable {
            path: dir.join(DEFINITION_FILE),
            message: e.to_string(),
        })?;
        write_bytes_atomic(&dir.join(DEFINITION_FILE), format!("{json}\n").as_bytes())?;
        let store = Store {
            dir: dir.to_path_buf(),
            rerun_timeouts,
        };
        store.remove_partials()?;
        Ok(store)
    }

    /// Whether the runs that timed out here run again: the folder's earlier sweep had a
    /// shorter `timeout_s` than this one.
    pub fn reruns_timeouts(&self) -> bool {
        self.rerun_timeouts
    }

    /// The folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Removes temporary files that a killed sweep left in `rows/`.
    fn remove_partials(&self) -> Result<(), StoreError> {
        let rows = self.dir.join(ROWS_DIR);
        for entry in fs::read_dir(&rows).map_err(io(&rows))? {
            let path = entry.map_err(io(&rows))?.path();
            let partial = path
                .file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with(PARTIAL_PREFIX));
            if partial {
                fs::remove_file(&path).map_err(io(&path))?;
            }
        }
        Ok(())
    }

    /// The finished rows of `definition` in this folder, by point.
    pub fn rows(&self, definition: &Definition) -> Result<BTreeMap<usize, Row>, StoreError> {
        read_rows(&self.dir, definition)
    }

    /// Writes one finished run's row, atomically.
    pub fn write_row(&self, row: &Row) -> Result<(), StoreError> {
        let path = self.dir.join(ROWS_DIR).join(format!("{}.json", row.id()));
        let json = serde_json::to_string(row).map_err(|e| StoreError::Unreadable {
            path: path.clone(),
            message: e.to_string(),
        })?;
        write_bytes_atomic(&path, format!("{json}\n").as_bytes())?;
        Ok(())
    }

    /// Rewrites the table (`sweep.csv` or `sweep.parquet`, the definition's format) from
    /// `rows`, atomically.
    pub fn write_table<'r>(
        &self,
        definition: &Definition,
        rows: impl IntoIterator<Item = &'r Row>,
    ) -> Result<(), StoreError> {
        let rows: Vec<Row> = rows.into_iter().cloned().collect();
        write_table(
            &table(definition, &rows),
            &self.dir,
            TABLE_STEM,
            definition.format,
        )?;
        Ok(())
    }

    /// Where run `point` writes: `runs/<id>` when it keeps something, else a scratch folder.
    pub fn run_dir(&self, point: PointId, keep: Keep) -> PathBuf {
        let parent = if keep == Keep::None {
            SCRATCH_DIR
        } else {
            RUNS_DIR
        };
        self.dir.join(parent).join(point.name())
    }
}

/// Reads the row files of `dir` made under `definition`; a row of another sweep is refused.
pub fn read_rows(dir: &Path, definition: &Definition) -> Result<BTreeMap<usize, Row>, StoreError> {
    let rows_dir = dir.join(ROWS_DIR);
    let mut rows = BTreeMap::new();
    if !rows_dir.is_dir() {
        return Ok(rows);
    }
    for entry in fs::read_dir(&rows_dir).map_err(io(&rows_dir))? {
        let path = entry.map_err(io(&rows_dir))?.path();
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        if name.starts_with(PARTIAL_PREFIX) || !name.ends_with(".json") {
            continue;
        }
        let text = fs::read_to_string(&path).map_err(io(&path))?;
        let row: Row = serde_json::from_str(&text).map_err(|e| StoreError::Unreadable {
            path: path.clone(),
            message: e.to_string(),
        })?;
        if !belongs(definition, &row) || name != format!("{}.json", row.id()) {
            return Err(StoreError::Foreign {
                dir: dir.to_path_buf(),
                what: format!("a row ({name}) that is not a point of this sweep"),
            });
        }
        rows.insert(row.point, row);
    }
    Ok(rows)
}
