//! The disk's contact switching said in the DSL: rolling, sliding, the two bridges between
//! them and the stops, as one switched model (docs/physics.md §7), beside the hand-written
//! system it is held to.
//!
//! Rolling is Box 1 and sliding Box 3 in the Cartesian slip chart: the modes include the rows
//! the smooth models of `crate::models` include (`models/box1_rolling.dsl`,
//! `models/box3_sliding.dsl`), with the air's terms zero at compile time (the graph models the
//! disk in still air), as in the smooth models' `still` variants, which a hand-written run in
//! still air integrates: the right-hand sides are theirs to the bit. The guards, clocks and
//! first steps are those of the hand-written system (module `system`), written as expressions,
//! rounded as it rounds them. Sliding carries
//! the slip `(u_X, u_Y)` in the slots where rolling carries the centre's velocity
//! `(V_X, V_Y)` (`states { u_X, u_Y } replace { V_X, V_Y }`), so the error norm sees what it
//! sees in the hand-written run. The bridges are modes whose right-hand side is a constant
//! derivative held in discrete values (`b_*`) until a held end time; the maps that no
//! expression gives (the onset direction is a search, sticking is a decision of the rolling
//! equations) are the hand-written ones, called as Rust functions: each builds the
//! hand-written system at the event and asks it (`DiskSystem::on_event`, through [`ask`]), so
//! both runs make every decision by the same code, and writes what the map told its observer
//! (the decision record, the bridge's slip) into the discrete values `n_*`, which the run of
//! the graph (module `graph`) reads back for its observer.
//!
//! What the DSL cannot say yet, the hand-written system still does alone: the air at compile
//! time, the polar slip chart and the paper's slip sign, the pruned variants and projection
//! after steps (model-macros/DSL.md, "The disk, said in the DSL").

