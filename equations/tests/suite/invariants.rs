//! Physical invariants of every implementation: the energy balance (docs/physics.md §8), the
//! steady motions, and `ν = μ_d` while sliding. Written once, run on each model family.

use crate::common;
use crate::common::dual::{energy_rate, Chart};
use crate::common::subject::{
    eval, CartesianGen, CartesianRef, Family, RollingGen, RollingRef, SlidingGen, SlidingRef,
    CARTESIAN_OUTPUTS, ROLLING_OUTPUTS, SLIDING_OUTPUTS,
};
use crate::common::{scales, Reach, Rng};
use equations::formulas::{self, BodyRates};
use equations::reference::{rolling, sliding_cartesian, sliding_polar};
use equations::DiskParams;
use nalgebra::Vector3;

const STATES: usize = 2000;

fn rates(y: &[f64; 12]) -> BodyRates {
    BodyRates {
        omega_x: y[9],
        omega_y: y[10],
        omega_z: y[11],
    }
}

/// Air power of one face, with the centre's normal velocity from the spatial velocity.
fn air_power(p: &DiskParams, y: &[f64; 12], v: Vector3<f64>) -> f64 {
    formulas::air_power(p, formulas::normal_velocity(y[6], y[7], &v), &rates(y))
}

fn params_with_air(rng: &mut Rng, air: bool) -> DiskParams {
    let p = common::some_params(rng);
    if air {
        DiskParams {
            mu_a: rng.uniform(0.1, 2.0),
            ..p
        }
    } else {
        DiskParams { mu_a: 0.0, ..p }
    }
}

fn rolling_energy_balance<F: Family<ROLLING_OUTPUTS>>(air: bool) {
    let mut rng = Rng::new(21 + air as u64);
    let mut agreement = common::Agreement::default();
    for reach in [Reach::Typical, Reach::Extreme] {
        for _ in 0..STATES {
            let p = params_with_air(&mut rng, air);
            let y = common::rolling_consistent_state(&mut rng, &p, reach);
            let e = eval(&F::build(&p), &y).unwrap();
            let rate = energy_rate(&p, Chart::Rolling, &y, &e.dy, &scales::rolling_full(&p, &y));
            let v = Vector3::new(y[3], y[4], y[5]);
            let energy = formulas::total_energy(&p, &v, &rates(&y), y[2]);
            let energy_scale = energy.abs() + 2.0 * (p.m * p.g * y[2]).abs();
            agreement.check(e.out[rolling::output::energy], energy, energy_scale, || {
                format!("{}: energy at {y:?}", F::NAME)
            });
            // Rolling: the contact force does no work; only air drains energy.
            let expected = air_power(&p, &y, Vector3::new(y[3], y[4], y[5]));
            agreement.check(rate.rate, expected, rate.scale, || {
                format!("{}: dE/dt at {y:?}", F::NAME)
            });
        }
    }
    agreement.assert_within(&format!("{} energy balance (air: {air})", F::NAME));
}

fn sliding_energy_balance<F: Family<SLIDING_OUTPUTS>>(air: bool) {
    let mut rng = Rng::new(23 + air as u64);
    let mut agreement = common::Agreement::default();
    for reach in [Reach::Typical, Reach::Extreme] {
        for _ in 0..STATES {
            let p = params_with_air(&mut rng, air);
            let y = common::sliding_consistent_state(&mut rng, &p, reach);
            let e = eval(&F::build(&p), &y).unwrap();
            let row = scales::sliding_polar_full(&p, &y);
            let rate = energy_rate(&p, Chart::SlidingPolar, &y, &e.dy, &row);
            let o = &e.out;
            let v = Vector3::new(
                o[sliding_polar::output::V_X],
                o[sliding_polar::output::V_Y],
                y[5],
            );
            let friction = formulas::friction_power(o[sliding_polar::output::T], y[3]);
            let expected = friction + air_power(&p, &y, v);
            // The friction power's own scale: T = μ_d m (V̇_Z + g), known to the size of its
            // terms, with V̇_Z known to its row scale.
            let t_scale = p.mu_d * p.m * (row[5].max(e.dy[5].abs()) + p.g.abs());
            let scale = rate.scale + t_scale * y[3].abs();
            agreement.check(rate.rate, expected, scale, || {
                format!("{}: dE/dt at {y:?}", F::NAME)
            });
            agreement.check(
                o[sliding_polar::output::friction_power],
                friction,
                friction.abs(),
                || format!("{}: friction power at {y:?}", F::NAME),
            );
            agreement.check(o[sliding_polar::output::nu], p.mu_d, p.mu_d, || {
                format!("{}: nu at {y:?}", F::NAME)
            });
        }
    }
    agreement.assert_within(&format!("{} energy balance (air: {air})", F::NAME));
}

