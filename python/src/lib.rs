//! `eulerdisk._native`: the compiled half of the Python package.
//!
//! The Python half (`eulerdisk/__init__.py`) gives the public API, its types and docstrings;
//! this module only moves data across: arguments in as the command line's own strings
//! (`TABLE.KEY=VALUE`, `NAME=VALUE`), so every check and every message is the command's,
//! and results out as plain Python objects, each sampled column as one `bytes` object that
//! NumPy views without a copy.
//!
//! Long work (a run, a sweep, a solve) runs on a worker thread while the calling thread,
//! with the GIL released, waits in slices of [`SLICE`]: between slices it takes the GIL
//! back to let Python handle signals, so Ctrl-C sets the run's cancellation flag and raises
//! `KeyboardInterrupt` once the worker has stopped, within a second; other Python threads
//! run meanwhile. Python's signal handlers run in the main thread only, so a call on another
//! thread (a worker of `Model.solve_many`, a sweep's shard on a thread pool) is stopped
//! through a [`Cancel`] token instead, which the main thread sets on Ctrl-C.

mod bridge;

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Mutex};
use std::time::Duration;

use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyBytes, PyDict, PyType};

use model_interpreted::DENSE_NODES;

use bridge::{FileModel, LoadedScene, RunRequest, SceneSource, SolveRequest, SweepSource};

create_exception!(
    eulerdisk,
    SceneError,
    PyValueError,
    "A scene that cannot be run: the command line's message, and in `key` the scene key it is about (`table.key`), or None."
);
create_exception!(
    eulerdisk,
    DslError,
    PyValueError,
    "A model file with errors: the message locates each (`file:line:col`) and shows the line with a caret."
);
create_exception!(
    eulerdisk,
    ModelInputError,
    PyValueError,
    "An unusable argument of `Model.eval` or `Model.solve`: an unknown name, a missing parameter, a bad event or setting."
);
create_exception!(
    eulerdisk,
    SolveError,
    PyRuntimeError,
    "A model that could not be evaluated or integrated (a singular pivot, a non-finite value, a failed step)."
);
create_exception!(
    eulerdisk,
    SweepError,
    PyValueError,
    "A sweep that cannot be run: the command line's message."
);
create_exception!(
    eulerdisk,
    RunError,
    PyRuntimeError,
    "A run whose outputs could not be written."
);

/// How long the calling thread waits, without the GIL, between two looks at its signals.
const SLICE: Duration = Duration::from_millis(50);

/// Runs `work` on a worker thread; the calling thread releases the GIL and checks Python's
/// signals every [`SLICE`]. A signal handler's exception (`KeyboardInterrupt`) sets the flag
/// `work` watches, waits for it to stop, and is returned. A `cancel` token set (before or
/// during the call) sets the flag too, and `work`'s result, stopped at its next step, is
/// returned: the caller that set the token knows.
fn interruptible<T: Send>(
    py: Python<'_>,
    cancel: Option<&Cancel>,
    work: impl FnOnce(&AtomicBool) -> T + Send,
) -> PyResult<T> {
    let cancelled = || cancel.is_some_and(|c| c.flag.load(Ordering::SeqCst));
    let interrupt = AtomicBool::new(cancelled());
    let (done_tx, done_rx) = mpsc::channel::<()>();
    // Shared with the GIL-free waits, which need a `Sync` handle on the receiver.
    let done_rx = Mutex::new(done_rx);
    std::thread::scope(|scope| {
        let flag = &interrupt;
        let worker = scope.spawn(move || {
            let result = work(flag);
            let _ = done_tx.send(());
            result
        });
        let mut raised = None;
        loop {
            let finished = py.detach(|| {
                let rx = done_rx
                    .lock()
                    .unwrap_or_else(|poisoned| poisoned.into_inner());
                match rx.recv_timeout(SLICE) {
                    Ok(()) | Err(mpsc::RecvTimeoutError::Disconnected) => true,
                    Err(mpsc::RecvTimeoutError::Timeout) => false,
                }
            });
            if finished {
                break;
            }
            if cancelled() {
                interrupt.store(true, Ordering::SeqCst);
            }
            if let Err(signal) = py.check_signals() {
                interrupt.store(true, Ordering::SeqCst);
                raised = Some(signal);
                break;
            }
        }
        let joined = py.detach(|| worker.join());
        match (raised, joined) {
            (Some(signal), _) => Err(signal),
            (None, Ok(result)) => Ok(result),
            (None, Err(_)) => Err(PyRuntimeError::new_err(
                "the simulation's worker thread panicked",
            )),
        }
    })
}

