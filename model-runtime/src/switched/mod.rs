//! Switched models given by tables: the runtime side of the model language's modes, events,
//! resets, terminal events and accumulations.
//!
//! Generated code and the model interpreter both describe a switched model the same way: a
//! [`ModeGraph`] (the modes, each mode's events, what every event does) and a
//! [`SwitchedModel`] that evaluates the numbers (right-hand sides, guard values, resets) by
//! mode and event index. [`Switched`] turns such a model into a [`HybridSystem`] that the
//! hybrid driver runs, so neither front end writes a transition map.
//!
//! # What the events do
//!
//! * [`EventAction::Record`]: the event is located and reported ([`SwitchedNote::Recorded`])
//!   and nothing else happens: a [`Transition::Pass`], no restart, the run's steps unchanged.
//! * [`EventAction::Reset`]: the model's reset assigns some states (every right-hand side of
//!   a reset reads the state *before* the event, as Modelica's `pre()`), and the run goes on
//!   in the target mode. A reset into the mode it fired in is a restart
//!   ([`Transition::Continue`]: the event's own guard does not fire again on leaving its
//!   surface); into another mode, a [`Transition::Switch`].
//! * [`EventAction::Stop`]: the run ends with [`SwitchedStop::Event`].
//! * [`EventAction::Decide`]: the model's [`SwitchedModel::decide`] assigns the states and
//!   names the next mode (a restart if it is the same; restarts are watched for accumulation
//!   like a reset's, and an accumulation stops the run), or stops the run like a terminal event.
//!   A mode index outside the graph fails the run with [`EvalError::Undecided`].
//!
//! A reset that assigns a state that is not finite fails the run with
//! [`EvalError::ResetNotFinite`] naming the event (inside [`crate::HybridError::Transition`]).
//!
//! # Accumulation
//!
//! A reset that restarts its own mode can fire again and again at ever shorter intervals: a
//! bouncing ball coming to rest (Zeno behaviour). [`Switched`] feeds the times of successive
//! restarts by each event to an [`AccumulationDetector`] of its own: "successive" means the
//! same event restarting the same mode, with no switch to another mode in between (events
//! that only pass do not interrupt, nor do restarts by the mode's other events: a rimless
//! wheel rocking between two spokes restarts its mode by each in turn; a switch starts every
//! history afresh). When the
//! detector's [`AccumulationRule`] declares an accumulation (the latest intervals all shrink
//! and the remaining time, extrapolated from a steady ratio or bounded by the slowest of
//! wobbling ones, is at most the rule's `tail`), the firing that showed it does not apply its
//! ordinary reset:
//!
//! * with an [`AccumulationAction`], the model's accumulation reset is applied instead and
//!   the run continues in the action's mode, at the firing's time; the note
//!   ([`SwitchedNote::Accumulated`]) carries the extrapolated accumulation point `t_inf`
//!   (within `tail` of the firing) and the ratio, for a front end that reports the resting
//!   event at `t_inf`;
//! * without one, the run ends with [`SwitchedStop::Accumulation`]: a normal end with a
//!   reason, not a chattering error and not a step-size collapse.
//!
//! An accumulation the rule does not recognise (an interval that grows among ones that
//! shrink) is not declared; if it truly accumulates, the driver's [`crate::ChatterLimit`] ends
//! it.
//!
//! A guard of a [`Switched`] model that holds where its mode is entered fires at once
//! ([`HybridSystem::fires_on_entry`]; see [`crate::GuardSpec`]).

pub(crate) mod graph;
pub(crate) mod outcome;

use crate::accumulation::{Accumulation, AccumulationDetector, AccumulationRule};
use crate::dim::{Const, Dim, Matrix, Vector};
use crate::error::{EvalError, InputError};
use crate::events::{EventHit, GuardInputs, GuardSpec};
use crate::hybrid::{HybridSystem, Transition};
use crate::jacobian::finite_difference_jacobian;
use graph::{EventAction, EventId, ModeGraph, ModeId};
use outcome::{SwitchedNote, SwitchedStop};

/// A hybrid model given by tables: implemented by the code `model!` emits and by the model
/// interpreter. Modes and events are indices into [`SwitchedModel::graph`].
pub trait SwitchedModel<D: Dim> {
    /// The modes and events (the same graph for as long as the model lives: [`Switched`]
    /// reads it once for the guards).
    fn graph(&self) -> &ModeGraph;