fn cartesian_energy_balance<F: Family<CARTESIAN_OUTPUTS>>(air: bool) {
    let mut rng = Rng::new(25 + air as u64);
    let mut agreement = common::Agreement::default();
    for reach in [Reach::Typical, Reach::Extreme] {
        for _ in 0..STATES {
            let p = params_with_air(&mut rng, air);
            let polar = common::sliding_consistent_state(&mut rng, &p, reach);
            let y = common::polar_to_cartesian(&polar);
            let e = eval(&F::build(&p), &y).unwrap();
            let row = scales::sliding_cartesian_full(&p, &y);
            let rate = energy_rate(&p, Chart::SlidingCartesian, &y, &e.dy, &row);
            let o = &e.out;
            let out = sliding_cartesian::output::V_X;
            let v = Vector3::new(o[out], o[sliding_cartesian::output::V_Y], y[5]);
            let friction = formulas::friction_power(o[sliding_cartesian::output::T], polar[3]);
            let expected = friction + air_power(&p, &y, v);
            let t_scale = p.mu_d * p.m * (row[5].max(e.dy[5].abs()) + p.g.abs());
            let scale = rate.scale + t_scale * polar[3].abs();
            agreement.check(rate.rate, expected, scale, || {
                format!("{}: dE/dt at {y:?}", F::NAME)
            });
        }
    }
    agreement.assert_within(&format!("{} energy balance (air: {air})", F::NAME));
}

/// Steady motions (μ_a = 0): spinning in place and rolling on a circle keep θ and Ω fixed.
fn steady_motions<F: Family<ROLLING_OUTPUTS>>() {
    let mut rng = Rng::new(27);
    let mut agreement = common::Agreement::default();
    for _ in 0..500 {
        let p = DiskParams {
            mu_a: 0.0,
            ..common::some_params(&mut rng)
        };
        let theta0 = rng.uniform(0.01, std::f64::consts::PI - 0.01);
        let spin_rate = formulas::spinning_in_place_rate(&p, theta0).unwrap() * rng.sign();
        let precession = if rng.chance(0.5) {
            spin_rate
        } else {
            rng.sign() * rng.log_uniform(0.1, 200.0)
        };
        let omega_z = formulas::steady_circle_spin(&p, theta0, precession).unwrap();
        let mut y = [0.0; 12];
        y[6] = common::angle(&mut rng);
        y[7] = theta0;
        y[8] = common::angle(&mut rng);
        y[9] = -precession * theta0.sin();
        y[11] = omega_z;
        common::make_rolling_consistent(&p, &mut y);
        let e = eval(&F::build(&p), &y).unwrap();
        // The natural size of the angular accelerations here: the gyroscopic terms.
        let accel_scale = precession * precession + omega_z * omega_z + p.g / p.a;
        for i in [
            rolling::state::Omega_x,
            rolling::state::Omega_y,
            rolling::state::Omega_z,
        ] {
            agreement.check(e.dy[i], 0.0, accel_scale, || {
                format!("{}: der({}) at {y:?}", F::NAME, rolling::STATE_NAMES[i])
            });
        }
        let rate_scale = precession.abs() + omega_z.abs();
        agreement.check(e.dy[rolling::state::theta], 0.0, rate_scale, || {
            format!("{}: der(theta) at {y:?}", F::NAME)
        });
        agreement.check(e.dy[rolling::state::psi], precession, rate_scale, || {
            format!("{}: der(psi) at {y:?}", F::NAME)
        });
        let weight = p.m * p.g;
        let n = e.out[rolling::output::N];
        let force_scale = weight + p.m * p.a * accel_scale;
        agreement.check(n, weight, force_scale, || {
            format!("{}: N at {y:?}", F::NAME)
        });
        let friction = p.m * p.a * (omega_z * precession).abs();
        agreement.check(e.out[rolling::output::T], friction, force_scale, || {
            format!("{}: T at {y:?}", F::NAME)
        });
    }
    agreement.assert_within(&format!("{} steady motions", F::NAME));
}

#[test]
fn reference_rolling_conserves_energy_without_air() {
    rolling_energy_balance::<RollingRef>(false);
}

#[test]
fn reference_rolling_loses_energy_to_air_only() {
    rolling_energy_balance::<RollingRef>(true);
}

#[test]
fn reference_sliding_loses_energy_to_friction_and_air() {
    sliding_energy_balance::<SlidingRef>(false);
    sliding_energy_balance::<SlidingRef>(true);
}

#[test]
fn reference_cartesian_sliding_loses_energy_to_friction_and_air() {
    cartesian_energy_balance::<CartesianRef>(false);
    cartesian_energy_balance::<CartesianRef>(true);
}

#[test]
fn reference_steady_motions_are_steady() {
    steady_motions::<RollingRef>();
}

#[test]
fn generated_rolling_conserves_energy_without_air() {
    rolling_energy_balance::<RollingGen>(false);
}

#[test]
fn generated_rolling_loses_energy_to_air_only() {
    rolling_energy_balance::<RollingGen>(true);
}

#[test]
fn generated_sliding_loses_energy_to_friction_and_air() {
    sliding_energy_balance::<SlidingGen>(false);
    sliding_energy_balance::<SlidingGen>(true);
}

#[test]
fn generated_cartesian_sliding_loses_energy_to_friction_and_air() {
    cartesian_energy_balance::<CartesianGen>(false);
    cartesian_energy_balance::<CartesianGen>(true);
}

#[test]
fn generated_steady_motions_are_steady() {
    steady_motions::<RollingGen>();
}
