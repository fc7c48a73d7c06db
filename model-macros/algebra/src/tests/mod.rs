//! Cross-stage tests: whole models compiled and run through the interpreter.

mod flat;
mod linear_systems;
mod props;
mod random_models;
