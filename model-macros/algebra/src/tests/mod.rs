//! Cross-stage tests: whole models compiled and run through the interpreter.

mod diagnostics;
mod end_to_end;
mod props;
mod rolling_disk;
