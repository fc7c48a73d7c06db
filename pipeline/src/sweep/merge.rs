//! `eulerdisk sweep merge DIR...`: the shards' rows joined into one sweep folder.
//!
//! Every input must hold the same sweep (equal definitions); a folder without `sweep.json`
//! stands for the shard folders inside it (`out/shard-0-of-4`, ...). The merged folder is a
//! sweep folder like any other — definition, rows, table, figures — so a sweep started on it
//! runs exactly the missing points. Missing points and points found in more than one input
//! are listed; a duplicate whose rows differ (timing aside) is a conflict. A merge holds the
//! output's sweep lock (`sweep.lock`) while it writes, and refuses an input that a running
//! sweep is still writing into.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

use super::expand::{Definition, PointId};
use super::lock::{self, FolderLock, LockError};
use super::row::Row;
use super::store::{
    read_manifest, read_rows, Manifest, Store, StoreError, DEFINITION_FILE, RUNS_DIR,
};

/// A point found in more than one input.
#[derive(Clone, Debug, PartialEq)]
pub struct Duplicate {
    /// The point.
    pub point: PointId,
    /// The folders holding it (the first one's row is kept).
    pub dirs: Vec<PathBuf>,
    /// Whether the rows agree, timing aside.
    pub agree: bool,
}

/// What a merge found.
#[derive(Clone, Debug, PartialEq)]
pub struct MergeReport {
    /// The folders read (shard folders found inside the arguments included).
    pub inputs: Vec<PathBuf>,
    /// Points of the sweep.
    pub points: usize,
    /// Rows merged.
    pub rows: usize,
    /// Points without a row in any input.
    pub missing: Vec<PointId>,
    /// Points with rows in several inputs.
    pub duplicates: Vec<Duplicate>,
}

impl MergeReport {
    /// Whether the merged table is complete and free of conflicts.
    pub fn complete(&self) -> bool {
        self.missing.is_empty() && self.duplicates.iter().all(|d| d.agree)
    }
}

