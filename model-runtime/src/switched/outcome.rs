//! What a run of a [`crate::Switched`] system reports: why it stopped, and what it tells the
//! observer about each event.

use super::graph::{EventId, ModeId};
use crate::accumulation::Accumulation;

/// Why a [`crate::Switched`] run stopped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SwitchedStop {
    /// A terminal event ([`crate::EventAction::Stop`]) fired.
    Event {
        /// Its mode.
        mode: ModeId,
        /// Its position in the mode's events.
        event: usize,
        /// When it fired.
        t: f64,
    },
    /// The resets of an event without an accumulation action accumulated.
    Accumulation {
        /// Its mode.
        mode: ModeId,
        /// Its position in the mode's events.
        event: usize,
        /// The extrapolated accumulation point (the run ends at the last firing, within the
        /// rule's tail before it).
        t_inf: f64,
    },
}

impl SwitchedStop {
    /// The event that ended the run (named by [`crate::ModeGraph::event_name`]).
    pub fn event(&self) -> EventId {
        match *self {
            SwitchedStop::Event { mode, event, .. }
            | SwitchedStop::Accumulation { mode, event, .. } => EventId { mode, event },
        }
    }
}

/// What a [`crate::Switched`] system tells the observer about an event
/// ([`crate::TransitionRecord::note`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SwitchedNote {
    /// A [`crate::EventAction::Record`] event passed.
    Recorded(EventId),
    /// A [`crate::EventAction::Reset`] event applied its reset.
    Reset(EventId),
    /// The event's resets accumulated: its accumulation reset was applied instead.
    Accumulated {
        /// The event.
        event: EventId,
        /// Where the firings accumulate and their ratio.
        accumulation: Accumulation,
    },
}
