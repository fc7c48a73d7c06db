//! A run of the disk's switched model (module `switching`) on the same driver, settings and
//! start as the hand-written run, reporting its events by name and its mode decisions: what
//! the tests and the bench hold against [`super::simulate`] event by event. The run that
//! feeds a [`super::DiskObserver`] as [`super::simulate`] does is [`super::simulate_graph`].

use super::drive::{drive, Drive, Failed, Start};
use super::graph::Engine;
use super::run::{initial_phase, validate};
use super::switching::disk;
use super::system::{DiskSystem, Phase};
use super::{GeneratedModels, SimError, SimFailure};
use crate::config::DiskConfig;
use crate::modes::{SlipChart, DIM};
use crate::params::DiskParams;
use crate::start::InitialState;
use model_runtime::{
    AccumulationRule, Const, EventId, HybridError, InputError, ModeGraph, ModeId, Observed,
    Observer, Stats, StopReason, Switched, SwitchedModel, SwitchedNote, TransitionKind,
    TransitionRecord,
};

/// One event of a switched run: where it fired and where the run went on.
#[derive(Clone, Debug, PartialEq)]
pub struct SwitchedEvent {
    /// Its time (s).
    pub t: f64,
    /// The mode it fired in.
    pub mode: String,
    /// Its name.
    pub event: String,
    /// The mode the run went on in (`None`: the run stopped there).
    pub next: Option<String>,
}

impl SwitchedEvent {
    /// Whether the event is a mode decision as the hand-written run counts them: an onset of
    /// sliding, a decision at the slip's zero, or a decision the stick made at once (without
    /// the bridge to the zero).
    pub fn is_decision(&self) -> bool {
        match (self.mode.as_str(), self.event.as_str()) {
            ("rolling", "slips") | ("stopping", "halts") => true,
            ("sliding", "sticks") => self.next.as_deref() != Some("stopping"),
            _ => false,
        }
    }
}

/// What a run of the switched disk did.
#[derive(Clone, Debug)]
pub struct SwitchedDiskRun {
    /// Every event, in order (the stop's included).
    pub events: Vec<SwitchedEvent>,
    /// Where it ended (s).
    pub t: f64,
    /// The event that stopped it (`None`: the end time).
    pub stopped_by: Option<String>,
    /// Integrator work.
    pub stats: Stats,
}

impl SwitchedDiskRun {
    /// The times of the mode decisions ([`SwitchedEvent::is_decision`]).
    pub fn decisions(&self) -> Vec<f64> {
        (self.events.iter().filter(|e| e.is_decision()))
            .map(|e| e.t)
            .collect()
    }
}

/// Runs the disk's switched model from `initial` under `config` (still air, Cartesian slip
/// chart, DOP853 or DP5, physical or regularised time), starting where the hand-written run
/// starts (its initial decision, bridge included). Settings it cannot run are refused by key
/// ([`SimError::Invalid`]).
pub fn simulate_switched(
    params: &DiskParams,
    config: &DiskConfig,
    initial: &InitialState,
) -> Result<SwitchedDiskRun, SimFailure> {
    let models = GeneratedModels::generated(*params, SlipChart::Cartesian)
        .map_err(|e| SimFailure::from(SimError::Params(e)))?;
    validate(&models, config, initial)?;
    let refused = Engine::graph_refusals(params, config, config.chart());
    if !refused.is_empty() {
        return Err(SimFailure::from(SimError::Invalid { issues: refused }));
    }
    run(&models, config, initial)
}

fn run(
    models: &GeneratedModels,
    config: &DiskConfig,
    initial: &InitialState,
) -> Result<SwitchedDiskRun, SimFailure> {
    let mut hand_written = DiskSystem::new(models, config);
    let (start, _) = initial_phase(&mut hand_written, models, config, initial)?;
    let mut model = disk::Model::for_run(&models.params, config);
    let mode = match start.phase {
        Phase::Rolling => disk::mode::rolling,
        Phase::Sliding => disk::mode::sliding,
        Phase::Bridge => model.hold(&hand_written.bridge),
    };
    let refused = |error: InputError| {
        SimFailure::from(SimError::Solve {
            mode: start.phase.mode(),
            error: error.into(),
        })
    };
    let mut system = Switched::new(model, AccumulationRule::default()).map_err(refused)?;
    let graph = system.model().graph().clone();
    let modes: Vec<ModeId> = graph.ids().collect();
    let tolerance = config.tolerance(SlipChart::Cartesian).map_err(refused)?;
    let mut collector = Collector {
        graph,
        events: Vec::new(),
    };
    // The collector takes events only: no samples to interpolate.
    let how = Drive {
        config,
        tolerance,
        sample_rate: None,
    };
    let start = Start {
        t: initial.t,
        mode: modes[mode],
        y: start.y,
    };
    let out = drive(how, &mut system, &modes, start, &mut collector).map_err(
        |Failed { error, stats }| SimFailure {
            error: hybrid_error(error),
            stats,
            last: None,
        },
    )?;
    let stopped_by = match out.stop {
        StopReason::User(stop) => {
            let (mode, name) = collector.names(stop.event());
            collector.events.push(SwitchedEvent {
                t: out.t,
                mode,
                event: name.clone(),
                next: None,
            });
            Some(name)
        }
        StopReason::EndTime | StopReason::Observer => None,
    };
    Ok(SwitchedDiskRun {
        events: collector.events,
        t: out.t,
        stopped_by,
        stats: out.stats,
    })
}

/// A driver error of the switched disk, its mode named by the contact mode.
fn hybrid_error(error: HybridError<ModeId>) -> SimError {
    SimError::from_driver(error, |id: ModeId| match id.index() {
        disk::mode::rolling => crate::Mode::Rolling,
        _ => crate::Mode::Sliding,
    })
}

/// Collects the events.
struct Collector {
    graph: ModeGraph,
    events: Vec<SwitchedEvent>,
}

impl Collector {
    /// The mode's and the event's names.
    fn names(&self, event: EventId) -> (String, String) {
        let mode = self.graph.mode(event.mode);
        (mode.name.clone(), mode.events[event.event].name.clone())
    }
}

impl Observer<Const<DIM>, ModeId, EventId, SwitchedNote> for Collector {
    fn on_transition(
        &mut self,
        record: TransitionRecord<Const<DIM>, ModeId, EventId, SwitchedNote>,
    ) -> Observed {
        let (mode, event) = self.names(record.hit.guard);
        let next = match record.kind {
            TransitionKind::Switch { to } => self.graph.mode_name(to).to_string(),
            TransitionKind::Continue | TransitionKind::Pass => mode.clone(),
        };
        self.events.push(SwitchedEvent {
            t: record.hit.t,
            mode,
            event,
            next: Some(next),
        });
        Ok(())
    }
}