use super::system::{
    AfterBridge, BridgePlan, DiskGuard, DiskNote, DiskSystem, DiskTransition, Phase,
};
use super::{GeneratedModels, TransitionRecord, Trigger};
use crate::config::DiskConfig;
use crate::modes::{ConstraintResiduals, Mode, Slip, SlipChart, DIM};
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
            /// The note of the latest decision, as the hand-written map told it (a decision
            /// made, its time, modes, trigger, directions and drift; the slip a bridge entered
            /// starts from): written by the Rust functions for the run's observer, read by no
            /// equation.
            n_decided = 0.0, n_t = 0.0, n_from = 0.0, n_to = 0.0,
            n_trigger = 0.0, n_ratio = 0.0, n_normal = 0.0,
            n_has_slip_direction = 0.0, n_slip_direction = 0.0,
            n_has_rolling_direction = 0.0, n_rolling_direction = 0.0,
            n_height = 0.0, n_vertical_speed = 0.0, n_no_slip = 0.0,
            n_bridge = 0.0, n_bridge_speed = 0.0, n_bridge_direction = 0.0,
        }

        let A = m*a^2/4;
        let C = m*a^2/2;
        // Still air: the boxes' air terms vanish at compile time (the drag coefficients `k_F`,
        // `k_M` and the air's vertical speed `w_z` are zero), as in the `still` variants of the
        // smooth models, which a hand-written run in still air integrates: the right-hand
        // sides are theirs to the bit.
        let k_F = 0;
        let k_M = 0;
        let w_z = 0;
        // The distance from lying flat on either face.
        let lying = min(theta, pi - theta);

        /// Rolling without slipping (Box 1).
        mode rolling {
            include "../models/box1_rolling.dsl";
            time_scale = lying/(lying + theta_s);
            // The friction rolling needs and the normal force.
            let T = sqrt((m*der(V_X) + k_F*(v_z - w_z)*sin(theta)*cos(psi))^2
                + (m*der(V_Y) + k_F*(v_z - w_z)*sin(theta)*sin(psi))^2);
            let N = m*(der(V_Z) + g) + k_F*(v_z - w_z)*cos(theta);
            /// Rolling would need more friction than static friction gives: the slip starts in
            /// the consistent direction, across a bridge (or at once), or the run stops. Above
            /// `mu_st = 1` the margin is divided by `mu_st`, so that a grip as large as
            /// `1.8e308` never overflows it (the same zero).
            when slips: if(mu_st > 1, T/mu_st - N, T - mu_st*N) > 0
                -> starting | sliding | stop by slip_onset;
            /// The floor would have to pull.
            when lifts_off: N < 0 -> stop;
            /// The disk lies flat.
            when lies_flat: lying < theta_min -> stop;
        }

        /// Sliding (Box 3, the Cartesian slip chart).
        mode sliding {
            states { u_X, u_Y } replace { V_X, V_Y }
            let v_C = sqrt(u_X^2 + u_Y^2);
            let alpha = atan2(-u_Y, -u_X);
            include "../models/box3_sliding.dsl";
            // `max(.., 0)` keeps the two factors apart (the simplifier would join them into one
            // quotient), so the clock rounds as the hand-written one does.
            time_scale = max(lying/(lying + theta_s), 0)*v_C/(v_C + u_s);
            /// Starting near the stick threshold the slip is stiff: the first step is a fraction
            /// of its doubling time (none further away).
            // `max(3*v_C, 0)` (`3*v_C`: v_C >= 0) is multiplied before the division, as the
            // hand-written `3 v_C / hypot(..)` is; a bare `3*v_C/..` would divide first.
            first_step = if(v_C > 4*delta, 0, max(3*v_C, 0)/hypot(der(u_X), der(u_Y)));
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
    /// and the inclination floor; the clock's scales are the hand-written run's). The graph's
    /// air is still whatever `params` say: a run with air is the hand-written system's
    /// (`Engine::graph_refusals` names `air.mu_a`, `air.w_z`).
    pub fn for_run(params: &DiskParams, config: &DiskConfig) -> Self {
        let mut values = disk::Params::default().to_array();
        values[disk::param::m] = params.m;
        values[disk::param::a] = params.a;
        values[disk::param::g] = params.g;
        values[disk::param::mu_d] = params.mu_d;
        values[disk::param::mu_st] = params.mu_st;
        values[disk::param::delta] = config.stick_threshold;
        values[disk::param::theta_min] = config.min_inclination;
        values[disk::param::theta_s] = crate::settings::TimeVariable::THETA_SCALE;
        values[disk::param::u_s] = crate::settings::TimeVariable::SLIP_SCALE;
        disk::Model::new(values)
    }

    /// The disk's parameters, in still air.
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
        write_plan(plan, &mut self.params[FIRST..])
    }

    /// The discrete values as they are now.
    pub(crate) fn held(&self) -> &[f64] {
        &self.params[FIRST..]
    }

    /// The note of the latest decision a Rust function of the events made (module docs):
    /// what the hand-written map told its observer there.
    pub(crate) fn last_note(&self) -> DiskNote {
        read_note(self.held())
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

/// The bridge plan held in the discrete values `held`, ending as `then` says.
fn read_plan(held: &[f64], then: AfterBridge) -> BridgePlan {
    let mut slope = [0.0; DIM];
    slope.copy_from_slice(&held[SLOPE..SLOPE + DIM]);
    BridgePlan {
        t_end: held[slot(disk::discrete::t_end)],
        slope,
        then,
    }
}

/// A contact mode as a discrete value.
fn mode_value(mode: Mode) -> f64 {
    match mode {
        Mode::Rolling => 0.0,
        Mode::Sliding => 1.0,
    }
}

/// The contact mode a discrete value of [`mode_value`] stands for.
fn value_mode(value: f64) -> Mode {
    if value == 0.0 {
        Mode::Rolling
    } else {
        Mode::Sliding
    }
}

/// Writes an optional value into a flag and a value among `held`.
fn write_option(held: &mut [f64], (flag, value): (usize, usize), x: Option<f64>) {
    held[slot(flag)] = if x.is_some() { 1.0 } else { 0.0 };
    held[slot(value)] = x.unwrap_or(0.0);
}

/// The optional value of a flag and a value among `held`.
fn read_option(held: &[f64], (flag, value): (usize, usize)) -> Option<f64> {
    (held[slot(flag)] != 0.0).then_some(held[slot(value)])
}

/// The note's slots: the slip direction's flag and value.
const SLIP_DIRECTION: (usize, usize) = (
    disk::discrete::n_has_slip_direction,
    disk::discrete::n_slip_direction,
);
/// The note's slots: the rolling direction's flag and value.
const ROLLING_DIRECTION: (usize, usize) = (
    disk::discrete::n_has_rolling_direction,
    disk::discrete::n_rolling_direction,
);

/// Writes `note` into the discrete values `held` (the `n_*` values, every field of it).
fn write_note(note: &DiskNote, held: &mut [f64]) {
    use disk::discrete as d;
    held[slot(d::n_decided)] = if note.decision.is_some() { 1.0 } else { 0.0 };
    if let Some(r) = note.decision {
        let (kind, ratio, normal) = match r.trigger {
            Trigger::InitialFriction { ratio } => (0.0, ratio, 0.0),
            Trigger::FrictionLimit { ratio } => (1.0, ratio, 0.0),
            Trigger::SlipStopped {
                rolling_ratio,
                rolling_normal,
            } => (2.0, rolling_ratio, rolling_normal),
        };
        held[slot(d::n_t)] = r.t;
        held[slot(d::n_from)] = mode_value(r.from);
        held[slot(d::n_to)] = mode_value(r.to);
        held[slot(d::n_trigger)] = kind;
        held[slot(d::n_ratio)] = ratio;
        held[slot(d::n_normal)] = normal;
        write_option(held, SLIP_DIRECTION, r.slip_direction);
        write_option(held, ROLLING_DIRECTION, r.rolling_direction);
        held[slot(d::n_height)] = r.drift.height;
        held[slot(d::n_vertical_speed)] = r.drift.vertical_speed;
        held[slot(d::n_no_slip)] = r.drift.no_slip;
    }
    let bridge = note.bridge.map(|s| (s.speed, s.direction));
    write_option(held, (d::n_bridge, d::n_bridge_speed), bridge.map(|b| b.0));
    held[slot(d::n_bridge_direction)] = bridge.map_or(0.0, |b| b.1);
}

/// The note [`write_note`] wrote into `held`.
fn read_note(held: &[f64]) -> DiskNote {
    use disk::discrete as d;
    let value = |index: usize| held[slot(index)];
    let decision = (value(d::n_decided) != 0.0).then(|| {
        let (ratio, normal) = (value(d::n_ratio), value(d::n_normal));
        let trigger = match value(d::n_trigger) {
            0.0 => Trigger::InitialFriction { ratio },
            1.0 => Trigger::FrictionLimit { ratio },
            _ => Trigger::SlipStopped {
                rolling_ratio: ratio,
                rolling_normal: normal,
            },
        };
        TransitionRecord {
            t: value(d::n_t),
            from: value_mode(value(d::n_from)),
            to: value_mode(value(d::n_to)),
            trigger,
            slip_direction: read_option(held, SLIP_DIRECTION),
            rolling_direction: read_option(held, ROLLING_DIRECTION),
            drift: ConstraintResiduals {
                height: value(d::n_height),
                vertical_speed: value(d::n_vertical_speed),
                no_slip: value(d::n_no_slip),
            },
        }
    });
    let bridge = read_option(held, (d::n_bridge, d::n_bridge_speed)).map(|speed| Slip {
        speed,
        direction: value(d::n_bridge_direction),
    });
    DiskNote { decision, bridge }
}

/// Which hand-written map an event's Rust function asks: the phase and the guard it stands
/// for there, and at the end of a bridge what the bridge was for (read from the held plan).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Asked {
    /// The phase the event fires in.
    pub phase: Phase,
    /// The hand-written guard it stands for.
    pub guard: DiskGuard,
    /// At a bridge's end: what the bridge was for.
    pub then: Option<AfterBridge>,
}

