//! The tables of a switched model: its modes, each mode's events, and what every event does.
//! Checked once, when the graph is built, so that the adaptor can follow them without checks.

use std::fmt;

/// A mode of a switched model: its name and its events, in priority order (on equal event
/// times the first listed wins).
#[derive(Clone, Debug, PartialEq)]
pub struct ModeDecl {
    /// The mode's name, unique in the graph.
    pub name: String,
    /// Its events.
    pub events: Vec<EventDecl>,
}

/// An event of a mode: a guard crossing (`direction`), what it does, and what happens when it
/// accumulates.
#[derive(Clone, Debug, PartialEq)]
pub struct EventDecl {
    /// The event's name, unique in its mode.
    pub name: String,
    /// Which crossings of its guard fire it.
    pub direction: crate::events::Direction,
    /// What it does when it fires.
    pub action: EventAction,
    /// What an accumulation of its resets turns into (only for [`EventAction::Reset`]); with
    /// `None`, an accumulation stops the run.
    pub on_accumulation: Option<AccumulationAction>,
}

/// What an event does when it fires.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventAction {
    /// Recorded, the run goes on untouched (a [`crate::Transition::Pass`]).
    Record,
    /// Apply the event's reset (if `reset` is true) and continue in mode `to` (or restart the
    /// same mode when `to` is `None`).
    Reset {
        /// The index of the next mode; `None` for the same one.
        to: Option<usize>,
        /// Whether the event assigns states ([`crate::SwitchedModel::reset`]).
        reset: bool,
    },
    /// End the run; the event's name is the reason.
    Stop,
    /// The model decides ([`crate::SwitchedModel::decide`]): it assigns states and names the
    /// mode the run continues in (a restart when it names the event's own), or stops the run
    /// with the event's name as the reason. For a transition that depends on the state in a
    /// way no single target says: a slip that stops may stick or slide on.
    Decide,
}

/// What an accumulation of an event's resets turns into: a switch to mode `to` (the same mode
/// when `None`) after the accumulation reset (if `reset`), e.g. a bouncing ball that comes to
/// rest.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AccumulationAction {
    /// The index of the mode the run continues in; `None` for the same one.
    pub to: Option<usize>,
    /// Whether the accumulation assigns states ([`crate::SwitchedModel::reset`] with
    /// `accumulation` true).
    pub reset: bool,
}

/// A mode of a [`ModeGraph`], by its position in it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ModeId(usize);

impl ModeId {
    /// The mode's position in its graph.
    pub fn index(self) -> usize {
        self.0
    }
}

/// An event of a [`ModeGraph`]: its mode and its position in that mode's list.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct EventId {
    /// The mode.
    pub mode: ModeId,
    /// The event's position in the mode's list.
    pub event: usize,
}

/// The modes of a switched model and their events, checked: names unique, every target a
/// mode of the graph, accumulation actions only on resets.
#[derive(Clone, Debug, PartialEq)]
pub struct ModeGraph {
    modes: Vec<ModeDecl>,
}

impl ModeGraph {
    /// The graph of these modes, or what is wrong with them (the first problem found).
    pub fn new(modes: Vec<ModeDecl>) -> Result<Self, GraphError> {
        if modes.is_empty() {
            return Err(GraphError::NoModes);
        }
        let count = modes.len();
        for (m, mode) in modes.iter().enumerate() {
            if let Some(first) = modes[..m].iter().position(|o| o.name == mode.name) {
                return Err(GraphError::DuplicateMode {
                    name: mode.name.clone(),
                    first,
                    second: m,
                });
            }
            for (e, event) in mode.events.iter().enumerate() {
                let names = || (mode.name.clone(), event.name.clone());
                if let Some(first) = mode.events[..e].iter().position(|o| o.name == event.name) {
                    let (mode, name) = names();
                    return Err(GraphError::DuplicateEvent {
                        mode,
                        name,
                        first,
                        second: e,
                    });
                }
                let reset_to = match event.action {
                    EventAction::Reset { to, .. } => Some(to),
                    _ => None,
                };
                let targets = [
                    (reset_to.flatten(), "reset"),
                    (event.on_accumulation.and_then(|a| a.to), "accumulation"),
                ];
                for (to, what) in targets {
                    if let Some(to) = to.filter(|&to| to >= count) {
                        let (mode, event) = names();
                        return Err(GraphError::TargetOutOfRange {
                            mode,
                            event,
                            what,
                            to,
                            modes: count,
                        });
                    }
                }
                if event.on_accumulation.is_some() && reset_to.is_none() {
                    let (mode, event) = names();
                    return Err(GraphError::AccumulationWithoutReset { mode, event });
                }
            }
        }
        Ok(ModeGraph { modes })
    }

