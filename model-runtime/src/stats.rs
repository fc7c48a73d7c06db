//! Work counters, so a run's cost can be reported and compared between methods.

use std::ops::AddAssign;

/// What an integration cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected step attempts.
    pub rejected: u64,
    /// Right-hand side evaluations (including those for dense output and event location).
    pub rhs_evals: u64,
    /// Jacobian evaluations.
    pub jacobian_evals: u64,
    /// LU decompositions of an iteration matrix.
    pub decompositions: u64,
    /// Guard evaluations (each evaluates all guards of the current mode once).
    pub guard_evals: u64,
    /// Guard estimates from the dense output (no model evaluation; see
    /// [`crate::events::InteriorChecks::Screened`]).
    pub guard_estimates: u64,
    /// Events located (guards that fired).
    pub events: u64,
}

impl AddAssign for Stats {
    fn add_assign(&mut self, o: Stats) {
        self.steps += o.steps;
        self.rejected += o.rejected;
        self.rhs_evals += o.rhs_evals;
        self.jacobian_evals += o.jacobian_evals;
        self.decompositions += o.decompositions;
        self.guard_evals += o.guard_evals;
        self.guard_estimates += o.guard_estimates;
        self.events += o.events;
    }
}
