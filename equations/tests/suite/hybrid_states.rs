//! The hybrid disk from hand-made states: the consistent onset direction, invariants of pure
//! rolling and of spinning in place, a slide that ends at once, loss of contact, and a guard
//! that is exactly zero when a segment starts.

use equations::layout::*;
use equations::reference::SlidingPolarReference;
use equations::DiskParams;
use equations::{
    consistent_slip_direction, simulate, DiskRecorder, GeneratedModels, StopReason, Trigger,
};
use equations::{ContactForce, Mode, PhysicalState, Slip, SlipChart, DIM};
use equations::{DiskConfig, InitialState, Integrator};
use model_runtime::Model;
use proptest::prelude::*;

/// The generated models (the hand-written reference is the oracle, not the subject, here).
fn models(params: DiskParams, chart: SlipChart) -> GeneratedModels {
    GeneratedModels::generated(params, chart).unwrap()
}

/// A rolling-consistent state from the angles and angular velocities.
fn rolling_state(p: &DiskParams, psi: f64, theta: f64, omega: [f64; 3]) -> [f64; DIM] {
    let mut y = [0.0; DIM];
    y[PSI] = psi;
    y[THETA] = theta;
    y[OMEGA_X] = omega[0];
    y[OMEGA_Y] = omega[1];
    y[OMEGA_Z] = omega[2];
    let mut s = PhysicalState::from_rolling(&y, 0.0);
    s.project(p, Mode::Rolling);
    s.y
}

