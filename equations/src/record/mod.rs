//! A run's records in named fields: what every front end (the command line, the Python
//! package) writes, plots and summarises.
//!
//! The simulation streams arrays in a model's index order and typed events ([`DiskSample`],
//! [`TransitionRecord`], [`StopReason`]); front ends read names instead. The conversion is
//! written here once, so a front end holds no state order, no friction law and no spelling of
//! a stop reason of its own: it formats these types and matches on them.
//!
//! [`DiskSample`]: crate::DiskSample
//! [`TransitionRecord`]: crate::TransitionRecord
//! [`StopReason`]: crate::StopReason

mod quantity;
mod sample;
mod stop;
mod trigger;

pub use quantity::{forget_frozen, Quantity};
pub use sample::{ContactForces, DiskState, FrictionLaw, Sample};
pub use stop::{Stop, StopKind};
pub use trigger::TriggerKind;
