//! A model file as compiled, the value the loader makes and the cache keeps. Its own file so
//! that the loader (which asks the cache) and the cache (which stores and returns files) both
//! use it without using each other.

use model_dsl::{CompiledSwitched, TextModel};

/// A model file as compiled: a smooth model (with its charts) or a switched one.
#[derive(Clone, Debug)]
pub enum ModelFile {
    /// The model, then each of its charts.
    Smooth(Vec<TextModel>),
    /// A model with modes and events.
    Switched(CompiledSwitched),
}
