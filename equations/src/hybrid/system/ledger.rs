//! What a run of the disk counts besides its states: the mode decisions (all of them, and the
//! latest within the chattering window) and the largest constraint drift seen. Both engines
//! of the disk keep one, the hand-written system (module `system`) and the mode graph's
//! (module `graph`), so that the counts and the stop they lead to are the same code.

use super::{Halted, Phase};
use crate::config::DiskConfig;
use crate::hybrid::StopReason;
use crate::modes::{ConstraintResiduals, PhysicalState, DIM};
use crate::params::DiskParams;
use std::cell::Cell;
use std::collections::VecDeque;

/// A run's mode decisions and constraint drift.
#[derive(Clone, Debug)]
pub(crate) struct Ledger {
    /// Event-driven mode decisions so far.
    pub transitions: u64,
    /// The times of the decisions within the chattering window.
    recent: VecDeque<f64>,
    /// Decisions allowed within the window.
    chatter_max: usize,
    /// The chattering window (s).
    chatter_window: f64,
    /// The largest drift noted (a cell: drift is noted where the driver holds the system
    /// shared, after every step).
    max_drift: Cell<ConstraintResiduals>,
}

impl Ledger {
    /// An empty ledger with the chattering limit of `config`.
    pub(crate) fn new(config: &DiskConfig) -> Self {
        Ledger {
            transitions: 0,
            recent: VecDeque::new(),
            chatter_max: config.chatter.max_transitions,
            chatter_window: config.chatter.window,
            max_drift: Cell::new(ConstraintResiduals::default()),
        }
    }

    /// The largest drift noted, component by component.
    pub(crate) fn max_drift(&self) -> ConstraintResiduals {
        self.max_drift.get()
    }

    /// Notes the drift `r`.
    pub(crate) fn note_drift(&self, r: ConstraintResiduals) {
        let m = self.max_drift.get();
        self.max_drift.set(ConstraintResiduals {
            height: m.height.max(r.height.abs()),
            vertical_speed: m.vertical_speed.max(r.vertical_speed.abs()),
            no_slip: m.no_slip.max(r.no_slip),
        });
    }

    /// Notes the drift of the state `y` after a step in `phase` (none on a bridge, which is
    /// a straight line off the constraints by design); returns the state in rolling variables
    /// for a projection.
    pub(crate) fn note_step(
        &self,
        params: &DiskParams,
        phase: Phase,
        y: &[f64; DIM],
    ) -> Option<PhysicalState> {
        if phase == Phase::Bridge {
            return None;
        }
        let state = PhysicalState::from_rolling(y, 0.0);
        self.note_drift(state.residuals(params, phase.mode()));
        Some(state)
    }

    /// Counts a decision at `t` in the chattering window; true when the limit is exceeded.
    pub(crate) fn chattering(&mut self, t: f64) -> bool {
        self.recent.push_back(t);
        while (self.recent.front()).is_some_and(|&t0| t0 < t - self.chatter_window) {
            self.recent.pop_front();
        }
        self.recent.len() > self.chatter_max
    }

    /// The stop for chattering at `t`.
    pub(crate) fn chatter_stop(&self, t: f64) -> Halted {
        Halted::plain(StopReason::Chattering {
            t,
            transitions: self.recent.len(),
            window: self.chatter_window,
        })
    }
}
