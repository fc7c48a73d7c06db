//! The settings of one run in the form the run uses: the scene's solver and run tables plus
//! what follows from them (the stick threshold, the chattering window), checked by one set
//! of rules.
//!
//! A scene is resolved into a [`DiskConfig`]; a program may also build one directly. Either
//! way [`DiskConfig::issues`] is the check, and [`crate::simulate`] applies it too, so a
//! setting means the same and is refused for the same reason whoever gives it. The keys of
//! the issues are the scene's (`solver.rtol`); the derived settings a scene cannot write are
//! named by their field (`stick_threshold`).

use crate::issue::{Checks, Issue, Rule};
use crate::modes::{Mode, SlipChart};
use crate::settings::{
    ChatterLimit, ErrorNorm, Integrator, RunTable, SlipSign, SolverTable, TimeVariable,
};
use crate::work::{WorkBound, WORK_BOUND_KEY};
use model_runtime::{InteriorChecks, LimitingComponent, StepControl};
use std::f64::consts::FRAC_PI_2;

/// Smallest relative tolerance accepted: below it the error target is below round-off.
pub const RTOL_MIN: f64 = 1e-14;
/// Largest relative tolerance accepted.
pub const RTOL_MAX: f64 = 1.0;
/// Largest absolute tolerance accepted (SI units).
pub const ATOL_MAX: f64 = 1.0;
/// The most samples a run may deliver to its observer (about a day of a fast observer's
/// time): finite is not enough, 1e300 samples per second would never finish.
pub const MAX_DELIVERED_SAMPLES: f64 = 1e9;

/// The modes a run may enter (the scene's `modes.allowed`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AllowedModes {
    /// Rolling may be entered.
    pub rolling: bool,
    /// Sliding may be entered.
    pub sliding: bool,
}

impl AllowedModes {
    /// Both modes.
    pub const ALL: AllowedModes = AllowedModes {
        rolling: true,
        sliding: true,
    };

    /// The modes listed in `modes`.
    pub fn of(modes: &[Mode]) -> Self {
        AllowedModes {
            rolling: modes.contains(&Mode::Rolling),
            sliding: modes.contains(&Mode::Sliding),
        }
    }

    /// Whether `mode` may be entered.
    pub fn allows(self, mode: Mode) -> bool {
        match mode {
            Mode::Rolling => self.rolling,
            Mode::Sliding => self.sliding,
        }
    }

    /// The allowed modes, rolling first.
    pub fn modes(self) -> Vec<Mode> {
        [Mode::Rolling, Mode::Sliding]
            .into_iter()
            .filter(|m| self.allows(*m))
            .collect()
    }
}

impl Default for AllowedModes {
    fn default() -> Self {
        AllowedModes::ALL
    }
}

/// Everything a run needs besides the models and the initial state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiskConfig {
    /// The integrator.
    pub integrator: Integrator,
    /// Relative tolerance (every component).
    pub rtol: f64,
    /// Absolute tolerance (every component, in its own unit).
    pub atol: f64,
    /// Whether the error of a vector is measured against its own components or its length.
    pub error_norm: ErrorNorm,
    /// How the step size follows the error estimates (adaptive methods).
    pub step_control: StepControl,
    /// Whether the run counts, for every accepted step, the state component with the largest
    /// scaled error (the one that limited the step) in `RunOutcome::stats.limiting`.
    /// A diagnostic: tracking costs a search over the components per step.
    pub limiting_component: LimitingComponent,
    /// End time (s).
    pub t_end: f64,
    /// Reading of the slip speed's sign.
    pub slip_sign: SlipSign,
    /// Slip speed δ (m/s) at which the end of sliding is detected; the remaining approach to
    /// zero is bridged exactly, so δ does not move the events (tested: 1e-9 and 1e-10 give the
    /// same times to < 1e-9 s). Must lie well above the integration error of the slip (a few
    /// `atol`) and far below the slip speeds of interest; sliding starts at `2δ`.
    pub stick_threshold: f64,
    /// The run stops when the disk comes this close to lying flat (rad): when θ falls to it,
    /// or, for a disk leaning past upright, when π − θ does. Positive: both models are singular
    /// at sin θ = 0, and the event's state must still be one they can evaluate.
    pub min_inclination: f64,
    /// Project onto the contact constraints after every accepted step (always at switches).
    pub project_each_step: bool,
    /// Samples per second delivered to the observer; `None` for none.
    pub sample_rate: Option<f64>,
    /// Interior points of each step where the guards are checked too. A friction ratio can
    /// rise through `μ_st` and fall back within one step near a peak of `N`; checked at the
    /// step ends only, the paper run finds 6085 transitions; with 4 exact interior checks
    /// 6585; screening 64 interior points on the dense output (no model evaluation unless an
    /// estimate shows a crossing, and only 2 estimates in a step whose guards stay clear of
    /// zero) finds 7435, and 128 or 256 points find the same (7438, 7437) — the default, at
    /// about 15% more time than no checks (BENCHMARKS.md, "Guard checks").
    pub guard_checks: InteriorChecks,
    /// Chattering detection.
    pub chatter: ChatterLimit,
    /// Budget of step attempts for the whole run.
    pub max_steps: u64,
    /// Accepted steps allowed per simulated second (the scene's `solver.max_steps_per_s`).
    pub work: WorkBound,
    /// The time variable the integrator steps in (adaptive integrators only).
    pub time: TimeVariable,
    /// The modes the disk may enter: a decision for another one ends the run with
    /// [`crate::StopReason::ModeNotAllowed`].
    pub allowed: AllowedModes,
}

