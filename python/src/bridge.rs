//! Every call this package makes into the `eulerdisk` crate, in one place.
//!
//! The Python functions run exactly what the command line runs (`eulerdisk run`, `eulerdisk
//! model eval|solve|show`, `eulerdisk sweep`), through the crate's library API; nothing here
//! simulates, parses or checks anything itself. Keeping the calls in one module means a change
//! of that API (a new single entry point) changes this file only. Nothing here knows Python.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use eulerdisk::{
    load_scene, load_sweep, merge, model_event_spec, model_named, model_value_error, parse_scene,
    parse_sweep, plan, run_scene, run_sweep, show_switched, Backend, ExecOptions, LoadedSweep,
    ModelArguments, ModelFileError, ModelFormat, Override, ProgressStyle, Provenance, RunOptions,
    RunReport, Scene, SceneError, Shard, SweepReport, DEFAULT_SCENE, TABLE_FILE,
};
use model_algebra::CompiledModel;
use model_dsl::CompiledSwitched;
use model_interpreted::{
    evaluate, initial_state, CacheUse, Control, LoadError, Loaded, ModelCache, ModelFile, ModelRef,
    Solution, Stepping, Stop,
};
use model_runtime::{Method, Stats};

/// Where a scene comes from.
pub enum SceneSource {
    /// A built-in scene's name or a scene file's path, as `eulerdisk run` takes it.
    Named(String),
    /// A scene file's text (TOML), under a name of its own.
    Text {
        /// The scene's name.
        name: String,
        /// The TOML text.
        toml: String,
    },
}

/// A scene ready to run, with how it was produced.
pub struct LoadedScene {
    /// The scene.
    pub scene: Scene,
    /// Program, scene source, overrides, settings.
    pub provenance: Provenance,
}

/// Loads a scene with `--set TABLE.KEY=VALUE` overrides, as `eulerdisk run` does.
pub fn scene(source: &SceneSource, sets: &[String]) -> Result<LoadedScene, SceneError> {
    let overrides = (sets.iter())
        .map(|s| Override::parse(s))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(match source {
        SceneSource::Named(name) => {
            let scene = load_scene(name, &overrides)?;
            let provenance = Provenance::new(&scene, name, &overrides);
            LoadedScene { scene, provenance }
        }
        SceneSource::Text { name, toml } => {
            let scene = parse_scene(name, toml, &overrides)?;
            let mut provenance = Provenance::new(&scene, name, &overrides);
            provenance.scene_file = "a table given from Python".to_string();
            LoadedScene { scene, provenance }
        }
    })
}

/// The name of the scene `eulerdisk run` runs when none is given.
pub fn default_scene() -> &'static str {
    DEFAULT_SCENE
}

/// The scene key a scene error is about (`table.key`), if it is about one.
pub fn scene_error_key(error: &SceneError) -> Option<String> {
    match error {
        SceneError::Key { key, .. } => Some(key.clone()),
        SceneError::Invalid { issues, .. } => issues.first().map(|i| i.key.clone()),
        SceneError::Override { spec, .. } => spec.split_once('=').map(|(k, _)| k.to_string()),
        _ => None,
    }
}

/// How a run from Python reports and what it leaves in its folder.
pub struct RunRequest<'a> {
    /// The output folder (`trajectory.csv` only when `trajectory_file`).
    pub out_dir: &'a Path,
    /// Progress lines on standard error.
    pub progress: bool,
    /// Whether to write `trajectory.csv` too (the samples are returned in any case).
    pub trajectory_file: bool,
    /// Whether to draw the paper's figures.
    pub figures: bool,
}

/// Runs a loaded scene as `eulerdisk run` does; `interrupt` stops it at its next step.
pub fn run(
    loaded: &LoadedScene,
    request: &RunRequest<'_>,
    interrupt: &AtomicBool,
) -> Result<RunReport, String> {
    let options = RunOptions {
        out_dir: request.out_dir.to_path_buf(),
        progress: progress_style(request.progress),
        backend: Backend::Generated,
        engine: eulerdisk::DEFAULT_ENGINE,
        figures: request.figures,
        trajectory: request.trajectory_file,
        provenance: loaded.provenance.clone(),
    };
    run_scene(&loaded.scene, &options, interrupt).map_err(|e| e.to_string())
}

