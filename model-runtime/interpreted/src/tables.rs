//! A recorded run made into its [`Solution`]: each point's row (`t`, the states, the discrete
//! values in force, the outputs of the mode in force, evaluated by the interpreter with those
//! values), the events' rows, and how the run ended: at its end, at an event, interrupted
//! (the solution so far), or failed (the solution so far inside the failure).
//!
//! An output that is NaN or infinite at a recorded point is the error `model eval` gives at
//! that point, never a number written: a file holds what the model says, or the run says why
//! not.

use crate::engine::Engine;
use crate::error::{PointError, RunFailure, SolveFailure, WorkHint};
use crate::recording::{Halt, Recording};
use crate::solution::{AccumulationPoint, EventKind, Solution, SolvedEvent, Stop};
use model_algebra::{CompiledModel, EvalFailure};
use model_runtime::Stats;
use std::cell::RefCell;

/// How a run ended, before its rows are made.
pub(crate) enum Ended {
    /// The driver returned: at the end time, at a terminal event, or stopped by the
    /// recording (its [`Recording::halt`]).
    Ran {
        /// Why, as far as the driver knows (`Stop::Interrupted` for a halt).
        stop: Stop,
        /// The work done.
        stats: Stats,
    },
    /// The driver failed.
    Failed {
        /// Why, in the model's terms.
        message: String,
        /// The work done until then.
        stats: Stats,
    },
}

/// What the rows of a model's solution are made of.
pub(crate) struct Tables<'a> {
    /// The model's name.
    pub(crate) name: String,
    /// Each mode's model (a smooth model's is its only one).
    pub(crate) models: Vec<&'a CompiledModel>,
    /// Each mode's engine, made from its model.
    pub(crate) engines: Vec<&'a Engine>,
    /// The modes' names (none for a smooth model).
    pub(crate) modes: Vec<String>,
    /// The model's own parameter values (each mode's model reads the discrete values after
    /// them).
    pub(crate) params: &'a [f64],
    /// The column names: `t`, the states, the discrete values, the outputs.
    pub(crate) columns: Vec<String>,
    /// The number of states.
    pub(crate) states: usize,
    /// The number of discrete values.
    pub(crate) discrete: usize,
    /// Whether the method is explicit (a work bound reached then suggests an implicit one).
    pub(crate) explicit: bool,
    /// What a row is computed in, reused from row to row.
    pub(crate) buffers: RefCell<RowBuffers>,
}

/// The values a row's outputs are computed from and into: the parameters with the discrete
/// values, the derivatives, the outputs. Kept by [`Tables`] so that a million rows allocate
/// only the trajectory's buffer.
#[derive(Debug, Default)]
pub(crate) struct RowBuffers {
    values: Vec<f64>,
    der: Vec<f64>,
    outputs: Vec<f64>,
}

