//! `eulerdisk sweep`: many scenes at once, on one machine or as shards of a cluster job.
//!
//! A sweep file names a base scene and axes over its keys; the stages are one file each:
//!
//! - `spec`: the sweep file's shape (unknown keys rejected by path);
//! - `axes`: an axis' values (explicit, `linspace`, `logspace`, seeded random);
//! - `expand`: the points (grid or zip) and every point's scene, validated by the scene
//!   loader `eulerdisk run` uses, before anything runs;
//! - `shard`: a deterministic share of the points for one job of an array;
//! - `run_point`: one point through `run`'s own code path (the only entry into `crate::run`);
//! - `execute`: the points without a row, on a rayon pool, with per-run timeouts and Ctrl-C;
//! - `row`, `store`: one atomically written row file per finished run, the definition, and
//!   the table rebuilt from the rows (so resuming is "run the points without a row");
//! - `lock`: one sweep at a time in a folder;
//! - `merge`: shards joined, missing and duplicated points listed;
//! - `figures`: each requested key against an axis, and heat maps.
//!
//! Why rows and not an appended CSV: a file renamed into place is whole or absent, so no
//! kill, lost node or full disk can leave half a row, and the table is rebuilt in point order,
//! identical however many workers or shards made it.

mod axes;
pub mod columns;
pub mod execute;
pub mod expand;
mod figures;
pub mod lock;
pub mod merge;
pub mod row;
pub mod run_point;
pub mod shard;
pub mod spec;
pub mod store;

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use execute::{execute, ExecError, ExecOptions, ExecReport};
use expand::Plan;
use store::{Manifest, Store, StoreError};

/// Why a sweep stopped before it was done.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// The folder cannot be used, or running failed.
    #[error(transparent)]
    Exec(#[from] ExecError),
    /// The folder cannot be used.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// Another sweep is running into the folder.
    #[error(transparent)]
    Lock(#[from] lock::LockError),
    /// A figure cannot be written.
    #[error(transparent)]
    Figures(#[from] crate::output::atomic::WriteError),
}

/// What a sweep did.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepReport {
    /// The folder written (`--out`, or the shard's folder inside it).
    pub dir: PathBuf,
    /// The runs.
    pub exec: ExecReport,
    /// The figures drawn (stems).
    pub figures: Vec<String>,
}

/// The folder a sweep (or a shard of it) writes into under `out`.
pub fn sweep_dir(out: &Path, shard: Option<shard::Shard>) -> PathBuf {
    match shard {
        Some(s) => out.join(s.folder()),
        None => out.to_path_buf(),
    }
}

/// Runs `plan` into `out` (a shard into its folder inside `out`), skipping the points that
/// already have a row there; `interrupt` is Ctrl-C.
pub fn run_sweep(
    plan: &Plan,
    out: &Path,
    opts: &ExecOptions,
    interrupt: &AtomicBool,
) -> Result<SweepReport, SweepError> {
    let dir = sweep_dir(out, opts.shard);
    let _lock = lock::FolderLock::take(&dir)?;
    let store = Store::open(&dir, &Manifest::new(plan.definition.clone(), opts.shard))?;
    let exec = execute(plan, &store, opts, interrupt)?;
    // A shard holds part of the points: its figures would mislead; `merge` draws them.
    let figures = if opts.shard.is_none() {
        draw(&plan.definition, &store)?
    } else {
        Vec::new()
    };
    Ok(SweepReport { dir, exec, figures })
}

/// Draws the figures of the rows in `store`.
fn draw(d: &expand::Definition, store: &Store) -> Result<Vec<String>, SweepError> {
    let rows: Vec<row::Row> = store.rows(d)?.into_values().collect();
    Ok(figures::write_figures(d, &rows, store.dir())?)
}
