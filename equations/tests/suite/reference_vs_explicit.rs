//! The reference (vector Newton–Euler, numeric LU) against the reduced explicit forms of
//! docs/physics.md (§3.2, §4.2) at random states: two independent roads to the same derivatives.

use crate::common;
use crate::common::explicit;
use crate::common::scales;
use crate::common::tracked::Tracked;
use crate::common::{Agreement, Reach, Rng};
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

/// How often a relative error `size` in one derivative (cycling through the twelve) is caught
/// at typical rolling states: `(caught, tried)` per derivative.
fn detection(size: f64) -> [(usize, usize); 12] {
    let mut rng = Rng::new(14);
    let mut counts = [(0usize, 0usize); 12];
    for k in 0..STATES {
        let p = common::some_params(&mut rng);
        let y = common::rolling_state(&mut rng, &p, Reach::Typical);
        let mut dy = [0.0; 12];
        RollingReference::new(p)
            .unwrap()
            .rhs(0.0, &y, &mut dy)
            .unwrap();
        let i = k % 12;
        if dy[i] == 0.0 {
            continue;
        }
        dy[i] *= 1.0 + size;
        let e = explicit::rolling::<Tracked>(&p, &y);
        let rows = scales::rolling(&p, &y, &e.dy.map(|x| x.v));
        let mut agreement = Agreement::default();
        agreement.check_derivatives(&common::ROLLING, &y, &dy, &e.dy, &rows);
        counts[i].1 += 1;
        counts[i].0 += usize::from(agreement.worst > 1.0);
    }
    counts
}

/// The comparison is sharp: a relative error of 1e-10 in one derivative is caught at most
/// states, 1e-8 at nearly all. Not at every state: a derivative far smaller than the others of
/// its units (`Ω̇_x` or `Ω̇_z` next to `Ω̇_y ~ g/a`) is held only to ε of the largest one,
/// the norm-wise accuracy of any coupled solve (see `Agreement::check_derivative_pair`).
#[test]
fn small_errors_are_caught() {
    let fine = detection(1e-10);
    let coarse = detection(1e-8);
    for i in 0..12 {
        let name = rolling::STATE_NAMES[i];
        let ((f, ft), (c, ct)) = (fine[i], coarse[i]);
        println!("der({name}): 1e-10 caught {f}/{ft}, 1e-8 caught {c}/{ct}");
        assert!(
            f * 10 >= ft * 6,
            "der({name}): 1e-10 caught at only {f}/{ft} states"
        );
        assert!(
            c * 10 >= ct * 9,
            "der({name}): 1e-8 caught at only {c}/{ct} states"
        );
    }
}
