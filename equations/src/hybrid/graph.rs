//! The disk's mode graph (module `switching`) as the system a run of the disk drives: the
//! DSL's [`Switched`] model, with what a run owes its observer added around it — the
//! decision records and bridge slips of the hand-written system ([`DiskNote`]), its stops
//! ([`Halted`]), and its counts (the decisions, the chattering window, the largest
//! constraint drift: a [`Ledger`], as the hand-written system keeps).
//!
//! # How a decision's note reaches the observer
//!
//! The graph's decisions are Rust functions that ask the hand-written transition map
//! (`switching::ask`); the map's answer carries the note the hand-written run hands its
//! observer. The functions write that note into discrete values of the model (`n_*`, read by
//! no equation), and this system reads it back after the event, so the record the observer
//! gets is the map's own, bit for bit, and the decision is made once. (Re-asking the map on
//! the observer's side would make every decision twice; a typed note returned by the DSL's
//! Rust functions would need the model language to know notes.) A stop has no note to write
//! — its reason may carry an error the discrete values cannot hold — so at the one stop of a
//! run that a decision makes, the map is asked again for it.

use super::switching::{ask, disk, Answer, Role};
use super::system::{DiskNote, Halted, Ledger, Phase};
use super::StopReason;
use crate::config::DiskConfig;
use crate::issue::{Issue, Rule};
use crate::modes::layout::THETA;
use crate::modes::{SlipChart, DIM};
use crate::params::DiskParams;
use crate::settings::Integrator;
use model_runtime::Switched;
use model_runtime::{
    AccumulationRule, Const, EvalError, EventHit, EventId, GuardInputs, GuardSpec, HybridSystem,
    InputError, ModeId, SwitchedModel, SwitchedStop, TimeScale, Transition,
};

/// A mode of a system of the disk, seen as the phase it stands for: the hand-written
/// system's [`Phase`], or a mode of the graph (`rolling`, `sliding`, and the two bridges,
/// `starting` and `stopping`).
pub(crate) trait DiskPhase: Copy + PartialEq + std::fmt::Debug {
    /// The phase.
    fn phase(self) -> Phase;
}

impl DiskPhase for Phase {
    fn phase(self) -> Phase {
        self
    }
}

impl DiskPhase for ModeId {
    fn phase(self) -> Phase {
        match self.index() {
            disk::mode::rolling => Phase::Rolling,
            disk::mode::sliding => Phase::Sliding,
            _ => Phase::Bridge,
        }
    }
}

/// The disk's mode graph as a run drives it.
pub(crate) struct GraphSystem {
    switched: Switched<disk::Model>,
    /// The disk's parameters (the drift is measured with them).
    params: DiskParams,
    /// Each event's role, by mode and event (`None`: an event the disk does not know).
    roles: Vec<Vec<Option<Role>>>,
    /// The decisions so far and the largest drift.
    pub(crate) ledger: Ledger,
}

impl GraphSystem {
    /// The graph of `model` run under `config` (its chattering limit).
    pub(crate) fn new(model: disk::Model, config: &DiskConfig) -> Result<Self, InputError> {
        let params = model.disk_params();
        let switched = Switched::new(model, AccumulationRule::default())?;
        let graph = switched.model().graph();
        let roles = (graph.ids())
            .map(|id| {
                let events = &graph.mode(id).events;
                (events.iter())
                    .map(|e| super::switching::role(id.index(), &e.name))
                    .collect()
            })
            .collect();
        Ok(GraphSystem {
            switched,
            params,
            roles,
            ledger: Ledger::new(config),
        })
    }

    /// Every mode of the graph.
    pub(crate) fn modes(&self) -> Vec<ModeId> {
        self.switched.model().graph().ids().collect()
    }

    /// The role of the event `id`.
    fn role(&self, id: EventId) -> Result<Role, EvalError> {
        self.roles[id.mode.index()][id.event].ok_or_else(|| EvalError::Undecided {
            event: self.switched.model().graph().event_name(id),
            mode: None,
        })
    }

    /// The note of a transition the event of `role` made at `t`, with the decision counted
    /// (or the chattering stop it leads to).
    fn noted(&mut self, role: Role, t: f64) -> Noted {
        let note = match role {
            Role::Decision(_) | Role::StartsSliding => self.switched.model().last_note(),
            Role::Stop(_) => DiskNote::default(),
        };
        if let Some(decision) = note.decision {
            // As the hand-written map does: the drift at the decision noted, the chattering
            // window counted before the decision takes effect.
            self.ledger.note_drift(decision.drift);
            if self.ledger.chattering(t) {
                return Noted::Stops(self.ledger.chatter_stop(t));
            }
            self.ledger.transitions += 1;
        }
        Noted::Goes(note)
    }

