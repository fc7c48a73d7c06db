//! A nearly flat disk, θ0 = 1e-2, 1e-4, 1e-6 rad, started rolling and sliding.
//!
//! Near `sin θ = 0` two things blow up (docs/physics.md §10): the precession rate
//! `ψ̇ = −Ω_x / sin θ` and the normal force, `N/mg = α1 + α2 / sin θ` (eqs. 13–16). Two
//! families of starts show both ends of what the program must do there:
//!
//! * **Spinning flat** (`Ω_x = 1` rad/s): `N/mg` at the start must follow the paper's closed
//!   forms, and so grow like `1/sin θ`: `sin θ · N/mg` tends to `α2(0)`. The term
//!   `A Ω_x² cot θ` of `Ω̇_y` throws the disk back up before it reaches the floor, so the run
//!   must resolve the motion: reach its end time, turn where the energy balance says, without a
//!   non-finite number, with the constraint drift and (rolling) the energy drift within the
//!   accumulated integration error.
//! * **Falling flat** (at rest, `Ω = 0`): nothing holds the disk up, `θ̈ = −κ cos θ` with
//!   `κ = m g a / (A + m a²)` while rolling, so the run must stop with "inclination reached 0"
//!   (at the floor θ = 1e-9 rad of the default settings) at the time this scalar equation
//!   gives, computed here independently (and, for the sliding start whose slip lies along the
//!   disk's plane, from the sliding `θ` equation of docs/physics.md §4.2, which is closed
//!   when `Ω_x = Ω_z = 0` and `sin(α − ψ) = 0`).

use crate::common::extreme::{
    accumulated_error_bound, dop853, models, rolling_state, Rates, Watch,
};
use equations::formulas::{self, BodyRates};
use equations::layout::{PSI, THETA};
use equations::DiskParams;
use equations::{simulate, StopReason};
use equations::{DiskConfig, InitialState};
use equations::{Mode, Slip, DIM};

/// The inclinations of the issue.
const THETAS: [f64; 3] = [1e-2, 1e-4, 1e-6];

/// The slip of the sliding starts (m/s), along `E_X`, i.e. along the disk's plane at `ψ = 0`.
const SLIP: f64 = 0.05;

/// How a run starts.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Start {
    Rolling,
    Sliding,
}

fn initial(p: &DiskParams, theta0: f64, omega_x: f64, start: Start) -> InitialState {
    let y = rolling_state(
        p,
        0.0,
        theta0,
        Rates {
            x: omega_x,
            y: 0.0,
            z: 0.0,
        },
    );
    match start {
        Start::Rolling => InitialState::rolling(0.0, y),
        Start::Sliding => InitialState::sliding(p, 0.0, y, Slip::from_vector([SLIP, 0.0])),
    }
}

/// `N/mg` by the paper's closed forms in the sample's mode.
fn closed_form_ratio(p: &DiskParams, mode: Mode, y: &[f64; DIM], alpha: f64) -> f64 {
    let w = BodyRates {
        omega_x: y[9],
        omega_y: y[10],
        omega_z: y[11],
    };
    match mode {
        Mode::Rolling => formulas::rolling_normal_force_ratio(p, y[THETA], &w),
        Mode::Sliding => formulas::sliding_normal_force_ratio(p, y[THETA], alpha - y[PSI], &w),
    }
    .unwrap()
}

