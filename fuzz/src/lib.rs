//! Fuzzing that stays: the workspace's fuzz targets and the one harness that runs them, on
//! stable Rust.
//!
//! ```text
//! cargo run --profile test -p eulerdisk-fuzz -- [TARGET...|all] [--inputs N] [--seconds S] [--seed K]
//! ```
//!
//! The targets ([`targets::ALL`]):
//!
//! - `dsl-front`, `dsl-compile`, `dsl-eval`: the DSL's parser and validator, its compiler,
//!   and the compiled programs at extreme values ([`targets::dsl`]);
//! - `scene`: the scene loader with `--set` overrides ([`targets::scene`]);
//! - `sweep`: the sweep loader, its expansion and `--dry-run`'s listing ([`targets::sweep`]);
//! - `models`: the disk's generated and hand-written models at extreme states
//!   ([`targets::models`]).
//!
//! Every input must give a value or a clear error: a panic, an abort (a stack overflow), an
//! input slower than 10 s, a wrong answer that does not crash (an `Ok` carrying a NaN, a
//! listed point the loader refuses) and a file left behind are findings. Each target runs
//! `--inputs N` inputs or for `--seconds S` (10 s when neither is given), made from the seed
//! `K` (default 1) and the input's index alone, so `--inputs` makes a run deterministic. The
//! program prints inputs/s and findings per target and exits nonzero on any finding; each is
//! saved under `fuzz/findings/` as `TARGET-KIND-seedK-INDEX.EXT`.
//!
//! Why a harness of our own and not `cargo fuzz`: that needs a nightly compiler and
//! sanitizers, and this workspace builds on stable; the findings that matter here (stack
//! overflows, hangs, NaN in an `Ok`) need a supervising process, not coverage guidance
//! ([`supervisor`]). The mutations are shared by the text targets and know no grammar
//! ([`mutate`]), so a target is its seeds, its words and its check.
//!
//! Seeds live in `fuzz/corpus/<target>/` (the scene and sweep targets also take the
//! repository's `scenes/` and `sweeps/`). A finding, once fixed at its cause, is copied into
//! its target's corpus: the test `tests/corpus.rs` runs every seed through its target's
//! check, so each becomes a regression test, and the fuzzer mutates it from then on.
#![warn(missing_docs)]

pub mod mutate;
pub mod rng;
pub mod supervisor;
pub mod targets;
