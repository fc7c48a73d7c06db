//! Chattering detection: the transitions of the latest time window, so that a run caught
//! switching back and forth without advancing in time stops with the modes involved instead
//! of looping. Passes are not transitions and are never recorded here.

use super::{ChatterLimit, HybridError};
use std::collections::VecDeque;

/// The transitions `(t, from, to)` within the limit's window before the latest one.
#[derive(Clone, Debug)]
pub(super) struct RecentTransitions<Md> {
    limit: ChatterLimit,
    recent: VecDeque<(f64, Md, Md)>,
}

impl<Md: Copy + PartialEq> RecentTransitions<Md> {
    /// None yet, against `limit`.
    pub(super) fn new(limit: ChatterLimit) -> Self {
        RecentTransitions {
            limit,
            recent: VecDeque::with_capacity(limit.max_transitions + 1),
        }
    }

    /// Records a transition at `t` from `from` to `to`: chattering if the window ending at `t`
    /// now holds more transitions than the limit allows.
    pub(super) fn record(&mut self, t: f64, from: Md, to: Md) -> Result<(), HybridError<Md>> {
        let limit = self.limit;
        self.recent.push_back((t, from, to));
        while let Some(&(t_old, _, _)) = self.recent.front() {
            if t_old < t - limit.window {
                self.recent.pop_front();
            } else {
                break;
            }
        }
        if self.recent.len() > limit.max_transitions {
            let mut modes = Vec::new();
            for &(_, a, b) in &self.recent {
                for m in [a, b] {
                    if !modes.contains(&m) {
                        modes.push(m);
                    }
                }
            }
            return Err(HybridError::Chattering {
                t,
                transitions: self.recent.len(),
                window: limit.window,
                modes,
            });
        }
        Ok(())
    }
}
