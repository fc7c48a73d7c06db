//! Runs at the edges of the model: hand-made states, settings, and a streaming observer that
//! watches every step for what must never happen (a non-finite number) and keeps only summaries
//! of what may (constraint drift, energy change, the range of θ), so that long runs stay flat in
//! memory.

use equations::layout::{OMEGA_X, OMEGA_Y, OMEGA_Z, PSI, THETA};
use equations::DiskParams;
use equations::{DiskConfig, Integrator, RunTable, SolverTable, TimeVariable};
use equations::{DiskObserver, DiskRecorder, DiskSample, GeneratedModels, TransitionRecord};
use equations::{Mode, PhysicalState, SlipChart, DIM};

/// The generated models in the given slip chart.
pub fn models_in(params: DiskParams, chart: SlipChart) -> GeneratedModels {
    GeneratedModels::generated(params, chart).expect("valid parameters")
}

/// The generated models in the Cartesian slip chart (the default of the CLI).
pub fn models(params: DiskParams) -> GeneratedModels {
    models_in(params, SlipChart::Cartesian)
}

/// Angular velocity in the moving frame `(Ω_x, Ω_y, Ω_z)` (rad/s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rates {
    /// About the diameter through the contact point.
    pub x: f64,
    /// About the horizontal diameter (`θ̇`).
    pub y: f64,
    /// About the normal (spin).
    pub z: f64,
}

impl Rates {
    /// At rest.
    pub const ZERO: Rates = Rates {
        x: 0.0,
        y: 0.0,
        z: 0.0,
    };
}

/// A rolling-consistent state at the origin from `ψ`, `θ` and the body rates.
pub fn rolling_state(p: &DiskParams, psi: f64, theta: f64, w: Rates) -> [f64; DIM] {
    let mut y = [0.0; DIM];
    y[PSI] = psi;
    y[THETA] = theta;
    y[OMEGA_X] = w.x;
    y[OMEGA_Y] = w.y;
    y[OMEGA_Z] = w.z;
    let mut s = PhysicalState::from_rolling(&y, 0.0);
    s.project(p, Mode::Rolling);
    s.y
}

/// DOP853 in physical time at the given tolerances (`atol = rtol / 100`) up to `t_end`, the
/// rest as a scene sets it (the stick threshold follows atol), without samples.
pub fn dop853(rtol: f64, t_end: f64) -> DiskConfig {
    let solver = SolverTable {
        integrator: Integrator::Dop853,
        rtol,
        atol: rtol * 1e-2,
        time: TimeVariable::Physical,
        ..SolverTable::default()
    };
    DiskConfig {
        sample_rate: None,
        ..DiskConfig::new(&solver, &RunTable::lasting(t_end))
    }
}

/// Whether every number of a sample is finite.
pub fn all_finite(s: &DiskSample) -> bool {
    let r = &s.residuals;
    s.t.is_finite()
        && s.state.y.iter().all(|v| v.is_finite())
        && s.state.slip.speed.is_finite()
        && s.state.slip.direction.is_finite()
        && [s.force.r_x, s.force.r_y, s.force.normal, s.energy]
            .iter()
            .all(|v| v.is_finite())
        && [r.height, r.vertical_speed, r.no_slip]
            .iter()
            .all(|v| v.is_finite())
}

/// Summaries of a run, updated at every accepted step and sample; optionally keeps everything.
#[derive(Clone, Debug)]
pub struct Watch {
    /// Step ends and samples seen.
    pub seen: u64,
    /// Energy of the first state seen (J).
    pub first_energy: Option<f64>,
    /// Largest `|E − E0| / E0` seen in rolling while no transition has happened yet.
    pub rolling_energy_drift: f64,
    /// Largest constraint drift seen (m or m/s), before any projection.
    pub max_drift: f64,
    /// Smallest and largest θ seen (rad).
    pub theta_range: (f64, f64),
    /// The first sample with a non-finite number.
    pub first_non_finite: Option<DiskSample>,
    /// Mode decisions seen.
    pub transitions: u64,
    /// Everything, when asked for (short runs only).
    pub kept: Option<DiskRecorder>,
    /// Also keep the step ends (not only the samples).
    pub keep_steps: bool,
}

