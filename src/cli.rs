//! The command line: `eulerdisk [run [SCENE]] | eval | scenes | sound | sweep`.
//!
//! Flags map onto scene keys (`--rtol` is `--set solver.rtol=...`) so every value from the
//! command line passes the same validation as the scene file. Every subcommand spells states,
//! parameters, integrators and tolerances the same way (`args.rs` lists the vocabulary);
//! defaults are written as a reader writes them (`1e-8`, not `0.00000001`).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::args::{FormatArg, IntegratorName, RunArgs};
use equations::Mode;
use eulerdisk::ModelFormat;

/// Euler's disk rolling and sliding on a rough plane (Saje & Zupan's model).
#[derive(Debug, Parser)]
#[command(name = "eulerdisk", version, about)]
pub struct Cli {
    /// What to do (default: run the default scene).
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Simulate a scene and write trajectory, events, the paper's figures and a summary.
    Run(RunArgs),
    /// Evaluate the equations of one mode at one state and print JSON.
    Eval(EvalArgs),
    /// List the built-in scenes.
    Scenes,
    /// Simulate a scene and hear its rattle: a WAV of the normal-force peaks, their rate
    /// against the paper's, and a spectrogram.
    Sound(crate::sound::SoundArgs),
    /// Run many scenes at once: axes over any scene key, a table of their summaries, figures;
    /// resumable, and shardable over a cluster's job array (`sweep merge` joins the shards).
    Sweep(crate::sweep::SweepArgs),
    /// A model's equations as the compiler solved them (`model show rolling`), and a model of
    /// one's own from a DSL file: shown, evaluated or solved without compiling Rust.
    #[command(subcommand)]
    Model(ModelCommand),
}

/// `eulerdisk model ...`.
#[derive(Debug, Subcommand)]
pub enum ModelCommand {
    /// The solved explicit equations block by block, their pivots and the outputs (Markdown,
    /// or LaTeX with `--format latex`); for `rolling` also N/mg at the paper's start beside
    /// the paper's formula (13). A DSL file shows its model and each of its charts.
    Show {
        /// `rolling`, `sliding`, `sliding-cartesian`, or a DSL file (what goes inside
        /// `model! { .. }`).
        model: String,
        /// Markdown (DSL syntax) or LaTeX.
        #[arg(short, long, value_enum, default_value = "markdown")]
        format: ShowFormat,
        /// Compile the file even if the cache of compiled models holds it, and keep nothing
        /// there (the cache: `$XDG_CACHE_HOME/eulerdisk/models` or `~/.cache/eulerdisk/models`).
        #[arg(long)]
        no_cache: bool,
    },
    /// Evaluate a model of the disk (`model eval rolling`), or a DSL file's model interpreted,
    /// at one state: derivatives (`der(x)`) and outputs by name, as JSON.
    Eval(ModelEvalArgs),
    /// Integrate a DSL file's model, interpreted, and write `t`, the states and the outputs as
    /// CSV.
    Solve(ModelSolveArgs),
}

/// How `model show` prints the equations (the library's [`ModelFormat`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ShowFormat {
    /// Markdown, the equations in DSL syntax.
    Markdown,
    /// A LaTeX `align*` environment.
    Latex,
}

impl From<ShowFormat> for ModelFormat {
    fn from(format: ShowFormat) -> ModelFormat {
        match format {
            ShowFormat::Markdown => ModelFormat::Markdown,
            ShowFormat::Latex => ModelFormat::Latex,
        }
    }
}

/// The model, state and parameters of `model eval` and `model solve`.
#[derive(Debug, Args)]
pub struct ModelPointArgs {
    /// A DSL file; for `model eval` also a model of the disk (`rolling`, `sliding`,
    /// `sliding-cartesian`), as `model show` takes it.
    pub model: String,
    /// One of the model's charts instead of the model itself.
    #[arg(long)]
    pub chart: Option<String>,
    /// A state value, `NAME=VALUE` (repeatable): it overrides the initial value the file
    /// writes (`states { x = 2 }`); a state given neither here nor there is 0.
    #[arg(long = "state", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub state: Vec<String>,
    /// A parameter value, `NAME=VALUE` (repeatable; the others keep the file's defaults).
    #[arg(
        short,
        long = "set",
        value_name = "NAME=VALUE",
        allow_hyphen_values = true
    )]
    pub set: Vec<String>,
    /// Compile the file even if the cache of compiled models holds it, and keep nothing
    /// there (the cache: `$XDG_CACHE_HOME/eulerdisk/models` or `~/.cache/eulerdisk/models`).
    #[arg(long)]
    pub no_cache: bool,
}

