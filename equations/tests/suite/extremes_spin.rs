//! Huge spin: rolling with `|Ω|` from 10 to 1e3 rad/s.
//!
//! Fast rates make the step sizes shrink (the methods resolve the fastest rotation, so the
//! step count grows about in proportion to `|Ω|`), and nothing else may change: the run must
//! finish, and the energy, exactly conserved in rolling with `μ_a = 0` (docs/physics.md §8), may
//! drift only by the accumulated integration error, `2 (rtol + atol)` per step at most (see
//! [`common::extreme::accumulated_error_bound`]).
//!
//! The states are steady circles of docs/physics.md §9 with a nudge `Ω_y = 0.1` rad/s, so that
//! the disk nutates rather than sitting on an exact solution: a fast precession
//! (`Ω_x = ∓|Ω|`, `p = |Ω| / sin θ0`) and a fast roller (`Ω_z = ±|Ω|` on a wide circle, the
//! small root `p` of the steady-circle condition). Static friction is made unlimited
//! (`μ_st = 1e6`) so that the disk rolls throughout, which is the regime whose energy is
//! conserved.

use crate::common::extreme::{
    accumulated_error_bound, dop853, models, rolling_state, Rates, Watch,
};
use equations::formulas::steady_circle_spin;
use equations::DiskParams;
use equations::InitialState;
use equations::{simulate, StopReason};

/// The two kinds of fast motion.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Fast {
    /// `|Ω_x| = rate`: precession `p = rate / sin θ0`.
    Precession,
    /// `|Ω_z| = rate`: a rolling wheel on a wide circle.
    Roller,
}

const THETA0: f64 = 1.0;

/// The nudge `Ω_y(0)` (rad/s) that makes the disk nutate.
const NUDGE: f64 = 0.1;

/// The precession rate of a steady circle at `THETA0` with spin `omega_z` that tends to zero
/// with the gravity term: the small root of
/// `A sin θ cos θ p² − (C + m a²) Ω_z sin θ p − m g a cos θ = 0` (docs/physics.md §9), without
/// cancellation.
fn slow_precession(p: &DiskParams, omega_z: f64) -> f64 {
    let (s, c) = THETA0.sin_cos();
    let quad = p.A() * s * c;
    let lin = -(p.C() + p.m * p.a * p.a) * omega_z * s;
    let constant = -p.m * p.g * p.a * c;
    let q = -0.5 * (lin + lin.signum() * (lin * lin - 4.0 * quad * constant).sqrt());
    constant / q
}

fn start(p: &DiskParams, kind: Fast, rate: f64) -> [f64; 12] {
    let precession = match kind {
        Fast::Precession => rate / THETA0.sin(),
        Fast::Roller => slow_precession(p, rate),
    };
    let spin = steady_circle_spin(p, THETA0, precession).unwrap();
    if kind == Fast::Roller {
        assert!((spin - rate).abs() < 1e-9 * rate.abs(), "{spin} vs {rate}");
    }
    let omega_x = -precession * THETA0.sin();
    let nudge = NUDGE;
    rolling_state(
        p,
        0.0,
        THETA0,
        Rates {
            x: omega_x,
            y: nudge,
            z: spin,
        },
    )
}

#[test]
fn huge_spin_finishes_with_the_energy_drift_within_the_accumulated_error() {
    let p = DiskParams {
        mu_st: 1e6,
        ..DiskParams::paper()
    };
    let config = dop853(1e-10, 1.0);
    for kind in [Fast::Precession, Fast::Roller] {
        for sign in [1.0, -1.0] {
            let mut steps = Vec::new();
            for rate in [10.0, 100.0, 1e3] {
                let y = start(&p, kind, sign * rate);
                let mut watch = Watch::streaming();
                let out = simulate(
                    &models(p),
                    &config,
                    &InitialState::from_velocity(&p, 0.0, y),
                    &mut watch,
                )
                .unwrap();
                let bound = accumulated_error_bound(&config, out.stats.steps);
                println!(
                    "{kind:?} {:+e}: stop {:?}, steps {}, energy drift {:.2e} (bound {bound:.1e}), \
                     constraint drift {:.2e}, θ in {:?}",
                    sign * rate,
                    out.stop,
                    out.stats.steps,
                    watch.rolling_energy_drift,
                    watch.max_drift,
                    watch.theta_range
                );
                watch.assert_finite("huge spin");
                assert_eq!(out.stop, StopReason::EndTime);
                assert_eq!(watch.transitions, 0);
                assert!(watch.rolling_energy_drift <= bound);
                assert!(watch.max_drift <= bound);
                steps.push(out.stats.steps);
            }
            // The steps shrink with the rate: a hundredfold rate, at least tenfold the steps.
            assert!(steps[2] >= 10 * steps[0], "{kind:?}: {steps:?}");
        }
    }
}
