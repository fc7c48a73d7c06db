//! The upright disk, θ = π/2: at rest, and rolling with a spin just below and just above the
//! stability threshold of docs/physics.md §9.
//!
//! Why these expectations (δ = θ − π/2, rolling, `μ_a = 0`, docs/physics.md §3.2):
//!
//! * **At rest** (`Ω = 0`): `Ω̇_x = Ω̇_z = 0`, so `δ̈ = Ω̇_y = −m g a cos θ / (A + m a²) = κ sin δ`
//!   with `κ = m g a / (A + m a²) = 4g / (5a)`. Linearised, `δ(t) = δ0 cosh(λ t)`, `λ = √κ`
//!   (14.46 s⁻¹ for the paper's disk): the disk falls away from upright on the side of its
//!   initial lean, at that rate. `θ0 = π/2` in floating point is not the exact upright: it lies
//!   `δ0 = −cos(θ0) = −6.1e-17` below it, so it too falls, toward `θ = 0`, after about
//!   `acosh(1e-3 / 6.1e-17) / λ = 2.3 s`. That `δ0` is below half an ulp of θ there (1.1e-16),
//!   so the integrator's rounding of θ reseeds it: only its growth *rate* is predicted sharply.
//!   Whichever way it falls, it must stop flat on that face: "inclination reached 0" at the
//!   floor θ = 1e-9, or "inclination reached pi" at π − 1e-9 (the models are singular at
//!   `sin θ = 0` on both sides).
//! * **Rolling** with spin `n` and a nudge `Ω_y(0) = ε`: to first order `Ω_x = −(C/A) n δ`,
//!   `Ω_z = n`, and `δ̈ = (4/5)(g/a − 3 n²) δ`, the characteristic polynomial
//!   `λ² (5aλ² + 12an² − 4g)` of docs/physics.md §9. Below `n_c = √(g / 3a)` (9.33 rad/s) δ grows
//!   like `(ε/λ) sinh λt` with `λ² = (4g − 12an²)/(5a)`: the disk leaves upright (and, beyond the
//!   linear range, settles on a tilted circle). Above, it wobbles as
//!   `(ε/ω) sin ωt`, `ω² = (12an² − 4g)/(5a)`, and keeps rolling; the frequency is measured from
//!   the upward zero crossings of `Ω_y` (each period exactly, whatever the mean of the wobble).

use crate::common::extreme::{dop853, models, rolling_state, Rates, Watch};
use equations::layout::{OMEGA_Y, THETA};
use equations::DiskParams;
use equations::Mode;
use equations::{simulate, DiskSample, StopReason};
use equations::{DiskConfig, InitialState};
use std::f64::consts::FRAC_PI_2;

/// `κ = m g a / (A + m a²)`: the square of the rate at which the disk falls from upright (s⁻²).
fn kappa(p: &DiskParams) -> f64 {
    p.m * p.g * p.a / (p.A() + p.m * p.a * p.a)
}

/// `δ = θ − π/2` of a sample, accurate to round-off near upright (`cos θ = −sin δ`).
fn lean(s: &DiskSample) -> f64 {
    -s.state.y[THETA].cos()
}

/// The first sample at which `|δ|` reaches `level`.
fn first_beyond(samples: &[DiskSample], level: f64) -> &DiskSample {
    samples
        .iter()
        .find(|s| lean(s).abs() >= level)
        .unwrap_or_else(|| panic!("|δ| never reached {level}"))
}

/// The exponential growth rate of `|δ|` between the levels `lo` and `hi`.
fn growth_rate(samples: &[DiskSample], lo: f64, hi: f64) -> f64 {
    let (a, b) = (first_beyond(samples, lo), first_beyond(samples, hi));
    (lean(b).abs() / lean(a).abs()).ln() / (b.t - a.t)
}

fn run(p: &DiskParams, config: &DiskConfig, y: [f64; 12]) -> (StopReason, Watch) {
    let mut watch = Watch::keeping();
    let out = simulate(
        &models(*p),
        config,
        &InitialState::from_velocity(p, 0.0, y),
        &mut watch,
    )
    .unwrap();
    watch.assert_finite("upright");
    (out.stop, watch)
}

