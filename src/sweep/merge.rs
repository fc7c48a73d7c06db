//! `eulerdisk sweep merge DIR...`: the shards' rows joined into one sweep folder.
//!
//! Every input must hold the same sweep (equal definitions); a folder without `sweep.json`
//! stands for the shard folders inside it (`out/shard-0-of-4`, ...). The merged folder is a
//! sweep folder like any other — definition, rows, table, figures — so a sweep started on it
//! runs exactly the missing points. Missing points and points found in more than one input
//! are listed; a duplicate whose rows differ (timing aside) is a conflict.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

use super::expand::{Definition, PointId};
use super::row::Row;
use super::store::{read_manifest, read_rows, Manifest, Store, StoreError, DEFINITION_FILE};

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
            Some((first, d)) if *d != manifest.definition => {
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
        if let Some((_, row)) = copies.into_iter().next() {
            rows.push(row);
        }
    }
    let have: BTreeSet<usize> = rows.iter().map(|r| r.point).collect();
    let missing = (0..definition.points.len())
        .filter(|p| !have.contains(p))
        .map(PointId)
        .collect();
    let store = Store::open(out, &Manifest::new(definition.clone(), None))?;
    for row in &rows {
        store.write_row(row)?;
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
