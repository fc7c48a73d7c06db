//! Euler's disk: the paper's rolling and sliding models, an independent reference, and the
//! paper's mode rules.
//!
//! The same physics is written three times, on purpose: as the paper's boxes in the equation
//! DSL ([`models`], compiled to explicit Rust), as vector Newton–Euler solved numerically
//! ([`reference`](mod@reference), the oracle), and as the closed forms a reader can check by hand
//! ([`formulas`]). The tests hold each to the others at random and extreme states. All of
//! them take their parameters from one validated [`DiskParams`].
#![warn(missing_docs)]

pub mod formulas;
pub mod hybrid;
pub mod models;
pub mod modes;
pub mod params;
pub mod reference;

pub use params::{DiskParams, ParamError};