#[test]
fn spinning_flat_the_normal_force_grows_like_one_over_sin_theta_and_the_motion_is_resolved() {
    let p = DiskParams::paper();
    for start in [Start::Rolling, Start::Sliding] {
        for theta0 in THETAS {
            let config = DiskConfig {
                sample_rate: Some(1e3),
                ..dop853(1e-10, 0.05)
            };
            let mut watch = Watch::keeping();
            let out = simulate(
                &models(p),
                &config,
                &initial(&p, theta0, 1.0, start),
                &mut watch,
            )
            .unwrap();
            let first = watch.samples()[0];
            let n_over_mg = first.force.normal / (p.m * p.g);
            let expected =
                closed_form_ratio(&p, first.mode, &first.state.y, first.state.slip.direction);
            println!(
                "{start:?} θ0 = {theta0:e}: start {:?}, N/mg = {n_over_mg:.6e} (closed form {expected:.6e}), \
                 stop {:?}, θ in {:?}, drift {:.2e}, E drift {:.2e}, steps {}, transitions {}",
                first.mode, out.stop, watch.theta_range, watch.max_drift,
                watch.rolling_energy_drift, out.stats.steps, out.transitions
            );
            watch.assert_finite("spinning flat");
            assert!(
                (n_over_mg - expected).abs() <= 1e-9 * expected,
                "{n_over_mg} vs {expected}"
            );
            // 1/sin θ: sin θ · N/mg tends to α2(θ = 0) = a A Ω_x² / (g (m a² + A)); what is
            // left is α1 sin θ with |α1| < 1 here.
            let limit = p.a * p.A() / (p.g * (p.m * p.a * p.a + p.A()));
            let s = theta0.sin();
            assert!(
                (n_over_mg * s - limit).abs() <= s,
                "{start:?} θ0 = {theta0}: sin θ · N/mg = {} vs {limit}",
                n_over_mg * s
            );
            assert_eq!(out.stop, StopReason::EndTime, "{start:?} {theta0}");
            // Thrown back before the floor: θ turns where the crude balance predicts.
            let turn = other_turning_point(&p, theta0, 1.0);
            let (lo, hi) = watch.theta_range;
            let (start_end, other_end) = if turn < theta0 { (hi, lo) } else { (lo, hi) };
            assert!(
                (start_end - theta0).abs() <= 1e-2 * theta0,
                "{:?}",
                watch.theta_range
            );
            assert!(
                (other_end - turn).abs() <= 1e-2 * turn,
                "{start:?} θ0 = {theta0}: turned at {other_end}, predicted {turn}"
            );
            assert!(
                watch.max_drift <= accumulated_error_bound(&config, out.stats.steps),
                "{start:?} θ0 = {theta0}: drift {:e}",
                watch.max_drift
            );
            if start == Start::Rolling {
                assert_eq!(out.transitions, 0);
                assert!(
                    watch.rolling_energy_drift <= accumulated_error_bound(&config, out.stats.steps)
                );
            }
        }
    }
}

