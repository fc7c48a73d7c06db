//! Output files: written atomically, in plain formats.

pub mod atomic;
pub mod tables;
