//! Whole models read from DSL text by the front end, compiled by `model_algebra` and run
//! through its interpreter: the compiler's cross-stage tests (end to end against hand
//! derivations, the disk models of the `equations` crate, operation counts, pivots, the
//! compiler's own diagnostics), and the text front end's located errors.

mod cartesian_disk;
mod common;
mod diagnostics;
mod end_to_end;
mod held;
mod hostile;
mod include;
mod nonsmooth;
mod op_counts;
mod pivots;
mod rolling_disk;
mod sliding_disk;
mod switching;
mod text;
mod variants;
