//! The disk as a [`HybridSystem`]: phases, guards and the transition maps of docs/physics.md §7.
//!
//! Besides rolling and sliding there is a third phase, the *bridge*: a short segment with a
//! constant derivative that carries the slip exactly between zero and the stick threshold,
//! where neither sliding chart can be evaluated (see the module docs of [`crate::hybrid`]).
//! Integrating a constant derivative is exact for every Runge–Kutta method, and the bridge's
//! only guard is its end time, so the generic driver times it to a few ulps.

use super::models::DiskModels;
use super::onset::{consistent_slip_direction, OnsetError};
use super::{StopReason, TransitionRecord, Trigger};
use crate::config::DiskConfig;
use crate::modes::layout::{THETA, U_X, U_Y, V_C, V_X, V_Y, V_Z};
use crate::modes::{ConstraintResiduals, ContactForce, Mode, PhysicalState, Slip, SlipChart, DIM};
use crate::settings::{SlipSign, TimeVariable};
use model_runtime::Const;
use model_runtime::{
    Direction, EvalError, EventHit, GuardInputs, GuardSpec, HybridSystem, Model, TimeScale,
    Transition,
};
use std::cell::Cell;

mod bridge;
mod inputs;
mod ledger;

pub(crate) use bridge::{AfterBridge, BridgePlan};
pub(crate) use bridge::{BridgeStart, Entry};
pub(crate) use ledger::Ledger;

/// What the integrator is doing: one of the two modes, or a bridge between zero slip and the
/// stick threshold (part of sliding).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Phase {
    Rolling,
    Sliding,
    Bridge,
}

impl Phase {
    /// The contact mode this phase belongs to.
    pub(crate) fn mode(self) -> Mode {
        match self {
            Phase::Rolling => Mode::Rolling,
            Phase::Sliding | Phase::Bridge => Mode::Sliding,
        }
    }
}

/// The disk's guards.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DiskGuard {
    /// Rolling: `T − μ_st N`, upward.
    FrictionLimit,
    /// Sliding: slip speed minus the stick threshold, downward.
    SlipStops,
    /// Either mode: `N`, downward.
    ContactLost,
    /// Either mode: `min(θ, π − θ) − θ_min`, downward.
    InclinationFloor,
    /// Bridge: time minus the bridge's end, upward.
    BridgeEnd,
}

const fn guard(id: DiskGuard, direction: Direction) -> GuardSpec<DiskGuard> {
    GuardSpec { id, direction }
}

const ROLLING_GUARDS: [GuardSpec<DiskGuard>; 3] = [
    guard(DiskGuard::FrictionLimit, Direction::Up),
    guard(DiskGuard::ContactLost, Direction::Down),
    guard(DiskGuard::InclinationFloor, Direction::Down),
];
const SLIDING_GUARDS: [GuardSpec<DiskGuard>; 3] = [
    guard(DiskGuard::SlipStops, Direction::Down),
    guard(DiskGuard::ContactLost, Direction::Down),
    guard(DiskGuard::InclinationFloor, Direction::Down),
];
const BRIDGE_GUARDS: [GuardSpec<DiskGuard>; 1] = [guard(DiskGuard::BridgeEnd, Direction::Up)];

/// Sliding segments starting with a slip below this many stick thresholds get a first step
/// from the slip's time scale (the ones after a bridge start at two).
const FIRST_STEP_SLIP_LIMIT: f64 = 4.0;
/// The first step after a bridge, as a fraction of the slip's doubling time `|u| / |u̇|`.
const FIRST_STEP_FRACTION: f64 = 3.0;

/// Why the system asked the driver to stop.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Halt {
    Stop(StopReason),
    Onset { t: f64, source: OnsetError },
}

/// The disk's stop: why, and the mode decision taken just before it (a start of sliding that
/// turns out impossible was still decided, and the observer hears of it).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Halted {
    pub halt: Halt,
    pub decision: Option<TransitionRecord>,
}

impl Halted {
    /// A stop with no decision before it.
    pub(crate) fn plain(reason: StopReason) -> Self {
        Halted {
            halt: Halt::Stop(reason),
            decision: None,
        }
    }
}

