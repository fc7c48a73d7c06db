//! Symbolic algebra for the equation compiler (see the module docs of each stage).
#![warn(missing_docs)]

pub mod program;
pub mod spec;