    /// The first mode, where a run starts (a graph always has one).
    pub fn first(&self) -> ModeId {
        ModeId(0)
    }

    /// The modes, in order.
    pub fn modes(&self) -> &[ModeDecl] {
        &self.modes
    }

    /// Every mode, in order.
    pub fn ids(&self) -> impl Iterator<Item = ModeId> {
        (0..self.modes.len()).map(ModeId)
    }

    /// The mode at position `index`, if there is one.
    pub fn id(&self, index: usize) -> Option<ModeId> {
        (index < self.modes.len()).then_some(ModeId(index))
    }

    /// The mode called `name`, if there is one.
    pub fn mode_id(&self, name: &str) -> Option<ModeId> {
        self.modes.iter().position(|m| m.name == name).map(ModeId)
    }

    /// The declaration of `mode`.
    ///
    /// # Panics
    ///
    /// If `mode` is not a mode of this graph (an id of a larger graph).
    pub fn mode(&self, mode: ModeId) -> &ModeDecl {
        &self.modes[mode.0]
    }

    /// The declaration of `event`.
    ///
    /// # Panics
    ///
    /// If `event` is not an event of this graph.
    pub fn event(&self, event: EventId) -> &EventDecl {
        &self.mode(event.mode).events[event.event]
    }

    /// The name of `mode`.
    pub fn mode_name(&self, mode: ModeId) -> &str {
        &self.mode(mode).name
    }

    /// `event` named as `mode.event`.
    pub fn event_name(&self, event: EventId) -> String {
        format!("{}.{}", self.mode_name(event.mode), self.event(event).name)
    }

    /// The mode an event's action or accumulation continues in: `to`, or `from` itself.
    pub(crate) fn target(&self, from: ModeId, to: Option<usize>) -> ModeId {
        to.map_or(from, ModeId)
    }
}

/// What is wrong with the modes of a [`ModeGraph`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum GraphError {
    /// There is no mode.
    NoModes,
    /// Two modes have the same name.
    DuplicateMode {
        /// The name.
        name: String,
        /// The first mode's position.
        first: usize,
        /// The second mode's position.
        second: usize,
    },
    /// Two events of one mode have the same name.
    DuplicateEvent {
        /// The mode's name.
        mode: String,
        /// The events' name.
        name: String,
        /// The first event's position.
        first: usize,
        /// The second event's position.
        second: usize,
    },
    /// An event's action or accumulation continues in a mode that does not exist.
    TargetOutOfRange {
        /// The event's mode.
        mode: String,
        /// The event.
        event: String,
        /// Which target: `reset` or `accumulation`.
        what: &'static str,
        /// The target's index.
        to: usize,
        /// The number of modes.
        modes: usize,
    },
    /// An event that does not reset has an accumulation action (only resets accumulate).
    AccumulationWithoutReset {
        /// The event's mode.
        mode: String,
        /// The event.
        event: String,
    },
}

impl fmt::Display for GraphError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GraphError::NoModes => write!(f, "a switched model needs at least one mode"),
            GraphError::DuplicateMode {
                name,
                first,
                second,
            } => write!(f, "modes {first} and {second} are both called `{name}`"),
            GraphError::DuplicateEvent {
                mode,
                name,
                first,
                second,
            } => write!(
                f,
                "events {first} and {second} of mode `{mode}` are both called `{name}`"
            ),
            GraphError::TargetOutOfRange {
                mode,
                event,
                what,
                to,
                modes,
            } => write!(
                f,
                "the {what} of event `{mode}.{event}` goes to mode {to}, but there are only \
                 {modes} modes"
            ),
            GraphError::AccumulationWithoutReset { mode, event } => write!(
                f,
                "event `{mode}.{event}` has an accumulation action but does not reset: only \
                 resets accumulate"
            ),
        }
    }
}

impl std::error::Error for GraphError {}
