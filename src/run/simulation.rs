//! The bridge to the equations crate's run: the simulation's records -> the CLI's named
//! records.
//!
//! The simulation runs on a worker thread and streams what it observes through a bounded
//! channel, in batches; the caller's thread writes and collects meanwhile (on a second core,
//! the files cost the simulation nothing). The worker asks only for the samples of the
//! [`SamplePlan`], and it stops by itself, through its observer, when the caller raises the
//! stop flag (Ctrl-C); a mode the scene forbids ends the run by itself
//! ([`StopReason::ModeNotAllowed`]).

use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::thread::Scope;

use equations::DIM;
use equations::{
    simulate, AllowedModes, DiskConfig, DiskModels, DiskObserver, DiskParams, DiskSample, Extremum,
    InitialState, Mode, RunOutcome, StopReason, TransitionRecord, Trigger,
};
use model_runtime::{Model, Readable};

use super::model::{with_models, ModelChoice, ModelsTask};
use super::plan::SamplePlan;
use crate::record::{EventRow, StopRecord, TriggerKind};
use crate::sample::{ContactForces, DiskState, Sample, Slip};
use crate::scene::Scene;

/// What the worker sends.
#[derive(Debug)]
pub enum Message {
    /// Samples of the plan, in order.
    Samples(Vec<Sample>),
    /// A mode decision.
    Event(EventRow),
    /// Located extrema, in order.
    Extrema(Vec<Extremum>),
    /// The run ended (boxed: an outcome holds a whole sample).
    Done(Box<Result<Outcome, Failure>>),
}

/// A simulation that failed: why, and the work it did until then.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// The error, in words.
    pub message: String,
    /// Accepted steps until the failure.
    pub steps: u64,
    /// Right-hand-side evaluations until the failure.
    pub rhs_evals: u64,
    /// When it failed (s), if the error says.
    pub t: Option<f64>,
}

impl Failure {
    /// A failure before the simulation started (its models could not be built): no work.
    fn before_start(message: String) -> Self {
        Failure {
            message,
            steps: 0,
            rhs_evals: 0,
            t: None,
        }
    }
}

/// The end of a run, in the CLI's terms.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// Why it ended.
    pub stop: StopRecord,
    /// Accepted steps.
    pub steps: u64,
    /// Right-hand-side evaluations.
    pub rhs_evals: u64,
    /// Largest constraint drift (SI units).
    pub constraint_drift_max: f64,
    /// The exact final state.
    pub last: Sample,
}

/// The friction law's coefficients: they give ν where `T/N` of the computed forces does not.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrictionLaw {
    /// Dynamic friction `μ_d`.
    pub mu_d: f64,
    /// Static friction `μ_st`.
    pub mu_st: f64,
}

impl FrictionLaw {
    /// The coefficients of the disk `p`.
    pub fn of(p: &DiskParams) -> Self {
        FrictionLaw {
            mu_d: p.mu_d,
            mu_st: p.mu_st,
        }
    }

    /// The friction ratio ν in `mode` of a contact force with friction `t` and normal force
    /// `n`. Sliding: `μ_d` (`T = μ_d N` holds by construction; `T/N` of the computed forces
    /// would be `0/0`, or `−μ_d` from round-off, at the located instant the contact is lost).
    /// Rolling: `T/N` while the contact is compressed, `N > 0`; at the located loss of contact
    /// `N` is zero to round-off and `T/N` was `0/0` (NaN) or round-off's sign and size
    /// (−9.8e15 seen): there ν is the bound `μ_st` it stayed below while rolling, the one value
    /// the rolling law gives the ratio where the contact carries no force.
    pub fn nu(self, mode: Mode, t: f64, n: f64) -> f64 {
        match mode {
            Mode::Sliding => self.mu_d,
            Mode::Rolling if n > 0.0 && (t / n).is_finite() => t / n,
            Mode::Rolling => self.mu_st,
        }
    }
}

/// Converts one simulation sample of a disk whose friction follows `law`.
pub fn convert_sample(s: &DiskSample, law: FrictionLaw) -> Sample {
    let f = &s.force;
    let friction = f.r_x.hypot(f.r_y);
    let nu = law.nu(s.mode, friction, f.normal);
    Sample {
        t: s.t,
        mode: s.mode,
        state: DiskState::from_array(&s.state.y),
        slip: Slip {
            v_c: s.state.slip.speed,
            alpha: s.state.slip.direction,
        },
        forces: ContactForces {
            normal: f.normal,
            friction,
            nu,
            r_x: f.r_x,
            r_y: f.r_y,
        },
        energy: s.energy,
    }
}

