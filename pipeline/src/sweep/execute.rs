//! Running the points that have no row yet, on every core, each run on its own.
//!
//! A rayon pool of `--jobs` workers takes the points; each worker runs one point at a time
//! (a run is single-threaded), writes its row file the moment it finishes and hands the row
//! to the calling thread, which shows progress and rebuilds `sweep.csv` (at most every
//! [`TABLE_EVERY`], and at the end). A watchdog thread turns the sweep's `timeout_s` and
//! Ctrl-C into the runs' interrupt flags: a run past its time becomes a `timeout` row; a run
//! cut short by Ctrl-C leaves no row, so the next start runs it again.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::sync::{Arc, Mutex, Weak};
use std::time::{Duration, Instant};

use rayon::prelude::*;

use super::columns::scalar_entries;
use super::expand::{Plan, PointId};
use super::row::{PointStop, Row, Status, SweepStop};
use super::run_point::{process_cpu_s, run_point};
use super::shard::Shard;
use super::store::{Store, StoreError, SCRATCH_DIR};
use crate::run::progress::{Bar, Counting, ProgressStyle};
use crate::run::Ending;

/// How often `sweep.csv` is rebuilt while runs finish, at most.
pub const TABLE_EVERY: Duration = Duration::from_secs(1);
/// How often the watchdog looks at the runs.
const WATCH_EVERY: Duration = Duration::from_millis(20);

/// How to execute.
#[derive(Clone, Copy, Debug)]
pub struct ExecOptions {
    /// Runs at once (each single-threaded).
    pub jobs: usize,
    /// Progress reporting.
    pub progress: ProgressStyle,
    /// Which share of the points, if not all.
    pub shard: Option<Shard>,
}

/// What an execution did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ExecReport {
    /// Points of this sweep (or shard).
    pub points: usize,
    /// Points that already had a row and were skipped.
    pub skipped: usize,
    /// Runs that finished now (failures and timeouts included).
    pub ran: usize,
    /// Of those, runs that failed or timed out.
    pub failed: usize,
    /// Whether Ctrl-C stopped the sweep before every point had a row.
    pub interrupted: bool,
}

/// Why execution stopped.
#[derive(Debug, thiserror::Error)]
pub enum ExecError {
    /// The folder cannot be read or written.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// The worker pool cannot start.
    #[error("cannot start {jobs} workers: {message}")]
    Pool {
        /// Workers asked for.
        jobs: usize,
        /// The pool's message.
        message: String,
    },
}

/// One run's stop flag, set by the watchdog on a timeout or on Ctrl-C.
struct RunFlag {
    stop: AtomicBool,
    timed_out: AtomicBool,
    deadline: Option<Instant>,
}

/// Watches the running runs: sets their flags at their deadline or on Ctrl-C.
#[derive(Default)]
struct Watchdog {
    runs: Mutex<Vec<Weak<RunFlag>>>,
}

impl Watchdog {
    fn register(&self, timeout: Option<Duration>) -> Arc<RunFlag> {
        let flag = Arc::new(RunFlag {
            stop: AtomicBool::new(false),
            timed_out: AtomicBool::new(false),
            deadline: timeout.map(|t| Instant::now() + t),
        });
        if let Ok(mut runs) = self.runs.lock() {
            runs.retain(|w| w.strong_count() > 0);
            runs.push(Arc::downgrade(&flag));
        }
        flag
    }

    /// Looks until `done`.
    fn watch(&self, interrupt: &AtomicBool, done: &AtomicBool) {
        while !done.load(Ordering::SeqCst) {
            let now = Instant::now();
            let stop_all = interrupt.load(Ordering::SeqCst);
            if let Ok(runs) = self.runs.lock() {
                for flag in runs.iter().filter_map(Weak::upgrade) {
                    if flag.deadline.is_some_and(|d| now >= d) && !stop_all {
                        flag.timed_out.store(true, Ordering::SeqCst);
                        flag.stop.store(true, Ordering::SeqCst);
                    }
                    if stop_all {
                        flag.stop.store(true, Ordering::SeqCst);
                    }
                }
            }
            std::thread::sleep(WATCH_EVERY);
        }
    }
}