fn scene_error(py: Python<'_>, error: &eulerdisk::SceneError) -> PyErr {
    let err = SceneError::new_err(error.to_string());
    let key = bridge::scene_error_key(error);
    if let Err(e) = err.value(py).setattr("key", key) {
        return e;
    }
    err
}

fn model_error(error: &eulerdisk::ModelFileError) -> PyErr {
    let message = error.to_string();
    if bridge::is_dsl_error(error) {
        DslError::new_err(message)
    } else if bridge::is_failure(error) {
        SolveError::new_err(message)
    } else {
        ModelInputError::new_err(message)
    }
}

/// One column of numbers as the bytes of native `f64`s (NumPy views them with `frombuffer`).
fn column<'py>(
    py: Python<'py>,
    n: usize,
    value: impl Fn(usize) -> f64,
) -> PyResult<Bound<'py, PyBytes>> {
    PyBytes::new_with(py, n * 8, |bytes| {
        for (i, chunk) in bytes.chunks_exact_mut(8).enumerate() {
            chunk.copy_from_slice(&value(i).to_ne_bytes());
        }
        Ok(())
    })
}

/// Native `f64`s from their bytes (NumPy's `tobytes()`); a trailing partial number is
/// ignored (the Python side passes whole arrays).
fn floats(bytes: &[u8]) -> Vec<f64> {
    (bytes.chunks_exact(8))
        .map(|chunk| f64::from_ne_bytes(chunk.try_into().expect("chunks of 8 bytes")))
        .collect()
}

/// Loads a scene and checks it; raises `SceneError` as `eulerdisk run` would fail.
fn load(
    py: Python<'_>,
    scene: String,
    toml: Option<String>,
    sets: &[String],
) -> PyResult<LoadedScene> {
    let source = match toml {
        Some(toml) => SceneSource::Text { name: scene, toml },
        None => SceneSource::Named(scene),
    };
    bridge::scene(&source, sets).map_err(|e| scene_error(py, &e))
}

/// A flag that stops a call running on another thread at its next step: `cancel.set()`, then
/// the call returns what it computed (a solve stopped as `interrupted`, a sweep with its
/// complete runs). It pickles as a fresh token (a process of its own cannot see this one).
#[pyclass(frozen, module = "eulerdisk._native")]
struct Cancel {
    flag: AtomicBool,
}

#[pymethods]
impl Cancel {
    #[new]
    fn new() -> Self {
        Cancel {
            flag: AtomicBool::new(false),
        }
    }

    /// Stops the calls that watch this token, at their next step.
    fn set(&self) {
        self.flag.store(true, Ordering::SeqCst);
    }

    /// Whether the token was set.
    fn is_set(&self) -> bool {
        self.flag.load(Ordering::SeqCst)
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> (Bound<'py, PyType>, ()) {
        (slf.get_type(), ())
    }
}

/// Runs a scene as `eulerdisk run` does, writing its small files into `out_dir`; returns the
/// sampled columns and how the run ended.
#[pyfunction]
#[pyo3(signature = (scene, toml, sets, out_dir, progress, trajectory_file, figures))]
#[allow(clippy::too_many_arguments)]
fn run<'py>(
    py: Python<'py>,
    scene: String,
    toml: Option<String>,
    sets: Vec<String>,
    out_dir: PathBuf,
    progress: bool,
    trajectory_file: bool,
    figures: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let loaded = load(py, scene, toml, &sets)?;
    let request = RunRequest {
        out_dir: &out_dir,
        progress,
        trajectory_file,
        figures,
    };
    let report = interruptible(py, None, |interrupt| {
        bridge::run(&loaded, &request, interrupt)
    })?
    .map_err(RunError::new_err)?;
    let samples = &report.data.samples;
    let n = samples.len();
    let params = &loaded.scene.params;
    let columns = PyDict::new(py);
    columns.set_item("t", column(py, n, |i| samples[i].t)?)?;
    for q in &loaded.scene.quantities {
        columns.set_item(q.name(), column(py, n, |i| q.value(&samples[i], params))?)?;
    }
    let mut mode_names: Vec<String> = Vec::new();
    let mut codes = Vec::with_capacity(n);
    for s in samples {
        let name = s.mode.to_string();
        let code = match mode_names.iter().position(|m| *m == name) {
            Some(k) => k,
            None => {
                mode_names.push(name);
                mode_names.len() - 1
            }
        };
        codes.push(code as u8);
    }
    let out = PyDict::new(py);
    out.set_item("columns", columns)?;
    out.set_item("mode_codes", PyBytes::new(py, &codes))?;
    out.set_item("mode_names", mode_names)?;
    out.set_item("ending", format!("{:?}", report.ending).to_lowercase())?;
    out.set_item("provenance", serde_json::to_string(&loaded.provenance).ok())?;
    Ok(out)
}

