//! `eulerdisk run`: simulate a scene and write the trajectory, the events, the paper's figures
//! and the summary.
//!
//! The simulation runs on a worker thread and is asked only for the samples that are kept
//! ([`plan`]); this thread writes `trajectory.csv` row by row as they arrive, so on a machine
//! with two cores the file costs the simulation nothing. After the run the analysis, the
//! figures (rendered on every core) and the small files follow. Every file is written under a
//! temporary name and renamed when complete, so `out/` always holds complete files; an
//! interrupted run still writes what it had, marked as such in `events.csv` and
//! `summary.json`. The split of the time between the four stages goes into the summary.

mod collect;
pub mod model;
mod owned;
pub mod plan;
pub mod progress;
pub mod provenance;
pub mod simulation;
mod trajectory;

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::mpsc::RecvTimeoutError;
use std::time::{Duration, Instant};

use crate::analysis::extrema::Located;
use crate::analysis::summary::Summary;
use crate::eval::Backend;
use crate::figures::paper::{write_paper_figures, FIGURE_STEMS};
use crate::output::atomic::{write_bytes_atomic, WriteError};
use crate::output::files::write_table;
use crate::output::tables::events_table;
use crate::record::{RunData, Timings};
use crate::scene::Scene;
use collect::Collector;
use equations::record::Quantity;
use equations::record::{Sample, Stop, StopKind};
use equations::Mode;
use model::ModelChoice;
use plan::SamplePlan;
use progress::{Progress, ProgressStyle};
use provenance::{is_papers_scene, Provenance};
use simulation::{Failure, Message, Outcome};
pub use trajectory::TrajectoryFile;

/// Options of a run besides the scene.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Output directory.
    pub out_dir: PathBuf,
    /// Progress reporting.
    pub progress: ProgressStyle,
    /// Which models run.
    pub backend: Backend,
    /// Which engine runs them ([`model::DEFAULT_ENGINE`] unless asked otherwise).
    pub engine: model::EngineChoice,
    /// Whether to draw the figures.
    pub figures: bool,
    /// Whether to write `trajectory.csv` (a sweep that keeps only summaries does not: the
    /// samples are still collected for the summary).
    pub trajectory: bool,
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
    /// What the run recorded (samples, events, extrema, stop), for a caller that keeps it in
    /// memory rather than reading the files back.
    pub data: RunData,
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

/// Runs `scene`; once `interrupt` is set, the simulation stops at its next step and the run
/// writes what it has.
pub fn run_scene(
    scene: &Scene,
    opts: &RunOptions,
    interrupt: &AtomicBool,
) -> Result<RunReport, RunError> {
    std::fs::create_dir_all(&opts.out_dir).map_err(|source| RunError::OutDir {
        path: opts.out_dir.clone(),
        source,
    })?;
    // Files an earlier run left here go first (module `owned`): the new ones, the trajectory
    // among them, are being written from the start.
    owned::clear_owned(&opts.out_dir)?;
    let started = Instant::now();
    let choice = model::choose(scene, opts.backend, opts.figures).on_engine(opts.engine, scene);
    let file = opts
        .trajectory
        .then(|| {
            TrajectoryFile::create(
                &opts.out_dir,
                scene.file.cli.output.format,
                &scene.quantities,
                scene.params,
            )
        })
        .transpose()?;
    let mut progress = Progress::new(opts.progress, scene.file.settings.run.t_end);
    let simulated = simulate(scene, choice, interrupt, &mut progress, file, started);
    progress.finish();
    let Simulated {
        run: SceneRun { data, ending },
        file,
        timings,
    } = simulated?;
    let (summary, files) = write_outputs(scene, &data, opts, file, timings, started, interrupt)?;
    // An interrupt while the figures were drawn: the run ends as interrupted, its data complete.
    let ending = if summary.figures_not_drawn.is_empty() {
        ending
    } else {
        Ending::Interrupted
    };
    Ok(RunReport {
        summary,
        ending,
        files,
        data,
    })
}

/// How a run that ended with `stop` ended, for the exit code.
fn ending_of(stop: &Stop) -> Ending {
    match stop.kind {
        StopKind::Interrupted => Ending::Interrupted,
        kind if kind.is_failure() => Ending::Failed,
        _ => Ending::Completed,
    }
}