/// What a transition of the disk tells the observer (its [`HybridSystem::Note`], carried by
/// the driver with the transition): the mode decision, if the transition made one, and, when it
/// enters a bridge, the slip the bridge starts from, whose direction labels the bridge's
/// samples (at zero slip a Cartesian state cannot carry it).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct DiskNote {
    pub decision: Option<TransitionRecord>,
    pub bridge: Option<Slip>,
}

/// A transition of the disk.
pub(crate) type DiskTransition = Transition<Const<DIM>, Phase, Halted, DiskNote>;

/// A mode decision that starts sliding, and where it leads: the next segment, or a stop.
pub(crate) struct SlidingStart {
    pub decision: Option<TransitionRecord>,
    pub next: BridgeStart,
}

impl SlidingStart {
    /// The driver's transition into the planned start (or the stop when there is none), with
    /// the decision as its note.
    fn into_transition(self) -> DiskTransition {
        let decision = self.decision;
        match self.next {
            Ok(entry) => Transition::Switch {
                to: entry.phase,
                y: entry.y,
                note: DiskNote {
                    decision,
                    bridge: entry.bridge,
                },
            },
            Err(halt) => Transition::Stop(Halted { halt, decision }),
        }
    }
}

/// The settings the transition maps need.
#[derive(Clone, Copy, Debug)]
struct Settings {
    stick: f64,
    sign: SlipSign,
    min_inclination: f64,
    project_each_step: bool,
}

pub(crate) struct DiskSystem<'a, R, S> {
    models: &'a DiskModels<R, S>,
    settings: Settings,
    pub(crate) bridge: BridgePlan,
    /// The decisions so far and the largest drift.
    pub(crate) ledger: Ledger,
    /// Sign of the polar slip speed in the current sliding segment.
    speed_sign: Cell<f64>,
}

impl<'a, R: Model<DIM>, S: Model<DIM>> DiskSystem<'a, R, S> {
    pub(crate) fn new(models: &'a DiskModels<R, S>, config: &DiskConfig) -> Self {
        DiskSystem {
            models,
            settings: Settings {
                stick: config.stick_threshold,
                sign: config.slip_sign,
                min_inclination: config.min_inclination,
                project_each_step: config.project_each_step,
            },
            bridge: BridgePlan {
                t_end: f64::NEG_INFINITY,
                slope: [0.0; DIM],
                then: AfterBridge::StickDecision,
            },
            ledger: Ledger::new(config),
            speed_sign: Cell::new(1.0),
        }
    }

    /// The slip speed the stick guard watches. In the polar chart `v_C` is signed and passes
    /// through zero smoothly, so the guard follows `v_C` times the sign it had when the segment
    /// started (its magnitude would touch zero inside a step without changing sign).
    fn slip_speed(&self, y: &[f64; DIM]) -> f64 {
        match self.models.chart {
            // Not `hypot`: slip speeds are far from overflow and underflow (δ ≥ 1e-9 m/s).
            SlipChart::Cartesian => (y[U_X] * y[U_X] + y[U_Y] * y[U_Y]).sqrt(),
            SlipChart::Polar => self.speed_sign.get() * y[V_C],
        }
    }

    /// Evaluates the rolling model at a physical state and returns its contact force.
    pub(crate) fn rolling_force(
        &self,
        t: f64,
        state: &PhysicalState,
    ) -> Result<ContactForce, EvalError> {
        let mut dy = [0.0; DIM];
        self.models.rolling.rhs(t, &state.y, &mut dy)?;
        Ok(ContactForce::rolling(&self.models.params, state, &dy))
    }

    /// A mode decision, counted in [`Self::transitions`] when `counted`.
    fn decide(&mut self, record: TransitionRecord, counted: bool) -> Option<TransitionRecord> {
        if counted {
            self.ledger.transitions += 1;
        }
        Some(record)
    }

