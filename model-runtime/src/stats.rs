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
    /// [`crate::InteriorChecks::Screened`]).
    pub guard_estimates: u64,
    /// Events located (guards that fired, passes included).
    pub events: u64,
    /// Accepted steps of an adaptive method by the component with the largest scaled error,
    /// the one that limited the step size. Counted only when the tolerance asks for it
    /// ([`crate::Tolerance::tracking_limiting`]); all zero otherwise.
    pub limiting: ComponentCounts,
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
        self.limiting += o.limiting;
    }
}

/// Counts per state component, for the first [`ComponentCounts::CAPACITY`] components (the
/// rest share one count).
///
/// A fixed array rather than one sized by the state dimension keeps [`Stats`] a plain `Copy`
/// value that every driver can add up without knowing `N`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ComponentCounts {
    counts: [u64; ComponentCounts::CAPACITY],
    beyond: u64,
}

impl Default for ComponentCounts {
    fn default() -> Self {
        ComponentCounts {
            counts: [0; ComponentCounts::CAPACITY],
            beyond: 0,
        }
    }
}

impl ComponentCounts {
    /// Components counted one by one.
    pub const CAPACITY: usize = 32;

    /// Counts one event of `component`.
    #[inline]
    pub fn record(&mut self, component: usize) {
        match self.counts.get_mut(component) {
            Some(c) => *c += 1,
            None => self.beyond += 1,
        }
    }

    /// The count of `component` (for one at or past [`ComponentCounts::CAPACITY`]: the shared
    /// count of all those).
    pub fn get(&self, component: usize) -> u64 {
        self.counts.get(component).copied().unwrap_or(self.beyond)
    }

    /// The sum over all components.
    pub fn total(&self) -> u64 {
        self.counts.iter().sum::<u64>() + self.beyond
    }

    /// `(component, count)` for every component below [`ComponentCounts::CAPACITY`] with a
    /// non-zero count, in component order.
    pub fn nonzero(&self) -> impl Iterator<Item = (usize, u64)> + '_ {
        self.counts
            .iter()
            .enumerate()
            .filter(|(_, &c)| c > 0)
            .map(|(i, &c)| (i, c))
    }
}

impl AddAssign for ComponentCounts {
    fn add_assign(&mut self, o: ComponentCounts) {
        for (a, b) in self.counts.iter_mut().zip(o.counts) {
            *a += b;
        }
        self.beyond += o.beyond;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_add_up_and_components_past_the_capacity_share_one() {
        let mut a = ComponentCounts::default();
        a.record(3);
        a.record(3);
        a.record(40);
        let mut b = ComponentCounts::default();
        b.record(3);
        b.record(0);
        b.record(ComponentCounts::CAPACITY);
        a += b;
        assert_eq!(a.get(3), 3);
        assert_eq!(a.get(0), 1);
        assert_eq!(a.get(40), 2);
        assert_eq!(a.get(1000), 2);
        assert_eq!(a.total(), 6);
        assert_eq!(a.nonzero().collect::<Vec<_>>(), [(0, 1), (3, 3)]);
    }
}
