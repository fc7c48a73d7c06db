//! Runtime for models emitted by `model-macros`: integrators, event location, hybrid driver.
#![warn(missing_docs)]

pub mod model;

pub use model::{EvalError, Model, ModelInfo, OpCounts, WithOutputs};