    /// Starts sliding from zero slip at `state` (rolling variables, on the constraints): finds
    /// the consistent direction nearest `guess` and plans the bridge of the slip to `2δ` (none
    /// for an onset of second order: sliding proper starts at once with the slip `2δ`).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn begin_sliding(
        &mut self,
        t: f64,
        state: PhysicalState,
        guess: f64,
        from: Mode,
        trigger: Trigger,
        drift: ConstraintResiduals,
        counted: bool,
    ) -> Result<SlidingStart, EvalError> {
        let models = self.models;
        let probe = |alpha| models.probe_onset(t, &state, alpha).map(|(acc, _)| acc);
        let onset = match consistent_slip_direction(guess, probe) {
            Ok(onset) => onset,
            Err(OnsetError::Model { source, .. }) => return Err(source),
            Err(source) => {
                return Ok(SlidingStart {
                    decision: None,
                    next: Err(Halt::Onset { t, source }),
                })
            }
        };
        let decision = self.decide(
            TransitionRecord {
                t,
                from,
                to: Mode::Sliding,
                trigger,
                slip_direction: Some(onset.direction),
                rolling_direction: Some(guess),
                drift,
            },
            counted,
        );
        // A second-order onset (μ_st = μ_d at the friction limit, docs/physics.md §7.1) has
        // no first-order rate to bridge with: sliding starts at once.
        let along = if onset.second_order {
            0.0
        } else {
            onset.acceleration.along
        };
        let next = self.bridge_into_sliding(t, &state, onset.direction, along)?;
        Ok(SlidingStart { decision, next })
    }

    /// At the exact zero of the slip: roll if static friction can hold, else slide on.
    fn decide_at_stop(&mut self, t: f64, y: &[f64; DIM]) -> Result<DiskTransition, EvalError> {
        let before = self.models.sliding_state(y);
        let drift = before.residuals(&self.models.params, Mode::Sliding);
        self.ledger.note_drift(drift);
        let mut state = before;
        // v_C = 0: the centre's velocity is the no-slip one (S1/S2 with v_C = 0).
        state.project(&self.models.params, Mode::Rolling);
        state.slip.speed = 0.0;
        let force = self.rolling_force(t, &state)?;
        let trigger = Trigger::SlipStopped {
            rolling_ratio: force.ratio(),
            rolling_normal: force.normal,
        };
        if self.ledger.chattering(t) {
            return Ok(Transition::Stop(self.ledger.chatter_stop(t)));
        }
        if force.admits_rolling(self.models.params.mu_st) {
            state.slip.direction = force.direction();
            let decision = self.decide(
                TransitionRecord {
                    t,
                    from: Mode::Sliding,
                    to: Mode::Rolling,
                    trigger,
                    slip_direction: None,
                    rolling_direction: None,
                    drift,
                },
                true,
            );
            return Ok(Transition::Switch {
                to: Phase::Rolling,
                y: state.rolling_vector(),
                note: DiskNote {
                    decision,
                    bridge: None,
                },
            });
        }
        match self.settings.sign {
            SlipSign::Physical => {
                let start = self.begin_sliding(
                    t,
                    state,
                    force.direction(),
                    Mode::Sliding,
                    trigger,
                    drift,
                    true,
                )?;
                Ok(start.into_transition())
            }
            SlipSign::Paper => {
                let direction = before.slip.direction;
                let (acc, _) = self.models.probe_onset(t, &state, direction)?;
                let decision = self.decide(
                    TransitionRecord {
                        t,
                        from: Mode::Sliding,
                        to: Mode::Sliding,
                        trigger,
                        slip_direction: Some(direction),
                        rolling_direction: Some(direction),
                        drift,
                    },
                    true,
                );
                let next = self.bridge_into_sliding(t, &state, direction, acc.along)?;
                Ok(SlidingStart { decision, next }.into_transition())
            }
        }
    }

    /// The bridge into sliding is over: sliding proper starts with the planned slip.
    pub(crate) fn start_sliding(&self, y: &[f64; DIM], slip: Slip) -> [f64; DIM] {
        self.speed_sign
            .set(if slip.speed < 0.0 { -1.0 } else { 1.0 });
        let mut state = self.models.sliding_state(y);
        state.project(&self.models.params, Mode::Sliding);
        state.sliding_vector(self.models.chart, slip)
    }
}

