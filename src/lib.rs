//! The `eulerdisk` command line: scenes in, trajectories, events, figures and a summary out.
//!
//! The binary is a thin shell over this library so that integration tests can drive the same
//! scene loader, parsers and writers the command uses, with random inputs, without a process
//! per case.
//!
//! # What is here and what is below
//!
//! This crate keeps what a command line needs: arguments, scene files and their overrides,
//! progress, the files (their names, formats and atomic writing), the figures and the printed
//! summary. The physics and the run's records are the library's: the samples, the named
//! state layout, the quantities and their units, the friction ratio, the mode decisions and
//! the stop reasons with the words the files write are `equations::record`'s types, which
//! this crate formats and matches on, never spelling or converting them itself; a model
//! file is loaded and solved by `model_interpreted`. A second front end (the Python package)
//! calls the same library functions.
//!
//! # The API by theme
//!
//! The modules are private; what the binary and the tests use is re-exported here, once, under
//! one name, so a caller's imports never depend on how the crate is split into files. Where two
//! modules name things alike, the root name says which (`load_scene`, `load_sweep`,
//! `sweep_command`, `sound_command`).
//!
//! * **The command line**: [`Cli`], [`Command`], [`RunArgs`], [`EvalArgs`], the exit codes
//!   [`EXIT_INPUT`], [`EXIT_FAILED`], [`EXIT_INTERRUPTED`], and the shared pieces [`backend`],
//!   [`progress_style`], [`interrupt_on_ctrl_c`].
//! * **Scenes**: [`load_scene`], [`parse_scene`], [`BUILTIN_SCENES`], [`DEFAULT_SCENE`],
//!   [`Scene`] (its file, [`SceneFile`], with the command line's own tables [`CliTables`] and
//!   [`OutputTable`]), [`Override`], [`SceneError`].
//! * **Running a scene**: [`run_scene`] with [`RunOptions`] gives a [`RunReport`] ([`Ending`],
//!   [`RunError`]) and the files of `eulerdisk run`; the same run in memory, for another front
//!   end, [`simulate_scene`] ([`SceneRun`]); the model it runs, [`choose`] ([`ModelChoice`], [`RunModel`]); the run's
//!   origin, [`Provenance`]; one simulation and what it keeps, [`record_run`] ([`SamplePlan`],
//!   [`Progress`], [`ProgressStyle`], [`Recorded`]).
//! * **What a run gives**: [`RunData`] (of `equations::record`'s samples, mode decisions and
//!   stop), [`Summary`]; the paper's figures,
//!   [`paper_charts`], [`write_paper_figures`], [`FIGURE_STEMS`], [`Chart`]; a run built by
//!   hand, [`SyntheticRun`].
//! * **Sweeps**: [`sweep_command`]; [`load_sweep`], [`parse_sweep`], [`BUILTIN_SWEEPS`]
//!   ([`LoadedSweep`], [`Keep`]); [`plan`] ([`Plan`], [`PlanError`], [`run_arguments`]);
//!   [`run_sweep`] ([`ExecOptions`], [`ExecReport`], [`SweepReport`], [`SweepError`],
//!   [`Shard`], [`sweep_dir`], [`run_options`], [`process_cpu_s`]); the stored rows,
//!   [`read_manifest`], [`read_rows`], [`Row`], [`Status`], [`PointStop`], [`SweepStop`],
//!   [`scalar_entries`],
//!   [`TIMING_COLUMNS`], [`TABLE_FILE`], [`ROWS_DIR`]; [`merge`].
//! * **Sound**: [`sound_command`]; [`sound_scene`] with [`SoundOptions`] ([`SoundReport`],
//!   [`SoundError`], [`wav_name`]); the pieces, [`record_force`] ([`ForceTrace`],
//!   [`TimeSpan`]), [`major_peaks`] ([`PeakRule`]), [`analyse`], [`render`]
//!   ([`RenderOptions`], [`HEADROOM`]), [`spectrogram`] ([`StftSettings`]).
//! * **Model commands**: [`model_command`]; a model file's loading and solving are the library
//!   `model_interpreted`'s, this crate keeps the flags, the CSV files and the sentences; for
//!   other front ends, the arguments read as the flags are ([`model_named`],
//!   [`model_event_spec`], [`model_value_error`], [`ModelArguments`], [`ModelFileError`]) and [`show_switched`]
//!   ([`ModelFormat`]).
//! * **Evaluation**: [`evaluate`], [`parse_params`], [`parse_state`], [`Backend`],
//!   [`EvalCommandError`]; named numbers on the command line, [`parse_named_numbers`].
//! * **Reading the outputs**: [`EVENTS_HEADER`], [`split_fields`]; the tables' format,
//!   [`TableFormat`]; a table as cells, [`Table`] ([`Cell`]), and a Parquet file read back
//!   into one, `read_parquet` (`ParquetReadError`), with the default feature `parquet`. A build
//!   without it (the Python package's) refuses `output.format = "parquet"` by its key.
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
mod args;
mod cli;
mod eval;
mod figures;
mod model_command;
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

