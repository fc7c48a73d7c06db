//! A generic hybrid (mode-switching) driver.
//!
//! A hybrid system has a finite set of modes sharing one state dimension `N`. In each mode it
//! has a right-hand side and a list of guards; when a guard fires, the system's transition map
//! decides what happens: switch to another mode with a new state, restart the same mode from a
//! reset state, or stop. The driver integrates one mode at a time with any [`crate::Stepper`],
//! locates the earliest guard crossing exactly (see [`crate::GuardSpec`] for the semantics),
//! applies the transition and restarts the integrator cleanly: no stage is reused across a
//! transition (no first-same-as-last) and the initial step size is chosen afresh.
//!
//! An event can also be a mere observation ([`Transition::Pass`]: an extremum, a threshold
//! to log). Such an event is located and reported exactly like the others, but it changes
//! nothing, so it costs no restart: the step it fell in is kept, the rest of that step is
//! searched again for later crossings, and the run's steps, samples and final state are
//! those of the same run without the guard. Many such events per second are therefore cheap.
//!
//! The system is a trait with an enum-dispatch style (`fn rhs(&self, mode, ...)`), so the
//! inner loop is monomorphised: no dynamic dispatch, no allocation per step.
//!
//! What a transition map decided beyond the next mode and state (which rule fired, with which
//! numbers: what a caller logs) travels with the transition as the system's
//! [`HybridSystem::Note`], and the driver hands it to [`crate::Observer::on_transition`] by value
//! in the same record as the event. A system therefore needs no side channel between its
//! transition map and the observer (both are borrowed by the driver for the whole run).

// The children use this file's types; this file uses none of theirs (the crate root
// re-exports them), so the module and its children form no import circle.
pub(crate) mod backward;
mod chatter;
pub(crate) mod physical_time;
pub(crate) mod regularised;
pub(crate) mod run;

use crate::control::StepOptions;
use crate::dim::{Const, Dim, Matrix, Vector};
use crate::error::{EvalError, SolveError};
use crate::events::{EventHit, GuardInputs, GuardSpec, InteriorChecks};
use crate::jacobian::finite_difference_jacobian;
use crate::readable::Readable;
use crate::stats::Stats;
use std::fmt::{self, Debug};

/// A system with modes, guards and a transition map.
///
/// ```
/// use model_runtime::{
///     Const, Dop853, Direction, EvalError, EventHit, GuardSpec, HybridOptions, HybridSolver,
///     HybridSystem, StopReason, Tolerance, Transition,
/// };
///
/// /// A ball bouncing on the ground with restitution 0.9: y = (height, velocity).
/// struct Ball;
/// const GROUND: [GuardSpec<&str>; 1] = [GuardSpec { id: "ground", direction: Direction::Down }];
/// impl HybridSystem<Const<2>> for Ball {
///     type Mode = ();
///     type Guard = &'static str;
///     type Stop = ();
///     type Note = ();
///     fn rhs(&self, _: (), _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
///         *dy = [y[1], -9.81];
///         Ok(())
///     }
///     fn guards(&self, _: ()) -> &[GuardSpec<&'static str>] { &GROUND }
///     fn guard_values(&self, _: (), _t: f64, y: &[f64; 2], _dy: &[f64; 2], g: &mut [f64])
///         -> Result<(), EvalError> { g[0] = y[0]; Ok(()) }
///     fn on_event(&mut self, _: (), hit: &EventHit<Const<2>, &'static str>)
///         -> Result<Transition<Const<2>, (), ()>, EvalError> {
///         Ok(Transition::Continue { y: [0.0, -0.9 * hit.y[1]], note: () })
///     }
/// }
///
/// let mut solver = HybridSolver::new(Dop853::new(), Tolerance::scalar(1e-10, 1e-12),
///                                    HybridOptions::default()).unwrap();
/// let out = solver.run(&mut Ball, (), 0.0, &[1.0, 0.0], 2.0, &mut ()).unwrap();
/// assert_eq!(out.stop, StopReason::EndTime);
/// assert!(out.transitions >= 2);
/// ```
pub trait HybridSystem<D: Dim> {
    /// The modes (typically a fieldless enum).
    type Mode: Copy + PartialEq + Debug;
    /// Guard identifiers (typically a fieldless enum).
    type Guard: Copy + PartialEq + Debug;
    /// Why the system asked to stop (user-defined).
    type Stop: Clone + Debug;
    /// What a transition tells the observer besides the event and the states (user-defined;
    /// `()` for nothing): it travels in [`Transition::Switch`], [`Transition::Continue`] and
    /// [`Transition::Pass`] and reaches [`crate::Observer::on_transition`] in the [`crate::TransitionRecord`].
    type Note;

