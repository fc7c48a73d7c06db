//! `eulerdisk run`: simulate a scene and write the trajectory, the events, the paper's figures
//! and the summary.
//!
//! The outputs are written only after the simulation has ended (or was interrupted), each
//! atomically, so `out/` always holds complete files; an interrupted run still writes what it
//! had, marked as such in `events.csv` and `summary.json`.

pub mod collect;
pub mod model;
pub mod owned;
pub mod progress;
pub mod provenance;
pub mod simulation;

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::RecvTimeoutError;
use std::time::{Duration, Instant};

use crate::analysis::summary::Summary;
use crate::eval::Backend;
use crate::figures::paper::write_paper_figures;
use crate::output::atomic::{write_atomic, write_bytes_atomic, WriteError};
use crate::output::tables::{write_events, write_trajectory};
use crate::quantity::Quantity;
use crate::record::{RunData, StopRecord, Work};
use crate::scene::schema::ModeName;
use crate::scene::Scene;
use collect::{Collector, Sampling};
use progress::Progress;
use provenance::{is_papers_scene, Provenance};
use simulation::Message;

/// How a run reports while it runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProgressStyle {
    /// A progress bar (a terminal).
    Bar,
    /// A plain line every 10% (not a terminal).
    Lines,
    /// Nothing.
    Quiet,
}

/// Options of a run besides the scene.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Output directory.
    pub out_dir: PathBuf,
    /// Progress reporting.
    pub progress: ProgressStyle,
    /// Which models run.
    pub backend: Backend,
    /// Whether to draw the figures.
    pub figures: bool,
    /// How the run is produced (program, scene source, overrides, settings), for
    /// `summary.json`.
    pub provenance: Provenance,
}

/// How a run ended, for the exit code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ending {
    /// The simulation ended by itself (end time, contact lost, ...).
    Completed,
    /// Interrupted by the user; partial results written.
    Interrupted,
    /// The simulation failed or entered a forbidden mode; partial results written.
    Failed,
}

/// What a run produced.
#[derive(Clone, Debug)]
pub struct RunReport {
    /// The summary.
    pub summary: Summary,
    /// How it ended.
    pub ending: Ending,
    /// The files written.
    pub files: Vec<PathBuf>,
}

