//! Euler's disk: the paper's rolling and sliding models, an independent reference, and the
//! paper's mode rules.
#![warn(missing_docs)]

pub mod formulas;
pub mod hybrid;
pub mod models;
pub mod modes;
pub mod params;
pub mod reference;

pub use params::{DiskParams, ParamError};
