//! Every integration test of the equation compiler in one test binary, one module per former file: one
//! link instead of one per file, which is most of a cold `cargo test`.

mod belt;
mod cart_pendulum;
mod cartesian_pendulum;
mod common;
mod dense_chain;
mod guard_inputs;
mod held;
mod rotating_hoop;
mod rust_reset;
mod solve;
mod time_scale;
mod tiny_pivot;
