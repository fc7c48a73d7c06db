//! What a front end asks of [`crate::solve`]: the time span, the method and tolerances, the
//! sampling, the values by name and the events, all plain data, so that a command line and a
//! Python package fill the same struct; and its resolution against one model, which finds
//! every input error before anything is integrated.

use crate::error::{RequestError, UnknownEvent};
use crate::load::{quoted, ModelRef};
use crate::values::{initial_state, params, Named};
use model_runtime::WorkBound;
use model_runtime::{Direction, Method};
use std::sync::atomic::AtomicBool;

/// How to solve a model.
#[derive(Clone, Debug, PartialEq)]
pub struct SolveRequest {
    /// Start time.
    pub t0: f64,
    /// End time; before `t0`, a smooth model is integrated backward in time (the runtime's
    /// exact reversal, [`model_runtime::HybridSolver::run`]); a switched model runs forward
    /// only.
    pub t_end: f64,
    /// The integration method.
    pub method: Method,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// Record every `dt` from `t0` towards `t_end` (and at `t_end`; `dt` is a length, also
    /// backward); `None`: at every accepted step (or at `times`).
    pub dt: Option<f64>,
    /// Record at exactly these times (within the span, in the run's order: increasing, or
    /// decreasing for a backward run; a smooth model only);
    /// `None`: every `dt`, or every accepted step. Exclusive with `dt`.
    pub times: Option<Vec<f64>>,
    /// Parameter values by name; the others keep the file's defaults.
    pub params: Vec<Named>,
    /// Initial state values by name; the others start at the file's value, or zero.
    pub state: Vec<Named>,
    /// The events to locate, in the order given (the first wins a tie); only for a smooth
    /// model (a switched model declares its events in the file).
    pub events: Vec<EventRequest>,
    /// The work bound: by time `t` the run may have taken
    /// `max_steps_per_s × (|t − t0| + 0.1)` accepted steps ([`WorkBound`]); a run over it
    /// fails, keeping what it computed.
    pub max_steps_per_s: f64,
}

impl SolveRequest {
    /// The request's work bound.
    pub fn work_bound(&self) -> WorkBound {
        WorkBound {
            steps_per_s: self.max_steps_per_s,
        }
    }
}

/// What a caller controls while a solve runs: a flag that, once set (by a Ctrl-C handler,
/// say), stops the run at its next step with what it computed ([`crate::Stop::Interrupted`]).
#[derive(Clone, Copy, Debug)]
pub struct Control<'a> {
    /// Set to stop the run.
    pub interrupt: &'a AtomicBool,
}

impl SolveRequest {
    /// From 0 to `t_end` with DOP853 at `rtol = 1e-8`, `atol = 1e-10`, recording every step,
    /// the file's parameters and initial state, and no events.
    pub fn new(t_end: f64) -> Self {
        SolveRequest {
            t0: 0.0,
            t_end,
            method: Method::Dop853,
            rtol: 1e-8,
            atol: 1e-10,
            dt: None,
            times: None,
            params: Vec::new(),
            state: Vec::new(),
            events: Vec::new(),
            max_steps_per_s: WorkBound::DEFAULT.steps_per_s,
        }
    }
}

/// The most times a solve records at (`dt` or given times): a request asking for more is an
/// error found before anything is allocated.
pub const MAX_SAMPLES: usize = 100_000_000;

/// How a caller may shape the integrator's steps, beyond what a [`SolveRequest`] says: bounds
/// on the step size (SciPy's `first_step` and `max_step`), and whether to keep each accepted
/// step's interpolant ([`crate::DenseStep`]). The default changes nothing.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stepping {
    /// The first step of the run and of each restart after an event (`None`: chosen by the
    /// integrator; a switched model's mode may choose its own).
    pub first_step: Option<f64>,
    /// The largest step (`None`: unbounded).
    pub max_step: Option<f64>,
    /// Keep every accepted step's dense output in [`crate::Solution::dense`].
    pub dense: bool,
}

impl Stepping {
    /// The runtime's step options with these bounds, and no step budget (the work bound is
    /// the recording's, by simulated time).
    pub(crate) fn options(&self) -> model_runtime::StepOptions {
        let default = model_runtime::StepOptions::default();
        model_runtime::StepOptions {
            h_initial: self.first_step,
            h_max: self.max_step.unwrap_or(default.h_max),
            max_steps: u64::MAX,
            ..default
        }
    }
}