/// `rolling.slips`: the onset of sliding (the consistent direction, then a bridge).
const SLIP_ONSET: Asked = Asked {
    phase: Phase::Rolling,
    guard: DiskGuard::FrictionLimit,
    then: None,
};
/// `sliding.sticks`: the bridge to the slip's zero (or the decision at once).
const SLIP_STOPS: Asked = Asked {
    phase: Phase::Sliding,
    guard: DiskGuard::SlipStops,
    then: None,
};
/// `stopping.halts`: at zero slip, roll if static friction can hold, else slide on.
const STICK_OR_SLIDE: Asked = Asked {
    phase: Phase::Bridge,
    guard: DiskGuard::BridgeEnd,
    then: Some(AfterBridge::StickDecision),
};

/// What an event of the graph is to a run of it (module `graph`).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Role {
    /// A mode decision of the hand-written map (its Rust function asks it).
    Decision(Asked),
    /// The end of the bridge into sliding (`starting.slides`).
    StartsSliding,
    /// A stop, by the hand-written guard it stands for.
    Stop(DiskGuard),
}

/// The role of the event named `event` of the mode `mode` (`None`: not an event of the disk).
pub(crate) fn role(mode: usize, event: &str) -> Option<Role> {
    Some(match (mode, event) {
        (disk::mode::rolling, "slips") => Role::Decision(SLIP_ONSET),
        (disk::mode::sliding, "sticks") => Role::Decision(SLIP_STOPS),
        (disk::mode::stopping, "halts") => Role::Decision(STICK_OR_SLIDE),
        (disk::mode::starting, "slides") => Role::StartsSliding,
        (_, "lifts_off") => Role::Stop(DiskGuard::ContactLost),
        (_, "lies_flat") => Role::Stop(DiskGuard::InclinationFloor),
        _ => return None,
    })
}

