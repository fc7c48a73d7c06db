//! The disk's contact switching said in the DSL: rolling, sliding, the two bridges between
//! them and the stops, as one switched model (docs/physics.md §7), beside the hand-written
//! system it is held to.
//!
//! Rolling is Box 1 and sliding Box 3 in the Cartesian slip chart: the modes include the rows
//! the smooth models of `crate::models` include (`models/box1_rolling.dsl`,
//! `models/box3_sliding.dsl`), with the air's terms zero at compile time; the guards, clocks and first steps are those of the hand-written system
//! (module `system`), written as expressions. Sliding carries
//! the slip `(u_X, u_Y)` in the slots where rolling carries the centre's velocity
//! `(V_X, V_Y)` (`states { u_X, u_Y } replace { V_X, V_Y }`), so the error norm sees what it
//! sees in the hand-written run. The bridges are modes whose right-hand side is a constant
//! derivative held in discrete values (`b_*`) until a held end time; the maps that no
//! expression gives (the onset direction is a search, sticking is a decision of the rolling
//! equations) are the hand-written ones, called as Rust functions: each builds the
//! hand-written system at the event and asks it (`DiskSystem::on_event`), so both runs make
//! every decision by the same code.
//!
//! The model is the disk in still air (`mu_a = w_z = 0`, the default scenes): with the air
//! on, its terms would be paid for in every guard evaluation of a run in still air, and a
//! switched model cannot have variants yet that fix them. What the DSL cannot say yet, the
//! hand-written system still does alone: the air, the polar slip chart and the paper's slip
//! sign, the pruned variants, projection after steps, and the decision records (`TransitionRecord`) with their triggers (model-macros/DSL.md, "What the
//! disk still needs").

use super::system::{AfterBridge, BridgePlan, DiskGuard, DiskSystem, Phase};
use super::GeneratedModels;
use crate::config::DiskConfig;
use crate::modes::{SlipChart, DIM};
use crate::params::DiskParams;
use model_runtime::{Crossed, EvalError, EventHit, HybridSystem, Transition};

model_macros::model! {
    /// Euler's disk rolling and sliding on a rough plane, with the paper's transition rules.
    pub mod disk {
        params {
            m = 0.4387, a = 0.03755, g = 9.81, mu_d = 0.115, mu_st = 0.2,
            /// The stick threshold δ (m/s): sliding ends when the slip speed falls below it.
            delta = 1e-9,
            /// The lowest inclination (rad) from either face before the run stops.
            theta_min = 1e-9,
            /// The inclination scale of the regularised clock (rad).
            theta_s = 0.1,
            /// The slip scale of the regularised clock (m/s).
            u_s = 1e-3,
        }
        states { X, Y, Z, V_X, V_Y, V_Z, psi, theta, phi, Omega_x, Omega_y, Omega_z }
        discrete {
            /// When the bridge in force ends (s).
            t_end = 0.0,
            b_X = 0.0, b_Y = 0.0, b_Z = 0.0, b_u_X = 0.0, b_u_Y = 0.0, b_V_Z = 0.0,
            b_psi = 0.0, b_theta = 0.0, b_phi = 0.0,
            b_Omega_x = 0.0, b_Omega_y = 0.0, b_Omega_z = 0.0,
            /// The slip sliding starts with after a bridge from zero slip: speed and direction.
            slip_speed = 0.0, slip_direction = 0.0,
        }

        let A = m*a^2/4;
        let C = m*a^2/2;
        // Still air: the boxes' air terms vanish at compile time (`k_F`, `k_M` and the air's
        // velocity `w_z` are zero), as in the pruned variants of the smooth models.
        let k_F = 0;
        let k_M = 0;
        let w_z = 0;
        // The distance from lying flat on either face.
        let lying = min(theta, pi - theta);

        /// Rolling without slipping (Box 1).
        mode rolling {
            include "../models/box1_rolling.dsl";
            time_scale = lying/(lying + theta_s);
            /// Rolling would need more friction than static friction gives: the slip starts in
            /// the consistent direction, across a bridge (or at once), or the run stops.
            when slips: sqrt((m*der(V_X) + k_F*(v_z - w_z)*sin(theta)*cos(psi))^2
                    + (m*der(V_Y) + k_F*(v_z - w_z)*sin(theta)*sin(psi))^2)
                > mu_st*(m*(der(V_Z) + g) + k_F*(v_z - w_z)*cos(theta))
                -> starting | sliding | stop by slip_onset;
            /// The floor would have to pull.
            when lifts_off: m*(der(V_Z) + g) + k_F*(v_z - w_z)*cos(theta) < 0 -> stop;
            /// The disk lies flat.
            when lies_flat: lying < theta_min -> stop;
        }

        /// Sliding (Box 3, the Cartesian slip chart).
        mode sliding {
            states { u_X, u_Y } replace { V_X, V_Y }
            let v_C = sqrt(u_X^2 + u_Y^2);
            let alpha = atan2(-u_Y, -u_X);
            include "../models/box3_sliding.dsl";
            time_scale = lying/(lying + theta_s)*v_C/(v_C + u_s);
            /// Starting near the stick threshold the slip is stiff: the first step is a fraction
            /// of its doubling time (none further away).
            first_step = if(v_C > 4*delta, 0, 3*v_C/sqrt(der(u_X)^2 + der(u_Y)^2));
            /// The slip falls to the stick threshold: a bridge carries it to its exact zero,
            /// where the rolling equations decide (at once when the bridge would be degenerate).
            when sticks: v_C < delta -> stopping | rolling | starting | sliding | stop by slip_stops;
            /// The floor would have to pull.
            when lifts_off: m*(der(V_Z) + g) + k_F*(v_z - w_z)*cos(theta) < 0 -> stop;
            /// The disk lies flat.
            when lies_flat: lying < theta_min -> stop;
        }

        /// The bridge from zero slip to twice the stick threshold: a straight line.
        mode starting {
            states { u_X, u_Y } replace { V_X, V_Y }
            equations {
                der(X) = b_X; der(Y) = b_Y; der(Z) = b_Z; der(u_X) = b_u_X; der(u_Y) = b_u_Y;
                der(V_Z) = b_V_Z; der(psi) = b_psi; der(theta) = b_theta; der(phi) = b_phi;
                der(Omega_x) = b_Omega_x; der(Omega_y) = b_Omega_y; der(Omega_z) = b_Omega_z;
            }
            time_scale = 1;
            first_step = 2*(t_end - t);
            /// The bridge ends: sliding proper starts with the planned slip.
            when slides: t > t_end -> sliding by start_sliding;
        }

        /// The bridge from the stick threshold to the slip's exact zero: the same straight
        /// line, ending in a decision.
        mode stopping like starting {
            /// The slip is zero: roll if static friction can hold, else slide on.
            when halts: t > t_end -> rolling | starting | sliding | stop by stick_or_slide;
        }
    }
}

