//! What [`crate::Problem::solve`] returns: the recorded trajectory with the model's
//! names, the located events, the work done and why it stopped; or why it failed, in the
//! model's terms (a state by its name, an event by its name), never by an index.

use crate::dim::{Dim, Vector};
use crate::error::{EvalError, InputError, SolveError};
use crate::events::Crossed;
use crate::hybrid::HybridError;
use crate::model::{ModelInfo, SystemOutputs};
use crate::readable::Readable;
use crate::stats::Stats;
use std::fmt;
use std::io::{self, Write};

/// An event located during the run, with the exact state there.
#[derive(Clone, Debug, PartialEq)]
pub struct LocatedEvent<D: Dim> {
    /// The event's name.
    pub name: String,
    /// Its position in the problem's event list.
    pub index: usize,
    /// The event time (located to a few ulps, on the far side of the crossing).
    pub t: f64,
    /// The state at `t`, on the step's dense output.
    pub y: Vector<D>,
    /// The derivative at `(t, y)`.
    pub der: Vector<D>,
    /// How the event function crossed zero.
    pub crossed: Crossed,
}

/// Why a run ended normally.
#[derive(Clone, Debug, PartialEq)]
pub enum Termination {
    /// The end of the time span was reached.
    EndTime,
    /// A terminal event fired.
    Event {
        /// The event's name.
        name: String,
    },
}

/// A solved trajectory: the recorded points with their outputs, the located events, the
/// statistics and the stop reason, named after the model.
#[derive(Clone, Debug)]
pub struct Trajectory<D: Dim, const K: usize> {
    /// The model's names (states, parameters, outputs).
    pub info: ModelInfo,
    /// The recorded times, non-decreasing.
    pub t: Vec<f64>,
    /// The state at each recorded time.
    pub y: Vec<Vector<D>>,
    /// The outputs at each recorded time.
    pub outputs: Vec<[f64; K]>,
    /// The events located, in time order (a terminal event is the last).
    pub events: Vec<LocatedEvent<D>>,
    /// Work done: steps, rejections, evaluations, events.
    pub stats: Stats,
    /// Why the run ended.
    pub stop: Termination,
}

impl<D: Dim, const K: usize> Trajectory<D, K> {
    /// Evaluates the outputs at the recorded points.
    pub(crate) fn build<M: SystemOutputs<D, K>>(
        model: &M,
        t: Vec<f64>,
        y: Vec<Vector<D>>,
        events: Vec<LocatedEvent<D>>,
        stats: Stats,
        stop: Termination,
    ) -> Result<Self, SolveFailure> {
        let outputs = t
            .iter()
            .zip(&y)
            .map(|(&t, y)| {
                let mut der = D::of(y).zeros();
                let mut outputs = [0.0; K];
                (model.rhs(t, y, &mut der))
                    .and_then(|()| model.outputs(t, y, &der, &mut outputs))
                    .map(|()| outputs)
                    .map_err(|source| SolveFailure::Output { t, source })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Trajectory {
            info: model.info().clone(),
            t,
            y,
            outputs,
            events,
            stats,
            stop,
        })
    }

    /// The values of the state or output called `name` at the recorded times; `None` if the
    /// model has no such name.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        if let Some(i) = self.info.state_names.position(name) {
            return Some(self.y.iter().map(|y| y[i]).collect());
        }
        let k = self.info.output_names.position(name)?;
        Some(self.outputs.iter().map(|out| out[k]).collect())
    }

    /// The last recorded state.
    pub fn last(&self) -> Option<&Vector<D>> {
        self.y.last()
    }

    /// Writes the trajectory as CSV: a header `t,<states>,<outputs>` and one row per recorded
    /// time, every number in Rust's shortest round-trip form.
    pub fn write_csv(&self, mut out: impl Write) -> io::Result<()> {
        let mut header = vec!["t"];
        header.extend(self.info.state_names.iter());
        header.extend(self.info.output_names.iter());
        writeln!(out, "{}", header.join(","))?;
        for ((t, y), outputs) in self.t.iter().zip(&self.y).zip(&self.outputs) {
            let mut row = vec![t.to_string()];
            row.extend(y.as_ref().iter().chain(outputs).map(f64::to_string));
            writeln!(out, "{}", row.join(","))?;
        }
        Ok(())
    }
}

