//! The `model!` macro's user-facing diagnostics, pinned (`tests/diagnostics.rs`).
//!
//! This crate holds no code. Its tests give each diagnostic of the macro a file of its own
//! under `tests/ui` with the exact message and the token it points at, and `tests/pass` holds
//! expansions that must compile and run cleanly under strict lints. It is a crate of its own
//! because trybuild builds the cases with the crate's dev-dependencies in a separate target
//! folder: here those are only the macro and the runtime.