/// What the hand-written map answered at an event.
pub(crate) struct Answer {
    /// Its transition.
    pub transition: DiskTransition,
    /// The bridge it planned (the one held before, if it planned none).
    pub bridge: BridgePlan,
    /// The largest constraint drift it noted.
    pub drift: ConstraintResiduals,
}

/// The hand-written transition map `asked` at the event `(t, y, dy)` of `model`, whose
/// discrete values `held` hold the bridge in force.
pub(crate) fn ask(
    model: &disk::Model,
    asked: Asked,
    held: &[f64],
    (t, y, dy): (f64, &[f64; DIM], &[f64; DIM]),
) -> Result<Answer, EvalError> {
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
    if let Some(then) = asked.then {
        system.bridge = read_plan(held, then);
    }
    let hit = EventHit {
        guard: asked.guard,
        index: 0,
        t,
        before: t,
        y: *y,
        dy: *dy,
        value: 0.0,
        direction: Crossed::Up,
    };
    let transition = system.on_event(asked.phase, &hit)?;
    Ok(Answer {
        transition,
        bridge: system.bridge,
        drift: system.ledger.max_drift(),
    })
}

/// The hand-written map `asked` at the event `(t, y, dy)`: the next state and discrete values
/// (the bridge planned and the note told) into `new`, and the mode the run goes on in
/// (`None`: it stops).
fn transition(
    model: &disk::Model,
    asked: Asked,
    event: (f64, &[f64; DIM], &[f64; DIM]),
    new: &mut Values,
) -> Result<Option<usize>, EvalError> {
    let Answer {
        transition, bridge, ..
    } = ask(model, asked, &new[DIM..], event)?;
    match transition {
        Transition::Switch { to, y, note } => {
            new[..DIM].copy_from_slice(y.as_ref());
            write_note(&note, &mut new[DIM..]);
            Ok(Some(match to {
                Phase::Rolling => disk::mode::rolling,
                Phase::Sliding => disk::mode::sliding,
                Phase::Bridge => write_plan(&bridge, &mut new[DIM..]),
            }))
        }
        // The run re-asks at a stop, for the reason (module `graph`).
        Transition::Stop(_) => Ok(None),
        // The disk's maps always switch or stop.
        Transition::Continue { .. } | Transition::Pass { .. } => Err(EvalError::Undecided {
            event: format!("{:?}", asked.guard),
            mode: None,
        }),
    }
}