/// The name of the scene `eulerdisk run` runs when none is given.
#[pyfunction]
fn default_scene() -> &'static str {
    bridge::default_scene()
}

/// Runs a sweep into `out` as `eulerdisk sweep` does, or shard `(index, count)` of it as
/// `--shard index/count` does; returns the path of its table and the counts of the runs.
/// `cancel` set stops it as Ctrl-C does (complete runs kept).
#[pyfunction]
#[pyo3(signature = (sweep, toml, folder, sets, out, jobs, progress, shard=None, cancel=None))]
#[allow(clippy::too_many_arguments)]
fn sweep<'py>(
    py: Python<'py>,
    sweep: String,
    toml: Option<String>,
    folder: Option<PathBuf>,
    sets: Vec<String>,
    out: PathBuf,
    jobs: usize,
    progress: bool,
    shard: Option<(usize, usize)>,
    cancel: Option<Bound<'py, Cancel>>,
) -> PyResult<Bound<'py, PyDict>> {
    let source = match toml {
        Some(toml) => SweepSource::Text {
            name: sweep,
            toml,
            folder,
        },
        None => SweepSource::Named(sweep),
    };
    let cancel = cancel.as_ref().map(|c| c.get());
    let report = interruptible(py, cancel, |interrupt| {
        bridge::sweep(&source, &sets, (&out, shard), jobs, progress, interrupt)
    })?
    .map_err(SweepError::new_err)?;
    let e = report.exec;
    let out = PyDict::new(py);
    out.set_item("table", bridge::sweep_table(&report.dir))?;
    out.set_item("points", e.points)?;
    out.set_item("skipped", e.skipped)?;
    out.set_item("ran", e.ran)?;
    out.set_item("failed", e.failed)?;
    out.set_item("interrupted", e.interrupted)?;
    Ok(out)
}

/// Joins sweep folders (shards) into `out` as `eulerdisk sweep merge` does; returns the path
/// of its table and the counts of points, rows, missing and duplicated points.
#[pyfunction]
fn merge_sweep<'py>(
    py: Python<'py>,
    dirs: Vec<PathBuf>,
    out: PathBuf,
) -> PyResult<Bound<'py, PyDict>> {
    let merged = py
        .detach(|| bridge::merge_sweep(&dirs, &out))
        .map_err(SweepError::new_err)?;
    let report = PyDict::new(py);
    report.set_item("table", bridge::sweep_table(&out))?;
    report.set_item("points", merged.points)?;
    report.set_item("rows", merged.rows)?;
    report.set_item("missing", merged.missing)?;
    report.set_item("duplicates", merged.duplicates)?;
    Ok(report)
}

/// A compiled model file (the Python class `eulerdisk.Model` wraps it).
#[pyclass(frozen, module = "eulerdisk._native")]
struct NativeModel {
    model: FileModel,
    /// Whether the compiled models came from the cache.
    cache_hit: bool,
}

#[pymethods]
impl NativeModel {
    /// Compiles the model file at `path` (through the user's cache of compiled models when
    /// `cache`).
    #[staticmethod]
    #[pyo3(signature = (path, cache=true))]
    fn from_file(py: Python<'_>, path: PathBuf, cache: bool) -> PyResult<NativeModel> {
        let (model, cache_hit) = py
            .detach(|| FileModel::from_file(&path, cache))
            .map_err(|e| model_error(&e))?;
        Ok(NativeModel { model, cache_hit })
    }

    /// Compiles a model given as text; `name` stands for the file in messages (through the
    /// cache when `cache`).
    #[staticmethod]
    #[pyo3(signature = (name, text, cache=true))]
    fn from_text(py: Python<'_>, name: String, text: String, cache: bool) -> PyResult<NativeModel> {
        let (model, cache_hit) = py
            .detach(|| FileModel::from_text(&name, &text, cache))
            .map_err(|e| model_error(&e))?;
        Ok(NativeModel { model, cache_hit })
    }

    /// Whether the compiled models came from the cache (nothing was compiled).
    #[getter]
    fn cache_hit(&self) -> bool {
        self.cache_hit
    }

    /// The model's name.
    #[getter]
    fn name(&self) -> &str {
        self.model.name()
    }

    /// The states, in order.
    #[getter]
    fn states(&self) -> Vec<String> {
        self.model.first().states.clone()
    }

    /// The parameters with their defaults (None: required).
    #[getter]
    fn params(&self) -> Vec<(String, Option<f64>)> {
        self.model.first().params.clone()
    }

    /// The outputs, in order.
    #[getter]
    fn outputs(&self) -> Vec<String> {
        self.model.first().outputs.clone()
    }

    /// The charts' names.
    #[getter]
    fn charts(&self) -> Vec<String> {
        self.model.charts()
    }

