//! Friction at its limits, from the paper's start (docs/physics.md §11).
//!
//! * **No friction** (`μ_d = μ_st = 0`): the contact force is vertical, so the centre's horizontal
//!   velocity keeps its initial value, zero: X and Y stay where they were, the centre moves only
//!   vertically. Friction does no work and there is no air, so the energy is conserved
//!   (docs/physics.md §8), in every mode, to the accumulated integration error.
//! * **Equal coefficients** (`μ_st = μ_d`): friction is continuous across the transitions, so
//!   the rules of docs/physics.md §7 must hold (`ν ≤ μ_st` in rolling to the located event,
//!   `ν = μ_d` in sliding, the energy never rises); at the friction limit the slip starts at
//!   second order and the run goes on, the limit of runs with `μ_st = μ_d + δ` as `δ → 0`.
//! * **Unlimited static friction** (`μ_st = 1e6`): the disk never slides, so the hybrid run must
//!   agree with a plain integration of the rolling model alone (no guards, no driver) to the
//!   integration tolerance.

use crate::common::extreme::{accumulated_error_bound, dop853, models, Watch};
use equations::layout::{V_X, V_Y, X, Y};
use equations::DiskParams;
use equations::Mode;
use equations::{simulate, DiskRecorder, StopReason, Trigger};
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
/// so the slip's rate at onset is zero to round-off (against 15 m/s² with the friction
/// reversed): the slip leaves zero at second order (docs/physics.md §7.1), sliding starts at
/// once, and the run goes on. The rules hold throughout the first second.
#[test]
fn with_equal_coefficients_the_rules_hold_and_the_run_goes_on() {
    let p = DiskParams {
        mu_st: DiskParams::paper().mu_d,
        ..DiskParams::paper()
    };
    let config = DiskConfig {
        sample_rate: Some(1e3),
        ..dop853(1e-10, 1.0)
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
    println!(
        "μ_st = μ_d: {:?}, energy rise {rise:.2e}, worst rolling ν {worst_rolling}",
        result.as_ref().map(|out| (&out.stop, out.transitions))
    );
    watch.assert_finite("equal coefficients");
    let out = result.unwrap();
    assert_eq!(out.stop, StopReason::EndTime);
    let records = watch.transition_records();
    // The first friction limit, where the run used to stop, is passed.
    let onset = records
        .iter()
        .find(|r| matches!(r.trigger, Trigger::FrictionLimit { .. }))
        .unwrap();
    assert!((onset.t - 0.0765).abs() < 1e-4, "{onset:?}");
    assert!(records.len() > 3, "{}", records.len());
    assert!(worst_rolling <= p.mu_st * (1.0 + 1e-9), "{worst_rolling}");
    for s in watch.samples().iter().filter(|s| s.mode == Mode::Sliding) {
        assert!((s.force.ratio() - p.mu_d).abs() <= 1e-12, "{s:?}");
    }
    assert!(
        rise <= accumulated_error_bound(&config, 1 + watch.seen),
        "{rise}"
    );
}

/// The transitions of the first second as `(t, to)`.
fn first_second(mu_st: f64) -> Vec<(f64, Mode)> {
    let p = DiskParams {
        mu_st,
        ..DiskParams::paper()
    };
    let config = dop853(1e-10, 1.0);
    let mut record = DiskRecorder::default();
    let out = simulate(&models(p), &config, &InitialState::paper(&p), &mut record).unwrap();
    assert_eq!(out.stop, StopReason::EndTime, "mu_st = {mu_st}");
    record.transitions.iter().map(|r| (r.t, r.to)).collect()
}

/// The run at `μ_st = μ_d` is the limit of runs with `μ_st = μ_d + δ` as `δ → 0`: the same
/// decisions in the first second, at times that approach its own ones linearly in `δ` (the
/// largest gap is 7.1e-3 δ s for δ = 1e-4 … 1e-7: the friction limits come later by
/// `δ N / (d(T − μ N)/dt)`).
#[test]
fn equal_coefficients_are_the_limit_of_a_vanishing_friction_jump() {
    let mu_d = DiskParams::paper().mu_d;
    let limit = first_second(mu_d);
    let mut previous = f64::INFINITY;
    for delta in [1e-4, 1e-5, 1e-6, 1e-7] {
        let near = first_second(mu_d + delta);
        let modes = |v: &[(f64, Mode)]| v.iter().map(|&(_, m)| m).collect::<Vec<_>>();
        assert_eq!(modes(&near), modes(&limit), "delta = {delta}");
        let gap = near
            .iter()
            .zip(&limit)
            .map(|(a, b)| (a.0 - b.0).abs())
            .fold(0.0, f64::max);
        println!(
            "delta = {delta:e}: {} transitions, largest time gap {gap:.3e} s",
            near.len()
        );
        assert!(gap < previous, "delta = {delta}: {gap} after {previous}");
        assert!(gap <= 1e-2 * delta, "delta = {delta}: {gap}");
        previous = gap;
    }
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
