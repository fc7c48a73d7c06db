//! One point of a sweep, run through exactly the code `eulerdisk run` uses.
//!
//! This is the sweep's only entry into `crate::run`: [`run_scene`] with the options of
//! `eulerdisk run --quiet --no-figures --out <the run's folder>` (figures only when the sweep
//! keeps `all`). Same scene, same function, same options: the same numbers, bit for bit. What
//! the sweep does not keep is deleted afterwards. A panic inside a run is caught and becomes
//! that run's failure, never the sweep's end.

use std::fs;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::sync::atomic::AtomicBool;

use super::row::{PointStop, SweepStop};
use super::spec::Keep;
use crate::analysis::summary::Summary;
use crate::eval::DEFAULT_BACKEND;
use crate::output::format::TableFormat;
use crate::run::progress::ProgressStyle;
use crate::run::provenance::Provenance;
use crate::run::{run_scene, Ending, RunOptions};
use crate::scene::Scene;
use equations::record::{Stop, StopKind};

/// How one run ended, before the sweep decides what that means (a timeout or Ctrl-C).
#[derive(Clone, Debug, PartialEq)]
pub struct PointOutcome {
    /// The run's own ending (`Interrupted` when its interrupt flag was set).
    pub ending: Ending,
    /// The stop reason (`end_time`, `error`, `output_error`, `panic`, ...).
    pub stop_reason: PointStop,
    /// Its details.
    pub stop_detail: String,
    /// The summary, when the run got as far as writing one.
    pub summary: Option<Summary>,
}

/// The options `eulerdisk run` would get for this run. Its provenance names the base scene;
/// the point's own values are in its resolved settings (and in `sweep.json`).
pub fn run_options(scene: &Scene, dir: &Path, keep: Keep) -> RunOptions {
    let format = scene.file.cli.output.format;
    RunOptions {
        out_dir: dir.to_path_buf(),
        progress: ProgressStyle::Quiet,
        backend: DEFAULT_BACKEND,
        engine: crate::run::model::DEFAULT_ENGINE,
        figures: keep == Keep::All,
        trajectory: keep.files(format).contains(&format.file("trajectory")),
        provenance: Provenance::new(scene, &scene.name, &[]),
    }
}

/// Runs `scene` into `dir`, keeps what `keep` says there (removing `dir` when nothing), and
/// stops early once `interrupt` is set.
pub fn run_point(scene: &Scene, keep: Keep, dir: &Path, interrupt: &AtomicBool) -> PointOutcome {
    // A folder left by an earlier, killed attempt of this point must not leak into this one.
    let _ = fs::remove_dir_all(dir);
    let opts = run_options(scene, dir, keep);
    let result = catch_unwind(AssertUnwindSafe(|| run_scene(scene, &opts, interrupt)));
    let outcome = match result {
        Ok(Ok(report)) => {
            // A report without a stop would be a run that never ended: an error of the run.
            let stop = report.data.stop.clone().unwrap_or_else(|| Stop {
                kind: StopKind::Error,
                ..Stop::failed(
                    report.summary.t_end,
                    equations::Mode::Rolling,
                    String::new(),
                )
            });
            PointOutcome {
                ending: report.ending,
                stop_reason: PointStop::Run(stop.kind),
                stop_detail: stop.detail,
                summary: Some(report.summary),
            }
        }
        Ok(Err(e)) => failure(SweepStop::OutputError, e.to_string()),
        Err(panic) => {
            let message = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "a panic without a message".into());
            failure(SweepStop::Panic, message)
        }
    };
    tidy(dir, keep, scene.file.cli.output.format);
    outcome
}

fn failure(reason: SweepStop, detail: String) -> PointOutcome {
    PointOutcome {
        ending: Ending::Failed,
        stop_reason: PointStop::Sweep(reason),
        stop_detail: detail,
        summary: None,
    }
}

/// Deletes what the sweep does not keep of a run's folder.
fn tidy(dir: &Path, keep: Keep, format: TableFormat) {
    match keep {
        Keep::None => {
            let _ = fs::remove_dir_all(dir);
        }
        Keep::All => {}
        Keep::Summary | Keep::Events => {
            let kept = keep.files(format);
            let written = ["trajectory", "events", "extrema"].map(|stem| format.file(stem));
            for file in written.iter().filter(|f| !kept.contains(f)) {
                let _ = fs::remove_file(dir.join(file));
            }
        }
    }
}

/// CPU time of the whole process so far (s).
pub fn process_cpu_s() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec; the clock id is a constant of the platform.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    if rc == 0 {
        ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
    } else {
        f64::NAN
    }
}
