//! Symbolic algebra for the equation compiler.
//!
//! A model arrives as a [`spec::ModelSpec`] (the front end's parse, with a node id on every
//! part) and leaves as a [`program::CompiledModel`]: straight-line programs for the explicit
//! right-hand side, its Jacobian and the outputs. In between, one stage per module:
//! [`lower`] (syntax tree to interned expressions, with diagnostics at the user's nodes),
//! [`linear`] (each equation as coefficients of the derivatives), [`structure`] (matching and
//! block triangular form), [`solve`] (symbolic elimination per block, or a numeric block when
//! that would swell), [`jacobian`] (chain rule through the solution), [`cse`] (the DAG as a
//! program) and [`variant`] (reduced models). [`expr`], [`simplify`] and [`diff`] are the
//! algebra underneath; [`eval`] interprets a program, for tests.
#![warn(missing_docs)]

pub mod compile;
pub mod cse;
pub mod diff;
mod display;
pub mod eval;
pub mod expand;
pub mod expr;
pub mod jacobian;
pub mod linear;
pub mod lower;
pub mod ops;
pub mod print;
pub mod program;
pub mod simplify;
pub mod solve;
pub mod spec;
pub mod structure;
pub mod system;
pub mod variant;

pub use compile::{compile, CompileOptions};
pub use eval::{EvalFailure, Inputs, Stores};

#[cfg(test)]
mod testing;
#[cfg(test)]
mod tests;