impl DiskConfig {
    /// The run a scene's `[solver]` and `[run]` tables describe, delivering samples at the
    /// scene's rate, every mode allowed. The stick threshold sits above the slip's integration
    /// error, `max(10 atol, 1e-9 m/s)` (BENCHMARKS.md §2: with 1e-9 m/s at atol 1e-8 the slip
    /// hovers near zero and the step size collapses); chattering is 50 decisions within 1 µs.
    pub fn new(solver: &SolverTable, run: &RunTable) -> Self {
        DiskConfig {
            integrator: solver.integrator,
            rtol: solver.rtol,
            atol: solver.atol,
            error_norm: solver.error_norm,
            step_control: solver.step_control,
            limiting_component: LimitingComponent::Untracked,
            t_end: run.t_end,
            slip_sign: run.slip_sign,
            stick_threshold: (10.0 * solver.atol).max(1e-9),
            min_inclination: 1e-9,
            project_each_step: false,
            sample_rate: Some(run.sample_rate),
            guard_checks: solver.guard_checks,
            chatter: ChatterLimit {
                max_transitions: 50,
                window: 1e-6,
            },
            max_steps: 500_000_000,
            work: WorkBound {
                steps_per_s: solver.max_steps_per_s,
            },
            time: solver.time,
            allowed: AllowedModes::ALL,
        }
    }

    /// The paper's settings: DP5 (its `ode45`) in physical time, otherwise as
    /// [`DiskConfig::default`].
    pub fn paper() -> Self {
        DiskConfig {
            integrator: Integrator::Dopri5,
            time: TimeVariable::Physical,
            ..DiskConfig::default()
        }
    }

    /// The slip chart a run under these settings slides in ([`SlipSign::chart`]).
    pub fn chart(&self) -> SlipChart {
        self.slip_sign.chart()
    }

    /// Every rule these settings break for a run starting at `t0` whose sliding model uses
    /// `chart`, each with the key it is about; empty when they are usable.
    pub fn issues(&self, t0: f64, chart: SlipChart) -> Vec<Issue> {
        let mut c = Checks::default();
        c.in_range("solver.rtol", self.rtol, RTOL_MIN, RTOL_MAX, false);
        let atol_ok = c.positive("solver.atol", self.atol);
        if atol_ok && self.atol > ATOL_MAX {
            c.in_range("solver.atol", self.atol, 0.0, ATOL_MAX, false);
        }
        if let Integrator::Rk4 { h } = self.integrator {
            if c.positive("solver.integrator", h) && self.time == TimeVariable::Regularised {
                c.push(
                    "solver.time",
                    Rule::Incompatible {
                        value: self.time.to_string(),
                        reason: "cannot be followed by a fixed step: choose an adaptive integrator",
                    },
                );
            }
        }
        if c.positive("stick_threshold", self.stick_threshold)
            && atol_ok
            && self.stick_threshold < self.atol
        {
            // The slip's own error is about atol: a lower threshold is crossed by noise or,
            // more often, never (the run then slides past every stick, silently wrong).
            c.push(
                "stick_threshold",
                Rule::BelowOther {
                    value: self.stick_threshold,
                    other: "solver.atol",
                    other_value: self.atol,
                },
            );
        }
        let points = self.guard_checks.points();
        if points > InteriorChecks::MAX_POINTS {
            // The guard-check limit (a scene's spelling refuses it already when read).
            c.in_range(
                "solver.guard_checks",
                f64::from(points),
                0.0,
                f64::from(InteriorChecks::MAX_POINTS),
                false,
            );
        }
        c.positive(WORK_BOUND_KEY, self.work.steps_per_s);
        c.positive("chatter.window", self.chatter.window);
        if self.chatter.max_transitions == 0 {
            c.push("chatter.max_transitions", Rule::NotPositive { value: 0.0 });
        }
        // The models are singular at sin(theta) = 0.
        c.in_range(
            "min_inclination",
            self.min_inclination,
            0.0,
            FRAC_PI_2,
            true,
        );
        let span = self.t_end - t0;
        let t_end_ok = if t0 == 0.0 {
            c.positive("run.t_end", self.t_end)
        } else {
            c.finite("run.t_end", self.t_end)
                && c.in_range("run.t_end", self.t_end, t0, f64::INFINITY, true)
        };
        if let Some(rate) = self.sample_rate {
            let samples = rate * span;
            if c.positive("run.sample_rate", rate) && t_end_ok && samples > MAX_DELIVERED_SAMPLES {
                c.push(
                    "run.sample_rate",
                    Rule::TooManySamples {
                        samples,
                        limit: MAX_DELIVERED_SAMPLES,
                        t_end: span,
                        sample_rate: rate,
                    },
                );
            }
        }
        if self.slip_sign == SlipSign::Paper && chart != SlipChart::Polar {
            c.push(
                "run.slip_sign",
                Rule::Incompatible {
                    value: "paper".into(),
                    reason: "needs the polar slip chart (the sliding model's signed slip speed)",
                },
            );
        }
        c.issues
    }
}

impl Default for DiskConfig {
    /// The recommended settings of [`SolverTable::default`] over the paper's 100 s, without
    /// samples.
    fn default() -> Self {
        DiskConfig {
            sample_rate: None,
            ..DiskConfig::new(&SolverTable::default(), &RunTable::lasting(100.0))
        }
    }
}
