//! Euler's disk: the paper's rolling and sliding models, an independent reference, and the
//! paper's mode rules.
#![warn(missing_docs)]