fn dop853(t_end: f64) -> DiskConfig {
    DiskConfig {
        integrator: Integrator::Dop853,
        rtol: 1e-12,
        atol: 1e-14,
        t_end,
        ..DiskConfig::paper()
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// At random states the onset direction found by probing the integrated model is a root of
    /// `w` by the reference's exact zero-slip acceleration (another road: no probe speed), with
    /// the slip growing, and the probe agrees with the exact acceleration.
    #[test]
    fn the_onset_direction_is_consistent(
        psi in -3.0f64..3.0, theta in 0.15f64..1.4,
        ox in -30.0f64..30.0, oy in -10.0f64..10.0, oz in -30.0f64..30.0,
        chart in prop_oneof![Just(SlipChart::Cartesian), Just(SlipChart::Polar)],
    ) {
        let p = DiskParams::paper();
        let m = models(p, chart);
        let state = PhysicalState::from_rolling(&rolling_state(&p, psi, theta, [ox, oy, oz]), 0.0);
        let mut dy = [0.0; DIM];
        m.rolling.rhs(0.0, &state.y, &mut dy).unwrap();
        let guess = ContactForce::rolling(&p, &state, &dy).direction();
        let exact = SlidingPolarReference::new(p).unwrap();
        let onset = consistent_slip_direction(guess, |alpha| {
            m.probe_onset(0.0, &state, alpha).map(|(acc, _)| acc)
        });
        // A consistent direction need not exist at every state; where one is found it must hold.
        if let Ok(onset) = onset {
            let slip = Slip { speed: 0.0, direction: onset.direction };
            let reference_slip = equations::reference::Slip { speed: 0.0, alpha: onset.direction };
            let acc = exact.slip_acceleration(&state.sliding_vector(SlipChart::Polar, slip), reference_slip).unwrap();
            let scale = acc.along.hypot(acc.across);
            prop_assert!(acc.across.abs() <= 1e-12 * scale, "w = {} at scale {}", acc.across, scale);
            prop_assert!(acc.along > 0.0);
            prop_assert!((onset.acceleration.along - acc.along).abs() <= 1e-12 * scale);
            prop_assert!((onset.direction - guess).abs() <= std::f64::consts::PI + 1e-12);
        }
    }
}

#[test]
fn the_paper_onset_accelerates_the_slip_at_4_239() {
    let p = DiskParams::paper();
    let m = models(p, SlipChart::Cartesian);
    let state = PhysicalState::from_rolling(&InitialState::paper(&p).state.y, 0.0);
    let (acc, _) = m.probe_onset(0.0, &state, std::f64::consts::PI).unwrap();
    assert!((acc.along - 4.239).abs() < 5e-4, "{acc:?}");
    assert!(acc.across.abs() < 1e-14, "{acc:?}");
}

#[test]
fn pure_rolling_conserves_energy_to_1e_10_over_10_s() {
    let p = DiskParams {
        mu_st: 1e6,
        ..DiskParams::paper()
    };
    let theta0 = 1.0;
    let rate = 12.0;
    let spin = equations::formulas::steady_circle_spin(&p, theta0, rate).unwrap();
    // A steady circle with a nudge: the disk nutates while it rolls.
    let y = rolling_state(&p, 0.0, theta0, [-rate * theta0.sin(), 0.8, spin]);
    let config = DiskConfig {
        sample_rate: Some(100.0),
        ..dop853(10.0)
    };
    let mut rec = DiskRecorder::default();
    let out = simulate(
        &models(p, SlipChart::Cartesian),
        &config,
        &InitialState::from_velocity(&p, 0.0, y),
        &mut rec,
    )
    .unwrap();
    assert_eq!(out.stop, StopReason::EndTime);
    assert_eq!(out.transitions, 0);
    assert!(rec.transitions.is_empty());
    let e0 = rec.samples[0].energy;
    let drift = rec
        .samples
        .iter()
        .map(|s| (s.energy - e0).abs() / e0)
        .fold(0.0, f64::max);
    assert!(drift < 1e-10, "relative energy drift {drift:e}");
    // It did move: θ nutates.
    let theta_range = rec
        .samples
        .iter()
        .map(|s| s.state.y[THETA])
        .fold((f64::MAX, f64::MIN), |(lo, hi), t| (lo.min(t), hi.max(t)));
    assert!(theta_range.1 - theta_range.0 > 1e-3, "{theta_range:?}");
}

#[test]
fn spinning_in_place_is_held_to_1e_9_over_10_s() {
    let p = DiskParams::paper();
    let theta0 = 0.57;
    let rate = equations::formulas::spinning_in_place_rate(&p, theta0).unwrap();
    assert!((rate * rate - 4.0 * p.g / (p.a * theta0.sin())).abs() < 1e-9 * rate * rate);
    let y = rolling_state(&p, 0.3, theta0, [-rate * theta0.sin(), 0.0, 0.0]);
    let config = DiskConfig {
        sample_rate: Some(50.0),
        ..dop853(10.0)
    };
    let mut rec = DiskRecorder::default();
    let out = simulate(
        &models(p, SlipChart::Cartesian),
        &config,
        &InitialState::from_velocity(&p, 0.0, y),
        &mut rec,
    )
    .unwrap();
    assert_eq!(out.stop, StopReason::EndTime);
    assert!(rec.transitions.is_empty(), "{:?}", rec.transitions);
    for s in &rec.samples {
        assert_eq!(s.mode, Mode::Rolling);
        assert!(
            (s.state.y[THETA] - theta0).abs() < 1e-9,
            "theta at {}: {}",
            s.t,
            s.state.y[THETA]
        );
        assert!(
            s.state.y[X].abs() < 1e-9 && s.state.y[Y].abs() < 1e-9,
            "centre moved at {}",
            s.t
        );
        assert!(s.force.friction() < 1e-9 * s.force.normal);
    }
}

#[test]
fn a_slip_that_dies_at_once_ends_in_rolling() {
    // Spinning in place needs no friction, so a tiny initial slip is braked to zero within
    // ~1e-8 s and the disk rolls on: sliding starts and ends at once.
    let p = DiskParams::paper();
    let theta0 = 0.57;
    let rate = equations::formulas::spinning_in_place_rate(&p, theta0).unwrap();
    let mut y = rolling_state(&p, 0.0, theta0, [-rate * theta0.sin(), 0.0, 0.0]);
    y[V_X] += 1e-8;
    let mut rec = DiskRecorder::default();
    let config = DiskConfig {
        sample_rate: Some(10.0),
        ..dop853(1.0)
    };
    let out = simulate(
        &models(p, SlipChart::Cartesian),
        &config,
        &InitialState::from_velocity(&p, 0.0, y),
        &mut rec,
    )
    .unwrap();
    assert_eq!(out.stop, StopReason::EndTime);
    assert_eq!(rec.transitions.len(), 1, "{:?}", rec.transitions);
    let r = rec.transitions[0];
    assert_eq!((r.from, r.to), (Mode::Sliding, Mode::Rolling));
    assert!(r.t > 0.0 && r.t < 1e-7, "{}", r.t);
    let Trigger::SlipStopped { rolling_ratio, .. } = r.trigger else {
        panic!("{r:?}")
    };
    assert!(rolling_ratio < 1e-6);
    assert_eq!(out.last.mode, Mode::Rolling);
    assert!((out.last.state.y[THETA] - theta0).abs() < 1e-8);
}

#[test]
fn losing_contact_stops_the_run() {
    // Flung upward about the contact line: N < 0 from the start.
    let p = DiskParams::paper();
    let y = rolling_state(&p, 0.0, 1.2, [0.0, 60.0, 0.0]);
    let out = simulate(
        &models(p, SlipChart::Cartesian),
        &dop853(1.0),
        &InitialState::from_velocity(&p, 0.0, y),
        &mut (),
    )
    .unwrap();
    assert_eq!(
        out.stop,
        StopReason::ContactLost {
            t: 0.0,
            mode: Mode::Sliding
        }
    );
    assert!(out.last.force.normal < 0.0);
    // Tipped *up* fast: the rim must pull the centre down harder as θ grows. Rolling would
    // need N < 0 (so the disk slides, docs/physics.md §7.2), sliding starts with
    // N = A/β0 (1 − a Ω_y² sin θ / g) ≈ 0.1 A/β0 mg > 0, and N falls through zero as the disk
    // rises.
    let theta0: f64 = 1.0;
    let tip = (0.9 * p.g / (p.a * theta0.sin())).sqrt();
    let y = rolling_state(&p, 0.0, theta0, [0.0, tip, 0.0]);
    let initial = InitialState::from_velocity(&p, 0.0, y);
    let out = simulate(
        &models(p, SlipChart::Cartesian),
        &dop853(1.0),
        &initial,
        &mut (),
    )
    .unwrap();
    let StopReason::ContactLost { t, mode } = out.stop else {
        panic!("{:?}", out.stop)
    };
    assert_eq!(mode, Mode::Sliding);
    assert!(t > 0.0 && t < 0.1, "{t}");
    assert!(out.last.state.y[THETA] > theta0);
    let n = out.last.force.normal;
    assert!(n <= 0.0 && n > -1e-9 * p.m * p.g, "N = {n}");
}

#[test]
fn a_disk_tipped_more_gently_falls_flat_and_stops_at_zero_inclination() {
    let p = DiskParams::paper();
    let y = rolling_state(&p, 0.0, 1.3, [0.0, -12.0, 0.0]);
    let initial = InitialState::from_velocity(&p, 0.0, y);
    let m = models(p, SlipChart::Cartesian);
    let out = simulate(&m, &dop853(1.0), &initial, &mut ()).unwrap();
    let StopReason::InclinationReachedFloor { t, theta } = out.stop else {
        panic!("{:?}", out.stop)
    };
    assert_eq!(out.stop.name(), "inclination reached 0");
    // Stopped at the default floor (the models are singular at θ = 0 itself).
    let floor = dop853(1.0).min_inclination;
    assert!(floor > 0.0 && floor <= 1e-9);
    assert!(t > 0.0 && (theta - floor).abs() < 1e-12, "{t} {theta}");
}

#[test]
fn a_guard_exactly_zero_at_the_start_waits_for_its_next_crossing() {
    // θ starts exactly on the floor and rises first: the floor guard is disarmed at t = 0 and
    // fires only when θ comes back down through it.
    let p = DiskParams::paper();
    let theta0 = 0.6;
    let rate = equations::formulas::spinning_in_place_rate(&p, theta0).unwrap();
    let y = rolling_state(&p, 0.0, theta0, [-rate * theta0.sin(), 0.5, 0.0]);
    let config = DiskConfig {
        min_inclination: theta0,
        ..dop853(1.0)
    };
    let out = simulate(
        &models(p, SlipChart::Cartesian),
        &config,
        &InitialState::from_velocity(&p, 0.0, y),
        &mut (),
    )
    .unwrap();
    let StopReason::InclinationReachedFloor { t, theta } = out.stop else {
        panic!("{:?}", out.stop)
    };
    assert!(t > 1e-3, "{t}");
    assert!((theta - theta0).abs() < 1e-12);
}