/// Why a trajectory could not be computed. `Display` names states and events by their names.
#[derive(Clone, Debug)]
pub enum SolveFailure {
    /// The integration failed (or its inputs were unusable).
    Solve {
        /// What went wrong, with state components as indices.
        error: SolveError,
        /// The model's names, to say which state (boxed: the failure stays small).
        info: Box<ModelInfo>,
        /// The events' names, to say which event.
        events: Vec<String>,
    },
    /// A requested output time is not finite, out of the run's order, or outside the time span.
    OutputTime {
        /// Its position in the list.
        index: usize,
        /// The time.
        t: f64,
        /// The span's start.
        t0: f64,
        /// The span's end.
        t_end: f64,
    },
    /// The outputs could not be evaluated at a recorded point.
    Output {
        /// The time of the point.
        t: f64,
        /// The model's explanation.
        source: EvalError,
    },
    /// Events fired too often in too short a time (an event function that stays at zero).
    Chattering {
        /// The time it was detected.
        t: f64,
        /// Events within the window.
        events: usize,
        /// The window's width.
        window: f64,
    },
}

impl SolveFailure {
    /// The failure of a single-mode hybrid run (the run behind [`crate::Problem::solve`],
    /// or a front end's own one-mode system), in a solve's terms: states and events by name.
    pub fn from_hybrid(error: HybridError<()>, info: Box<ModelInfo>, events: &[String]) -> Self {
        let error = match error {
            HybridError::Solve { error, .. } => error,
            HybridError::Transition { t, source, .. } | HybridError::Observer { t, source, .. } => {
                SolveError::Eval { t, source }
            }
            HybridError::Chattering {
                t,
                transitions,
                window,
                ..
            } => {
                return SolveFailure::Chattering {
                    t,
                    events: transitions,
                    window,
                }
            }
        };
        SolveFailure::Solve {
            error,
            info,
            events: events.to_vec(),
        }
    }

    /// The state the failure is about, by name, when it is about one.
    pub fn state(&self) -> Option<&str> {
        let SolveFailure::Solve { error, info, .. } = self else {
            return None;
        };
        let component = match error {
            SolveError::StepSizeCollapse { component, .. }
            | SolveError::TransitionState { component, .. }
            | SolveError::InvalidInput(InputError::Tolerance { component, .. })
            | SolveError::InvalidInput(InputError::InitialState { component, .. }) => *component,
            _ => return None,
        };
        info.state_names.get(component)
    }
}

impl fmt::Display for SolveFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SolveFailure::Solve {
                error,
                info,
                events,
            } => {
                let state = self.state().unwrap_or("?");
                let model = &info.name;
                match error {
                    SolveError::StepSizeCollapse {
                        t,
                        h,
                        h_min,
                        error_norm,
                        ..
                    } => write!(
                        f,
                        "model `{model}`: step size collapsed at t = {t}: h = {h} (minimum \
                         {h_min}), largest error in state `{state}` (scaled error {error_norm})",
                        h = Readable(*h),
                        h_min = Readable(*h_min),
                        error_norm = Readable(*error_norm)
                    ),
                    SolveError::InvalidInput(InputError::Tolerance { rtol, atol, .. }) => write!(
                        f,
                        "model `{model}`: tolerance of state `{state}` unusable \
                         (rtol = {rtol}, atol = {atol})",
                        rtol = Readable(*rtol),
                        atol = Readable(*atol)
                    ),
                    SolveError::InvalidInput(InputError::InitialState { value, .. }) => write!(
                        f,
                        "model `{model}`: the initial value of state `{state}` is {value}"
                    ),
                    SolveError::GuardNotFinite { t, guard, value } => write!(
                        f,
                        "model `{model}`: event `{}` is not finite at t = {t}: {value}",
                        events.get(*guard).map_or("?", String::as_str)
                    ),
                    SolveError::GuardHolds { t, guard, value } => write!(
                        f,
                        "model `{model}`: event `{}` holds at t = {t} (guard value {value}) \
                         without having fired: a crossing was not located",
                        events.get(*guard).map_or("?", String::as_str)
                    ),
                    other => write!(f, "model `{model}`: {other}"),
                }
            }
            SolveFailure::OutputTime {
                index,
                t,
                t0,
                t_end,
            } => write!(
                f,
                "output time {index} ({t}) is not finite, comes before the previous one in \
                 the run's direction, or lies outside the time span [{t0}, {t_end}]"
            ),
            SolveFailure::Output { t, source } => {
                write!(f, "the outputs at t = {t} could not be evaluated: {source}")
            }
            SolveFailure::Chattering { t, events, window } => write!(
                f,
                "{events} events within {window} at t = {t}: an event function that stays \
                 at zero?",
                window = Readable(*window)
            ),
        }
    }
}

impl std::error::Error for SolveFailure {}
