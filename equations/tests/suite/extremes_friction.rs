//! Friction at its limits, from the paper's start (docs/physics.md §11).
//!
//! * **No friction** (`μ_d = μ_st = 0`): the contact force is vertical, so the centre's horizontal
//!   velocity keeps its initial value, zero: X and Y stay where they were, the centre moves only
//!   vertically. Friction does no work and there is no air, so the energy is conserved
//!   (docs/physics.md §8), in every mode, to the accumulated integration error.
//! * **Equal coefficients** (`μ_st = μ_d`): friction is continuous across the transitions, so
//!   the rules of docs/physics.md §7 must hold (`ν ≤ μ_st` in rolling to the located event,
//!   `ν = μ_d` in sliding, the energy never rises) — until the friction limit, where the slip
//!   cannot start at first order and the run must stop with a typed reason, not integrate on.
//! * **Unlimited static friction** (`μ_st = 1e6`): the disk never slides, so the hybrid run must
//!   agree with a plain integration of the rolling model alone (no guards, no driver) to the
//!   integration tolerance.

use crate::common::extreme::{accumulated_error_bound, dop853, models, Watch};
use equations::layout::{V_X, V_Y, X, Y};
use equations::DiskParams;
use equations::Mode;
use equations::{simulate, OnsetError, SimError, StopReason};
use equations::{DiskConfig, InitialState};
use model_runtime::{integrate, Dop853, StepOptions, Tolerance};

/// The largest relative change of the energy among kept samples.
fn energy_change(watch: &Watch) -> (f64, f64) {
    let e0 = watch.samples()[0].energy;
    let rel = |s: &equations::DiskSample| (s.energy - e0) / e0.abs();
    let rise = watch.samples().iter().map(rel).fold(f64::MIN, f64::max);
    let change = watch
        .samples()
        .iter()
        .map(|s| rel(s).abs())
        .fold(0.0, f64::max);
    (rise, change)
}

#[test]
fn without_friction_the_centre_moves_only_vertically_and_the_energy_is_conserved() {
    let p = DiskParams {
        mu_d: 0.0,
        mu_st: 0.0,
        ..DiskParams::paper()
    };
    let config = DiskConfig {
        sample_rate: Some(1e3),
        ..dop853(1e-11, 2.0)
    };
    let mut watch = Watch::keeping_steps();
    let out = simulate(&models(p), &config, &InitialState::paper(&p), &mut watch).unwrap();
    let (_, change) = energy_change(&watch);
    let horizontal = watch
        .samples()
        .iter()
        .map(|s| {
            let y = &s.state.y;
            y[X].abs()
                .max(y[Y].abs())
                .max(y[V_X].abs())
                .max(y[V_Y].abs())
        })
        .fold(0.0, f64::max);
    println!(
        "μ = 0: stop {:?}, transitions {}, steps {}, energy change {change:.2e}, max |X|,|Y|,|V_X|,|V_Y| {horizontal:.2e}, θ in {:?}",
        out.stop, out.transitions, out.stats.steps, watch.theta_range
    );
    watch.assert_finite("frictionless");
    assert_eq!(out.stop, StopReason::EndTime);
    assert!(watch.samples().iter().all(|s| s.mode == Mode::Sliding));
    assert!(horizontal <= 1e-12, "{horizontal}");
    assert!(
        change <= accumulated_error_bound(&config, out.stats.steps),
        "{change}"
    );
}

/// With `μ_st = μ_d` the friction needed at the friction limit equals the sliding friction,
/// so the slip's rate at onset is zero (4.3e-13 m/s², round-off, against 15 m/s² with the
/// friction reversed): the slip would grow only at second order, which the bridge from zero
/// slip (constant slip acceleration) cannot carry. Up to there the rules hold; there the run
/// stops with the typed onset error that says so, at the first friction limit (t = 0.0765 s,
/// after the first stick at 0.0722 s).
#[test]
fn with_equal_coefficients_the_rules_hold_until_a_slip_that_cannot_grow_stops_the_run() {
    let p = DiskParams {
        mu_st: DiskParams::paper().mu_d,
        ..DiskParams::paper()
    };
    let config = DiskConfig {
        sample_rate: Some(1e3),
        ..dop853(1e-10, 5.0)
    };
    let mut watch = Watch::keeping_steps();
    let result = simulate(&models(p), &config, &InitialState::paper(&p), &mut watch);
    let (rise, _) = energy_change(&watch);
    let worst_rolling = watch
        .samples()
        .iter()
        .filter(|s| s.mode == Mode::Rolling)
        .map(|s| s.force.ratio())
        .fold(0.0, f64::max);
    println!("μ_st = μ_d: {result:?}, energy rise {rise:.2e}, worst rolling ν {worst_rolling}");
    watch.assert_finite("equal coefficients");
    let Err(SimError::Onset {
        t,
        source: OnsetError::NoSlipGrowth { along, scale, .. },
    }) = result
    else {
        panic!("{result:?}")
    };
    assert!((t - 0.0765).abs() < 1e-4, "{t}");
    assert!(along.abs() < 1e-9 * scale);
    let to: Vec<Mode> = watch.transition_records().iter().map(|r| r.to).collect();
    assert_eq!(to, [Mode::Sliding, Mode::Rolling]);
    assert!(worst_rolling <= p.mu_st * (1.0 + 1e-9), "{worst_rolling}");
    for s in watch.samples().iter().filter(|s| s.mode == Mode::Sliding) {
        assert!((s.force.ratio() - p.mu_d).abs() <= 1e-12, "{s:?}");
    }
    assert!(
        rise <= accumulated_error_bound(&config, 1 + watch.seen),
        "{rise}"
    );
}

#[test]
fn with_unlimited_static_friction_the_disk_rolls_as_the_rolling_model_alone() {
    let p = DiskParams {
        mu_st: 1e6,
        ..DiskParams::paper()
    };
    let models = models(p);
    let config = dop853(1e-12, 1.0);
    let initial = InitialState::paper(&p);
    let mut watch = Watch::streaming();
    let out = simulate(&models, &config, &initial, &mut watch).unwrap();
    watch.assert_finite("unlimited static friction");
    let alone = integrate(
        &models.rolling,
        Dop853::new(),
        Tolerance::scalar(config.rtol, config.atol),
        StepOptions::default(),
        0.0,
        &initial.state.y,
        out.last.t,
    )
    .unwrap();
    let worst = (0..12)
        .map(|i| (out.last.state.y[i] - alone.y[i]).abs() / (1.0 + alone.y[i].abs()))
        .fold(0.0, f64::max);
    println!(
        "μ_st = 1e6: stop {:?} at t = {}, transitions {}, worst difference {worst:.2e}",
        out.stop, out.last.t, out.transitions
    );
    assert_eq!(watch.transitions, 0);
    assert_eq!(out.last.mode, Mode::Rolling);
    assert!(worst <= 1e3 * config.rtol, "{worst}");
}