/// `eulerdisk model eval NAME|FILE`.
#[derive(Debug, Args)]
pub struct ModelEvalArgs {
    /// The model and the point.
    #[command(flatten)]
    pub point: ModelPointArgs,
    /// The time.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub t: f64,
    /// For a model of the disk: the hand-written reference instead of the generated model.
    #[arg(long)]
    pub reference: bool,
}

/// `eulerdisk model solve FILE`.
#[derive(Debug, Args)]
pub struct ModelSolveArgs {
    /// The model and the initial point.
    #[command(flatten)]
    pub point: ModelPointArgs,
    /// Start time.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub t0: f64,
    /// End time; before `--t0`, a smooth model is integrated backward in time (as SciPy's
    /// `solve_ivp` does; an event's `up` or `down` is the crossing as the run proceeds); a
    /// switched model runs forward only.
    #[arg(long, allow_negative_numbers = true)]
    pub t_end: f64,
    /// The integrator.
    #[arg(long, value_enum, default_value = "dop853")]
    pub integrator: IntegratorName,
    /// Deprecated spelling of `--integrator`.
    #[arg(long, value_enum, hide = true)]
    pub method: Option<IntegratorName>,
    /// Relative tolerance.
    #[arg(long, default_value = "1e-8", allow_negative_numbers = true)]
    pub rtol: f64,
    /// Absolute tolerance.
    #[arg(long, default_value = "1e-10", allow_negative_numbers = true)]
    pub atol: f64,
    /// Record every DT from the start towards the end time (and at it) instead of at every
    /// step.
    #[arg(long, allow_negative_numbers = true)]
    pub dt: Option<f64>,
    /// The trajectory file (`-`: standard output, as CSV): `t`, `mode` (a switched model),
    /// the states, the discrete values, the outputs.
    #[arg(short, long, default_value = "-")]
    pub out: PathBuf,
    /// The format of the files (Parquet: to files only).
    #[arg(short, long, value_enum, default_value = "csv")]
    pub format: FormatArg,
    /// The work bound, as `run`'s `solver.max_steps_per_s`: by simulated time `t` the run may
    /// have taken `MAX × (|t − t0| + 0.1)` steps; a run over it fails, keeping what it
    /// computed.
    #[arg(long, value_name = "MAX", default_value = "1e6")]
    pub max_steps_per_s: f64,
    /// An event, `NAME[:up|:down][:stop]` (repeatable): located where the state or output
    /// NAME crosses zero (upwards, downwards, or both by default); `:stop` ends the run there.
    /// For a threshold other than zero, add an output to the file (`hit = theta - 0.1`) and
    /// watch it.
    #[arg(long = "event", value_name = "SPEC")]
    pub event: Vec<String>,
    /// Write the events to this file (`event,phase`, then the trajectory's columns: the state
    /// before each event and after its reset, and a last row `stop` saying how the run
    /// ended; `-`: standard output); without it, each event is said on standard error.
    #[arg(long, value_name = "PATH")]
    pub events: Option<PathBuf>,
    /// Evaluate the model with the flat evaluator only, never compiling it to machine code
    /// (the same results; by default each program is compiled once it has been evaluated
    /// often enough to pay for its compile, and machines without a code generator never
    /// compile).
    #[arg(long)]
    pub no_jit: bool,
}

impl ModelSolveArgs {
    /// The integrator asked for: `--integrator`, or the deprecated `--method` when given.
    pub fn integrator(&self) -> IntegratorName {
        self.method.unwrap_or(self.integrator)
    }
}

/// A mode on the command line.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum ModeArg {
    /// The contact particle at rest.
    Rolling,
    /// The contact particle slipping (polar slip: v_C, alpha).
    Sliding,
}

impl From<ModeArg> for Mode {
    fn from(m: ModeArg) -> Mode {
        match m {
            ModeArg::Rolling => Mode::Rolling,
            ModeArg::Sliding => Mode::Sliding,
        }
    }
}

/// `eulerdisk eval`.
#[derive(Debug, Args)]
pub struct EvalArgs {
    /// The mode whose equations are evaluated.
    #[arg(long, value_enum)]
    pub mode: ModeArg,
    /// Use the hand-written reference instead of the generated models.
    #[arg(long)]
    pub reference: bool,
    /// A state value by the paper's name, `NAME=VALUE` (repeatable; missing entries are 0).
    #[arg(long = "state", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub state: Vec<String>,
    /// A parameter, `NAME=VALUE` (repeatable; m, a, g, mu_d, mu_st, mu_a, w_z; the others
    /// keep the paper's values).
    #[arg(
        short,
        long = "set",
        value_name = "NAME=VALUE",
        allow_hyphen_values = true
    )]
    pub set: Vec<String>,
    /// Deprecated: the parameters as a JSON object (write `--set NAME=VALUE`).
    #[arg(long, hide = true)]
    pub params: Option<String>,
}
