//! The reference (vector Newton–Euler, numeric LU) against the reduced explicit forms of
//! EQUATIONS.md at random states: two independent roads to the same derivatives.

mod common;

use common::explicit;
use common::scales;
use common::tracked::Tracked;
use common::{Agreement, Reach, Rng};
use equations::reference::{
    rolling, sliding_polar, RollingReference, SlidingCartesianReference, SlidingPolarReference,
};
use model_runtime::{Model, WithOutputs};

const STATES: usize = 3000;

#[test]
fn rolling_reference_matches_the_explicit_form() {
    let mut rng = Rng::new(11);
    let mut agreement = Agreement::default();
    for reach in [Reach::Typical, Reach::Extreme] {
        for _ in 0..STATES {
            let p = common::some_params(&mut rng);
            let y = common::rolling_state(&mut rng, &p, reach);
            let model = RollingReference::new(p).unwrap();
            let mut dy = [0.0; 12];
            model.rhs(0.0, &y, &mut dy).unwrap();
            let e = explicit::rolling::<Tracked>(&p, &y);
            let rows = scales::rolling(&p, &y, &e.dy.map(|x| x.v));
            agreement.check_derivatives(&common::ROLLING, &y, &dy, &e.dy, &rows);
            let mut out = [0.0; rolling::N_OUTPUTS];
            model.outputs(0.0, &y, &dy, &mut out).unwrap();
            for (i, x) in [
                (rolling::output::N, e.n),
                (rolling::output::R_X, e.r_x),
                (rolling::output::R_Y, e.r_y),
            ] {
                agreement.check(out[i], x.v, x.scale, || {
                    format!("{} at {y:?}", rolling::OUTPUT_NAMES[i])
                });
            }
        }
    }
    agreement.assert_within("rolling");
}

#[test]
fn sliding_polar_reference_matches_the_explicit_form() {
    let mut rng = Rng::new(12);
    let mut agreement = Agreement::default();
    for reach in [Reach::Typical, Reach::Extreme] {
        for _ in 0..STATES {
            let p = common::some_params(&mut rng);
            let y = common::sliding_state(&mut rng, &p, reach);
            let model = SlidingPolarReference::new(p).unwrap();
            let mut dy = [0.0; 12];
            model.rhs(0.0, &y, &mut dy).unwrap();
            let e = explicit::sliding_polar::<Tracked>(&p, &y);
            let rows = scales::sliding_polar(&p, &y, &e.dy.map(|x| x.v));
            agreement.check_derivatives(&common::POLAR, &y, &dy, &e.dy, &rows);
            let mut out = [0.0; sliding_polar::N_OUTPUTS];
            model.outputs(0.0, &y, &dy, &mut out).unwrap();
            for (i, x) in [
                (sliding_polar::output::N, e.n),
                (sliding_polar::output::R_X, e.r_x),
                (sliding_polar::output::R_Y, e.r_y),
                (sliding_polar::output::V_X, e.v_x),
                (sliding_polar::output::V_Y, e.v_y),
            ] {
                agreement.check(out[i], x.v, x.scale, || {
                    format!("{} at {y:?}", sliding_polar::OUTPUT_NAMES[i])
                });
            }
        }
    }
    agreement.assert_within("sliding polar");
}

#[test]
fn sliding_cartesian_reference_matches_the_explicit_form() {
    let mut rng = Rng::new(13);
    let mut agreement = Agreement::default();
    for reach in [Reach::Typical, Reach::Extreme] {
        for _ in 0..STATES {
            let p = common::some_params(&mut rng);
            let y = common::polar_to_cartesian(&common::sliding_state(&mut rng, &p, reach));
            let model = SlidingCartesianReference::new(p).unwrap();
            let mut dy = [0.0; 12];
            model.rhs(0.0, &y, &mut dy).unwrap();
            let e = explicit::sliding_cartesian::<Tracked>(&p, &y);
            let polar_y = common::cartesian_to_polar(&y);
            let polar_dy = explicit::sliding_polar::<f64>(&p, &polar_y).dy;
            let rows = scales::sliding_cartesian(&p, &polar_y, &polar_dy);
            agreement.check_derivatives(&common::CARTESIAN, &y, &dy, &e.dy, &rows);
        }
    }
    agreement.assert_within("sliding cartesian");
}
