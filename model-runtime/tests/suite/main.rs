//! Every integration test of the runtime in one test binary, one module per former file: one
//! link instead of one per file, which is most of a cold `cargo test`.

mod backward;
mod common;
mod convergence;
mod events;
mod failures;
mod guard_inputs;
mod hybrid;
mod long_runs;
mod norm;
mod notes;
mod passes;
mod properties;
mod sizes;
mod stiff;
mod stored;
mod switched;
mod switched_regularised;