/// What one pass of the simulation left: the data (with its stop record), the simulation's
/// outcome if it ended by itself, and the trajectory file, complete but not committed.
pub struct Recorded {
    /// Samples, events and the stop.
    pub data: RunData,
    /// The simulation's outcome (`None` when it failed).
    pub outcome: Option<Outcome>,
    /// `trajectory.csv`, if it was written.
    pub file: Option<TrajectoryFile>,
}

/// The scene's sampling: from 0 to its end time at its rate, finer in its windows.
fn scene_plan(scene: &Scene) -> SamplePlan {
    let run = &scene.file.settings.run;
    SamplePlan::new(0.0, run.t_end, run.sample_rate).with_windows(&scene.file.cli.output.windows)
}

/// A scene's run in memory: its data (samples, events, stop, work) and how it ended.
#[derive(Debug)]
pub struct SceneRun {
    /// Samples, both fine windows, events, extrema, the stop and the work done.
    pub data: RunData,
    /// How it ended.
    pub ending: Ending,
}

/// Runs `scene` once in memory, as a front end other than the command line wants it: the
/// models `backend` chooses for the scene's quantities, the scene's sampling, no file, no
/// progress, no figures. [`run_scene`] is the same run with the files of `eulerdisk run`.
/// Once `interrupt` is set, the simulation stops at its next step.
pub fn simulate_scene(
    scene: &Scene,
    backend: Backend,
    interrupt: &AtomicBool,
) -> Result<SceneRun, WriteError> {
    let choice = model::choose(scene, backend, false);
    let mut quiet = Progress::new(ProgressStyle::Quiet, scene.file.settings.run.t_end);
    let started = Instant::now();
    simulate(scene, choice, interrupt, &mut quiet, None, started).map(|simulated| simulated.run)
}

/// A run simulated, with the trajectory file (complete, not committed) and the time spent.
struct Simulated {
    run: SceneRun,
    file: Option<TrajectoryFile>,
    timings: Timings,
}

/// The simulation of `scene` with the models of `choice` (in one pass: the last second of an
/// early stop is sampled from the steps the run kept), and the work and drift filled in.
fn simulate(
    scene: &Scene,
    choice: ModelChoice,
    interrupt: &AtomicBool,
    progress: &mut Progress,
    file: Option<TrajectoryFile>,
    started: Instant,
) -> Result<Simulated, WriteError> {
    let plan = scene_plan(scene);
    let recorded = record(scene, &choice, plan, interrupt, progress, file);
    let Recorded {
        mut data,
        outcome,
        file,
    } = recorded?;
    let timings = Timings {
        simulation_s: started.elapsed().as_secs_f64(),
        ..Timings::default()
    };
    let stop = data.stop.clone().expect("a recorded run has a stop");
    let ending = ending_of(&stop);
    data.work.wall_s = timings.simulation_s;
    // The drift includes `Z - a sin(theta)`: meaningless where Z is frozen.
    data.constraint_drift_max = outcome
        .as_ref()
        .map(|o| o.constraint_drift_max)
        .filter(|_| choice.computes(Quantity::ResidualZ));
    data.model = choice;
    Ok(Simulated {
        run: SceneRun { data, ending },
        file,
        timings,
    })
}

/// Runs the simulation of `scene` once, keeping what `plan` asks for and writing the
/// trajectory into `file` as it comes.
pub fn record(
    scene: &Scene,
    choice: &ModelChoice,
    plan: SamplePlan,
    interrupt: &AtomicBool,
    progress: &mut Progress,
    file: Option<TrajectoryFile>,
) -> Result<Recorded, WriteError> {
    let mut collector = Collector::new(plan.clone());
    if let Some(file) = file {
        collector = collector.writing(file);
    }
    let ended = if collector.writes_file() || progress.shows() {
        // Two threads: the simulation on one, writing and progress on the other.
        std::thread::scope(|scope| {
            let rx = simulation::start(scope, scene, choice, plan, interrupt);
            collect(&rx, &mut collector, progress)
        })?
    } else {
        // Nothing to overlap (a sweep's quiet run without a trajectory): one thread, so that
        // parallel runs each keep one core.
        let mut inline = Inline {
            collector: &mut collector,
            error: None,
        };
        let result = simulation::simulate_into(scene, choice, plan, interrupt, &mut inline);
        if let Some(e) = inline.error {
            return Err(e);
        }
        Ended::of(result, &collector)
    };
    let Ended {
        outcome,
        stop,
        steps,
        rhs_evals,
        last_state,
    } = ended;
    let (mut data, file) = collector.finish(outcome.as_ref().map(|o| o.last))?;
    data.stop = Some(stop);
    data.last_state = last_state;
    // A failed run reports the work it did too.
    data.work.steps = steps;
    data.work.rhs_evals = rhs_evals;
    Ok(Recorded {
        data,
        outcome,
        file,
    })
}