// The command line: the parsed arguments, the exit codes, the pieces every command shares.
pub use args::{
    backend, interrupt_on_ctrl_c, print_json, print_out, progress_style, IntegratorName, RunArgs,
    EXIT_FAILED, EXIT_INPUT, EXIT_INTERRUPTED, EXIT_STOPPED,
};
pub use cli::{Cli, Command, EvalArgs};

// Scenes: loading, parsing and overriding a scene file.
pub use scene::{
    load as load_scene, parse as parse_scene, CliTables, OutputTable, Override, Scene, SceneError,
    SceneFile, BUILTIN as BUILTIN_SCENES, DEFAULT_SCENE, MAX_LISTED_ISSUES, REQUIRED_KEYS,
};

// Running a scene: options, report, the model chosen, one simulation and what it keeps.
pub use run::model::{choose, ModelChoice, RunModel};
pub use run::plan::SamplePlan;
pub use run::progress::Progress;
pub use run::provenance::Provenance;
pub use run::{
    record as record_run, run_scene, simulate_scene, Ending, ProgressStyle, Recorded, RunError,
    RunOptions, RunReport, SceneRun,
};

// What a run gives: its data, its summary, its quantities and the paper's figures.
pub use analysis::summary::Summary;
pub use analysis::synthetic::SyntheticRun;
pub use figures::chart::Chart;
pub use figures::paper::{paper_charts, write_paper_figures, FiguresDrawn, FIGURE_STEMS};
pub use record::RunData;

// Sweeps: the command, the sweep file, its plan, its execution and its stored rows.
pub use sweep::args::command as sweep_command;
pub use sweep::columns::{scalar_entries, TIMING_COLUMNS};
pub use sweep::execute::{ExecOptions, ExecReport};
pub use sweep::expand::{plan, run_arguments, Plan, PlanError};
pub use sweep::merge::merge;
pub use sweep::row::{PointStop, Row, Status, SweepStop};
pub use sweep::run_point::{process_cpu_s, run_options};
pub use sweep::shard::Shard;
pub use sweep::spec::{
    load as load_sweep, parse as parse_sweep, Keep, LoadedSweep, BUILTIN as BUILTIN_SWEEPS,
};
pub use sweep::store::{read_manifest, read_rows, ROWS_DIR, TABLE_FILE};
pub use sweep::{run_sweep, sweep_dir, SweepError, SweepReport};

// Sound: the command, a scene's rattle, and the pieces it is made of.
pub use sound::args::command as sound_command;
pub use sound::peaks::{major_peaks, PeakRule};
pub use sound::render::{render, RenderOptions, HEADROOM};
pub use sound::spectrogram::{spectrogram, StftSettings};
pub use sound::trace::{record_force, ForceTrace, TimeSpan};
pub use sound::{analyse, sound_scene, wav_name, SoundError, SoundOptions, SoundReport};

// Model commands: `eulerdisk model ...`.
pub use model_command::run as model_command;

// Models from files, for other front ends (the Python package): the command line's way of
// reading `NAME=VALUE` and event arguments and of saying the library's errors with them.
pub use model_file::{
    event_spec as model_event_spec, named as model_named, show_switched,
    value_error as model_value_error, Arguments as ModelArguments, ModelFileError,
};
pub use model_show::Format as ModelFormat;

// Evaluation: the right-hand side at one state, and the parsers of its arguments.
pub use eval::{
    evaluate, evaluate_model, parse_model_state, parse_params, parse_state, Backend,
    EvalCommandError,
};
pub use named_numbers::{is_json_object, parse_assignments, parse_named_numbers};

// Reading the outputs: the events table's header and one CSV line's fields.
pub use output::cells::{Cell, Table};
pub use output::format::TableFormat;
#[cfg(feature = "parquet")]
pub use output::parquet::{read_table as read_parquet, ReadError as ParquetReadError};
pub use output::tables::{split_fields, EVENTS_HEADER};