/// An event: where a state or an output of the model crosses zero.
#[derive(Clone, Debug, PartialEq)]
pub struct EventRequest {
    /// The state's or output's name (the event's name).
    pub name: String,
    /// Which crossings fire.
    pub direction: Direction,
    /// Whether the run ends at the first one.
    pub stop: bool,
}

/// What an event watches: one of the model's states or outputs, by index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Watched {
    /// The state at this index.
    State(usize),
    /// The output at this index.
    Output(usize),
}

/// An event resolved against the model.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ResolvedEvent {
    pub(crate) request: EventRequest,
    pub(crate) watched: Watched,
}

/// The times a run records at, in its order, read one by one as the run reaches them: the
/// request's own, borrowed (a million times are not copied), or every `dt`, computed when
/// reached (never stored).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Times<'r> {
    /// The request's times, checked.
    Given(&'r [f64]),
    /// `t0 + k × step` for `k` in `0..=count`, then `end` if that falls short of it.
    Every {
        /// The first.
        t0: f64,
        /// `dt`, negative for a run backward in time.
        step: f64,
        /// The last `k`.
        count: u64,
        /// The run's end, where the steps fall short of it.
        end: Option<f64>,
    },
}

impl Times<'_> {
    /// How many times there are.
    pub(crate) fn len(&self) -> usize {
        match *self {
            Times::Given(times) => times.len(),
            Times::Every { count, end, .. } => count as usize + 1 + usize::from(end.is_some()),
        }
    }

    /// The `k`th time, if there are as many.
    pub(crate) fn get(&self, k: usize) -> Option<f64> {
        match *self {
            Times::Given(times) => times.get(k).copied(),
            Times::Every {
                t0,
                step,
                count,
                end,
            } => match (k as u64).cmp(&(count + 1)) {
                std::cmp::Ordering::Less => Some(t0 + k as f64 * step),
                std::cmp::Ordering::Equal => end,
                std::cmp::Ordering::Greater => None,
            },
        }
    }
}

/// A request resolved against one model: the values in the model's order, the events by
/// index, the sampling times.
#[derive(Clone, Debug)]
pub(crate) struct Resolved<'r> {
    pub(crate) params: Vec<f64>,
    pub(crate) y0: Vec<f64>,
    pub(crate) events: Vec<ResolvedEvent>,
    pub(crate) times: Option<Times<'r>>,
}

impl<'r> Resolved<'r> {
    /// Resolves `request` for `model`; every problem is a [`RequestError`].
    pub(crate) fn new(
        model: ModelRef<'_>,
        request: &'r SolveRequest,
    ) -> Result<Self, RequestError> {
        let bound = request.max_steps_per_s;
        if !(bound.is_finite() && bound > 0.0) {
            return Err(RequestError::WorkBound { steps_per_s: bound });
        }
        let params = params(model, &request.params).map_err(RequestError::Params)?;
        let y0 = initial_state(model, &request.state).map_err(RequestError::State)?;
        if let ModelRef::Switched(switched) = model {
            if request.t_end < request.t0 {
                return Err(RequestError::BackwardOfSwitched {
                    model: switched.name.clone(),
                    t0: request.t0,
                    t_end: request.t_end,
                });
            }
        }
        let events = match model {
            ModelRef::Switched(_) => match request.events.first() {
                Some(event) => {
                    return Err(RequestError::EventsOfSwitched {
                        name: event.name.clone(),
                    })
                }
                None => Vec::new(),
            },
            ModelRef::Smooth(_) => (request.events.iter().enumerate())
                .map(|(index, event)| resolve_event(model, index, event))
                .collect::<Result<_, _>>()?,
        };
        let times = match (request.dt, &request.times) {
            (Some(_), Some(_)) => return Err(RequestError::StepAndTimes),
            (Some(dt), None) => Some(sample_times(request.t0, request.t_end, dt)?),
            (None, Some(times)) => Some(checked_times(model, request, times)?),
            (None, None) => None,
        };
        Ok(Resolved {
            params,
            y0,
            events,
            times,
        })
    }
}