/// The simulation's stream taken straight into a collector on the same thread.
struct Inline<'a> {
    collector: &'a mut Collector,
    error: Option<WriteError>,
}

impl simulation::Outlet for &mut Inline<'_> {
    fn deliver(&mut self, m: Message) -> bool {
        let written = match m {
            Message::Samples(batch) => batch.into_iter().try_for_each(|s| self.collector.sample(s)),
            Message::Event(e) => {
                self.collector.event(e);
                Ok(())
            }
            Message::Extrema(batch) => {
                self.collector.extrema(batch);
                Ok(())
            }
            Message::LastSecond(samples) => {
                self.collector.last_second(samples);
                Ok(())
            }
            Message::Done(_) => Ok(()),
        };
        match written {
            Ok(()) => true,
            Err(e) => {
                self.error = Some(e);
                false
            }
        }
    }
}

/// Receives the worker's stream into `collector` until the simulation ends. A write error
/// leaves the loop at once; dropping the receiver then makes the worker's sends fail, and
/// its observer stops the simulation at the next step.
fn collect(
    rx: &std::sync::mpsc::Receiver<Message>,
    collector: &mut Collector,
    progress: &mut Progress,
) -> Result<Ended, WriteError> {
    Ok(loop {
        match rx.recv_timeout(Duration::from_millis(100)) {
            Ok(Message::Samples(batch)) => {
                if let Some(last) = batch.last() {
                    progress.update(last.t);
                }
                for s in batch {
                    collector.sample(s)?;
                }
            }
            Ok(Message::Event(e)) => collector.event(e),
            Ok(Message::Extrema(batch)) => collector.extrema(batch),
            Ok(Message::LastSecond(samples)) => collector.last_second(samples),
            Ok(Message::Done(done)) => break Ended::of(*done, collector),
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => {
                let why = "the simulation thread died".to_string();
                break Ended {
                    outcome: None,
                    stop: abandoned(collector, why, None, None),
                    steps: None,
                    rhs_evals: None,
                    last_state: None,
                };
            }
        }
    })
}

/// How the simulation ended: its outcome (`None` when it failed), the stop record, the
/// work it reported (`None` when it reported none: its thread died) and, when it failed, the
/// last state it reached.
struct Ended {
    outcome: Option<Outcome>,
    stop: Stop,
    steps: Option<u64>,
    rhs_evals: Option<u64>,
    last_state: Option<Sample>,
}

impl Ended {
    /// The simulation's result, a failure stopped where `collector` last heard of the run.
    fn of(result: Result<Outcome, Failure>, collector: &Collector) -> Ended {
        match result {
            Ok(o) => Ended {
                stop: o.stop.clone(),
                steps: Some(o.steps),
                rhs_evals: Some(o.rhs_evals),
                outcome: Some(o),
                last_state: None,
            },
            Err(failure) => Ended {
                outcome: None,
                stop: abandoned(
                    collector,
                    failure.message,
                    failure.t,
                    failure.last.as_deref(),
                ),
                steps: Some(failure.steps),
                rhs_evals: Some(failure.rhs_evals),
                last_state: failure.last.map(|s| *s),
            },
        }
    }
}

/// The stop of a run that failed without an outcome, dated at `t` (the failure's own time),
/// at its last accepted state `last` or where the collector last heard of it, whichever is
/// latest; in the mode of the latest of those it knows.
fn abandoned(c: &Collector, detail: String, t: Option<f64>, last: Option<&Sample>) -> Stop {
    let heard = c.latest_t().unwrap_or(0.0);
    let reached = last.map_or(heard, |s| s.t.max(heard));
    let mode = (last.filter(|s| s.t >= heard).map(|s| s.mode))
        .or(c.latest_mode())
        .unwrap_or(Mode::Rolling);
    Stop::failed(
        t.filter(|t| t.is_finite())
            .map_or(reached, |t| t.max(reached)),
        mode,
        detail,
    )
}