/// Converts one mode decision.
pub fn convert_event(r: &TransitionRecord) -> EventRow {
    let (trigger, value) = match r.trigger {
        Trigger::InitialFriction { ratio } => (TriggerKind::InitialFriction, ratio),
        Trigger::FrictionLimit { ratio } => (TriggerKind::FrictionLimit, ratio),
        Trigger::SlipStopped { rolling_ratio, .. } => (TriggerKind::SlipStopped, rolling_ratio),
    };
    EventRow {
        t: r.t,
        from: r.from,
        to: r.to,
        trigger,
        value,
        slip_direction: r.slip_direction,
    }
}

/// Converts the simulation's stop reason; `allowed` are the modes the run was allowed.
pub fn convert_outcome(o: &RunOutcome, allowed: AllowedModes, law: FrictionLaw) -> Outcome {
    let mut mode = o.last.mode;
    let (reason, detail) = match o.stop {
        StopReason::ModeNotAllowed { t, mode: entered } => {
            mode = entered;
            (
                "mode_not_allowed",
                format!(
                    "the disk entered {entered} at t = {} s but modes.allowed = {:?}",
                    Readable(t),
                    allowed.modes().iter().map(|m| m.name()).collect::<Vec<_>>()
                ),
            )
        }
        StopReason::Requested { t } => (
            "interrupted",
            format!("stopped on request at t = {} s", Readable(t)),
        ),
        StopReason::EndTime => ("end_time", String::new()),
        StopReason::ContactLost { t, mode } => (
            "contact_lost",
            format!("N fell through 0 at t = {} s while {mode}", Readable(t)),
        ),
        StopReason::InclinationReachedFloor { t, theta } => (
            "inclination_reached_0",
            format!("theta = {} rad at t = {} s", Readable(theta), Readable(t)),
        ),
        StopReason::Chattering {
            t,
            transitions,
            window,
        } => (
            "chattering",
            format!(
                "{transitions} transitions within {} s at t = {} s",
                Readable(window),
                Readable(t)
            ),
        ),
    };
    Outcome {
        stop: StopRecord {
            t: o.last.t,
            mode,
            reason: reason.to_string(),
            detail,
        },
        steps: o.stats.steps,
        rhs_evals: o.stats.rhs_evals,
        constraint_drift_max: o.max_drift.max_abs(),
        last: convert_sample(&o.last, law),
    }
}

/// Samples per message: the channel's cost spread over many samples.
const BATCH: usize = 256;

/// Where the simulation's stream goes: a channel to another thread, or straight into a
/// collector on this one.
pub trait Outlet {
    /// Delivers `m`; false once the receiver is gone (the run then stops).
    fn deliver(&mut self, m: Message) -> bool;
}

impl Outlet for SyncSender<Message> {
    fn deliver(&mut self, m: Message) -> bool {
        self.send(m).is_ok()
    }
}

struct ChannelObserver<'a, O> {
    tx: O,
    open: bool,
    plan: SamplePlan,
    batch: Vec<Sample>,
    /// Extrema not yet sent (they go with the next batch of samples).
    extrema: Vec<Extremum>,
    /// Flush the batch once the simulation passes this time, so progress keeps moving even
    /// where samples are sparse.
    flush_at: f64,
    flush_every: f64,
    /// States the models do not integrate: blanked in every sample.
    frozen: Vec<&'static str>,
    /// The friction law, which gives ν where the forces do not.
    law: FrictionLaw,
    stop: &'a AtomicBool,
    /// Whether this observer stopped the run (the caller's stop flag or a closed channel).
    interrupted: bool,
}

impl<O: Outlet> ChannelObserver<'_, O> {
    fn send(&mut self, m: Message) {
        if self.open && !self.tx.deliver(m) {
            self.open = false;
        }
    }

    fn flush(&mut self) {
        if !self.extrema.is_empty() {
            let extrema = std::mem::take(&mut self.extrema);
            self.send(Message::Extrema(extrema));
        }
        if !self.batch.is_empty() {
            let batch = std::mem::replace(&mut self.batch, Vec::with_capacity(BATCH));
            self.send(Message::Samples(batch));
        }
    }
}

