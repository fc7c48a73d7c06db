//! The paper's models in the equation DSL, compiled to explicit Rust at build time.
//!
//! Each file reads like its box in the paper (row labels R1–R12, S1–S12); EQUATIONS.md lists
//! where the printed boxes were damaged and what was restored. The emitted modules implement
//! `model_runtime::Model<12>` and `WithOutputs`, with the same state and output order as the
//! hand-written reference in `crate::reference`, which the tests hold them to.

mod box1_rolling;
mod box3_sliding;
mod box3_sliding_cartesian;

pub use box1_rolling::rolling;
pub use box3_sliding::sliding;
pub use box3_sliding_cartesian::sliding_cartesian;
