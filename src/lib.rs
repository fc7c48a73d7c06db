//! The `eulerdisk` command line: scenes in, trajectories, events, figures and a summary out.
//!
//! The binary is a thin shell over this library so that integration tests can drive the same
//! scene loader, parsers and writers the command uses, with random inputs, without a process
//! per case.
#![warn(missing_docs)]

pub mod analysis;
pub mod args;
pub mod cli;
pub mod eval;
pub mod figures;
pub mod model_command;
pub mod model_file;
pub mod model_show;
pub mod model_solve;
pub mod named_numbers;
pub mod output;
pub mod quantity;
pub mod record;
pub mod run;
pub mod sample;
pub mod scene;
pub mod sound;
pub mod sweep;