    /// `dy = f(t, y)` in `mode`.
    fn rhs(&self, mode: usize, t: f64, y: &Vector<D>, dy: &mut Vector<D>) -> Result<(), EvalError>;

    /// The Jacobian in `mode`; the default uses central finite differences of
    /// [`SwitchedModel::rhs`].
    fn jacobian(
        &self,
        mode: usize,
        t: f64,
        y: &Vector<D>,
        jac: &mut Matrix<D>,
    ) -> Result<(), EvalError> {
        finite_difference_jacobian::<D>(|y, dy| self.rhs(mode, t, y, dy), y, jac)
    }

    /// The guard values of `mode`'s events at `(t, y)` with `dy = f(t, y)`: one slot per
    /// event, in the graph's order.
    fn event_values(
        &self,
        mode: usize,
        t: f64,
        y: &Vector<D>,
        dy: &Vector<D>,
        values: &mut [f64],
    ) -> Result<(), EvalError>;

    /// The state after event `event` of `mode` fired at `(t, y, dy)`: `out` holds a copy of
    /// `y` on entry and the model overwrites the states the reset assigns (every right-hand
    /// side reads the state before the event, as Modelica's `pre()`). `accumulation` selects
    /// the event's accumulation reset ([`graph::AccumulationAction`]) instead of its ordinary
    /// one.
    #[allow(clippy::too_many_arguments)] // The event's coordinates and its state, as written.
    fn reset(
        &mut self,
        mode: usize,
        event: usize,
        accumulation: bool,
        t: f64,
        y: &Vector<D>,
        dy: &Vector<D>,
        out: &mut Vector<D>,
    ) -> Result<(), EvalError>;

    /// The state after event `event` of `mode`, an [`EventAction::Decide`], fired at
    /// `(t, y, dy)`, into `out` (a copy of `y` on entry, as for [`SwitchedModel::reset`]), and
    /// the index of the mode the run continues in, or `None` to stop it. The default decides
    /// nothing ([`EvalError::Undecided`]): a model with such events implements it.
    #[allow(clippy::too_many_arguments)] // The event's coordinates and its state, as written.
    fn decide(
        &mut self,
        mode: usize,
        event: usize,
        _t: f64,
        _y: &Vector<D>,
        _dy: &Vector<D>,
        _out: &mut Vector<D>,
    ) -> Result<Option<usize>, EvalError> {
        Err(EvalError::Undecided {
            event: format!("{event} of mode {mode}"),
            mode: None,
        })
    }

    /// The components the guards of `mode` read (default, `None`: all); see
    /// [`HybridSystem::guard_inputs`].
    fn guard_inputs(&self, _mode: usize) -> Option<GuardInputs<D>> {
        None
    }

    /// How much physical time one unit of regularised time is at `y` in `mode` (default 1):
    /// what [`crate::Regularised`] integrates a [`Switched`] model with (see
    /// [`crate::TimeScale`]).
    fn time_scale(&self, _mode: usize, _y: &Vector<D>) -> f64 {
        1.0
    }

    /// The step to try first when a segment of `mode` starts at `(t, y)` (the run's start, a
    /// switch or a restart); `None` (the default) leaves it to the integrator's own guess (see
    /// [`HybridSystem::first_step`]).
    fn first_step(&self, _mode: usize, _t: f64, _y: &Vector<D>) -> Option<f64> {
        None
    }
}

/// A switched model in regularised time: its [`SwitchedModel::time_scale`].
impl<const N: usize, M: SwitchedModel<Const<N>>> crate::hybrid::regularised::TimeScale<N>
    for Switched<M>
{
    fn time_scale(&self, mode: ModeId, y: &[f64; N]) -> f64 {
        self.model.time_scale(mode.index(), y)
    }
}

