//! Driving a disk system in the time variable the settings choose, with the integrator they
//! choose: the one place where a run becomes a [`HybridSolver`] run, for the hand-written disk
//! ([`super::simulate`]) and the switched one ([`super::simulate_switched`]) alike.
//!
//! In physical time the system runs as it is. In regularised time it runs inside
//! [`Regularised`] (one more state, the clock), its observer behind [`PhysicalTime`], and what
//! comes back is turned into physical terms here, so that a caller sees the same outcome and
//! the same errors, dated in seconds, whichever variable the run used. The integrator's
//! stepper is made here too, for the state size of the variable in use, so a caller names a
//! method, never a stepper type.

use crate::config::DiskConfig;
use crate::modes::{SlipChart, DIM};
use crate::settings::{Integrator, TimeVariable};
use model_runtime::{
    Const, HybridError, HybridOptions, HybridOutcome, HybridSolver, InputError, LimitingComponent,
    Method, Observer, PhysicalTime, Regularised, Stats, Stepper, TimeScale, Tolerance, WithStepper,
};

/// The clocked state's dimension in regularised time.
const CLOCKED: usize = DIM + 1;

/// How a run is driven: its settings, the error norm of its states, and the grid its observer
/// is sampled on.
pub(super) struct Drive<'c> {
    /// The run's settings (integrator, time variable, span, driver options).
    pub config: &'c DiskConfig,
    /// The error norm of the disk's states (in regularised time the clock is added to it).
    pub tolerance: Tolerance<Const<DIM>>,
    /// Samples for the observer at `t0 + k / rate` in physical time (`None`: none).
    pub sample_rate: Option<f64>,
}

/// Where a driven run starts: time, mode and state.
pub(super) struct Start<Md> {
    /// Physical time (s).
    pub t: f64,
    /// The first mode.
    pub mode: Md,
    /// The disk's state.
    pub y: [f64; DIM],
}

/// A driven run that failed: why, in physical time, and the work until then.
pub(super) struct Failed<Md> {
    /// What went wrong (dated in seconds).
    pub error: HybridError<Md>,
    /// The driver's work until the failure (boxed: the counters are large, a failure rare).
    pub stats: Box<Stats>,
}

/// What a driven run gives: its end in physical terms (in `N` states: the disk's, or the
/// clocked ones inside this module), or its failure.
pub(super) type Driven<Md, U, const N: usize = DIM> =
    Result<HybridOutcome<Const<N>, Md, U>, Failed<Md>>;

/// Runs `system` from `start` under `drive`, in the configured time variable, handing its output
/// to `observer` in physical time. `modes` lists every mode the run may enter.
pub(super) fn drive<H, O>(
    drive: Drive<'_>,
    system: &mut H,
    modes: &[H::Mode],
    start: Start<H::Mode>,
    observer: &mut O,
) -> Driven<H::Mode, H::Stop>
where
    H: TimeScale<DIM>,
    H::Guard: Copy,
    O: Observer<Const<DIM>, H::Mode, H::Guard, H::Note>,
{
    let method = method(drive.config.integrator);
    match drive.config.time {
        TimeVariable::Physical => method.with_stepper(
            Const,
            InPhysicalTime {
                drive,
                system,
                start,
                observer,
            },
        ),
        TimeVariable::Regularised => method.with_stepper(
            Const,
            InRegularisedTime {
                drive,
                system,
                modes,
                start,
                observer,
            },
        ),
    }
}

/// The runtime's method for the settings' integrator.
fn method(integrator: Integrator) -> Method {
    match integrator {
        Integrator::Dopri5 => Method::Dopri5,
        Integrator::Dop853 => Method::Dop853,
        Integrator::Rodas4 => Method::Rodas4,
        Integrator::Rk4 { h } => Method::Rk4 { h },
    }
}

/// The driver's options for a run under `config` (a backstop for chattering; the disk's own
/// limit fires first), sampling at `sample_rate` in the driver's variable.
fn options(config: &DiskConfig, sample_rate: Option<f64>) -> HybridOptions {
    HybridOptions {
        step: model_runtime::StepOptions {
            max_steps: config.max_steps,
            control: config.step_control,
            ..model_runtime::StepOptions::default()
        },
        // The disk counts its own decisions (each may take three driver transitions through
        // bridges) and stops with a named reason before this fires.
        chatter: model_runtime::ChatterLimit {
            max_transitions: 3 * config.chatter.max_transitions + 3,
            window: config.chatter.window,
        },
        sample_rate,
        guard_checks: config.guard_checks,
    }
}