impl<R: Model<DIM>, S: Model<DIM>> HybridSystem<Const<DIM>> for DiskSystem<'_, R, S> {
    type Mode = Phase;
    type Guard = DiskGuard;
    type Stop = Halted;
    type Note = DiskNote;

    #[inline]
    fn rhs(
        &self,
        phase: Phase,
        t: f64,
        y: &[f64; DIM],
        dy: &mut [f64; DIM],
    ) -> Result<(), EvalError> {
        match phase {
            Phase::Rolling => self.models.rolling.rhs(t, y, dy),
            Phase::Sliding => self.models.sliding.rhs(t, y, dy),
            Phase::Bridge => {
                *dy = self.bridge.slope;
                Ok(())
            }
        }
    }

    /// The models' own Jacobians (symbolic in generated code) instead of the driver's finite
    /// differences, which cost 24 extra evaluations per Jacobian; a bridge's derivative is
    /// constant.
    fn jacobian(
        &self,
        phase: Phase,
        t: f64,
        y: &[f64; DIM],
        jac: &mut [[f64; DIM]; DIM],
    ) -> Result<(), EvalError> {
        match phase {
            Phase::Rolling => self.models.rolling.jacobian(t, y, jac),
            Phase::Sliding => self.models.sliding.jacobian(t, y, jac),
            Phase::Bridge => {
                *jac = [[0.0; DIM]; DIM];
                Ok(())
            }
        }
    }

    fn guards(&self, phase: Phase) -> &[GuardSpec<DiskGuard>] {
        match phase {
            Phase::Rolling => &ROLLING_GUARDS,
            Phase::Sliding => &SLIDING_GUARDS,
            Phase::Bridge => &BRIDGE_GUARDS,
        }
    }

    /// What [`Self::guard_values`] reads in `phase` (module `inputs`), so that screening
    /// interpolates four components instead of twenty-four.
    fn guard_inputs(&self, phase: Phase) -> Option<GuardInputs<Const<DIM>>> {
        let with_air = self.models.params.k_F() != 0.0;
        Some(inputs::guard_inputs(phase, self.models.chart, with_air))
    }

    fn guard_values(
        &self,
        phase: Phase,
        t: f64,
        y: &[f64; DIM],
        dy: &[f64; DIM],
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        let p = &self.models.params;
        // The distance from lying flat on either face: a kink at π/2 is harmless, the guard
        // only needs to be continuous.
        let theta = y[THETA];
        let floor = theta.min(std::f64::consts::PI - theta) - self.settings.min_inclination;
        match phase {
            Phase::Rolling => {
                let f = ContactForce::rolling(p, &PhysicalState::from_rolling(y, 0.0), dy);
                values[0] = if p.k_F() == 0.0 {
                    still_friction_margin(p, dy)
                } else {
                    f.friction_margin(p.mu_st)
                };
                values[1] = f.normal;
                values[2] = floor;
            }
            Phase::Sliding => {
                values[0] = self.slip_speed(y) - self.settings.stick;
                values[1] = ContactForce::sliding_normal(p, self.models.chart, y, dy);
                values[2] = floor;
            }
            Phase::Bridge => values[0] = t - self.bridge.t_end,
        }
        Ok(())
    }

    fn on_event(
        &mut self,
        phase: Phase,
        hit: &EventHit<Const<DIM>, DiskGuard>,
    ) -> Result<DiskTransition, EvalError> {
        match hit.guard {
            DiskGuard::ContactLost => {
                Ok(Transition::Stop(Halted::plain(StopReason::ContactLost {
                    t: hit.t,
                    mode: phase.mode(),
                })))
            }
            DiskGuard::InclinationFloor => Ok(Transition::Stop(Halted::plain(
                StopReason::InclinationReachedFloor {
                    t: hit.t,
                    theta: hit.y[THETA],
                },
            ))),
            DiskGuard::FrictionLimit => {
                let mut state = PhysicalState::from_rolling(&hit.y, 0.0);
                let force = ContactForce::rolling(&self.models.params, &state, &hit.dy);
                let drift = state.residuals(&self.models.params, Mode::Rolling);
                self.ledger.note_drift(drift);
                state.project(&self.models.params, Mode::Rolling);
                if self.ledger.chattering(hit.t) {
                    return Ok(Transition::Stop(self.ledger.chatter_stop(hit.t)));
                }
                let trigger = Trigger::FrictionLimit {
                    ratio: force.ratio(),
                };
                let start = self.begin_sliding(
                    hit.t,
                    state,
                    force.direction(),
                    Mode::Rolling,
                    trigger,
                    drift,
                    true,
                )?;
                Ok(start.into_transition())
            }
            DiskGuard::SlipStops => self.bridge_to_stop(hit),
            DiskGuard::BridgeEnd => match self.bridge.then {
                AfterBridge::StickDecision => self.decide_at_stop(hit.t, &hit.y),
                AfterBridge::StartSliding { slip } => Ok(Transition::Switch {
                    to: Phase::Sliding,
                    y: self.start_sliding(&hit.y, slip),
                    note: DiskNote::default(),
                }),
            },
        }
    }

    /// Sliding that starts from the stick threshold is stiff in the slip direction (∝ 1/|u|),
    /// and the generic first-step guess, which sees only the size of `f`, overshoots and costs
    /// a cascade of rejections. The slip's own time scale `|u| / |u̇|` (the time it takes to
    /// double, for a slip that grows linearly from zero) is the step that an error-controlled
    /// method accepts there. A bridge is integrated in one step that covers its end.
    fn first_step(&self, phase: Phase, t: f64, y: &[f64; DIM]) -> Option<f64> {
        match phase {
            Phase::Rolling => None,
            Phase::Bridge => Some(2.0 * (self.bridge.t_end - t)),
            Phase::Sliding => {
                let speed = self.slip_speed(y).abs();
                if speed > FIRST_STEP_SLIP_LIMIT * self.settings.stick {
                    return None;
                }
                let mut dy = [0.0; DIM];
                self.models.sliding.rhs(t, y, &mut dy).ok()?;
                let rate = match self.models.chart {
                    SlipChart::Cartesian => dy[U_X].hypot(dy[U_Y]),
                    SlipChart::Polar => dy[V_C].abs(),
                };
                let h = FIRST_STEP_FRACTION * speed / rate;
                (h.is_finite() && h > 0.0).then_some(h)
            }
        }
    }

    fn project(&self, phase: Phase, _t: f64, y: &mut [f64; DIM]) -> bool {
        let Some(mut state) = self.ledger.note_step(&self.models.params, phase, y) else {
            return false;
        };
        if !self.settings.project_each_step {
            return false;
        }
        // In sliding only Z and V_Z move, which sit at the same indices in every layout.
        state.project(&self.models.params, phase.mode());
        let changed = state.y != *y;
        *y = state.y;
        changed
    }
}