impl Tables<'_> {
    /// The outputs of mode `mode` at `(t, y)` with the discrete values `discrete`, handed to
    /// `use_outputs` in the buffer they were computed in; a NaN or infinite output is the
    /// error `model eval` gives there.
    fn with_outputs<R>(
        &self,
        mode: usize,
        (t, y, discrete): (f64, &[f64], &[f64]),
        use_outputs: impl FnOnce(&[f64]) -> R,
    ) -> Result<R, SolveFailure> {
        let model = self.models[mode];
        let mut buffers = self.buffers.borrow_mut();
        let RowBuffers {
            values,
            der,
            outputs,
        } = &mut *buffers;
        values.clear();
        values.extend(self.params.iter().chain(discrete));
        let at_t = |failure: PointError| SolveFailure::Eval { t, failure };
        let interpreter = |failure: EvalFailure| {
            at_t(PointError::Interpreter {
                model: model.name.clone(),
                failure,
            })
        };
        let engine = self.engines[mode];
        der.resize(y.len(), 0.0);
        outputs.resize(engine.n_outputs(), 0.0);
        (engine.outputs_at(t, y, values, &mut der[..y.len()], &mut outputs[..]))
            .map_err(interpreter)?;
        let outputs = &outputs[..engine.n_outputs()];
        if let Some(k) = outputs.iter().position(|v| !v.is_finite()) {
            return Err(at_t(PointError::NonFinite {
                model: model.name.clone(),
                name: model.outputs[k].clone(),
                value: outputs[k],
            }));
        }
        Ok(use_outputs(outputs))
    }

    /// `t`, the states, the discrete values and the outputs of mode `mode` at `(t, y)` with
    /// the discrete values `discrete`.
    pub(crate) fn row(
        &self,
        mode: usize,
        t: f64,
        y: &[f64],
        discrete: &[f64],
    ) -> Result<Vec<f64>, SolveFailure> {
        self.with_outputs(mode, (t, y, discrete), |outputs| {
            let mut row = Vec::with_capacity(self.columns.len());
            row.push(t);
            row.extend_from_slice(y);
            row.extend_from_slice(discrete);
            row.extend_from_slice(outputs);
            row
        })
    }

    /// An event's row: `(t, y)` in `mode` with the discrete values `discrete`, named.
    pub(crate) fn event(
        &self,
        name: &str,
        kind: EventKind,
        mode: usize,
        (t, y, discrete): (f64, &[f64], &[f64]),
    ) -> Result<SolvedEvent, SolveFailure> {
        Ok(SolvedEvent {
            name: name.to_string(),
            kind,
            mode: self.modes.get(mode).cloned(),
            row: self.row(mode, t, y, discrete)?,
            after: None,
            mode_after: None,
            request: None,
        })
    }

    /// The solution of a recorded run: its rows, `events`, `accumulations`, and how it
    /// `ended`. An
    /// interrupted run is a solution stopped as [`Stop::Interrupted`]; a failed one, or one
    /// over its work bound, a [`SolveFailure::Run`] holding the solution until then.
    pub(crate) fn finish(
        &self,
        recording: Recording<'_>,
        events: Vec<SolvedEvent>,
        accumulations: Vec<AccumulationPoint>,
        ended: Ended,
    ) -> Result<Solution, SolveFailure> {
        let mut trajectory = recording.table;
        debug_assert_eq!(trajectory.width(), self.columns.len());
        // A smooth model has no modes to say.
        let switched = !self.modes.is_empty();
        let mut row_modes = Vec::with_capacity(if switched { trajectory.len() } else { 0 });
        let outputs_from = 1 + self.states + self.discrete;
        let mut y = Vec::with_capacity(self.states);
        for (k, point) in recording.points.iter().enumerate() {
            let (mode, discrete) = (point.mode as usize, point.discrete as usize);
            let discrete = &recording.snapshots[discrete];
            let t = trajectory.get(k, 0);
            trajectory.read(k, 1, self.states, &mut y);
            self.with_outputs(mode, (t, &y, discrete), |outputs| {
                trajectory.set(k, outputs_from, outputs);
            })?;
            if switched {
                row_modes.push(mode);
            }
        }
        let trajectory = trajectory.compacted();
        let steps = recording.steps;
        let dense = recording.dense.unwrap_or_default();
        let (stop, stats, failure) = match (ended, recording.halt) {
            (Ended::Failed { message, stats }, _) => {
                let stop = Stop::Failed {
                    reason: message.clone(),
                };
                (stop, stats, Some((message, None)))
            }
            (Ended::Ran { stats, .. }, Some(Halt::Work(over))) => {
                // The library's own spelling of the setting; a front end names its flag
                // through `RunFailure::describe`.
                let reason = over.describe("max_steps_per_s", "");
                let stop = Stop::Failed {
                    reason: reason.clone(),
                };
                (stop, stats, Some((reason, Some(over))))
            }
            (Ended::Ran { stats, .. }, Some(Halt::Interrupted)) => (Stop::Interrupted, stats, None),
            (Ended::Ran { stop, stats }, None) => (stop, stats, None),
        };
        let n_events = events.len();
        let solution = Solution {
            model: self.name.clone(),
            columns: self.columns.clone(),
            states: self.states,
            discrete: self.discrete,
            modes: self.modes.clone(),
            row_modes,
            trajectory,
            events,
            stop,
            stats,
            accumulations,
            warnings: Vec::new(),
            dense,
        };
        match failure {
            None => Ok(solution),
            Some((message, work)) => Err(SolveFailure::Run(RunFailure {
                message,
                steps: Some(steps),
                events: n_events,
                hint: work
                    .as_ref()
                    .and_then(|_| WorkHint::of(steps, n_events, self.explicit)),
                work,
                partial: Some(Box::new(solution)),
            })),
        }
    }
}