/// One run of the driver: `system` from `t` and `y` in `mode` until `t_end` (in the driver's
/// variable), with `stepper` and `tolerance`; a failure keeps the work done.
fn run_driver<H, O, S, const N: usize>(
    stepper: S,
    tolerance: Tolerance<Const<N>>,
    options: HybridOptions,
    system: &mut H,
    (t, mode, y): (f64, H::Mode, &[f64; N]),
    t_end: f64,
    observer: &mut O,
) -> Driven<H::Mode, H::Stop, N>
where
    H: model_runtime::HybridSystem<Const<N>>,
    O: Observer<Const<N>, H::Mode, H::Guard, H::Note>,
    S: Stepper<Const<N>>,
{
    let mut solver = HybridSolver::new(stepper, tolerance, options).map_err(|error| Failed {
        error: HybridError::Solve {
            mode,
            error: error.into(),
        },
        stats: Box::default(),
    })?;
    let out = solver.run(system, mode, t, y, t_end, observer);
    out.map_err(|error| Failed {
        error,
        stats: Box::new(solver.stats()),
    })
}

/// A run in physical time, waiting for its stepper.
struct InPhysicalTime<'a, 'c, H: TimeScale<DIM>, O> {
    drive: Drive<'c>,
    system: &'a mut H,
    start: Start<H::Mode>,
    observer: &'a mut O,
}

impl<H, O> WithStepper<Const<DIM>> for InPhysicalTime<'_, '_, H, O>
where
    H: TimeScale<DIM>,
    O: Observer<Const<DIM>, H::Mode, H::Guard, H::Note>,
{
    type Output = Driven<H::Mode, H::Stop>;

    fn run<S: Stepper<Const<DIM>>>(self, stepper: S) -> Self::Output {
        let Drive {
            config,
            tolerance,
            sample_rate,
        } = self.drive;
        let start = (self.start.t, self.start.mode, &self.start.y);
        let options = options(config, sample_rate);
        let t_end = config.t_end;
        run_driver(
            stepper,
            tolerance,
            options,
            self.system,
            start,
            t_end,
            self.observer,
        )
    }
}

/// A run in regularised time, waiting for its stepper.
struct InRegularisedTime<'a, 'c, H: TimeScale<DIM>, O> {
    drive: Drive<'c>,
    system: &'a mut H,
    modes: &'a [H::Mode],
    start: Start<H::Mode>,
    observer: &'a mut O,
}

impl<H, O> WithStepper<Const<CLOCKED>> for InRegularisedTime<'_, '_, H, O>
where
    H: TimeScale<DIM>,
    H::Guard: Copy,
    O: Observer<Const<DIM>, H::Mode, H::Guard, H::Note>,
{
    type Output = Driven<H::Mode, H::Stop>;

    fn run<S: Stepper<Const<CLOCKED>>>(self, stepper: S) -> Self::Output {
        let (config, t0) = (self.drive.config, self.start.t);
        let mut clocked =
            Regularised::<_, DIM, CLOCKED>::new(self.system, self.modes, t0, config.t_end);
        // The clock is held to the states' tolerances (in seconds): the same cost per step
        // and, on the paper's scene, the same phase accuracy as a run in physical time. A
        // clock held 1000 times tighter makes the transition times 400 times more accurate
        // for 1.4 times the work (BENCHMARKS.md §3).
        let tolerance = clocked.tolerance(&self.drive.tolerance, (config.rtol, config.atol));
        // The driver's own grid would be in τ: the samples come from the observer's side, in t.
        let options = options(config, None);
        let rate = self.drive.sample_rate;
        let mut physical = PhysicalTime::<_, DIM, CLOCKED>::new(self.observer, t0, rate);
        let z0 = Regularised::<H, DIM, CLOCKED>::start(&self.start.y);
        let start = (t0, self.start.mode, &z0);
        let out = run_driver(
            stepper,
            tolerance,
            options,
            &mut clocked,
            start,
            f64::MAX,
            &mut physical,
        );
        match out {
            Ok(out) => Ok(clocked.physical_outcome(out)),
            Err(Failed { error, stats }) => Err(Failed {
                error: clocked.physical_error(error),
                stats,
            }),
        }
    }
}

impl DiskConfig {
    /// The error norm of a run sliding in `chart`: the tolerances, the vector groups of
    /// [`DiskConfig::error_norm`], and whether the limiting component is counted.
    pub fn tolerance(&self, chart: SlipChart) -> Result<Tolerance<Const<DIM>>, InputError> {
        let tol = self
            .error_norm
            .groups(chart)
            .iter()
            .try_fold(Tolerance::scalar(self.rtol, self.atol), |tol, g| {
                tol.with_group(g.clone())
            })?;
        Ok(match self.limiting_component {
            LimitingComponent::Untracked => tol,
            LimitingComponent::Tracked => tol.tracking_limiting(),
        })
    }
}