/// A borrowed model is a model: [`Switched`] can own the model or borrow it (mutably: events
/// may change the model's discrete values).
impl<D: Dim, M: SwitchedModel<D> + ?Sized> SwitchedModel<D> for &mut M {
    fn graph(&self) -> &ModeGraph {
        (**self).graph()
    }
    fn rhs(&self, mode: usize, t: f64, y: &Vector<D>, dy: &mut Vector<D>) -> Result<(), EvalError> {
        (**self).rhs(mode, t, y, dy)
    }
    fn jacobian(
        &self,
        mode: usize,
        t: f64,
        y: &Vector<D>,
        jac: &mut Matrix<D>,
    ) -> Result<(), EvalError> {
        (**self).jacobian(mode, t, y, jac)
    }
    fn event_values(
        &self,
        mode: usize,
        t: f64,
        y: &Vector<D>,
        dy: &Vector<D>,
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        (**self).event_values(mode, t, y, dy, values)
    }
    fn reset(
        &mut self,
        mode: usize,
        event: usize,
        accumulation: bool,
        t: f64,
        y: &Vector<D>,
        dy: &Vector<D>,
        out: &mut Vector<D>,
    ) -> Result<(), EvalError> {
        (**self).reset(mode, event, accumulation, t, y, dy, out)
    }
    fn decide(
        &mut self,
        mode: usize,
        event: usize,
        t: f64,
        y: &Vector<D>,
        dy: &Vector<D>,
        out: &mut Vector<D>,
    ) -> Result<Option<usize>, EvalError> {
        (**self).decide(mode, event, t, y, dy, out)
    }
    fn guard_inputs(&self, mode: usize) -> Option<GuardInputs<D>> {
        (**self).guard_inputs(mode)
    }
    fn time_scale(&self, mode: usize, y: &Vector<D>) -> f64 {
        (**self).time_scale(mode, y)
    }
    fn first_step(&self, mode: usize, t: f64, y: &Vector<D>) -> Option<f64> {
        (**self).first_step(mode, t, y)
    }
}

/// A [`SwitchedModel`] as a [`HybridSystem`] (modes [`ModeId`], guards [`EventId`]), owning or
/// borrowing the model, with the accumulation history of the event that restarts its mode.
///
/// ```
/// use model_runtime::{
///     Const, AccumulationRule, Direction, Dop853, EvalError, EventAction, EventDecl, HybridOptions,
///     HybridSolver, ModeDecl, ModeGraph, StopReason, Switched, SwitchedModel, SwitchedStop,
///     Tolerance,
/// };
///
/// /// A ball, y = (height, velocity), bouncing with restitution 0.5.
/// struct Ball(ModeGraph);
/// impl SwitchedModel<Const<2>> for Ball {
///     fn graph(&self) -> &ModeGraph { &self.0 }
///     fn rhs(&self, _: usize, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
///         *dy = [y[1], -9.81];
///         Ok(())
///     }
///     fn event_values(&self, _: usize, _t: f64, y: &[f64; 2], _dy: &[f64; 2], g: &mut [f64])
///         -> Result<(), EvalError> { g[0] = y[0]; Ok(()) }
///     fn reset(&mut self, _: usize, _: usize, _: bool, _t: f64, y: &[f64; 2], _dy: &[f64; 2],
///              out: &mut [f64; 2]) -> Result<(), EvalError> {
///         out[1] = -0.5 * y[1];
///         Ok(())
///     }
/// }
///
/// let impact = EventDecl {
///     name: "impact".into(),
///     direction: Direction::Down,
///     action: EventAction::Reset { to: None, reset: true },
///     on_accumulation: None,
/// };
/// let graph = ModeGraph::new(vec![ModeDecl { name: "flying".into(), events: vec![impact] }]);
/// let graph = graph.unwrap();
/// let flying = graph.mode_id("flying").unwrap();
/// let mut ball = Switched::new(Ball(graph), AccumulationRule::default()).unwrap();
/// let mut solver = HybridSolver::new(Dop853::new(), Tolerance::scalar(1e-10, 1e-12),
///                                    HybridOptions::default()).unwrap();
/// let out = solver.run(&mut ball, flying, 0.0, &[1.0, 0.0], 10.0, &mut ()).unwrap();
/// // Dropped from 1 m, it would bounce forever before 3 sqrt(2 / g) ≈ 1.355 s.
/// let StopReason::User(SwitchedStop::Accumulation { t_inf, .. }) = out.stop else {
///     panic!("{:?}", out.stop)
/// };
/// assert!((t_inf - 3.0 * (2.0f64 / 9.81).sqrt()).abs() < 1e-9);
/// assert!(out.transitions > 20);
/// ```
#[derive(Clone, Debug)]
pub struct Switched<M> {
    model: M,
    /// Each mode's guards, one per event.
    specs: Vec<Vec<GuardSpec<EventId>>>,
    /// One detector per event of the current mode (its restarts since the mode was entered),
    /// as many as the largest mode has events.
    detectors: Vec<AccumulationDetector>,
    /// The mode whose restarts the detectors have seen.
    watching: Option<ModeId>,
}