/// The event `request` of `model`, by what it watches.
fn resolve_event(
    model: ModelRef<'_>,
    index: usize,
    request: &EventRequest,
) -> Result<ResolvedEvent, RequestError> {
    let position = |names: &[String]| names.iter().position(|n| *n == request.name);
    let watched = (position(model.states()).map(Watched::State))
        .or_else(|| position(model.outputs()).map(Watched::Output))
        .ok_or_else(|| {
            RequestError::UnknownEvent(UnknownEvent {
                index,
                name: request.name.clone(),
                states: quoted(model.states()),
                outputs: quoted(model.outputs()),
            })
        })?;
    Ok(ResolvedEvent {
        request: request.clone(),
        watched,
    })
}

/// The times a request asks to record at, checked: finite, inside the run's span, in its
/// order (increasing, or decreasing for a run backward in time, as SciPy's `t_eval`), and for
/// a smooth model (a switched model records at a rate or at every step).
fn checked_times<'r>(
    model: ModelRef<'_>,
    request: &SolveRequest,
    times: &'r [f64],
) -> Result<Times<'r>, RequestError> {
    if let ModelRef::Switched(model) = model {
        return Err(RequestError::TimesOfSwitched {
            model: model.name.clone(),
        });
    }
    if times.len() > MAX_SAMPLES {
        return Err(RequestError::TimeCount { count: times.len() });
    }
    let (t0, t_end) = (request.t0.min(request.t_end), request.t0.max(request.t_end));
    let backward = request.t_end < request.t0;
    for (index, &t) in times.iter().enumerate() {
        let problem = if !t.is_finite() {
            Some("is not finite")
        } else if t < t0 || t > t_end {
            Some("is outside the run's span")
        } else if index > 0 && !backward && t <= times[index - 1] {
            Some("does not come after the one before")
        } else if index > 0 && backward && t >= times[index - 1] {
            Some("does not come before the one before (a run backward in time records at decreasing times)")
        } else {
            None
        };
        if let Some(problem) = problem {
            return Err(RequestError::Time {
                index,
                t,
                problem,
                t0: request.t0,
                t_end: request.t_end,
            });
        }
    }
    Ok(Times::Given(times))
}

/// `t0, t0 + dt, ...` up to and including `t_end` (`t0, t0 − dt, ...` down to it for a run
/// backward in time: `dt` is a length).
fn sample_times(t0: f64, t_end: f64, dt: f64) -> Result<Times<'static>, RequestError> {
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(RequestError::SampleStep { dt });
    }
    let count = ((t_end - t0).abs() / dt).floor();
    if !(0.0..MAX_SAMPLES as f64).contains(&count) {
        return Err(RequestError::SampleCount { dt, t0, t_end });
    }
    let step = if t_end < t0 { -dt } else { dt };
    let count = count as u64;
    let last = t0 + count as f64 * step;
    // Short of `t_end` in the run's direction.
    let end = ((t_end - last) * step > 0.0).then_some(t_end);
    Ok(Times::Every {
        t0,
        step,
        count,
        end,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The times of `sample_times`, listed.
    fn listed(times: Times<'_>) -> Vec<f64> {
        (0..).map_while(|k| times.get(k)).collect()
    }

    #[test]
    fn every_dt_is_the_list_it_stands_for() {
        // The list as it was built before the times became a stream: `t0 + k dt` up to the
        // last not past `t_end`, then `t_end` if short of it.
        let list = |t0: f64, t_end: f64, dt: f64| {
            let count = ((t_end - t0).abs() / dt).floor() as u64;
            let step = if t_end < t0 { -dt } else { dt };
            let mut times: Vec<f64> = (0..=count).map(|k| t0 + k as f64 * step).collect();
            if times.last().is_some_and(|&t| (t_end - t) * step > 0.0) {
                times.push(t_end);
            }
            times
        };
        for (t0, t_end, dt) in [
            (0.0, 1.0, 0.1),
            (0.0, 1.0, 0.3),
            (0.5, 0.5, 0.1),
            (2.0, -1.0, 0.25),
            (2.0, -1.0, 0.7),
            (1e-3, 7.0, 1e-2),
        ] {
            let times = sample_times(t0, t_end, dt).unwrap();
            let got = listed(times);
            assert_eq!(times.len(), got.len(), "{t0} {t_end} {dt}");
            assert_eq!(got, list(t0, t_end, dt), "{t0} {t_end} {dt}");
            assert!(got.len() > 1 || t0 == t_end, "{t0} {t_end} {dt}");
        }
    }
}