/// The other turning point of θ for a start at rest in θ with `Ω_x = omega_x`, `Ω_z = 0`, from
/// a crude balance: `Ω_x sin θ` is conserved up to the small coupling to `Ω_z` (its rate is
/// `−(C/A) Ω_y Ω_z sin θ`, and `Ω_z` stays ~1e-2 rad/s here), and at a turning point the energy
/// is `½ A Ω_x² + m g a sin θ` up to `½ C Ω_z²` and the centre's speed, both negligible. So
/// `½ A L² / sin² θ + m g a sin θ` takes the same value at both turning points, `L = Ω_x sin θ0`.
fn other_turning_point(p: &DiskParams, theta0: f64, omega_x: f64) -> f64 {
    let l = omega_x * theta0.sin();
    let mga = p.m * p.g * p.a;
    let level = |th: f64| 0.5 * p.A() * l * l / th.sin().powi(2) + mga * th.sin();
    let e0 = level(theta0);
    // The balance is least at sin³ θm = A L² / (m g a); the other root lies across θm.
    let theta_m = (p.A() * l * l / mga).cbrt().asin();
    let (mut lo, mut hi) = if theta0 < theta_m {
        (theta_m, std::f64::consts::FRAC_PI_2)
    } else {
        (theta_m * 1e-6, theta_m)
    };
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        // `level − e0` is negative at θm and positive beyond the root on either side.
        if (level(mid) - e0 < 0.0) == (theta0 < theta_m) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// `θ̈ = f(θ, θ̇)` from `θ0` at rest until `θ = floor`, by RK4 with a fine fixed step; the
/// crossing by linear interpolation within the last step (its error is `O(h² θ̈ / θ̇)`, far below
/// 1e-12 s).
fn landing_time(theta0: f64, floor: f64, accel: impl Fn(f64, f64) -> f64) -> f64 {
    let guess = (2.0 * theta0 / accel(theta0, 0.0).abs()).sqrt();
    let h = guess / 2e5;
    let (mut t, mut th, mut om) = (0.0, theta0, 0.0);
    let f = |th: f64, om: f64| (om, accel(th, om));
    loop {
        let k1 = f(th, om);
        let k2 = f(th + 0.5 * h * k1.0, om + 0.5 * h * k1.1);
        let k3 = f(th + 0.5 * h * k2.0, om + 0.5 * h * k2.1);
        let k4 = f(th + h * k3.0, om + h * k3.1);
        let th1 = th + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
        let om1 = om + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        if th1 <= floor {
            return t + h * (th - floor) / (th - th1);
        }
        (t, th, om) = (t + h, th1, om1);
    }
}

/// Falls one disk from `θ0` at rest and checks the stop against [`landing_time`].
fn falls_flat(start: Start, theta0: f64, rtol: f64) {
    let p = DiskParams::paper();
    let (m, a, g) = (p.m, p.a, p.g);
    let ma2 = m * a * a;
    // Rolling with Ω_x = Ω_z = 0 (docs/physics.md §3.2): Ω̇_y = −m g a cos θ / (A + m a²).
    let rolling = |th: f64, _om: f64| -m * g * a * th.cos() / (p.A() + ma2);
    // Sliding with the slip along E_X (α = π, ψ = 0: K = −1, S = 0), docs/physics.md §4.2 line 3.
    let sliding = |th: f64, om: f64| {
        let (s, c) = th.sin_cos();
        let k = p.mu_d * -s + c;
        (-m * g * a * k + ma2 * k * s * om * om) / (p.A() + ma2 * c * k)
    };
    let config = dop853(rtol, 1.0);
    let floor = config.min_inclination;
    let expected = match start {
        Start::Rolling => landing_time(theta0, floor, rolling),
        Start::Sliding => landing_time(theta0, floor, sliding),
    };
    let mut watch = Watch::streaming();
    let out = simulate(
        &models(p),
        &config,
        &initial(&p, theta0, 0.0, start),
        &mut watch,
    )
    .unwrap_or_else(|e| panic!("{start:?} θ0 = {theta0}, rtol {rtol}: {e}"));
    watch.assert_finite("falling flat");
    let StopReason::InclinationReachedFloor { t, theta } = out.stop else {
        panic!("{start:?} {theta0}: {:?}", out.stop)
    };
    assert_eq!(out.stop.name(), "inclination reached 0");
    assert!((theta - floor).abs() < 1e-15, "{theta}");
    // Located to the integration error (rtol of the rates, over the fall).
    assert!(
        (t - expected).abs() < 1e2 * rtol * expected,
        "{start:?} θ0 = {theta0}, rtol {rtol}: {t} vs {expected}"
    );
    assert_eq!(watch.transitions, 0);
    let mode = match start {
        Start::Rolling => Mode::Rolling,
        Start::Sliding => Mode::Sliding,
    };
    assert_eq!(out.last.mode, mode);
}

/// Every fall ends with the named stop, never with the flat disk's singular pivot: the floor
/// lies at `min_inclination` = 1e-9 rad, where the models can still be evaluated. (With the
/// floor at 0, a third of these runs ended with `SingularPivot "sin(theta)" = 0` when the event
/// locator landed on θ = 0.0 exactly.)
#[test]
fn falling_flat_stops_at_the_floor_at_the_predicted_time() {
    for rtol in [1e-8, 1e-10, 1e-12] {
        for start in [Start::Rolling, Start::Sliding] {
            for theta0 in [1e-2, 1e-3, 1e-4, 3e-5, 1e-5, 1e-6] {
                falls_flat(start, theta0, rtol);
            }
        }
    }
}