/// Runs every point of `plan` (in `opts.shard`) that has no row in `store` (or a `timeout`
/// row, when the store gives runs more time than before); `interrupt` is Ctrl-C.
pub fn execute(
    plan: &Plan,
    store: &Store,
    opts: &ExecOptions,
    interrupt: &AtomicBool,
) -> Result<ExecReport, ExecError> {
    let d = &plan.definition;
    let mut rows = store.rows(d)?;
    if store.reruns_timeouts() {
        // Given more time than before: the runs that timed out are not done.
        rows.retain(|_, r| r.status != Status::Timeout);
    }
    let mine: Vec<usize> = (0..d.points.len())
        .filter(|&p| Shard::selects(opts.shard, p))
        .collect();
    let todo: Vec<usize> = mine
        .iter()
        .copied()
        .filter(|p| !rows.contains_key(p))
        .collect();
    let mut report = ExecReport {
        points: mine.len(),
        skipped: mine.len() - todo.len(),
        ..ExecReport::default()
    };
    store.write_table(d, rows.values())?;
    let jobs = opts.jobs.max(1);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| ExecError::Pool {
            jobs,
            message: e.to_string(),
        })?;
    let watchdog = Watchdog::default();
    let done = AtomicBool::new(false);
    let halt = AtomicBool::new(false);
    let timeout = d.file.timeout_s.map(Duration::from_secs_f64);
    let mut progress = SweepProgress::new(opts.progress, todo.len());
    let mut first_error = None;
    std::thread::scope(|scope| {
        let (tx, rx) = mpsc::channel::<Result<Row, StoreError>>();
        scope.spawn(|| watchdog.watch(interrupt, &done));
        let workers = scope.spawn(|| {
            pool.install(|| {
                todo.par_iter().for_each_with(tx, |tx, &point| {
                    if interrupt.load(Ordering::SeqCst) || halt.load(Ordering::SeqCst) {
                        return;
                    }
                    let flag = watchdog.register(timeout);
                    if let Some(row) = run_one(plan, store, point, &flag, jobs == 1) {
                        let sent = store.write_row(&row).map(|()| row);
                        let _ = tx.send(sent);
                    }
                });
            })
        });
        let mut last_table = Instant::now();
        for received in rx {
            match received {
                Ok(row) => {
                    report.ran += 1;
                    if row.status != Status::Completed {
                        report.failed += 1;
                    }
                    progress.finished(&row, report.failed);
                    rows.insert(row.point, row);
                    if last_table.elapsed() >= TABLE_EVERY {
                        if let Err(e) = store.write_table(d, rows.values()) {
                            first_error.get_or_insert(e);
                            halt.store(true, Ordering::SeqCst);
                        }
                        last_table = Instant::now();
                    }
                }
                Err(e) => {
                    first_error.get_or_insert(e);
                    halt.store(true, Ordering::SeqCst);
                }
            }
        }
        let _ = workers.join();
        done.store(true, Ordering::SeqCst);
    });
    progress.finish();
    // The scratch folder of runs that keep nothing, once empty.
    let _ = std::fs::remove_dir(store.dir().join(SCRATCH_DIR));
    store.write_table(d, rows.values())?;
    if let Some(e) = first_error {
        return Err(e.into());
    }
    report.interrupted = report.skipped + report.ran < report.points;
    Ok(report)
}

/// Runs one point; `None` when Ctrl-C cut it short (no row: it runs again next time).
fn run_one(plan: &Plan, store: &Store, point: usize, flag: &RunFlag, own_cpu: bool) -> Option<Row> {
    let d = &plan.definition;
    let keep = d.file.keep;
    let dir = store.run_dir(PointId(point), keep);
    let started = Instant::now();
    let cpu0 = process_cpu_s();
    let outcome = run_point(&plan.scenes[point], keep, &dir, &flag.stop);
    let wall_s = started.elapsed().as_secs_f64();
    let cpu_s = own_cpu.then(|| process_cpu_s() - cpu0);
    let timed_out = flag.timed_out.load(Ordering::SeqCst);
    let (status, stop_reason, stop_detail) = match outcome.ending {
        Ending::Interrupted if !timed_out => return None,
        Ending::Interrupted => (
            Status::Timeout,
            PointStop::Sweep(SweepStop::Timeout),
            format!(
                "stopped after timeout_s = {} s at t = {} s",
                d.file.timeout_s.unwrap_or_default(),
                outcome.summary.as_ref().map_or(0.0, |s| s.t_end)
            ),
        ),
        Ending::Completed => (Status::Completed, outcome.stop_reason, outcome.stop_detail),
        Ending::Failed => (Status::Failed, outcome.stop_reason, outcome.stop_detail),
    };
    Some(Row {
        point,
        values: d.points[point].clone(),
        status,
        stop_reason,
        stop_detail,
        summary: outcome
            .summary
            .as_ref()
            .map(scalar_entries)
            .unwrap_or_default(),
        wall_s,
        cpu_s,
    })
}

/// Runs done, failures and ETA: a bar on a terminal, a line per tenth otherwise.
struct SweepProgress {
    style: ProgressStyle,
    total: usize,
    done: usize,
    next_tenth: usize,
    bar: Option<Box<dyn Bar>>,
}

impl SweepProgress {
    fn new(style: ProgressStyle, total: usize) -> SweepProgress {
        let bar = style.bar(total as u64, Counting::Runs);
        if let Some(bar) = &bar {
            bar.show(0, "0 failed");
        }
        SweepProgress {
            style,
            total,
            done: 0,
            next_tenth: 1,
            bar,
        }
    }

    fn finished(&mut self, row: &Row, failed: usize) {
        self.done += 1;
        if let Some(bar) = &self.bar {
            bar.show(self.done as u64, &format!("{failed} failed"));
        }
        if row.status != Status::Completed && !self.style.is_quiet() {
            let line = format!(
                "run {} {}: {} {}",
                row.id(),
                row.status.as_str(),
                row.stop_reason,
                row.stop_detail
            );
            match &self.bar {
                Some(bar) => bar.println(&line),
                None => eprintln!("{line}"),
            }
        }
        if self.style.is_lines() {
            while self.next_tenth <= 10 && self.done * 10 >= self.next_tenth * self.total {
                eprintln!("sweep: {}/{} runs, {failed} failed", self.done, self.total);
                self.next_tenth += 1;
            }
        }
    }

    fn finish(&mut self) {
        if let Some(bar) = &self.bar {
            bar.finish();
        }
    }
}
