//! What a mode's guards read, so that screening interpolates only that.
//!
//! A screening estimate (see [`crate::GuardSpec`]) evaluates the guards on the
//! dense output and its derivative. Interpolating every component of both costs as much as
//! the rest of the estimate when the guards read a handful of them, and estimates outnumber
//! steps several times over. A system therefore declares, per mode, which components of the
//! state and of its derivative its guards read; estimates interpolate those and fill every
//! other component with NaN. A declaration that misses a component cannot go unnoticed or
//! change a result: the guard that reads it gets a non-finite estimate, which (like any
//! non-finite estimate) only asks for the exact evaluation, with the full state. Exact
//! evaluations never depend on the declaration.

use crate::dim::{Const, Dim};
use crate::stepper::Components;

/// The components of the state `y` and of its derivative `dy` that a mode's guards read.
#[derive(Clone, Debug, PartialEq)]
pub struct GuardInputs<D: Dim> {
    /// The components of `y` the guards read.
    pub state: Components<D>,
    /// The components of `dy` the guards read.
    pub rates: Components<D>,
}

impl<D: Dim> GuardInputs<D> {
    /// Every component of both, in states of size `dim`: what a system that declares nothing
    /// gets.
    pub fn all(dim: D) -> Self {
        GuardInputs {
            state: Components::all(dim),
            rates: Components::all(dim),
        }
    }
}

impl<const N: usize> Copy for GuardInputs<Const<N>> {}

impl<const N: usize> GuardInputs<Const<N>> {
    /// Every component of both.
    pub const ALL: Self = GuardInputs {
        state: Components::ALL,
        rates: Components::ALL,
    };

    /// Guards that read only the components `state` of `y` and `rates` of `dy`.
    ///
    /// # Panics
    ///
    /// If an index is `N` or more (at compile time for a constant).
    pub const fn of(state: &[usize], rates: &[usize]) -> Self {
        GuardInputs {
            state: Components::of(state),
            rates: Components::of(rates),
        }
    }

    /// The inputs of both sets of guards.
    pub const fn union(self, other: Self) -> Self {
        GuardInputs {
            state: self.state.union(other.state),
            rates: self.rates.union(other.rates),
        }
    }
}

impl<const N: usize> Default for GuardInputs<Const<N>> {
    /// [`GuardInputs::ALL`].
    fn default() -> Self {
        Self::ALL
    }
}
