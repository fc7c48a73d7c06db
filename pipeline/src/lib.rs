//! Euler's disk from a scene to its results: scene files in; trajectories, events, extrema,
//! the paper's figures, a summary, the rattle's sound and sweeps out.
//!
//! This is the library under both front ends: the `eulerdisk` command line (the root
//! package, which keeps the flags, the terminal, Ctrl-C and the exit codes) and the Python
//! package. It links no flag parser, terminal or signal crate: a front end says how progress
//! is drawn ([`ProgressStyle`], with its own [`Bars`] on a terminal) and hands every long
//! call an interrupt flag (`&AtomicBool`) that its Ctrl-C handler sets. The package is
//! `eulerdisk-pipeline`; its library is named `eulerdisk`.
//!
//! # What is here and what is below
//!
//! This crate keeps what a front end needs from a scene to its files: scene files and their
//! overrides, the run (plan, simulate, collect, write), progress as a front end draws it, the
//! files (their names, formats and atomic writing), the figures, the printed summary, the
//! sound and sweeps. The physics and the run's records are the `equations` crate's: the
//! samples, the named state layout, the quantities and their units, the friction ratio, the
//! mode decisions and the stop reasons with the words the files write are
//! `equations::record`'s types, which this crate formats and matches on, never spelling or
//! converting them itself; a model file is loaded and solved by `model_interpreted`.
//!
//! # The API by theme
//!
//! The modules are private; what the front ends and the tests use is re-exported here, once,
//! under one name, so a caller's imports never depend on how the crate is split into files.
//! Where two modules name things alike, the root name says which (`load_scene`, `load_sweep`).
//!
//! * **Scenes**: [`load_scene`], [`parse_scene`], [`BUILTIN_SCENES`], [`DEFAULT_SCENE`],
//!   [`Scene`] (its file, [`SceneFile`], with the front ends' own tables [`CliTables`] and
//!   [`OutputTable`]), [`Override`], [`SceneError`].
//! * **Running a scene**: [`run_scene`] with [`RunOptions`] gives a [`RunReport`] ([`Ending`],
//!   [`RunError`]) and the files of `eulerdisk run`; the same run in memory, for another front
//!   end, [`simulate_scene`] ([`SceneRun`]); the model it runs, [`choose`] ([`ModelChoice`],
//!   [`RunModel`]); the run's origin, [`Provenance`]; one simulation and what it keeps,
//!   [`record_run`] ([`SamplePlan`], [`Progress`], [`Recorded`]).
//! * **Progress**: [`ProgressStyle`] (a bar, lines or nothing), the bars a front end draws
//!   ([`Bars`], [`Bar`], [`Counting`]).
//! * **What a run gives**: [`RunData`] (of `equations::record`'s samples, mode decisions and
//!   stop), [`Summary`]; the paper's figures,
//!   [`paper_charts`], [`write_paper_figures`], [`FIGURE_STEMS`], [`Chart`]; a run built by
//!   hand, [`SyntheticRun`].
//! * **Sweeps**: [`load_sweep`], [`parse_sweep`], [`BUILTIN_SWEEPS`]
//!   ([`LoadedSweep`], [`Keep`]); [`plan`] ([`Plan`], [`PlanError`], [`PointId`],
//!   [`run_arguments`], [`SWEEP_FORMAT_KEY`]); [`run_sweep`] ([`ExecOptions`], [`ExecReport`],
//!   [`SweepReport`], [`SweepError`], [`Shard`], [`sweep_dir`], [`run_options`],
//!   [`process_cpu_s`]); the stored rows, [`read_manifest`], [`read_rows`], [`Row`],
//!   [`Status`], [`PointStop`], [`SweepStop`], [`scalar_entries`], [`TIMING_COLUMNS`],
//!   [`TABLE_STEM`], [`TABLE_FILE`], [`ROWS_DIR`]; [`merge`] ([`MergeReport`]).
//! * **Sound**: [`sound_scene`] with [`SoundOptions`] ([`SoundReport`], [`SoundError`],
//!   [`wav_name`]); the pieces, [`record_force`] ([`ForceTrace`], [`TimeSpan`]),
//!   [`major_peaks`] ([`PeakRule`]), [`analyse`], [`render`] ([`RenderOptions`], [`Ring`],
//!   [`Compression`], [`HEADROOM`]), [`spectrogram`] ([`StftSettings`]).
//! * **Models**: a model file's loading and solving are the library `model_interpreted`'s;
//!   this crate keeps what the front ends say about them: a file read ([`read_model_file`])
//!   and shown ([`show_model_file`], [`show_switched`], [`ModelFormat`]), the disk's models by
//!   name ([`ModelName`], [`show_disk_model`]), the arguments read as the flags are
//!   ([`model_named`], [`model_event_spec`], [`model_value_error`], [`ModelArguments`],
//!   [`ModelFileError`]) and a solution as tables ([`solution_trajectory`],
//!   [`solution_events`]).
//! * **Evaluation**: [`evaluate`], [`evaluate_model`], [`parse_params`], [`parse_state`],
//!   [`parse_model_state`], [`Backend`] ([`DEFAULT_BACKEND`]), [`EvalCommandError`]; named
//!   numbers, [`parse_named_numbers`], [`parse_assignments`], [`is_json_object`].
//! * **Writing and reading the outputs**: [`EVENTS_HEADER`], [`split_fields`]; the tables'
//!   format, [`TableFormat`]; a table as cells, [`Table`] ([`Cell`]), written whole or not at
//!   all, [`write_table_at`], [`write_atomic`] ([`WriteError`]). Parquet is written by the
//!   writer a front end installs ([`install_parquet`], [`ParquetWriter`], [`ParquetRows`]; the
//!   command line installs `eulerdisk-parquet`'s, which also reads a file back); a front end
//!   without one (the Python package) refuses `output.format = "parquet"` by its key.
//!
//! ```
//! use eulerdisk::{load_scene, split_fields, Override, DEFAULT_SCENE};
//!
//! let shorter = Override::parse("run.t_end=0.5").unwrap();
//! let scene = load_scene(DEFAULT_SCENE, &[shorter]).unwrap();
//! assert_eq!(scene.file.settings.run.t_end, 0.5);
//! // A bad value is rejected by its key.
//! let negative = Override::parse("run.t_end=-1").unwrap();
//! let err = load_scene(DEFAULT_SCENE, &[negative]).unwrap_err();
//! assert!(err.to_string().contains("run.t_end"), "{err}");
//! // The tables quote a field that holds a comma.
//! assert_eq!(split_fields(r#"0.5,"a, b""#), ["0.5", "a, b"]);
//! ```
#![warn(missing_docs)]

