//! The command line: `eulerdisk [run [SCENE]] | eval | scenes`.
//!
//! Flags map onto scene keys (`--rtol` is `--set solver.rtol=...`) so every value from the
//! command line passes the same validation as the scene file.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::eval::Backend;
use crate::scene::schema::ModeName;
use crate::scene::{Override, SceneError, DEFAULT_SCENE};

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
    Sound(crate::sound::args::SoundArgs),
    /// Print a model's equations as the compiler solved them (`model show rolling`).
    #[command(subcommand)]
    Model(ModelCommand),
}

/// `eulerdisk model ...`.
#[derive(Debug, Subcommand)]
pub enum ModelCommand {
    /// The solved explicit equations block by block, their pivots and the outputs (Markdown,
    /// or LaTeX with `--format latex`); for `rolling` also N/mg at the paper's start beside
    /// the paper's formula (13).
    Show {
        /// The model.
        #[arg(value_enum)]
        model: crate::model_show::ModelName,
        /// Markdown (DSL syntax) or LaTeX.
        #[arg(long, value_enum, default_value = "markdown")]
        format: crate::model_show::Format,
    },
}

/// `eulerdisk run`.
#[derive(Debug, Args, Default)]
pub struct RunArgs {
    /// A scene file, or the name of a built-in scene.
    #[arg(default_value = DEFAULT_SCENE)]
    pub scene: String,
    /// Override `run.t_end` (s).
    #[arg(long, allow_negative_numbers = true)]
    pub t_end: Option<f64>,
    /// Override `solver.rtol`.
    #[arg(long, allow_negative_numbers = true)]
    pub rtol: Option<f64>,
    /// Override `solver.atol`.
    #[arg(long, allow_negative_numbers = true)]
    pub atol: Option<f64>,
    /// Override `solver.integrator` (dopri5, dop853, rodas4).
    #[arg(long)]
    pub integrator: Option<String>,
    /// Output directory.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// No progress output.
    #[arg(long)]
    pub quiet: bool,
    /// Override any scene key: `--set table.key=value` (repeatable).
    #[arg(long = "set", value_name = "TABLE.KEY=VALUE")]
    pub set: Vec<String>,
    /// Run the hand-written reference models instead of the generated ones.
    #[arg(long)]
    pub reference: bool,
    /// Skip the figures.
    #[arg(long)]
    pub no_figures: bool,
}

impl RunArgs {
    /// The scene overrides these arguments ask for, in order (`--set` last, so it wins).
    pub fn overrides(&self) -> Result<Vec<Override>, SceneError> {
        let mut out = Vec::new();
        if let Some(v) = self.t_end {
            out.push(Override::new("run", "t_end", v));
        }
        if let Some(v) = self.rtol {
            out.push(Override::new("solver", "rtol", v));
        }
        if let Some(v) = self.atol {
            out.push(Override::new("solver", "atol", v));
        }
        if let Some(v) = &self.integrator {
            out.push(Override::new("solver", "integrator", v.as_str()));
        }
        for spec in &self.set {
            out.push(Override::parse(spec)?);
        }
        Ok(out)
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

impl From<ModeArg> for ModeName {
    fn from(m: ModeArg) -> ModeName {
        match m {
            ModeArg::Rolling => ModeName::Rolling,
            ModeArg::Sliding => ModeName::Sliding,
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
    /// The state as a JSON object by the paper's names (missing entries are 0).
    #[arg(long)]
    pub state: Option<String>,
    /// Parameters as a JSON object (m, a, g, mu_d, mu_st, mu_a, w_z; missing: the paper's).
    #[arg(long)]
    pub params: Option<String>,
}

/// The models the CLI runs unless `--reference` is given: the one line to switch.
pub const DEFAULT_BACKEND: Backend = Backend::Generated;

/// The backend a `--reference` flag selects.
pub fn backend(reference: bool) -> Backend {
    if reference {
        Backend::Reference
    } else {
        DEFAULT_BACKEND
    }
}