/// A Rust function of the disk's events that asks the hand-written map of one guard: the
/// three decisions differ only in which.
macro_rules! decision {
    ($(#[$doc:meta])* $name:ident = $asked:expr) => {
        $(#[$doc])*
        pub(crate) fn $name(
            model: &disk::Model,
            t: f64,
            y: &[f64; DIM],
            dy: &[f64; DIM],
            new: &mut Values,
        ) -> Result<Option<usize>, EvalError> {
            transition(model, $asked, (t, y, dy), new)
        }
    };
}

decision!(
    /// `rolling.slips`: the onset of sliding (the consistent direction, then a bridge).
    slip_onset = SLIP_ONSET
);
decision!(
    /// `sliding.sticks`: the bridge to the slip's zero (or the decision at once).
    slip_stops = SLIP_STOPS
);
decision!(
    /// `stopping.halts`: at zero slip, roll if static friction can hold, else slide on.
    stick_or_slide = STICK_OR_SLIDE
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
    let slip = Slip {
        speed: held[slot(disk::discrete::slip_speed)],
        direction: held[slot(disk::discrete::slip_direction)],
    };
    let asked = Asked {
        then: Some(AfterBridge::StartSliding { slip }),
        ..STICK_OR_SLIDE
    };
    match transition(model, asked, (t, y, dy), new)? {
        Some(mode) if mode == disk::mode::sliding => Ok(()),
        other => Err(EvalError::Undecided {
            event: "starting.slides".to_string(),
            mode: other,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modes::layout::{OMEGA_X, OMEGA_Y, OMEGA_Z, PSI, THETA, U_X, U_Y, V_Z, Z};
    use model_runtime::{Model, SwitchedModel};

    /// The graph's rolling and sliding integrate what a hand-written run in still air
    /// integrates (the generated models' `still` variants), to the bit, over states spread
    /// through both modes' terms: the one source of the rows, and the air compiled out the same
    /// way on both sides.
    #[test]
    fn the_modes_right_hand_sides_are_the_still_variants_to_the_bit() {
        let params = DiskParams::paper();
        let graph = disk::Model::for_run(&params, &DiskConfig::default());
        let models = GeneratedModels::generated(params, SlipChart::Cartesian).unwrap();
        let mut compared = 0;
        for k in 0..64 {
            let x = k as f64;
            let mut y = [0.0; DIM];
            y[THETA] = 0.05 + 0.047 * x;
            y[Z] = params.a * y[THETA].sin();
            y[PSI] = 0.37 * x;
            // `(V_X, V_Y)` rolling, the slip `(u_X, u_Y)` sliding.
            y[U_X] = 0.013 * (x - 31.5);
            y[U_Y] = -0.4 + 0.011 * x;
            y[V_Z] = 1e-3 * (x - 20.0);
            y[OMEGA_X] = 0.1 * (x - 7.0);
            y[OMEGA_Y] = -0.05 * x;
            y[OMEGA_Z] = 2.0 + 3.0 * x;
            for (mode, hand) in [
                (disk::mode::rolling, &models.rolling as &dyn Model<DIM>),
                (disk::mode::sliding, &models.sliding),
            ] {
                let (mut a, mut b) = ([0.0; DIM], [0.0; DIM]);
                graph.rhs(mode, 0.0, &y, &mut a).unwrap();
                hand.rhs(0.0, &y, &mut b).unwrap();
                assert_eq!(
                    a.map(f64::to_bits),
                    b.map(f64::to_bits),
                    "mode {mode}, state {k}"
                );
                compared += 1;
            }
        }
        assert_eq!(compared, 128);
    }
}