impl<M> Switched<M> {
    /// The system of `model`, watching for accumulations by `rule` (checked here).
    pub fn new<D: Dim>(model: M, rule: AccumulationRule) -> Result<Self, InputError>
    where
        M: SwitchedModel<D>,
    {
        let graph = model.graph();
        let specs = (graph.ids())
            .map(|mode| {
                let events = &graph.mode(mode).events;
                (events.iter().enumerate())
                    .map(|(event, e)| GuardSpec {
                        id: EventId { mode, event },
                        direction: e.direction,
                    })
                    .collect()
            })
            .collect::<Vec<Vec<_>>>();
        let most = specs.iter().map(Vec::len).max().unwrap_or(0);
        Ok(Switched {
            model,
            specs,
            detectors: vec![AccumulationDetector::new(rule)?; most],
            watching: None,
        })
    }

    /// The model.
    pub fn model(&self) -> &M {
        &self.model
    }

    /// The model, given back.
    pub fn into_model(self) -> M {
        self.model
    }

    /// Forgets the accumulation history (before reusing the system for an unrelated run;
    /// a run that starts earlier than the last firing restarts it anyway).
    pub fn forget(&mut self) {
        self.detectors
            .iter_mut()
            .for_each(AccumulationDetector::reset);
        self.watching = None;
    }

    /// Records that `event` restarted its mode at `t`: the accumulation if that shows one
    /// (the history is then forgotten: the accumulation ends the sequence). Each event of the
    /// mode keeps its own history, so that restarts by two events in turn (a rimless wheel
    /// rocking between two spokes) accumulate too.
    fn restarted(&mut self, event: EventId, t: f64) -> Option<Accumulation> {
        if self.watching != Some(event.mode) {
            self.forget();
            self.watching = Some(event.mode);
        }
        let accumulation = self.detectors[event.event].fire(t);
        if accumulation.is_some() {
            self.forget();
        }
        accumulation
    }

    /// The state after `event` fired at `hit`: the model's reset (ordinary or accumulation)
    /// if `reset`, else the event state; an error names the event if it is not finite.
    fn assigned<D: Dim>(
        &mut self,
        event: EventId,
        reset: bool,
        accumulation: bool,
        hit: &EventHit<D, EventId>,
    ) -> Result<Vector<D>, EvalError>
    where
        M: SwitchedModel<D>,
    {
        let mut out = hit.y.clone();
        if reset {
            let (m, e) = (event.mode.index(), event.event);
            (self.model).reset(m, e, accumulation, hit.t, &hit.y, &hit.dy, &mut out)?;
        }
        self.finite(event, accumulation, out)
    }

    /// `out`, the state after `event`, or the error that names the event and the component
    /// that is not finite.
    fn finite<D: Dim>(
        &self,
        event: EventId,
        accumulation: bool,
        out: Vector<D>,
    ) -> Result<Vector<D>, EvalError>
    where
        M: SwitchedModel<D>,
    {
        match out.as_ref().iter().position(|v| !v.is_finite()) {
            None => Ok(out),
            Some(component) => Err(EvalError::ResetNotFinite {
                event: self.model.graph().event_name(event)
                    + if accumulation { " (accumulation)" } else { "" },
                component,
                value: out[component],
            }),
        }
    }
}

impl<M> Switched<M> {
    /// The transition of an [`EventAction::Decide`] event: the model's state and choice, a
    /// restart fed to the accumulation watch like a reset's (an accumulation stops the run:
    /// a decided event has no accumulation action).
    fn decided<D: Dim>(
        &mut self,
        mode: ModeId,
        hit: &EventHit<D, EventId>,
    ) -> Result<Transition<D, ModeId, SwitchedStop, SwitchedNote>, EvalError>
    where
        M: SwitchedModel<D>,
    {
        let id = hit.guard;
        let mut out = hit.y.clone();
        let (m, e) = (mode.index(), id.event);
        let next = (self.model).decide(m, e, hit.t, &hit.y, &hit.dy, &mut out)?;
        let Some(next) = next else {
            self.forget();
            return Ok(Transition::Stop(SwitchedStop::Event {
                mode,
                event: e,
                t: hit.t,
            }));
        };
        let graph = self.model.graph();
        let Some(to) = graph.id(next) else {
            return Err(EvalError::Undecided {
                event: graph.event_name(id),
                mode: Some(next),
            });
        };
        let y = self.finite(id, false, out)?;
        if to != mode {
            self.forget();
        } else if let Some(accumulation) = self.restarted(id, hit.t) {
            return Ok(Transition::Stop(SwitchedStop::Accumulation {
                mode,
                event: e,
                t_inf: accumulation.t_inf,
            }));
        }
        Ok(continue_in(mode, to, y, SwitchedNote::Reset(id)))
    }
}