#[test]
fn at_rest_the_disk_falls_at_the_linearised_rate() {
    let p = DiskParams::paper();
    let lambda = kappa(&p).sqrt();
    assert!((lambda - (4.0 * p.g / (5.0 * p.a)).sqrt()).abs() < 1e-12 * lambda);
    for theta0 in [FRAC_PI_2, FRAC_PI_2 - 1e-9, FRAC_PI_2 + 1e-9] {
        let delta0 = -theta0.cos();
        let config = DiskConfig {
            sample_rate: Some(1e3),
            ..dop853(1e-12, 4.0)
        };
        let y = rolling_state(&p, 0.0, theta0, Rates::ZERO);
        let (stop, watch) = run(&p, &config, y);
        let samples = watch.samples();
        let rate = growth_rate(samples, 1e-8, 1e-4);
        let reach = first_beyond(samples, 1e-3);
        let predicted = (1e-3 / delta0.abs()).acosh() / lambda;
        println!(
            "θ0 = π/2 {:+e}: δ0 = {delta0:e}, rate {rate:.6} (λ = {lambda:.6}), |δ| = 1e-3 at {:.4} s \
             (predicted {predicted:.4}), stop {stop:?}, θ in {:?}, transitions {:?}",
            theta0 - FRAC_PI_2,
            reach.t,
            watch.theta_range,
            watch.transition_records().iter().map(|r| (r.t, r.to)).collect::<Vec<_>>()
        );
        // It falls on the side of its lean…
        assert_eq!(lean(reach).signum(), delta0.signum());
        // …at the linearised rate…
        assert!((rate - lambda).abs() < 1e-2 * lambda, "{rate} vs {lambda}");
        // …from the lean it had: sharp where the lean is above θ's rounding (to the sample
        // spacing, 1 ms), within a factor 10 of the seed (ln 10 / λ = 0.16 s) where it is not.
        let tolerance = if delta0.abs() > 1e-12 {
            1e-3
        } else {
            10f64.ln() / lambda
        };
        assert!(
            (reach.t - predicted).abs() < tolerance,
            "{} vs {predicted}",
            reach.t
        );
        // Rolling while the lean is small (it needs little friction then).
        assert!(samples
            .iter()
            .take_while(|s| s.t <= reach.t)
            .all(|s| s.mode == Mode::Rolling));
        // It slides on the way down and stops flat: on the face it leaned to.
        let StopReason::InclinationReachedFloor { t, theta } = stop else {
            panic!("{stop:?}")
        };
        let floor = config.min_inclination;
        let (name, flat) = if delta0 < 0.0 {
            ("inclination reached 0", floor)
        } else {
            ("inclination reached pi", std::f64::consts::PI - floor)
        };
        assert_eq!(stop.name(), name);
        assert!(t > reach.t && (theta - flat).abs() < 1e-12, "{t} {theta}");
        // Never past the floor by more than the event's location error (θ̇ ~ 4 rad/s there).
        assert!(
            watch.theta_range.0 >= floor - 1e-12,
            "{:?}",
            watch.theta_range
        );
        assert!(
            watch.theta_range.1 <= std::f64::consts::PI - floor + 1e-12,
            "{:?}",
            watch.theta_range
        );
    }
}

/// The spin of the stability threshold, `n_c = √(m g a A / (C (C + m a²)))`.
fn threshold(p: &DiskParams) -> f64 {
    equations::formulas::upright_stability_threshold(p).sqrt()
}

/// Rolls upright with spin `n` and the nudge `Ω_y = ε`.
fn roll_upright(p: &DiskParams, n: f64, t_end: f64) -> (StopReason, Watch) {
    let config = DiskConfig {
        sample_rate: Some(1e3),
        ..dop853(1e-12, t_end)
    };
    let y = rolling_state(
        p,
        0.0,
        FRAC_PI_2,
        Rates {
            x: 0.0,
            y: NUDGE,
            z: n,
        },
    );
    run(p, &config, y)
}

/// The nudge `Ω_y(0)` (rad/s).
const NUDGE: f64 = 1e-4;

#[test]
fn rolling_just_below_the_threshold_falls() {
    let p = DiskParams::paper();
    let n = 0.98 * threshold(&p);
    let lambda = ((4.0 * p.g - 12.0 * p.a * n * n) / (5.0 * p.a)).sqrt();
    let (stop, watch) = roll_upright(&p, n, 6.0);
    let samples = watch.samples();
    let rate = growth_rate(samples, 1e-4, 1e-2);
    println!(
        "n = {n:.4}: rate {rate:.5} (λ = {lambda:.5}), stop {stop:?}, θ in {:?}",
        watch.theta_range
    );
    assert!((rate - lambda).abs() < 1e-2 * lambda, "{rate} vs {lambda}");
    // It leaves upright; then (nonlinear) it settles on a tilted circle, short of the floor.
    assert!(first_beyond(samples, 0.1).t < 6.0);
    assert!(
        watch.theta_range.0 > 1.0 && watch.theta_range.1 < 2.0,
        "{:?}",
        watch.theta_range
    );
}

#[test]
fn rolling_just_above_the_threshold_wobbles_at_the_predicted_frequency() {
    let p = DiskParams::paper();
    let n = 1.02 * threshold(&p);
    let omega = ((12.0 * p.a * n * n - 4.0 * p.g) / (5.0 * p.a)).sqrt();
    let (stop, watch) = roll_upright(&p, n, 10.0);
    let samples = watch.samples();
    let crossings: Vec<f64> = samples
        .windows(2)
        .filter(|w| w[0].state.y[OMEGA_Y] < 0.0 && w[1].state.y[OMEGA_Y] >= 0.0)
        .map(|w| {
            let (a, b) = (w[0].state.y[OMEGA_Y], w[1].state.y[OMEGA_Y]);
            w[0].t + (w[1].t - w[0].t) * a / (a - b)
        })
        .collect();
    let periods = crossings.len() - 1;
    let measured =
        2.0 * std::f64::consts::PI * periods as f64 / (crossings[periods] - crossings[0]);
    let amplitude = samples.iter().map(|s| lean(s).abs()).fold(0.0, f64::max);
    println!(
        "n = {n:.4}: ω = {measured:.6} over {periods} periods (predicted {omega:.6}), \
         max |δ| = {amplitude:e} (ε/ω = {:e}), stop {stop:?}",
        NUDGE / omega
    );
    assert_eq!(stop, StopReason::EndTime);
    assert_eq!(watch.transitions, 0);
    assert!(samples.iter().all(|s| s.mode == Mode::Rolling));
    assert!(periods >= 3);
    assert!(
        (measured - omega).abs() < 1e-2 * omega,
        "{measured} vs {omega}"
    );
    assert!(amplitude < 1.5 * NUDGE / omega, "{amplitude}");
}