    /// Why the run stops at the event `hit` of `role` in `mode`, where the graph stopped with
    /// `stop`.
    fn halted(
        &mut self,
        mode: ModeId,
        role: Role,
        stop: SwitchedStop,
        hit: &EventHit<Const<DIM>, EventId>,
    ) -> Result<Halted, EvalError> {
        let t = hit.t;
        match (role, stop) {
            (Role::Stop(guard), _) => Ok(Halted::plain(match guard {
                super::DiskGuard::InclinationFloor => StopReason::InclinationReachedFloor {
                    t,
                    theta: hit.y[THETA],
                },
                _ => StopReason::ContactLost {
                    t,
                    mode: mode.phase().mode(),
                },
            })),
            (Role::Decision(asked), SwitchedStop::Event { .. }) => {
                let model = self.switched.model();
                let Answer {
                    transition, drift, ..
                } = ask(model, asked, model.held(), (t, &hit.y, &hit.dy))?;
                self.ledger.note_drift(drift);
                if self.ledger.chattering(t) {
                    return Ok(self.ledger.chatter_stop(t));
                }
                match transition {
                    Transition::Stop(halted) => {
                        if halted.decision.is_some() {
                            self.ledger.transitions += 1;
                        }
                        Ok(halted)
                    }
                    // The map asked again answers as it did.
                    _ => Err(undecided(self, hit.guard)),
                }
            }
            // Restarts of sliding at the stick threshold accumulating: the graph's own watch
            // of restarts saw chattering.
            (Role::Decision(_), SwitchedStop::Accumulation { .. }) => {
                Ok(self.ledger.chatter_stop(t))
            }
            (Role::StartsSliding, _) => Err(undecided(self, hit.guard)),
        }
    }
}

/// What a transition of the graph becomes for the run: a transition with the disk's note,
/// or the stop for chattering the decision it made leads to.
enum Noted {
    /// The transition goes ahead with this note.
    Goes(DiskNote),
    /// The decision exceeded the chattering limit: the run stops.
    Stops(Halted),
}

/// The error of an event whose outcome is not one its role allows.
fn undecided(system: &GraphSystem, id: EventId) -> EvalError {
    EvalError::Undecided {
        event: system.switched.model().graph().event_name(id),
        mode: None,
    }
}

impl HybridSystem<Const<DIM>> for GraphSystem {
    type Mode = ModeId;
    type Guard = EventId;
    type Stop = Halted;
    type Note = DiskNote;

    #[inline]
    fn rhs(
        &self,
        mode: ModeId,
        t: f64,
        y: &[f64; DIM],
        dy: &mut [f64; DIM],
    ) -> Result<(), EvalError> {
        self.switched.rhs(mode, t, y, dy)
    }

    fn jacobian(
        &self,
        mode: ModeId,
        t: f64,
        y: &[f64; DIM],
        jac: &mut [[f64; DIM]; DIM],
    ) -> Result<(), EvalError> {
        self.switched.jacobian(mode, t, y, jac)
    }

    fn guards(&self, mode: ModeId) -> &[GuardSpec<EventId>] {
        self.switched.guards(mode)
    }

    fn guard_values(
        &self,
        mode: ModeId,
        t: f64,
        y: &[f64; DIM],
        dy: &[f64; DIM],
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        self.switched.guard_values(mode, t, y, dy, values)
    }

    fn guard_inputs(&self, mode: ModeId) -> Option<GuardInputs<Const<DIM>>> {
        HybridSystem::<Const<DIM>>::guard_inputs(&self.switched, mode)
    }

    fn fires_on_entry(&self) -> bool {
        HybridSystem::<Const<DIM>>::fires_on_entry(&self.switched)
    }

    fn first_step(&self, mode: ModeId, t: f64, y: &[f64; DIM]) -> Option<f64> {
        self.switched.first_step(mode, t, y)
    }