/// Continues in `to` from `y`: a restart if that is the mode the event fired in.
fn continue_in<D: Dim>(
    from: ModeId,
    to: ModeId,
    y: Vector<D>,
    note: SwitchedNote,
) -> Transition<D, ModeId, SwitchedStop, SwitchedNote> {
    if to == from {
        Transition::Continue { y, note }
    } else {
        Transition::Switch { to, y, note }
    }
}

impl<D: Dim, M: SwitchedModel<D>> HybridSystem<D> for Switched<M> {
    type Mode = ModeId;
    type Guard = EventId;
    type Stop = SwitchedStop;
    type Note = SwitchedNote;

    fn rhs(
        &self,
        mode: ModeId,
        t: f64,
        y: &Vector<D>,
        dy: &mut Vector<D>,
    ) -> Result<(), EvalError> {
        self.model.rhs(mode.index(), t, y, dy)
    }

    fn jacobian(
        &self,
        mode: ModeId,
        t: f64,
        y: &Vector<D>,
        jac: &mut Matrix<D>,
    ) -> Result<(), EvalError> {
        self.model.jacobian(mode.index(), t, y, jac)
    }

    fn guards(&self, mode: ModeId) -> &[GuardSpec<EventId>] {
        &self.specs[mode.index()]
    }

    fn guard_values(
        &self,
        mode: ModeId,
        t: f64,
        y: &Vector<D>,
        dy: &Vector<D>,
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        self.model.event_values(mode.index(), t, y, dy, values)
    }

    fn guard_inputs(&self, mode: ModeId) -> Option<GuardInputs<D>> {
        self.model.guard_inputs(mode.index())
    }

    /// A model's guard that holds where a mode starts fires there (the model language's rule).
    fn fires_on_entry(&self) -> bool {
        true
    }

    fn first_step(&self, mode: ModeId, t: f64, y: &Vector<D>) -> Option<f64> {
        self.model.first_step(mode.index(), t, y)
    }

    fn on_event(
        &mut self,
        mode: ModeId,
        hit: &EventHit<D, EventId>,
    ) -> Result<Transition<D, ModeId, SwitchedStop, SwitchedNote>, EvalError> {
        let id = hit.guard;
        let graph = self.model.graph();
        let decl = graph.event(id);
        let on_accumulation = decl.on_accumulation;
        let (to, reset) = match decl.action {
            // A pass interrupts no history: nothing happened.
            EventAction::Record => {
                let note = SwitchedNote::Recorded(id);
                return Ok(Transition::Pass { note });
            }
            EventAction::Stop => {
                self.forget();
                let (event, t) = (id.event, hit.t);
                return Ok(Transition::Stop(SwitchedStop::Event { mode, event, t }));
            }
            EventAction::Reset { to, reset } => (graph.target(mode, to), reset),
            EventAction::Decide => return self.decided(mode, hit),
        };
        let accumulated = if to == mode {
            self.restarted(id, hit.t)
        } else {
            self.forget();
            None
        };
        let Some(accumulation) = accumulated else {
            let y = self.assigned(id, reset, false, hit)?;
            return Ok(continue_in(mode, to, y, SwitchedNote::Reset(id)));
        };
        let Some(action) = on_accumulation else {
            let (event, t_inf) = (id.event, accumulation.t_inf);
            return Ok(Transition::Stop(SwitchedStop::Accumulation {
                mode,
                event,
                t_inf,
            }));
        };
        let to = self.model.graph().target(mode, action.to);
        let y = self.assigned(id, action.reset, true, hit)?;
        let note = SwitchedNote::Accumulated {
            event: id,
            accumulation,
        };
        Ok(continue_in(mode, to, y, note))
    }
}