/// The clock of [`TimeVariable::Regularised`]: slowed near lying flat and near zero slip.
impl<R: Model<DIM>, S: Model<DIM>> TimeScale<DIM> for DiskSystem<'_, R, S> {
    #[inline]
    fn time_scale(&self, phase: Phase, y: &[f64; DIM]) -> f64 {
        let theta = y[THETA].min(std::f64::consts::PI - y[THETA]);
        let inclination = theta / (theta + TimeVariable::THETA_SCALE);
        match phase {
            Phase::Rolling => inclination,
            Phase::Sliding => {
                let slip = self.slip_speed(y).abs();
                inclination * slip / (slip + TimeVariable::SLIP_SCALE)
            }
            Phase::Bridge => 1.0,
        }
    }
}

/// [`ContactForce::friction_margin`] of rolling in still air (`T - mu_st N`, or `T/mu_st - N`
/// above `mu_st = 1`), rounded as the mode graph's compiled guard `slips` is, whose friction
/// is `sqrt(der(V_X)^2*m^2 + m^2*der(V_Y)^2)` and whose second term is `m*mu_st*(der(V_Z) + g)`
/// (`m*(der(V_Z) + g)` above 1): the same zero, and the same bits as the graph's, so that either
/// engine locates a crossing at the same instant (`equations/tests/suite/graph_engine.rs`).
fn still_friction_margin(p: &crate::params::DiskParams, dy: &[f64; DIM]) -> f64 {
    let m2 = p.m * p.m;
    let friction = (dy[V_X] * dy[V_X] * m2 + m2 * (dy[V_Y] * dy[V_Y])).sqrt();
    if p.mu_st > 1.0 {
        friction / p.mu_st - p.m * (dy[V_Z] + p.g)
    } else {
        friction - p.m * p.mu_st * (dy[V_Z] + p.g)
    }
}