    /// The modes' names (a switched model).
    #[getter]
    fn modes(&self) -> Vec<String> {
        self.model.modes()
    }

    /// The solved equations (`latex`: LaTeX, else Markdown).
    fn show(&self, latex: bool) -> String {
        self.model.show(latex)
    }

    /// The derivatives and outputs at one point (JSON).
    #[pyo3(signature = (chart, t, state, sets))]
    fn eval(
        &self,
        chart: Option<String>,
        t: f64,
        state: Vec<String>,
        sets: Vec<String>,
    ) -> PyResult<String> {
        (self.model)
            .eval(chart.as_deref(), t, &state, &sets)
            .map_err(|e| model_error(&e))
    }

    /// Integrates the model; returns the header, the number of states, the table (its
    /// columns one after another, native `f64`s in a `bytearray`), the
    /// events, the stop, the work counters, the notes and (with `dense`) every step's dense
    /// output. `times` are native `f64` bytes. `cancel` set stops it at its next step (its
    /// stop then `interrupted`).
    #[pyo3(signature = (chart, state, sets, events, t0, t_end, dt, times, method, rtol, atol, first_step, max_step, dense, cancel=None))]
    #[allow(clippy::too_many_arguments)]
    fn solve<'py>(
        &self,
        py: Python<'py>,
        chart: Option<String>,
        state: Vec<String>,
        sets: Vec<String>,
        events: Vec<String>,
        t0: f64,
        t_end: f64,
        dt: Option<f64>,
        times: Option<&[u8]>,
        method: &str,
        rtol: f64,
        atol: f64,
        first_step: Option<f64>,
        max_step: Option<f64>,
        dense: bool,
        cancel: Option<Bound<'py, Cancel>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let method = bridge::method(method).ok_or_else(|| {
            ModelInputError::new_err(format!(
                "method `{method}`: expected one of dopri5, dop853, rodas4"
            ))
        })?;
        let request = SolveRequest {
            chart: chart.as_deref(),
            state: &state,
            sets: &sets,
            events: &events,
            t0,
            t_end,
            dt,
            times: times.map(floats),
            method,
            rtol,
            atol,
            first_step,
            max_step,
            dense,
        };
        let model = &self.model;
        let cancel = cancel.as_ref().map(|c| c.get());
        let solved = interruptible(py, cancel, |interrupt| model.solve(&request, interrupt))?
            .map_err(|e| model_error(&e))?;
        // The trajectory's columns one after another, as NumPy's `(columns, rows)` array:
        // every column, and the states as SciPy's `y`, are views of it.
        let values = solved.trajectory.values();
        let table = PyByteArray::new_with(py, values.len() * 8, |bytes| {
            for (chunk, value) in bytes.chunks_exact_mut(8).zip(values) {
                chunk.copy_from_slice(&value.to_ne_bytes());
            }
            Ok(())
        })?;
        let found: Vec<(String, Option<usize>, Vec<f64>)> = (solved.events.iter())
            .map(|e| (e.label(), e.request, e.row.clone()))
            .collect();
        let out = PyDict::new(py);
        out.set_item("header", &solved.columns)?;
        out.set_item("states", solved.states)?;
        out.set_item("table", table)?;
        out.set_item("events", found)?;
        out.set_item("stop", bridge::termination(&solved.stop))?;
        out.set_item("stats", bridge::stats(&solved.stats))?;
        let notes: Vec<String> = solved.accumulations.iter().map(|a| a.to_string()).collect();
        out.set_item("notes", notes)?;
        let steps = &solved.dense;
        out.set_item(
            "dense_t",
            column(py, 2 * steps.len(), |i| {
                let step = &steps[i / 2];
                if i % 2 == 0 {
                    step.t0
                } else {
                    step.t1
                }
            })?,
        )?;
        let per_step = DENSE_NODES * solved.states;
        out.set_item(
            "dense_y",
            column(py, per_step * steps.len(), |i| {
                steps[i / per_step].values[i % per_step]
            })?,
        )?;
        Ok(out)
    }
}

/// The compiled half of the `eulerdisk` package.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(default_scene, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(merge_sweep, m)?)?;
    m.add_class::<NativeModel>()?;
    m.add_class::<Cancel>()?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("DslError", py.get_type::<DslError>())?;
    m.add("ModelInputError", py.get_type::<ModelInputError>())?;
    m.add("SolveError", py.get_type::<SolveError>())?;
    m.add("SweepError", py.get_type::<SweepError>())?;
    m.add("RunError", py.get_type::<RunError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("MAX_SAMPLES", model_interpreted::MAX_SAMPLES)?;
    m.add("DENSE_NODES", DENSE_NODES)?;
    Ok(())
}