impl Watch {
    /// A watch that keeps nothing but its summaries.
    pub fn streaming() -> Self {
        Watch {
            seen: 0,
            first_energy: None,
            rolling_energy_drift: 0.0,
            max_drift: 0.0,
            theta_range: (f64::INFINITY, f64::NEG_INFINITY),
            first_non_finite: None,
            transitions: 0,
            kept: None,
            keep_steps: false,
        }
    }

    /// A watch that also keeps the samples and transitions.
    pub fn keeping() -> Self {
        Watch {
            kept: Some(DiskRecorder::default()),
            ..Watch::streaming()
        }
    }

    /// A watch that keeps the samples, the step ends (in order, among the samples) and the
    /// transitions.
    pub fn keeping_steps() -> Self {
        Watch {
            keep_steps: true,
            ..Watch::keeping()
        }
    }

    /// The kept samples (empty unless kept).
    pub fn samples(&self) -> &[DiskSample] {
        self.kept.as_ref().map_or(&[], |k| &k.samples)
    }

    /// The kept transitions (empty unless kept).
    pub fn transition_records(&self) -> &[TransitionRecord] {
        self.kept.as_ref().map_or(&[], |k| &k.transitions)
    }

    /// Panics with the offending sample if any number was not finite.
    pub fn assert_finite(&self, label: &str) {
        assert!(
            self.first_non_finite.is_none(),
            "{label}: non-finite sample {:?}",
            self.first_non_finite
        );
        assert!(self.seen > 0, "{label}: nothing observed");
    }

    fn observe(&mut self, s: &DiskSample) {
        self.seen += 1;
        if !all_finite(s) {
            self.first_non_finite.get_or_insert(*s);
            return;
        }
        let e0 = *self.first_energy.get_or_insert(s.energy);
        if s.mode == Mode::Rolling && self.transitions == 0 {
            let drift = (s.energy - e0).abs() / e0.abs();
            self.rolling_energy_drift = self.rolling_energy_drift.max(drift);
        }
        self.max_drift = self.max_drift.max(s.residuals.max_abs());
        let theta = s.state.y[THETA];
        self.theta_range = (self.theta_range.0.min(theta), self.theta_range.1.max(theta));
    }
}

impl DiskObserver for Watch {
    fn on_sample(&mut self, sample: &DiskSample) {
        self.observe(sample);
        if let Some(k) = &mut self.kept {
            k.samples.push(*sample);
        }
    }
    fn wants_steps(&self) -> bool {
        true
    }
    fn on_step(&mut self, sample: &DiskSample) {
        self.observe(sample);
        if let (true, Some(k)) = (self.keep_steps, &mut self.kept) {
            k.samples.push(*sample);
        }
    }
    fn on_transition(&mut self, record: &TransitionRecord) {
        self.transitions += 1;
        if let Some(k) = &mut self.kept {
            k.transitions.push(*record);
        }
    }
}

/// A bound on what the integration error can do to a quantity that the exact solution keeps
/// fixed: the drift of the constraints imposed only in differential form (m or m/s) and the
/// relative change of the energy in pure rolling (docs/physics.md §8). Every accepted step adds
/// a local error of at most `atol + rtol |y|` per component; the drift indicators combine a
/// few components of size ≤ 1 (SI units, for these disks), the energy is quadratic in the
/// rates (a factor 2 on their relative error), and errors add up at worst linearly over the
/// steps: `2 (atol + rtol) · steps`. The methods' error estimates are of their lower-order
/// solutions, so what is measured is usually orders of magnitude below.
pub fn accumulated_error_bound(config: &DiskConfig, steps: u64) -> f64 {
    2.0 * (config.atol + config.rtol) * steps as f64
}