/// `summary.json`: the summary and how the run was produced.
#[derive(serde::Serialize)]
struct SummaryFile<'a> {
    #[serde(flatten)]
    summary: &'a Summary,
    produced_by: &'a Provenance,
}

/// Writes every output of `data` into `opts.out_dir` (the trajectory, streamed during the
/// run, is committed here); returns the summary and the paths written. Once `interrupt` is
/// set, no further figure is started (the data files and `summary.json` are still written,
/// the summary listing the figures left undrawn).
pub fn write_outputs(
    scene: &Scene,
    data: &RunData,
    opts: &RunOptions,
    trajectory: Option<TrajectoryFile>,
    mut timings: Timings,
    started: Instant,
    interrupt: &AtomicBool,
) -> Result<(Summary, Vec<PathBuf>), WriteError> {
    let dir: &Path = &opts.out_dir;
    let lap = |since: &mut f64| {
        let now = started.elapsed().as_secs_f64();
        let spent = now - *since;
        *since = now;
        spent
    };
    let mut clock = started.elapsed().as_secs_f64();
    let mut files = Vec::new();
    let format = scene.file.cli.output.format;
    let trajectory = match trajectory {
        Some(file) => Some(file),
        None if opts.trajectory => {
            let mut file = TrajectoryFile::create(dir, format, &scene.quantities, scene.params)?;
            data.samples.iter().try_for_each(|s| file.row(s))?;
            Some(file)
        }
        None => None,
    };
    if let Some(file) = trajectory {
        file.commit()?;
        files.push(dir.join(format.file(trajectory::STEM)));
    }
    files.push(write_table(
        &events_table(&data.events, data.stop.as_ref()),
        dir,
        "events",
        format,
    )?);
    let located = Located::new(&data.extrema, scene.params.weight());
    files.push(write_table(&located.table(), dir, "extrema", format)?);
    timings.outputs_s = lap(&mut clock);
    let mut summary = Summary::of(&scene.name, data, &scene.params);
    summary.compared_with_paper = is_papers_scene(scene);
    timings.analysis_s = lap(&mut clock);
    let path = dir.join("summary.json");
    if opts.figures && !data.samples.is_empty() {
        // The summary first, as if no figure were drawn: a second Ctrl-C while they are
        // drawn quits at once, and leaves a complete summary that says which are missing.
        let mut provisional = summary.clone();
        provisional.figures_not_drawn = FIGURE_STEMS.iter().map(|s| s.to_string()).collect();
        provisional.timings = timings;
        write_summary(&path, &provisional, data, opts)?;
        if !opts.progress.is_quiet() {
            eprintln!("drawing the figures (Ctrl-C skips the rest)");
        }
        let paper = summary.compared_with_paper;
        let figures = write_paper_figures(data, &scene.params, paper, dir, interrupt)?;
        for stem in figures.drawn {
            files.push(dir.join(format!("{stem}.png")));
            files.push(dir.join(format!("{stem}.svg")));
        }
        summary.figures_not_drawn = figures.not_drawn;
    }
    timings.figures_s = lap(&mut clock);
    timings.total_s = clock;
    summary.timings = timings;
    write_summary(&path, &summary, data, opts)?;
    files.push(path);
    Ok((summary, files))
}

/// Writes `summary` with the run's provenance to `path` (`summary.json`), atomically; the
/// engine named is the one that ran `data`.
fn write_summary(
    path: &Path,
    summary: &Summary,
    data: &RunData,
    opts: &RunOptions,
) -> Result<(), WriteError> {
    let produced_by = Provenance {
        engine: data.model.engine.name().to_string(),
        ..opts.provenance.clone()
    };
    let file = SummaryFile {
        summary,
        produced_by: &produced_by,
    };
    let json = serde_json::to_string_pretty(&file).map_err(|e| WriteError {
        path: path.to_path_buf(),
        source: std::io::Error::other(e),
    })?;
    write_bytes_atomic(path, format!("{json}\n").as_bytes())
}