    /// `dy = f(t, y)` in `mode`.
    fn rhs(
        &self,
        mode: Self::Mode,
        t: f64,
        y: &Vector<D>,
        dy: &mut Vector<D>,
    ) -> Result<(), EvalError>;

    /// The Jacobian in `mode` (used by implicit steppers). The default uses central finite
    /// differences of [`HybridSystem::rhs`].
    fn jacobian(
        &self,
        mode: Self::Mode,
        t: f64,
        y: &Vector<D>,
        jac: &mut Matrix<D>,
    ) -> Result<(), EvalError> {
        finite_difference_jacobian::<D>(|y, dy| self.rhs(mode, t, y, dy), y, jac)
    }

    /// The guards of `mode`, in priority order (on equal event times the first wins).
    fn guards(&self, mode: Self::Mode) -> &[GuardSpec<Self::Guard>];

    /// Evaluates all guards of `mode` at `(t, y)`, where `dy = f(t, y)` is already computed;
    /// `values` has one slot per entry of [`HybridSystem::guards`]. Called after every accepted
    /// step (with the step's last stage as `dy`, so it costs no extra evaluation) and at the
    /// interior points of a crossing search. A value that is not finite ends the run with
    /// [`SolveError::GuardNotFinite`].
    fn guard_values(
        &self,
        mode: Self::Mode,
        t: f64,
        y: &Vector<D>,
        dy: &Vector<D>,
        values: &mut [f64],
    ) -> Result<(), EvalError>;

    /// The components of the state and of its derivative that the guards of `mode` read
    /// (default, `None`: all). Screening estimates ([`InteriorChecks::Screened`]) interpolate only
    /// these and pass NaN in every other component; exact evaluations always get the full
    /// state. Declaring less than the guards read is safe but slow: the guard sees NaN, and a
    /// non-finite estimate only asks for an exact evaluation ([`crate::GuardSpec`]).
    fn guard_inputs(&self, _mode: Self::Mode) -> Option<GuardInputs<D>> {
        None
    }

    /// The transition map, called when a guard of `mode` fires (`hit` holds the guard, the
    /// exact time and the state there). It is called after the samples up to the event are
    /// delivered and the step's interpolant is built, so a map that changes what
    /// [`HybridSystem::rhs`] computes (a parameter, a clock) cannot change the output of the
    /// step it ends.
    fn on_event(
        &mut self,
        mode: Self::Mode,
        hit: &EventHit<D, Self::Guard>,
    ) -> Result<TransitionOf<D, Self>, EvalError>;

    /// A step size to try first in a segment of `mode` starting at `(t, y)` (the run's start
    /// or a restart after a transition); `None` (the default) keeps the configured
    /// [`StepOptions::h_initial`] or the automatic choice. Useful where a transition lands on a
    /// state the automatic guess misjudges (e.g. the onset of a motion whose derivative is
    /// nearly singular there): a good first step saves a cascade of rejections.
    fn first_step(&self, _mode: Self::Mode, _t: f64, _y: &Vector<D>) -> Option<f64> {
        None
    }

    /// Whether a guard that already holds where a segment starts (on the side its admitted
    /// crossings lead to, not on its surface) fires there at once: an instantaneous
    /// transition, as in a hybrid automaton (see "A guard that holds on entry" at
    /// [`crate::GuardSpec`]). The default, `false`, takes such a guard's side as its
    /// reference: it fires only after it has left that side and crossed back. [`crate::Switched`]
    /// models (the model language's) say `true`.
    fn fires_on_entry(&self) -> bool {
        false
    }