mod analysis;
mod eval;
mod figures;
mod model_file;
mod model_show;
mod model_tables;
mod named_numbers;
mod output;
mod record;
mod run;
mod scene;
mod sound;
mod sweep;

// Scenes: loading, parsing and overriding a scene file.
pub use scene::{
    load as load_scene, parse as parse_scene, CliTables, OutputTable, Override, Scene, SceneError,
    SceneFile, BUILTIN as BUILTIN_SCENES, DEFAULT_SCENE, MAX_LISTED_ISSUES, REQUIRED_KEYS,
};

// Running a scene: options, report, the model chosen, one simulation and what it keeps.
pub use run::model::{choose, EngineChoice, ModelChoice, RunModel, DEFAULT_ENGINE};
pub use run::plan::SamplePlan;
pub use run::progress::{Bar, Bars, Counting, Progress, ProgressStyle};
pub use run::provenance::Provenance;
pub use run::{
    record as record_run, run_scene, simulate_scene, Ending, Recorded, RunError, RunOptions,
    RunReport, SceneRun,
};

// What a run gives: its data, its summary, its quantities and the paper's figures.
pub use analysis::summary::Summary;
pub use analysis::synthetic::SyntheticRun;
pub use figures::chart::Chart;
pub use figures::paper::{paper_charts, write_paper_figures, FiguresDrawn, FIGURE_STEMS};
pub use record::RunData;

// Sweeps: the sweep file, its plan, its execution and its stored rows.
pub use sweep::columns::{scalar_entries, TIMING_COLUMNS};
pub use sweep::execute::{ExecOptions, ExecReport};
pub use sweep::expand::{
    plan, run_arguments, Plan, PlanError, PointId, FORMAT_KEY as SWEEP_FORMAT_KEY,
};
pub use sweep::merge::{merge, MergeReport};
pub use sweep::row::{PointStop, Row, Status, SweepStop};
pub use sweep::run_point::{process_cpu_s, run_options};
pub use sweep::shard::Shard;
pub use sweep::spec::{
    load as load_sweep, parse as parse_sweep, Keep, LoadedSweep, BUILTIN as BUILTIN_SWEEPS,
};
pub use sweep::store::{read_manifest, read_rows, ROWS_DIR, TABLE_FILE, TABLE_STEM};
pub use sweep::{run_sweep, sweep_dir, SweepError, SweepReport};

// Sound: a scene's rattle, and the pieces it is made of.
pub use sound::peaks::{major_peaks, PeakRule};
pub use sound::render::{render, Compression, RenderOptions, Ring, HEADROOM};
pub use sound::spectrogram::{spectrogram, StftSettings};
pub use sound::trace::{record_force, ForceTrace, TimeSpan};
pub use sound::{analyse, sound_scene, wav_name, SoundError, SoundOptions, SoundReport};

// Models: a file's model read, shown and its solution written, in the front ends' words (the
// way `NAME=VALUE` and event arguments are read and the library's errors said with them);
// the disk's models by name.
pub use model_file::{
    event_spec as model_event_spec, named as model_named, read as read_model_file,
    show as show_model_file, show_switched, value_error as model_value_error,
    Arguments as ModelArguments, ModelFileError,
};
pub use model_show::{show as show_disk_model, Format as ModelFormat, ModelName};
pub use model_tables::{events as solution_events, trajectory as solution_trajectory};

// Evaluation: the right-hand side at one state, and the parsers of its arguments.
pub use eval::{
    evaluate, evaluate_model, parse_model_state, parse_params, parse_state, Backend,
    EvalCommandError, DEFAULT_BACKEND,
};
pub use named_numbers::{is_json_object, parse_assignments, parse_named_numbers};

// Writing and reading the outputs: tables as cells, written atomically in a format; the
// events table's header and one CSV line's fields.
pub use output::atomic::{write_atomic, AtomicFile, WriteError};
pub use output::cells::{Cell, Table};
pub use output::files::write_table_at;
pub use output::format::TableFormat;
pub use output::parquet::{install_parquet, parquet_writer, ParquetRows, ParquetWriter};
pub use output::tables::{split_fields, EVENTS_HEADER};
