//! Numbers read off a run: oscillation periods, envelopes, the summary.

pub mod extrema;
pub mod oscillation;
pub mod summary;
pub mod synthetic;