/// What an event's Rust function writes: the states, then the discrete values.
type Values = [f64; disk::N_VALUES];

/// The first discrete value: the discrete values' indices in [`Values`] (after the states)
/// are theirs in the model's parameters less this.
const FIRST: usize = disk::N_PARAMS - disk::N_DISCRETE;
/// Where a bridge plan's slope starts among the discrete values (one per state).
const SLOPE: usize = disk::discrete::b_X - FIRST;
/// A discrete value's place among the discrete values.
const fn slot(index: usize) -> usize {
    index - FIRST
}

impl disk::Model {
    /// The switched disk for `params` and the run settings of `config` (the stick threshold
    /// and the inclination floor; the clock's scales are the hand-written run's).
    pub fn for_run(params: &DiskParams, config: &DiskConfig) -> Self {
        let mut values = disk::Params::default().to_array();
        values[..5].copy_from_slice(&params.to_array()[..5]);
        values[disk::param::delta] = config.stick_threshold;
        values[disk::param::theta_min] = config.min_inclination;
        values[disk::param::theta_s] = crate::settings::TimeVariable::THETA_SCALE;
        values[disk::param::u_s] = crate::settings::TimeVariable::SLIP_SCALE;
        disk::Model::new(values)
    }

    /// The disk's parameters (the first seven of the model's).
    pub fn disk_params(&self) -> DiskParams {
        let p = &self.params;
        DiskParams {
            m: p[disk::param::m],
            a: p[disk::param::a],
            g: p[disk::param::g],
            mu_d: p[disk::param::mu_d],
            mu_st: p[disk::param::mu_st],
            mu_a: 0.0,
            w_z: 0.0,
        }
    }

    /// Holds a bridge `plan`: its end, its slope and the slip sliding starts with after it;
    /// returns the bridge mode it drives.
    pub(crate) fn hold(&mut self, plan: &BridgePlan) -> usize {
        let n = disk::N_PARAMS - disk::N_DISCRETE;
        write_plan(plan, &mut self.params[n..])
    }
}

/// Writes `plan` into the discrete values `held` and returns the bridge mode it drives.
fn write_plan(plan: &BridgePlan, held: &mut [f64]) -> usize {
    held[slot(disk::discrete::t_end)] = plan.t_end;
    held[SLOPE..SLOPE + DIM].copy_from_slice(&plan.slope);
    match plan.then {
        AfterBridge::StartSliding { slip } => {
            held[slot(disk::discrete::slip_speed)] = slip.speed;
            held[slot(disk::discrete::slip_direction)] = slip.direction;
            disk::mode::starting
        }
        AfterBridge::StickDecision => disk::mode::stopping,
    }
}