    /// Optionally moves `y` back onto the constraints of `mode`; returns whether it changed
    /// `y`. Called after every accepted step (a change costs one evaluation of `f` and resets
    /// the guards' reference signs to the projected state) and on the state a transition
    /// starts from. It should move the state by no more than the integration error: a
    /// projection that pushes a guard across zero is not an event.
    fn project(&self, _mode: Self::Mode, _t: f64, _y: &mut Vector<D>) -> bool {
        false
    }
}

/// What the transition map decided; `Nt` is the system's [`HybridSystem::Note`], handed to
/// the observer with the applied transition.
#[derive(Clone, Debug, PartialEq)]
pub enum Transition<D: Dim, Md, R, Nt = ()> {
    /// Continue in mode `to` from state `y`.
    Switch {
        /// The new mode.
        to: Md,
        /// The state it starts from.
        y: Vector<D>,
        /// What the observer is told about it.
        note: Nt,
    },
    /// Restart the same mode from state `y` (e.g. after a velocity reset).
    Continue {
        /// The state it restarts from.
        y: Vector<D>,
        /// What the observer is told about it.
        note: Nt,
    },
    /// Nothing changes: the event is reported to the observer (as
    /// [`crate::TransitionKind::Pass`], with `note`) and the run goes on in the same step, as
    /// if the guard were not there. The integrator is not restarted, and the search of the
    /// step resumes where it found the event, so later events are located exactly where they
    /// would be without it; the guard that passed takes the sign beyond its crossing as its
    /// reference (or, if it is exactly zero at the event, the sign of its first nonzero value
    /// after it, without firing), so it fires again only when it crosses back in a direction
    /// its filter admits (see "Passes" at [`crate::GuardSpec`]). A pass is not a transition:
    /// [`HybridOutcome::transitions`] and the [`ChatterLimit`] do not count it (it restarts
    /// nothing, so it cannot trap the run at one time), [`HybridOutcome::passes`] does, and
    /// [`crate::Observer::proceed`] is asked after the step, not after each pass.
    Pass {
        /// What the observer is told about it.
        note: Nt,
    },
    /// End the run here.
    Stop(R),
}

impl<const N: usize, Md: Copy, R: Copy, Nt: Copy> Copy for Transition<Const<N>, Md, R, Nt> {}

/// The [`Transition`] of a system `H`: its modes, stop reasons and notes.
pub type TransitionOf<D, H> = Transition<
    D,
    <H as HybridSystem<D>>::Mode,
    <H as HybridSystem<D>>::Stop,
    <H as HybridSystem<D>>::Note,
>;

/// More than `max_transitions` transitions within any time window of width `window` is
/// chattering: the run stops with [`HybridError::Chattering`] instead of looping. Passes
/// ([`Transition::Pass`]) are not transitions and do not count.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChatterLimit {
    /// Transitions allowed within one window.
    pub max_transitions: usize,
    /// The window's width (in the system's time unit).
    pub window: f64,
}

impl Default for ChatterLimit {
    /// 100 transitions within 1e-9 time units.
    fn default() -> Self {
        ChatterLimit {
            max_transitions: 100,
            window: 1e-9,
        }
    }
}

/// Options of a hybrid run.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct HybridOptions {
    /// Step-size limits, initial step, step budget.
    pub step: StepOptions,
    /// Chattering detection.
    pub chatter: ChatterLimit,
    /// Samples per time unit delivered to [`crate::Observer::on_sample`] at `t0 + k / rate`;
    /// `None` for no samples.
    pub sample_rate: Option<f64>,
    /// Interior points of each step at which guards are also checked on the dense output
    /// (default: only at step ends). Catches a sign change and back within one step.
    pub guard_checks: InteriorChecks,
}

