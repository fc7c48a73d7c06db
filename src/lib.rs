//! The `eulerdisk` command line: scenes in, trajectories, events, figures and a summary out.
//!
//! The binary is a thin shell over this library so that integration tests can drive the same
//! scene loader, parsers and writers the command uses, with random inputs, without a process
//! per case.
#![warn(missing_docs)]

pub mod named_numbers;
pub mod quantity;
pub mod sample;
pub mod scene;
