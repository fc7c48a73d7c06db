//! Unit tests of the emitter and of the whole expansion, run on `proc_macro2` tokens outside the
//! compiler.

mod emit;
mod fuzz;
mod include;
mod timing;