    fn on_event(
        &mut self,
        mode: ModeId,
        hit: &EventHit<Const<DIM>, EventId>,
    ) -> Result<Transition<Const<DIM>, ModeId, Halted, DiskNote>, EvalError> {
        let role = self.role(hit.guard)?;
        Ok(match self.switched.on_event(mode, hit)? {
            Transition::Switch { to, y, .. } => match self.noted(role, hit.t) {
                Noted::Goes(note) => Transition::Switch { to, y, note },
                Noted::Stops(halted) => Transition::Stop(halted),
            },
            Transition::Continue { y, .. } => match self.noted(role, hit.t) {
                Noted::Goes(note) => Transition::Continue { y, note },
                Noted::Stops(halted) => Transition::Stop(halted),
            },
            Transition::Pass { .. } => Transition::Pass {
                note: DiskNote::default(),
            },
            Transition::Stop(stop) => Transition::Stop(self.halted(mode, role, stop, hit)?),
        })
    }

    /// Notes the drift after every step, as the hand-written system does (the graph runs
    /// only where no projection is asked for).
    fn project(&self, mode: ModeId, _t: f64, y: &mut [f64; DIM]) -> bool {
        self.ledger.note_step(&self.params, mode.phase(), y);
        false
    }
}

impl TimeScale<DIM> for GraphSystem {
    #[inline]
    fn time_scale(&self, mode: ModeId, y: &[f64; DIM]) -> f64 {
        self.switched.time_scale(mode, y)
    }
}

/// The engines that run the disk.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Engine {
    /// The DSL's mode graph ([`crate::simulate_graph`]): the main job's engine wherever it
    /// models the run ([`Engine::for_run`]).
    ModeGraph,
    /// The hand-written hybrid system ([`crate::simulate`]): the graph's reference, and what
    /// runs where the graph cannot (the default here, as it runs every scene).
    #[default]
    HandWritten,
}

/// The engine [`crate::simulate`] runs, named for a run's provenance (`summary.json`'s
/// `produced_by.engine`): the paper's mode rules written by hand (module `system`) over the
/// models the DSL compiles. It is the reference the DSL's mode graph ([`crate::simulate_graph`],
/// [`GRAPH_ENGINE`]) is held to, to the bit, and it runs what the graph cannot model
/// ([`Engine::for_run`]).
pub const ENGINE: &str = "hand-written hybrid system";

/// The engine [`crate::simulate_graph`] runs: the disk's mode graph said in the DSL (module
/// `switching`), its decisions the hand-written maps'.
pub const GRAPH_ENGINE: &str = "dsl mode graph";

impl Engine {
    /// Its name in a run's provenance (`summary.json`'s `produced_by.engine`).
    pub fn name(self) -> &'static str {
        match self {
            Engine::ModeGraph => GRAPH_ENGINE,
            Engine::HandWritten => ENGINE,
        }
    }

    /// The engine a run of the full models under `params` and `config` can use: the mode
    /// graph where it models the run ([`Engine::graph_refusals`] is empty), else the
    /// hand-written system.
    pub fn for_run(params: &DiskParams, config: &DiskConfig) -> Engine {
        if Engine::graph_refusals(params, config, config.chart()).is_empty() {
            Engine::ModeGraph
        } else {
            Engine::HandWritten
        }
    }

    /// What keeps the mode graph from running under `params` and `config` with a sliding
    /// model in `chart`, each by its key: the air (the graph is the disk in still air), the
    /// slip chart (Cartesian: `run.slip_sign = "physical"`), the integrator (DOP853 or DP5)
    /// and the projection after steps (the graph has none).
    pub fn graph_refusals(
        params: &DiskParams,
        config: &DiskConfig,
        chart: SlipChart,
    ) -> Vec<Issue> {
        let unsupported = |key: &str, name: String, expected: &str| {
            let rule = Rule::Unknown {
                name,
                expected: expected.to_string(),
            };
            Issue::new(key, rule)
        };
        let still = |value: f64| Rule::OutOfRange {
            value,
            min: 0.0,
            max: 0.0,
            open: false,
        };
        let mut issues: Vec<Issue> = [("air.mu_a", params.mu_a), ("air.w_z", params.w_z)]
            .into_iter()
            .filter(|&(_, value)| value != 0.0)
            .map(|(key, value)| Issue::new(key, still(value)))
            .collect();
        if chart != SlipChart::Cartesian || config.chart() != SlipChart::Cartesian {
            let sign = format!("{:?}", config.slip_sign);
            issues.push(unsupported("run.slip_sign", sign, "physical"));
        }
        if !matches!(config.integrator, Integrator::Dop853 | Integrator::Dopri5) {
            let name = format!("{:?}", config.integrator);
            issues.push(unsupported("solver.integrator", name, "dop853, dopri5"));
        }
        if config.project_each_step {
            let name = config.project_each_step.to_string();
            issues.push(unsupported("project_each_step", name, "false"));
        }
        issues
    }
}
