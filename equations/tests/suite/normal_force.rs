//! The paper's closed forms for the normal force, eqs. (13)–(16), against every model.
//! Without air (`μ_a = 0`) they must agree to round-off; with air they must not (the closed
//! forms leave the air terms out), which shows the comparison can fail.

use crate::common;
use crate::common::subject::{
    eval, Family, RollingGen, RollingRef, SlidingGen, SlidingRef, ROLLING_OUTPUTS, SLIDING_OUTPUTS,
};
use crate::common::{scales, Reach, Rng};
use equations::formulas::{self, BodyRates};
use equations::reference::{rolling, sliding_polar};
use equations::DiskParams;

const STATES: usize = 3000;

fn rates(y: &[f64; 12]) -> BodyRates {
    BodyRates {
        omega_x: y[9],
        omega_y: y[10],
        omega_z: y[11],
    }
}

/// Size of the terms of `α1 + α2 / sin θ` (or `α3 + α4 / sin θ`), and of the model's `N/mg`
/// through the row scale of `V̇_Z` (`N = m (V̇_Z + g)`).
fn ratio_scale(p: &DiskParams, y: &[f64; 12], vz_row_scale: f64) -> f64 {
    let (s, c) = y[7].sin_cos();
    let w = rates(y);
    let ma2 = p.m * p.a * p.a;
    let terms = 1.0
        + p.a
            * c.abs()
            * ((p.C() + ma2) * (w.omega_x * w.omega_z).abs() + p.m * p.g * p.a * c.abs())
            / (p.g * p.A())
        + p.a * w.omega_y * w.omega_y * s.abs() / p.g
        + p.a * w.omega_x * w.omega_x * c * c / (p.g * s.abs());
    terms.max(1.0 + vz_row_scale / p.g)
}

fn rolling_normal_force<F: Family<ROLLING_OUTPUTS>>(mu_a: f64) -> common::Agreement {
    let mut rng = Rng::new(31);
    let mut agreement = common::Agreement::default();
    for reach in [Reach::Typical, Reach::Extreme] {
        for _ in 0..STATES {
            let p = DiskParams {
                mu_a,
                ..common::some_params(&mut rng)
            };
            let y = common::rolling_consistent_state(&mut rng, &p, reach);
            let e = eval(&F::build(&p), &y).unwrap();
            let model = e.out[rolling::output::N] / (p.m * p.g);
            let closed = formulas::rolling_normal_force_ratio(&p, y[7], &rates(&y)).unwrap();
            let scale = ratio_scale(&p, &y, scales::rolling_full(&p, &y)[5]);
            agreement.check(model, closed, scale, || {
                format!("{}: N/mg at {y:?}", F::NAME)
            });
        }
    }
    agreement
}

fn sliding_normal_force<F: Family<SLIDING_OUTPUTS>>(mu_a: f64) -> common::Agreement {
    let mut rng = Rng::new(32);
    let mut agreement = common::Agreement::default();
    for reach in [Reach::Typical, Reach::Extreme] {
        for _ in 0..STATES {
            let p = DiskParams {
                mu_a,
                ..common::some_params(&mut rng)
            };
            let y = common::sliding_consistent_state(&mut rng, &p, reach);
            let e = eval(&F::build(&p), &y).unwrap();
            let model = e.out[sliding_polar::output::N] / (p.m * p.g);
            let closed =
                formulas::sliding_normal_force_ratio(&p, y[7], y[4] - y[6], &rates(&y)).unwrap();
            let beta = formulas::beta0(&p, y[7], y[4] - y[6]);
            let scale = ratio_scale(&p, &y, scales::sliding_polar_full(&p, &y)[5])
                * (p.A() + p.m * p.a * p.a)
                / beta;
            agreement.check(model, closed, scale, || {
                format!("{}: N/mg at {y:?}", F::NAME)
            });
        }
    }
    agreement
}

fn differs_with_air(agreement: &common::Agreement, label: &str) {
    assert!(
        agreement.worst > 1e6,
        "{label}: with air the closed form should miss the air terms, worst ratio only {}",
        agreement.worst
    );
}

#[test]
fn reference_rolling_normal_force_is_eq_13() {
    rolling_normal_force::<RollingRef>(0.0).assert_within("rolling N/mg, eq. (13)");
}

#[test]
fn reference_sliding_normal_force_is_eq_15() {
    sliding_normal_force::<SlidingRef>(0.0).assert_within("sliding N/mg, eq. (15)");
}

#[test]
fn closed_forms_miss_the_air_terms() {
    differs_with_air(&rolling_normal_force::<RollingRef>(1.0), "rolling");
    differs_with_air(&sliding_normal_force::<SlidingRef>(1.0), "sliding");
}

#[test]
fn generated_rolling_normal_force_is_eq_13() {
    rolling_normal_force::<RollingGen>(0.0).assert_within("generated rolling N/mg, eq. (13)");
}

#[test]
fn generated_sliding_normal_force_is_eq_15() {
    sliding_normal_force::<SlidingGen>(0.0).assert_within("generated sliding N/mg, eq. (15)");
}

#[test]
fn generated_closed_forms_miss_the_air_terms() {
    differs_with_air(
        &rolling_normal_force::<RollingGen>(1.0),
        "generated rolling",
    );
    differs_with_air(
        &sliding_normal_force::<SlidingGen>(1.0),
        "generated sliding",
    );
}