/// Progress as lines on standard error, or nothing (the bars are the command line's: the
/// library draws none, so that this package links no terminal crate).
fn progress_style(shown: bool) -> ProgressStyle {
    if shown {
        ProgressStyle::Lines
    } else {
        ProgressStyle::Quiet
    }
}

/// The file of a sweep's table in its folder.
pub fn sweep_table(dir: &Path) -> PathBuf {
    dir.join(TABLE_FILE)
}

/// Where a sweep comes from.
pub enum SweepSource {
    /// A built-in sweep's name or a sweep file's path.
    Named(String),
    /// A sweep file's text (TOML); relative scene paths start from `folder`.
    Text {
        /// The sweep's name.
        name: String,
        /// The TOML text.
        toml: String,
        /// Where relative paths start.
        folder: Option<PathBuf>,
    },
}

/// Loads, plans and runs a sweep into `out` as `eulerdisk sweep` does (resuming what `out`
/// already holds), or shard `(index, count)` of its points as `--shard index/count` does (into
/// its folder inside `out`); `Err` is the command line's message.
pub fn sweep(
    source: &SweepSource,
    sets: &[String],
    (out, shard): (&Path, Option<(usize, usize)>),
    jobs: usize,
    progress: bool,
    interrupt: &AtomicBool,
) -> Result<SweepReport, String> {
    let loaded = match source {
        SweepSource::Named(name) => load_sweep(name).map_err(|e| e.to_string())?,
        SweepSource::Text { name, toml, folder } => LoadedSweep {
            name: name.clone(),
            folder: folder.clone(),
            file: parse_sweep(name, toml).map_err(|e| e.to_string())?,
        },
    };
    let plan = plan(&loaded, sets).map_err(|e| e.to_string())?;
    let jobs = match jobs {
        0 => (plan.definition.file.jobs)
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())),
        n => n,
    };
    let options = ExecOptions {
        jobs,
        progress: progress_style(progress),
        shard: shard.map(|(index, count)| Shard { index, count }),
    };
    run_sweep(&plan, out, &options, interrupt).map_err(|e| e.to_string())
}

/// What `eulerdisk sweep merge` found joining sweep folders: the sweep's points, the rows
/// merged, the points without a row and those with rows in several folders.
pub struct Merged {
    /// Points of the sweep.
    pub points: usize,
    /// Rows merged.
    pub rows: usize,
    /// Points without a row.
    pub missing: usize,
    /// Points with rows in several folders.
    pub duplicates: usize,
}

/// Joins the sweep folders `dirs` (shards found inside them) into `out`, as `eulerdisk sweep
/// merge` does; `Err` is the command line's message.
pub fn merge_sweep(dirs: &[PathBuf], out: &Path) -> Result<Merged, String> {
    let (_, _, report) = merge(dirs, out).map_err(|e| e.to_string())?;
    Ok(Merged {
        points: report.points,
        rows: report.rows,
        missing: report.missing.len(),
        duplicates: report.duplicates.len(),
    })
}

/// A compiled model file: a smooth model with its charts, or a switched one. Only the
/// compiler's output is kept, not the syntax tree (which is bound to the thread that parsed
/// it), so that a model can be solved on any thread.
pub enum FileModel {
    /// The model, then each of its charts.
    Smooth(Vec<CompiledModel>),
    /// A model with modes and events.
    Switched(CompiledSwitched),
}

impl FileModel {
    fn of(file: ModelFile) -> FileModel {
        match file {
            ModelFile::Smooth(models) => {
                FileModel::Smooth(models.into_iter().map(|m| m.compiled).collect())
            }
            ModelFile::Switched(model) => FileModel::Switched(model),
        }
    }

