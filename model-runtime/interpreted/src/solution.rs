//! What [`crate::solve`] returns, typed: a table of `t`, the states, the discrete values and
//! the outputs with their names (and, for a switched model, the mode of each row), the events
//! with what they were and the state on both sides of a reset, why the run ended and the work
//! done. A front end formats these (a CSV, a sentence, a NumPy array); it matches on types,
//! never on text.

pub use crate::trajectory::Trajectory;
use model_runtime::Stats;

/// A solved trajectory of a model given as text.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// The model's name.
    pub model: String,
    /// Column names: `t`, the states, the discrete values, the outputs.
    pub columns: Vec<String>,
    /// The number of states (the columns `1..=states`).
    pub states: usize,
    /// The number of discrete values (the columns after the states), each row holding the
    /// values in force at its time.
    pub discrete: usize,
    /// The model's modes by name (none for a smooth model).
    pub modes: Vec<String>,
    /// The mode in force at each row, by index into [`Solution::modes`] (empty for a smooth
    /// model).
    pub row_modes: Vec<usize>,
    /// One row per recorded time, in the run's order (decreasing times for a run backward in
    /// time), stored column after column; after a terminal event the last row is the
    /// event's. The outputs read the discrete values of the row's own time.
    pub trajectory: Trajectory,
    /// The events the run met, in the run's order.
    pub events: Vec<SolvedEvent>,
    /// Why the run ended.
    pub stop: Stop,
    /// The work done.
    pub stats: Stats,
    /// Where the firings of an event accumulated (a switched model's Zeno points), in time
    /// order.
    pub accumulations: Vec<AccumulationPoint>,
    /// What the run found legal but likely not meant (a guard reading a derivative that
    /// starts on its threshold), for a front end to say.
    pub warnings: Vec<String>,
    /// Every accepted step's dense output, in the run's order (a step backward in time has
    /// `t1 < t0`), when the caller asked for it
    /// ([`crate::Stepping::dense`]); empty otherwise.
    pub dense: Vec<DenseStep>,
}

impl Solution {
    /// The column called `name` (`t`, a state, a discrete value or an output), over all rows.
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        let k = self.columns.iter().position(|c| c == name)?;
        Some(self.trajectory.column(k))
    }

    /// The recorded times (the column `t`).
    pub fn times(&self) -> &[f64] {
        self.trajectory.column(0)
    }

    /// The number of rows.
    pub fn len(&self) -> usize {
        self.trajectory.len()
    }

    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.trajectory.is_empty()
    }

    /// Row `k`: `t`, the states, the discrete values, the outputs (gathered from the columns).
    pub fn row(&self, k: usize) -> Vec<f64> {
        self.trajectory.row(k)
    }

    /// The last row, if any.
    pub fn last_row(&self) -> Option<Vec<f64>> {
        self.len().checked_sub(1).map(|k| self.row(k))
    }

    /// The state names.
    pub fn state_names(&self) -> &[String] {
        &self.columns[1..=self.states]
    }

    /// The discrete values' names.
    pub fn discrete_names(&self) -> &[String] {
        &self.columns[1 + self.states..1 + self.states + self.discrete]
    }

    /// The output names.
    pub fn output_names(&self) -> &[String] {
        &self.columns[1 + self.states + self.discrete..]
    }

    /// The name of the mode in force at row `k` (`None` for a smooth model).
    pub fn row_mode(&self, k: usize) -> Option<&str> {
        (self.row_modes.get(k)).map(|&mode| self.modes[mode].as_str())
    }

    /// The time of the last row.
    pub fn t_end(&self) -> Option<f64> {
        self.times().last().copied()
    }

    /// The time the run ended: the time of the event that stopped it (for an accumulation,
    /// its extrapolated point, the time its row and every message give), else of the last
    /// row.
    pub fn stop_time(&self) -> Option<f64> {
        match (&self.stop, self.events.last()) {
            (Stop::Event { name, kind }, Some(last))
                if last.name == *name && last.kind == *kind =>
            {
                Some(last.t())
            }
            _ => self.t_end(),
        }
    }
}

/// How many nodes of each step [`DenseStep`] keeps: enough to determine every method's
/// interpolating polynomial (DOP853's is of degree 7, DOPRI5's of 4, RODAS4's of 3).
pub const DENSE_NODES: usize = 8;

/// One accepted step's dense output, as values at fixed nodes: the interpolant of each
/// method is a polynomial in `t` of degree below [`DENSE_NODES`], so its values at the
/// step's [`DENSE_NODES`] Chebyshev–Lobatto nodes (`t0 + (t1 − t0)(1 − cos(kπ/7))/2`)
/// determine it, and barycentric interpolation through them gives it back anywhere in the
/// step, to rounding. A front end needs no method's coefficients, only these numbers.
#[derive(Clone, Debug, PartialEq)]
pub struct DenseStep {
    /// The step's start.
    pub t0: f64,
    /// The step's end.
    pub t1: f64,
    /// The state at each node, node after node ([`DENSE_NODES`] × the number of states).
    pub values: Vec<f64>,
}

impl DenseStep {
    /// The nodes of a step from `t0` to `t1`.
    pub fn nodes(t0: f64, t1: f64) -> [f64; DENSE_NODES] {
        let last = (DENSE_NODES - 1) as f64;
        std::array::from_fn(|k| {
            let theta = (1.0 - (k as f64 * std::f64::consts::PI / last).cos()) / 2.0;
            t0 + (t1 - t0) * theta
        })
    }

    /// The step from `t0` to `t1` of an interpolant `at(t, y)` of `n` states.
    pub(crate) fn sampled(
        t0: f64,
        t1: f64,
        n: usize,
        mut at: impl FnMut(f64, &mut Vec<f64>),
    ) -> Self {
        let mut values = Vec::with_capacity(DENSE_NODES * n);
        let mut y = vec![0.0; n];
        for t in Self::nodes(t0, t1) {
            at(t, &mut y);
            values.extend_from_slice(&y);
        }
        DenseStep { t0, t1, values }
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
    /// The mode it fired in (`None` for a smooth model).
    pub mode: Option<String>,
    /// `t`, the states, the discrete values and the outputs at the event, before any reset,
    /// as a trajectory row (for an accumulation: the state its rule sets, at the
    /// extrapolated point).
    pub row: Vec<f64>,
    /// The same just after the event's reset, in the mode the run went on in (`None` for an
    /// event that reset nothing: a record, a stop, a smooth model's crossing).
    pub after: Option<Vec<f64>>,
    /// The mode the run went on in after the event (`None` as for `after`).
    pub mode_after: Option<String>,
    /// A smooth model's event: its position in the request's events (two requests may watch
    /// the same quantity in two directions); `None` for an event the file declares.
    pub request: Option<usize>,
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
    /// The caller interrupted it (the rows are those computed until then).
    Interrupted,
    /// It failed (the stop of the solution a [`crate::RunFailure`] keeps).
    Failed {
        /// Why.
        reason: String,
    },
}

impl std::fmt::Display for Stop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Stop::EndTime => write!(f, "reached the end time"),
            Stop::Event { name, kind } => write!(f, "stopped by event `{}`", label(name, *kind)),
            Stop::Interrupted => write!(f, "interrupted"),
            Stop::Failed { .. } => write!(f, "failed"),
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
