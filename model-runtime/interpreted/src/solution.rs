//! What [`crate::solve`] returns, typed: a table of `t`, the states and the outputs with
//! their names, the events with what they were, why the run ended and the work done. A front
//! end formats these (a CSV, a sentence, a NumPy array); it matches on types, never on text.

use model_runtime::Stats;

/// A solved trajectory of a model given as text.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// The model's name.
    pub model: String,
    /// Column names: `t`, the states, the outputs.
    pub columns: Vec<String>,
    /// The number of states (the columns `1..=states`).
    pub states: usize,
    /// One row per recorded time, in time order; after a terminal event the last row is the
    /// event's.
    pub rows: Vec<Vec<f64>>,
    /// The events the run met, in time order.
    pub events: Vec<SolvedEvent>,
    /// Why the run ended.
    pub stop: Stop,
    /// The work done.
    pub stats: Stats,
    /// Where the firings of an event accumulated (a switched model's Zeno points), in time
    /// order.
    pub accumulations: Vec<AccumulationPoint>,
}

impl Solution {
    /// The column called `name` (`t`, a state or an output), over all rows.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let k = self.columns.iter().position(|c| c == name)?;
        Some(self.rows.iter().map(|row| row[k]).collect())
    }

    /// The state names.
    pub fn state_names(&self) -> &[String] {
        &self.columns[1..=self.states]
    }

    /// The output names.
    pub fn output_names(&self) -> &[String] {
        &self.columns[1 + self.states..]
    }

    /// The time the run ended.
    pub fn t_end(&self) -> Option<f64> {
        self.rows.last().map(|row| row[0])
    }
}

/// What an event was.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventKind {
    /// A located zero crossing of its guard (or of the watched state or output).
    Crossing,
    /// The point where the event's firings accumulate (extrapolated), with the state its
    /// rule sets.
    Accumulation,
}

/// One event of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct SolvedEvent {
    /// The event's name (the watched quantity, or the name declared in the file).
    pub name: String,
    /// What it was.
    pub kind: EventKind,
    /// `t`, the states and the outputs at the event, as a trajectory row.
    pub row: Vec<f64>,
}

impl SolvedEvent {
    /// The event time.
    pub fn t(&self) -> f64 {
        self.row[0]
    }

    /// The event as a table names it: its name, or `NAME accumulates`.
    pub fn label(&self) -> String {
        label(&self.name, self.kind)
    }
}

/// `NAME`, or `NAME accumulates` for an accumulation.
fn label(name: &str, kind: EventKind) -> String {
    match kind {
        EventKind::Crossing => name.to_string(),
        EventKind::Accumulation => format!("{name} accumulates"),
    }
}

/// Why a run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Stop {
    /// The end time was reached.
    EndTime,
    /// A terminal event ended it.
    Event {
        /// The event's name.
        name: String,
        /// A crossing, or an accumulation no rule continues from.
        kind: EventKind,
    },
}

impl std::fmt::Display for Stop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Stop::EndTime => write!(f, "reached the end time"),
            Stop::Event { name, kind } => write!(f, "stopped by event `{}`", label(name, *kind)),
        }
    }
}

/// Where the firings of an event accumulated, and what the run did there.
#[derive(Clone, Debug, PartialEq)]
pub struct AccumulationPoint {
    /// The event.
    pub event: String,
    /// The extrapolated accumulation time.
    pub t: f64,
    /// The mode the run went on in (`None`: the run stopped there).
    pub continued_in: Option<String>,
}

impl std::fmt::Display for AccumulationPoint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the firings of `{}` accumulate at t = {}: ",
            self.event, self.t
        )?;
        match &self.continued_in {
            Some(mode) => write!(f, "the run goes on in `{mode}`"),
            None => write!(
                f,
                "the run stops there (`when {} accumulates -> MODE {{ .. }}` says where it goes on)",
                self.event
            ),
        }
    }
}