    /// Compiles the model file at `path`, through the user's cache of compiled models when
    /// `cache` (as `eulerdisk model` without `--no-cache`); also whether the cache held it.
    pub fn from_file(path: &Path, cache: bool) -> Result<(FileModel, bool), ModelFileError> {
        let cache = cache.then(ModelCache::user).flatten();
        Ok(FileModel::loaded(ModelFile::read_reporting(
            path,
            cache.as_ref(),
        )?))
    }

    /// Compiles a model given as text, through the cache as [`FileModel::from_file`];
    /// `name` stands for the file in messages.
    pub fn from_text(
        name: &str,
        text: &str,
        cache: bool,
    ) -> Result<(FileModel, bool), ModelFileError> {
        let cache = cache.then(ModelCache::user).flatten();
        Ok(FileModel::loaded(ModelFile::from_text_reporting(
            name,
            text,
            cache.as_ref(),
        )?))
    }

    /// The models loaded, and whether they came from the cache.
    fn loaded(loaded: Loaded) -> (FileModel, bool) {
        (FileModel::of(loaded.file), loaded.cache == CacheUse::Hit)
    }

    /// The model's name.
    pub fn name(&self) -> &str {
        match self {
            FileModel::Smooth(models) => &models[0].name,
            FileModel::Switched(model) => &model.name,
        }
    }

    /// The model (its first mode, for a switched one): states, parameters, outputs.
    pub fn first(&self) -> &CompiledModel {
        match self {
            FileModel::Smooth(models) => &models[0],
            FileModel::Switched(model) => &model.modes[0].model,
        }
    }

    /// The charts' names (none for a switched model).
    pub fn charts(&self) -> Vec<String> {
        match self {
            FileModel::Smooth(models) => models[1..].iter().map(|m| m.name.clone()).collect(),
            FileModel::Switched(_) => Vec::new(),
        }
    }

    /// The modes' names (none for a smooth model).
    pub fn modes(&self) -> Vec<String> {
        match self {
            FileModel::Smooth(_) => Vec::new(),
            FileModel::Switched(model) => {
                model.modes.iter().map(|m| m.model.name.clone()).collect()
            }
        }
    }

    /// The solved equations, as `eulerdisk model show` prints them (`latex`: LaTeX, else
    /// Markdown).
    pub fn show(&self, latex: bool) -> String {
        let format = if latex {
            ModelFormat::Latex
        } else {
            ModelFormat::Markdown
        };
        match self {
            FileModel::Switched(model) => show_switched(model, format),
            FileModel::Smooth(models) => (models.iter().map(|m| &m.explanation))
                .map(|e| match format {
                    ModelFormat::Latex => e.latex.clone(),
                    ModelFormat::Markdown => e.markdown.clone(),
                })
                .collect::<Vec<_>>()
                .join("\n"),
        }
    }

    /// The model called `chart` (`None`: the file's model), as the library chooses it.
    fn model(&self, chart: Option<&str>) -> Result<ModelRef<'_>, LoadError> {
        match (self, chart) {
            (FileModel::Smooth(models), chart) => {
                model_interpreted::select_chart(models, chart).map(ModelRef::Smooth)
            }
            (FileModel::Switched(model), None) => Ok(ModelRef::Switched(model)),
            (FileModel::Switched(_), Some(chart)) => Err(LoadError::ChartOfSwitched {
                chart: chart.to_string(),
            }),
        }
    }

    /// The derivatives and outputs at one point, as `eulerdisk model eval` prints them (JSON).
    pub fn eval(
        &self,
        chart: Option<&str>,
        t: f64,
        state: &[String],
        sets: &[String],
    ) -> Result<String, ModelFileError> {
        let model = match self.model(chart)? {
            ModelRef::Smooth(model) => model,
            ModelRef::Switched(model) => {
                return Err(LoadError::Switched {
                    model: model.name.clone(),
                }
                .into())
            }
        };
        let values = |flag, given: &[String]| model_named(flag, given);
        let params = model_interpreted::params(ModelRef::Smooth(model), &values("--set", sets)?)
            .map_err(|e| model_value_error("--set", sets, e))?;
        let y = initial_state(ModelRef::Smooth(model), &values("--state", state)?)
            .map_err(|e| model_value_error("--state", state, e))?;
        let point = evaluate(model, t, &y, &params)?;
        Ok(serde_json::to_string(&point).expect("named numbers serialise"))
    }

    /// Integrates the model as `eulerdisk model solve` does; `interrupt` stops it at its
    /// next step.
    pub fn solve(
        &self,
        request: &SolveRequest<'_>,
        interrupt: &AtomicBool,
    ) -> Result<Solution, ModelFileError> {
        let model = self.model(request.chart)?;
        let events = (request.events.iter())
            .map(|text| model_event_spec(text))
            .collect::<Result<Vec<_>, _>>()?;
        let library = model_interpreted::SolveRequest {
            t0: request.t0,
            t_end: request.t_end,
            method: request.method,
            rtol: request.rtol,
            atol: request.atol,
            dt: request.dt,
            times: request.times.clone(),
            params: model_named("--set", request.sets)?,
            state: model_named("--state", request.state)?,
            events,
            max_steps_per_s: model_interpreted::WorkBound::DEFAULT.steps_per_s,
        };
        let arguments = ModelArguments {
            set: request.sets,
            state: request.state,
            event: request.events,
        };
        let stepping = Stepping {
            first_step: request.first_step,
            max_step: request.max_step,
            dense: request.dense,
        };
        let control = Control { interrupt };
        model_interpreted::solve_stepped(model, &library, &control, &stepping)
            .map_err(|f| arguments.solve_error(f))
    }
}