/// Why a merge cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// An input or the output cannot be used.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// An argument holds no sweep.
    #[error("{}: no {DEFINITION_FILE} there nor in a folder inside it", dir.display())]
    NotASweep {
        /// The argument.
        dir: PathBuf,
    },
    /// A figure cannot be written.
    #[error(transparent)]
    Figures(#[from] crate::output::atomic::WriteError),
    /// A run's kept files (`runs/<id>/`) cannot be copied.
    #[error("cannot copy {} to {}: {source}", from.display(), to.display())]
    CopyRun {
        /// The run's folder in an input.
        from: PathBuf,
        /// Its place in the output.
        to: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The output is being written by a sweep or another merge, or an input by a sweep.
    #[error(transparent)]
    Lock(#[from] LockError),
    /// Two inputs hold different sweeps.
    #[error("{} holds another sweep than {} (different axes, keys, settings or base scene)", other.display(), first.display())]
    Different {
        /// The first input.
        first: PathBuf,
        /// The input that differs.
        other: PathBuf,
    },
}

/// The sweep folders an argument stands for: itself, or the sweep folders inside it.
fn sweep_folders(arg: &Path) -> Result<Vec<PathBuf>, MergeError> {
    if arg.join(DEFINITION_FILE).is_file() {
        return Ok(vec![arg.to_path_buf()]);
    }
    let mut inside: Vec<PathBuf> = fs::read_dir(arg)
        .map(|entries| {
            entries
                .filter_map(Result::ok)
                .map(|e| e.path())
                .filter(|p| p.join(DEFINITION_FILE).is_file())
                .collect()
        })
        .unwrap_or_default();
    inside.sort();
    if inside.is_empty() {
        return Err(MergeError::NotASweep {
            dir: arg.to_path_buf(),
        });
    }
    Ok(inside)
}

/// Merges the sweep folders `args` into `out` (rows, table, figures); returns the definition,
/// the rows and what was found.
pub fn merge(
    args: &[PathBuf],
    out: &Path,
) -> Result<(Definition, Vec<Row>, MergeReport), MergeError> {
    let mut inputs = Vec::new();
    for arg in args {
        for dir in sweep_folders(arg)? {
            // The output itself may be among the arguments (merging into a shard's parent).
            if !inputs.contains(&dir) && dir != out {
                inputs.push(dir);
            }
        }
    }
    let mut definition: Option<(PathBuf, Definition)> = None;
    let mut found: BTreeMap<usize, Vec<(PathBuf, Row)>> = BTreeMap::new();
    for dir in &inputs {
        let manifest =
            read_manifest(dir)?.ok_or_else(|| MergeError::NotASweep { dir: dir.clone() })?;
        match &definition {
            Some((first, d)) if d.rows_defined() != manifest.definition.rows_defined() => {
                return Err(MergeError::Different {
                    first: first.clone(),
                    other: dir.clone(),
                })
            }
            Some(_) => {}
            None => definition = Some((dir.clone(), manifest.definition.clone())),
        }
        for (point, row) in read_rows(dir, &manifest.definition)? {
            found.entry(point).or_default().push((dir.clone(), row));
        }
    }
    let Some((_, definition)) = definition else {
        return Err(MergeError::NotASweep {
            dir: args.first().cloned().unwrap_or_default(),
        });
    };
    let mut rows = Vec::new();
    let mut sources = Vec::new();
    let mut duplicates = Vec::new();
    for (point, copies) in found {
        if copies.len() > 1 {
            let first = copies[0].1.untimed();
            duplicates.push(Duplicate {
                point: PointId(point),
                dirs: copies.iter().map(|(d, _)| d.clone()).collect(),
                agree: copies.iter().all(|(_, r)| r.untimed() == first),
            });
        }
        if let Some((dir, row)) = copies.into_iter().next() {
            sources.push((dir, row.id()));
            rows.push(row);
        }
    }
    let have: BTreeSet<usize> = rows.iter().map(|r| r.point).collect();
    let missing = (0..definition.points.len())
        .filter(|p| !have.contains(p))
        .map(PointId)
        .collect();
    let _lock = FolderLock::take(out)?;
    for dir in &inputs {
        if let Some(pid) = lock::running_holder(dir) {
            return Err(MergeError::Lock(LockError::Held {
                dir: dir.clone(),
                pid,
            }));
        }
    }
    let store = Store::open(out, &Manifest::new(definition.clone(), None))?;
    for row in &rows {
        store.write_row(row)?;
    }
    for (dir, id) in &sources {
        copy_run(&dir.join(RUNS_DIR).join(id), &out.join(RUNS_DIR).join(id))?;
    }
    store.write_table(&definition, &rows)?;
    super::figures::write_figures(&definition, &rows, out)?;
    let report = MergeReport {
        inputs,
        points: definition.points.len(),
        rows: rows.len(),
        missing,
        duplicates,
    };
    Ok((definition, rows, report))
}

/// Copies a run's kept files (`runs/<id>/` of the input whose row is kept) into the merged
/// folder: into a temporary name, renamed when whole, replacing an earlier copy. A run that
/// kept nothing has no folder, and nothing is copied; a folder already in place (merging into
/// the input itself) is left.
fn copy_run(from: &Path, to: &Path) -> Result<(), MergeError> {
    if !from.is_dir() || from == to {
        return Ok(());
    }
    let partial = to.with_extension("partial");
    let copied = (|| {
        if partial.exists() {
            fs::remove_dir_all(&partial)?;
        }
        copy_tree(from, &partial)?;
        if to.exists() {
            fs::remove_dir_all(to)?;
        }
        fs::rename(&partial, to)
    })();
    copied.map_err(|source| MergeError::CopyRun {
        from: from.to_path_buf(),
        to: to.to_path_buf(),
        source,
    })
}

/// Copies the folder `from` (files and folders in it) to `to`.
fn copy_tree(from: &Path, to: &Path) -> std::io::Result<()> {
    fs::create_dir_all(to)?;
    for entry in fs::read_dir(from)? {
        let entry = entry?;
        let target = to.join(entry.file_name());
        if entry.file_type()?.is_dir() {
            copy_tree(&entry.path(), &target)?;
        } else {
            fs::copy(entry.path(), &target)?;
        }
    }
    Ok(())
}
