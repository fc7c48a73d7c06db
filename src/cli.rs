//! The command line: `eulerdisk [run [SCENE]] | eval | scenes | sound | sweep`.
//!
//! Flags map onto scene keys (`--rtol` is `--set solver.rtol=...`) so every value from the
//! command line passes the same validation as the scene file.

use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::args::RunArgs;
use equations::Mode;

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
    /// Run many scenes at once: axes over any scene key, a table of their summaries, figures;
    /// resumable, and shardable over a cluster's job array (`sweep merge` joins the shards).
    Sweep(crate::sweep::args::SweepArgs),
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
    /// The state as a JSON object by the paper's names (missing entries are 0).
    #[arg(long)]
    pub state: Option<String>,
    /// Parameters as a JSON object (m, a, g, mu_d, mu_st, mu_a, w_z; missing: the paper's).
    #[arg(long)]
    pub params: Option<String>,
}