/// Why a run produced nothing.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The output directory cannot be created.
    #[error("cannot create the output directory {}: {source}", path.display())]
    OutDir {
        /// The directory.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// An output file cannot be written.
    #[error(transparent)]
    Write(#[from] WriteError),
}

/// Runs `scene`; `interrupt` is polled and, once set, the run stops and writes what it has.
pub fn run_scene(
    scene: &Scene,
    opts: &RunOptions,
    interrupt: &AtomicBool,
) -> Result<RunReport, RunError> {
    std::fs::create_dir_all(&opts.out_dir).map_err(|source| RunError::OutDir {
        path: opts.out_dir.clone(),
        source,
    })?;
    let sampling = Sampling::for_rate(scene.file.run.sample_rate);
    let started = Instant::now();
    let choice = model::choose(scene, opts.backend, opts.figures);
    let rx = simulation::start(scene, &choice, sampling.fine_rate());
    let mut progress = Progress::new(opts.progress, scene.file.run.t_end);
    let mut collector = Collector::new(sampling);
    let allowed = &scene.file.modes.allowed;
    let mut outcome = None;
    let mut ending = Ending::Completed;
    let stop;
    loop {
        if interrupt.load(Ordering::SeqCst) {
            ending = Ending::Interrupted;
            stop = Some(abandoned(
                &collector,
                "interrupted",
                "stopped by the user (Ctrl-C)".into(),
            ));
            break;
        }
        match rx.recv_timeout(Duration::from_millis(100)) {
            Ok(Message::Sample(s)) => {
                progress.update(s.t);
                collector.sample(s);
            }
            Ok(Message::Event(e)) => {
                if let Some(f) = collector.event(e, allowed) {
                    ending = Ending::Failed;
                    stop = Some(StopRecord {
                        t: f.t,
                        mode: f.mode,
                        reason: "mode_not_allowed".into(),
                        detail: format!(
                            "the disk entered {} at t = {} s but modes.allowed = {:?}",
                            f.mode,
                            f.t,
                            allowed.iter().map(|m| m.as_str()).collect::<Vec<_>>()
                        ),
                    });
                    break;
                }
            }
            Ok(Message::Done(Ok(o))) => {
                stop = Some(o.stop.clone());
                outcome = Some(o);
                break;
            }
            Ok(Message::Done(Err(message))) => {
                ending = Ending::Failed;
                stop = Some(abandoned(&collector, "error", message));
                break;
            }
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => {
                ending = Ending::Failed;
                stop = Some(abandoned(
                    &collector,
                    "error",
                    "the simulation thread died".into(),
                ));
                break;
            }
        }
    }
    progress.finish();
    let wall_s = started.elapsed().as_secs_f64();
    let mut data = collector.finish();
    data.stop = stop;
    data.work = Work {
        steps: outcome.as_ref().map(|o| o.steps),
        rhs_evals: outcome.as_ref().map(|o| o.rhs_evals),
        wall_s,
    };
    // The drift includes `Z - a sin(theta)`: meaningless where Z is frozen.
    data.constraint_drift_max = outcome
        .as_ref()
        .map(|o| o.constraint_drift_max)
        .filter(|_| choice.computes(Quantity::ResidualZ));
    data.model = choice;
    let (summary, files) = write_outputs(scene, &data, opts)?;
    Ok(RunReport {
        summary,
        ending,
        files,
    })
}

fn abandoned(c: &Collector, reason: &str, detail: String) -> StopRecord {
    StopRecord {
        t: c.latest_t().unwrap_or(0.0),
        mode: c.latest_mode().unwrap_or(ModeName::Rolling),
        reason: reason.to_string(),
        detail,
    }
}

/// `summary.json`: the summary and how the run was produced.
#[derive(serde::Serialize)]
struct SummaryFile<'a> {
    #[serde(flatten)]
    summary: &'a Summary,
    produced_by: &'a Provenance,
}

/// Writes every output of `data` into `opts.out_dir`, after clearing the files an earlier
/// run left there ([`owned`]); returns the summary and the paths written.
pub fn write_outputs(
    scene: &Scene,
    data: &RunData,
    opts: &RunOptions,
) -> Result<(Summary, Vec<PathBuf>), WriteError> {
    let dir: &Path = &opts.out_dir;
    owned::clear_owned(dir)?;
    let mut files = Vec::new();
    let path = dir.join("trajectory.csv");
    write_atomic(&path, |w| {
        write_trajectory(w, &scene.quantities, &data.samples, &scene.params)
    })?;
    files.push(path);
    let stop = data.stop.clone().unwrap_or(StopRecord {
        t: data.samples.last().map_or(0.0, |s| s.t),
        mode: data.samples.last().map_or(ModeName::Rolling, |s| s.mode),
        reason: "unknown".into(),
        detail: String::new(),
    });
    let path = dir.join("events.csv");
    write_atomic(&path, |w| write_events(w, &data.events, &stop))?;
    files.push(path);
    if opts.figures && !data.samples.is_empty() {
        for stem in write_paper_figures(data, &scene.params, dir)? {
            files.push(dir.join(format!("{stem}.png")));
            files.push(dir.join(format!("{stem}.svg")));
        }
    }
    let mut summary = Summary::of(&scene.name, data, &scene.params);
    summary.compared_with_paper = is_papers_scene(scene);
    let path = dir.join("summary.json");
    let file = SummaryFile {
        summary: &summary,
        produced_by: &opts.provenance,
    };
    let json = serde_json::to_string_pretty(&file).map_err(|e| WriteError {
        path: path.clone(),
        source: std::io::Error::other(e),
    })?;
    write_bytes_atomic(&path, format!("{json}\n").as_bytes())?;
    files.push(path);
    Ok((summary, files))
}