/// What `Model.solve` asks for, in the command line's terms.
pub struct SolveRequest<'a> {
    /// The chart (`None`: the model itself).
    pub chart: Option<&'a str>,
    /// `NAME=VALUE` initial states.
    pub state: &'a [String],
    /// `NAME=VALUE` parameters.
    pub sets: &'a [String],
    /// `NAME[:up|:down][:stop]` events.
    pub events: &'a [String],
    /// Start time.
    pub t0: f64,
    /// End time.
    pub t_end: f64,
    /// Sampling step (`None`: every accepted step, or `times`).
    pub dt: Option<f64>,
    /// Sampling times (`None`: every accepted step, or every `dt`).
    pub times: Option<Vec<f64>>,
    /// The integrator.
    pub method: Method,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// The first step (`None`: chosen by the integrator).
    pub first_step: Option<f64>,
    /// The largest step (`None`: unbounded).
    pub max_step: Option<f64>,
    /// Whether to keep every step's dense output.
    pub dense: bool,
}

/// The integrator called `name` (`dopri5`, `dop853`, `rodas4`), as `--method` takes it.
pub fn method(name: &str) -> Option<Method> {
    match name {
        "dopri5" => Some(Method::Dopri5),
        "dop853" => Some(Method::Dop853),
        "rodas4" => Some(Method::Rodas4),
        _ => None,
    }
}

/// Whether a model error is the user's input (a located DSL error, a name, a setting) rather
/// than a failed integration.
pub fn is_dsl_error(error: &ModelFileError) -> bool {
    matches!(
        error,
        ModelFileError::Load(LoadError::Dsl(_) | LoadError::Read { .. })
    )
}

/// Whether a model error is a failed evaluation or integration.
pub fn is_failure(error: &ModelFileError) -> bool {
    matches!(error, ModelFileError::Failed(_) | ModelFileError::Point(_))
}

/// Why a solve ended, in words: `end_time`, `event NAME`, `interrupted` or `failed`.
pub fn termination(stop: &Stop) -> String {
    match stop {
        Stop::EndTime => "end_time".to_string(),
        Stop::Event { name, .. } => format!("event {name}"),
        Stop::Interrupted => "interrupted".to_string(),
        Stop::Failed { .. } => "failed".to_string(),
    }
}

/// The integrator's work counters by name.
pub fn stats(stats: &Stats) -> Vec<(&'static str, u64)> {
    vec![
        ("steps", stats.steps),
        ("rejected", stats.rejected),
        ("rhs_evals", stats.rhs_evals),
        ("jacobian_evals", stats.jacobian_evals),
        ("decompositions", stats.decompositions),
        ("events", stats.events),
    ]
}