/// The bridge plan held in `values` (after the states), ending as `then` says.
fn read_plan(values: &Values, then: AfterBridge) -> BridgePlan {
    let held = &values[DIM..];
    let mut slope = [0.0; DIM];
    slope.copy_from_slice(&held[SLOPE..SLOPE + DIM]);
    BridgePlan {
        t_end: held[slot(disk::discrete::t_end)],
        slope,
        then,
    }
}

/// The hand-written transition map of `guard` in `phase` at the event `(t, y, dy)`: the next
/// state and discrete values into `new`, and the mode the run goes on in (`None`: it stops).
#[allow(clippy::too_many_arguments)] // The event as the model hands it over, and the map.
fn transition(
    model: &disk::Model,
    phase: Phase,
    guard: DiskGuard,
    then: Option<AfterBridge>,
    t: f64,
    y: &[f64; DIM],
    dy: &[f64; DIM],
    new: &mut Values,
) -> Result<Option<usize>, EvalError> {
    let params = model.disk_params();
    let models = GeneratedModels::generated(params, SlipChart::Cartesian).map_err(|_| {
        EvalError::NonFinite {
            model: "disk".into(),
            quantity: "a disk parameter (not finite and positive)".into(),
            value: f64::NAN,
        }
    })?;
    let config = DiskConfig {
        stick_threshold: model.params[disk::param::delta],
        min_inclination: model.params[disk::param::theta_min],
        ..DiskConfig::default()
    };
    let mut system = DiskSystem::new(&models, &config);
    if let Some(then) = then {
        system.bridge = read_plan(new, then);
    }
    let hit = EventHit {
        guard,
        index: 0,
        t,
        before: t,
        y: *y,
        dy: *dy,
        value: 0.0,
        direction: Crossed::Up,
    };
    match system.on_event(phase, &hit)? {
        Transition::Switch { to, y, .. } => {
            new[..DIM].copy_from_slice(y.as_ref());
            Ok(Some(match to {
                Phase::Rolling => disk::mode::rolling,
                Phase::Sliding => disk::mode::sliding,
                Phase::Bridge => write_plan(&system.bridge, &mut new[DIM..]),
            }))
        }
        Transition::Stop(_) => Ok(None),
        // The disk's maps always switch or stop.
        Transition::Continue { .. } | Transition::Pass { .. } => Err(EvalError::Undecided {
            event: format!("{guard:?}"),
            mode: None,
        }),
    }
}

/// A Rust function of the disk's events that asks the hand-written map of one guard: the
/// three decisions differ only in which.
macro_rules! decision {
    ($(#[$doc:meta])* $name:ident = $phase:expr, $guard:expr, $then:expr) => {
        $(#[$doc])*
        pub(crate) fn $name(
            model: &disk::Model,
            t: f64,
            y: &[f64; DIM],
            dy: &[f64; DIM],
            new: &mut Values,
        ) -> Result<Option<usize>, EvalError> {
            transition(model, $phase, $guard, $then, t, y, dy, new)
        }
    };
}

decision!(
    /// `rolling.slips`: the onset of sliding (the consistent direction, then a bridge).
    slip_onset = Phase::Rolling, DiskGuard::FrictionLimit, None
);
decision!(
    /// `sliding.sticks`: the bridge to the slip's zero (or the decision at once).
    slip_stops = Phase::Sliding, DiskGuard::SlipStops, None
);
decision!(
    /// `stopping.halts`: at zero slip, roll if static friction can hold, else slide on.
    stick_or_slide = Phase::Bridge, DiskGuard::BridgeEnd, Some(AfterBridge::StickDecision)
);

/// `starting.slides`: sliding proper starts with the planned slip.
pub(crate) fn start_sliding(
    model: &disk::Model,
    t: f64,
    y: &[f64; DIM],
    dy: &[f64; DIM],
    new: &mut Values,
) -> Result<(), EvalError> {
    let held = &new[DIM..];
    let slip = crate::modes::Slip {
        speed: held[slot(disk::discrete::slip_speed)],
        direction: held[slot(disk::discrete::slip_direction)],
    };
    let then = Some(AfterBridge::StartSliding { slip });
    match transition(
        model,
        Phase::Bridge,
        DiskGuard::BridgeEnd,
        then,
        t,
        y,
        dy,
        new,
    )? {
        Some(mode) if mode == disk::mode::sliding => Ok(()),
        other => Err(EvalError::Undecided {
            event: "starting.slides".to_string(),
            mode: other,
        }),
    }
}
