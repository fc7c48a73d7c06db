//! Cross-stage tests: whole models compiled and run through the interpreter.

mod cartesian_disk;
mod diagnostics;
mod end_to_end;
mod linear_systems;
mod op_counts;
mod pivots;
mod props;
mod random_models;
mod rolling_disk;
mod sliding_disk;