/// Why a run ended normally.
#[derive(Clone, Debug, PartialEq)]
pub enum StopReason<R> {
    /// The end time was reached.
    EndTime,
    /// The transition map asked to stop.
    User(R),
    /// The observer asked to stop ([`crate::Observer::proceed`]).
    Observer,
}

/// The end of a hybrid run.
#[derive(Clone, Debug, PartialEq)]
pub struct HybridOutcome<D: Dim, Md, R> {
    /// Final time.
    pub t: f64,
    /// Final state.
    pub y: Vector<D>,
    /// Final mode.
    pub mode: Md,
    /// Why it ended.
    pub stop: StopReason<R>,
    /// Work done.
    pub stats: Stats,
    /// Transitions applied (switches and restarts).
    pub transitions: u64,
    /// Events that passed ([`Transition::Pass`]): reported, nothing changed.
    pub passes: u64,
}

/// Why a hybrid run failed.
#[derive(Clone, Debug, PartialEq)]
pub enum HybridError<Md> {
    /// Integration failed inside a mode (or, for [`SolveError::TransitionState`], the mode's
    /// transition map returned an unusable state).
    Solve {
        /// The mode being integrated (whose transition map failed).
        mode: Md,
        /// What went wrong.
        error: SolveError,
    },
    /// The transition map could not evaluate the model at the event.
    Transition {
        /// The mode in which the event fired.
        mode: Md,
        /// The event time.
        t: f64,
        /// The model's explanation.
        source: EvalError,
    },
    /// Too many transitions within a short window.
    Chattering {
        /// Time of the transition that exceeded the limit.
        t: f64,
        /// Transitions counted within the window ending at `t`.
        transitions: usize,
        /// The window's width.
        window: f64,
        /// The modes involved, in order of first appearance in the window.
        modes: Vec<Md>,
    },
    /// The observer could not take the run's output: the model failed where it evaluated it
    /// ([`crate::ObserverError`]).
    Observer {
        /// The mode in force.
        mode: Md,
        /// Where the observer evaluated the model, in its own time variable.
        t: f64,
        /// The model's explanation.
        source: EvalError,
    },
}

impl<Md> HybridError<Md> {
    /// The same error with its modes converted by `f` (named, say, or mapped to the modes of
    /// the system a run was built from).
    pub fn map_mode<M2>(self, f: impl Fn(Md) -> M2) -> HybridError<M2> {
        match self {
            HybridError::Solve { mode, error } => HybridError::Solve {
                mode: f(mode),
                error,
            },
            HybridError::Transition { mode, t, source } => HybridError::Transition {
                mode: f(mode),
                t,
                source,
            },
            HybridError::Chattering {
                t,
                transitions,
                window,
                modes,
            } => HybridError::Chattering {
                t,
                transitions,
                window,
                modes: modes.into_iter().map(f).collect(),
            },
            HybridError::Observer { mode, t, source } => HybridError::Observer {
                mode: f(mode),
                t,
                source,
            },
        }
    }
}

impl<Md: Debug> fmt::Display for HybridError<Md> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HybridError::Solve { mode, error } => write!(f, "in mode {mode:?}: {error}"),
            HybridError::Transition { mode, t, source } => {
                write!(f, "transition out of mode {mode:?} at t = {t}: {source}")
            }
            HybridError::Chattering {
                t,
                transitions,
                window,
                modes,
            } => write!(
                f,
                "chattering at t = {t}: {transitions} transitions within {window} \
                 between modes {modes:?}",
                window = Readable(*window)
            ),
            HybridError::Observer { mode, t, source } => {
                write!(f, "output in mode {mode:?} at t = {t}: {source}")
            }
        }
    }
}

impl<Md: Debug> std::error::Error for HybridError<Md> {}

/// The result of [`crate::HybridSolver::run`] for a system `H`.
pub type HybridResult<D, H> = Result<
    HybridOutcome<D, <H as HybridSystem<D>>::Mode, <H as HybridSystem<D>>::Stop>,
    HybridError<<H as HybridSystem<D>>::Mode>,
>;