impl<O: Outlet> DiskObserver for ChannelObserver<'_, O> {
    fn wants_sample(&self, t: f64) -> bool {
        self.plan.wants(t)
    }

    fn on_sample(&mut self, sample: &DiskSample) {
        let mut s = convert_sample(sample, self.law);
        if !self.frozen.is_empty() {
            s.forget(&self.frozen);
        }
        self.batch.push(s);
        if self.batch.len() >= BATCH || s.t >= self.flush_at {
            self.flush_at = s.t + self.flush_every;
            self.flush();
        }
    }

    fn wants_extrema(&self) -> bool {
        true
    }

    fn on_extremum(&mut self, extremum: &Extremum) {
        self.extrema.push(*extremum);
    }

    fn on_transition(&mut self, record: &TransitionRecord) {
        self.flush();
        self.send(Message::Event(convert_event(record)));
    }

    fn proceed(&mut self) -> ControlFlow<()> {
        // A closed channel: the caller has given up on this run (a write error).
        if !self.open || self.stop.load(Ordering::Relaxed) {
            self.interrupted = true;
            return ControlFlow::Break(());
        }
        ControlFlow::Continue(())
    }
}

/// The worker's task: simulate and stream what is observed.
struct Streamed<'a, 'b, O> {
    config: &'a DiskConfig,
    initial: &'a InitialState,
    observer: &'a mut ChannelObserver<'b, O>,
}

impl<O: Outlet> ModelsTask for Streamed<'_, '_, O> {
    type Output = Result<Outcome, Failure>;

    fn run<R: Model<DIM>, S: Model<DIM>>(self, models: &DiskModels<R, S>) -> Self::Output {
        simulate(models, self.config, self.initial, self.observer)
            .map(|o| convert_outcome(&o, self.config.allowed, FrictionLaw::of(&models.params)))
            .map_err(|failure| Failure {
                message: failure.to_string(),
                steps: failure.stats.steps,
                rhs_evals: failure.stats.rhs_evals,
                t: failure.error.time(),
            })
    }
}

/// The stop record of a run the caller interrupted.
fn interrupted_record(stop: &StopRecord) -> StopRecord {
    StopRecord {
        reason: "interrupted".into(),
        detail: format!("stopped by the user (Ctrl-C) at t = {} s", stop.t),
        ..stop.clone()
    }
}

/// Runs the simulation of `scene` with the models of `choice` on this thread, delivering the
/// samples `plan` keeps and the mode decisions to `outlet`; raising `stop` ends it at its next
/// step.
pub fn simulate_into<O: Outlet>(
    scene: &Scene,
    choice: &ModelChoice,
    plan: SamplePlan,
    stop: &AtomicBool,
    outlet: O,
) -> Result<Outcome, Failure> {
    let config = DiskConfig {
        sample_rate: Some(plan.fine_rate()),
        ..scene.config
    };
    let flush_every = scene.config.t_end / 200.0;
    let mut observer = ChannelObserver {
        tx: outlet,
        open: true,
        plan,
        batch: Vec::with_capacity(BATCH),
        extrema: Vec::new(),
        flush_at: flush_every,
        flush_every,
        frozen: choice.frozen.clone(),
        law: FrictionLaw::of(&scene.params),
        stop,
        interrupted: false,
    };
    let task = Streamed {
        config: &config,
        initial: &scene.initial,
        observer: &mut observer,
    };
    let result = with_models(choice.model, scene.params, scene.config.chart(), task)
        .unwrap_or_else(|e| Err(Failure::before_start(e.to_string())));
    observer.flush();
    result.map(|mut o| {
        if observer.interrupted && matches!(o.stop.reason.as_str(), "interrupted") {
            o.stop = interrupted_record(&o.stop);
        }
        o
    })
}

/// Starts [`simulate_into`] on a worker thread of `scope`, streaming through a bounded
/// channel whose receiving end is returned; the last message is [`Message::Done`].
pub fn start<'scope>(
    scope: &'scope Scope<'scope, '_>,
    scene: &'scope Scene,
    choice: &'scope ModelChoice,
    plan: SamplePlan,
    stop: &'scope AtomicBool,
) -> Receiver<Message> {
    let (tx, rx) = sync_channel(64);
    scope.spawn(move || {
        let result = simulate_into(scene, choice, plan, stop, tx.clone());
        let _ = tx.send(Message::Done(Box::new(result)));
    });
    rx
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nu_is_the_friction_laws_where_the_forces_give_none() {
        let law = FrictionLaw {
            mu_d: 0.115,
            mu_st: 0.2,
        };
        assert_eq!(law.nu(Mode::Rolling, 0.3, 2.0), 0.15);
        // The located loss of contact: 0/0, finite/round-off, a negative round-off N.
        for (t, n) in [(0.0, 0.0), (30.4, -3.1e-15), (1.0, 0.0), (0.0, -0.0)] {
            assert_eq!(law.nu(Mode::Rolling, t, n), 0.2, "{t}/{n}");
        }
        for (t, n) in [(0.0, 0.0), (0.23, 2.0), (-1.8e-16, -7.8e-16)] {
            assert_eq!(law.nu(Mode::Sliding, t, n), 0.115, "{t}/{n}");
        }
    }
}
