//! The runtime integrates the reference exactly as it integrates generated code: the same
//! wobbling rolling motion and the same sliding motion, from both, must agree to the
//! integration tolerance; rolling without air keeps its energy and stays on the contact
//! manifold, sliding loses energy monotonically.

use crate::common;
use crate::common::subject::{
    CartesianGen, CartesianRef, Family, RollingGen, RollingRef, SlidingGen, SlidingRef,
};
use equations::reference::{rolling, sliding_polar};
use equations::{formulas, DiskParams};
use model_runtime::{integrate, Dop853, Model, StepOptions, Tolerance, WithOutputs};

/// A steady circle, nudged so that it nutates.
fn wobbling_start(p: &DiskParams) -> [f64; 12] {
    let theta0: f64 = 0.6;
    let precession = 25.0;
    let mut y = [0.0; 12];
    y[rolling::state::theta] = theta0;
    y[rolling::state::Omega_x] = -precession * theta0.sin();
    y[rolling::state::Omega_y] = 0.5;
    y[rolling::state::Omega_z] = formulas::steady_circle_spin(p, theta0, precession).unwrap();
    common::make_rolling_consistent(p, &mut y);
    y
}

fn run<M: Model<12>>(model: &M, y0: &[f64; 12], t1: f64) -> [f64; 12] {
    let tol = Tolerance::scalar(1e-11, 1e-13);
    integrate(
        model,
        Dop853::new(),
        tol,
        StepOptions::default(),
        0.0,
        y0,
        t1,
    )
    .unwrap_or_else(|e| panic!("{}: {e:?}", model.info().name))
    .y
}

fn assert_same_motion(a: &[f64; 12], b: &[f64; 12], names: &[&str], tol: f64) {
    for i in 0..12 {
        let scale = a[i].abs().max(b[i].abs()).max(1e-3);
        assert!(
            (a[i] - b[i]).abs() <= tol * scale,
            "{}: {} vs {}",
            names[i],
            a[i],
            b[i]
        );
    }
}

#[test]
fn rolling_reference_and_generated_roll_alike() {
    let p = DiskParams::paper();
    let y0 = wobbling_start(&p);
    let (gen, refr) = (RollingGen::build(&p), RollingRef::build(&p));
    let (yg, yr) = (run(&gen, &y0, 1.0), run(&refr, &y0, 1.0));
    assert_same_motion(&yg, &yr, &rolling::STATE_NAMES, 1e-8);

    let outputs = |y: &[f64; 12]| {
        let mut dy = [0.0; 12];
        refr.rhs(0.0, y, &mut dy).unwrap();
        let mut out = [0.0; rolling::N_OUTPUTS];
        refr.outputs(0.0, y, &dy, &mut out).unwrap();
        out
    };
    let (start, end) = (outputs(&y0), outputs(&yr));
    let e0 = start[rolling::output::energy];
    let drift = (end[rolling::output::energy] - e0).abs() / e0.abs();
    assert!(drift < 1e-9, "energy drift {drift:e}");
    for i in [
        rolling::output::z_residual,
        rolling::output::vz_residual,
        rolling::output::vx_residual,
        rolling::output::vy_residual,
    ] {
        assert!(
            end[i].abs() < 1e-9,
            "{} = {:e}",
            rolling::OUTPUT_NAMES[i],
            end[i]
        );
    }
    // It did wobble: θ moved away from its start.
    assert!((yr[rolling::state::theta] - y0[rolling::state::theta]).abs() > 1e-3);
}

#[test]
fn sliding_reference_and_generated_slide_alike_in_both_charts() {
    let p = DiskParams::paper();
    let mut y0 = wobbling_start(&p);
    y0[sliding_polar::state::v_C] = 0.3;
    y0[sliding_polar::state::alpha] = 1.0;
    let t1 = 0.02; // well before the slip stops
    let (yg, yr) = (
        run(&SlidingGen::build(&p), &y0, t1),
        run(&SlidingRef::build(&p), &y0, t1),
    );
    assert_same_motion(&yg, &yr, &sliding_polar::STATE_NAMES, 1e-8);
    let yc0 = common::polar_to_cartesian(&y0);
    let ycg = run(&CartesianGen::build(&p), &yc0, t1);
    let ycr = run(&CartesianRef::build(&p), &yc0, t1);
    assert_same_motion(&ycg, &ycr, &sliding_polar::STATE_NAMES, 1e-8);
    assert_same_motion(
        &common::polar_to_cartesian(&yr),
        &ycr,
        &sliding_polar::STATE_NAMES,
        1e-8,
    );

    let energy = |y: &[f64; 12]| {
        let model = SlidingRef::build(&p);
        let mut dy = [0.0; 12];
        model.rhs(0.0, y, &mut dy).unwrap();
        let mut out = [0.0; sliding_polar::N_OUTPUTS];
        model.outputs(0.0, y, &dy, &mut out).unwrap();
        out[sliding_polar::output::energy]
    };
    let mut last = energy(&y0);
    for k in 1..=4 {
        let e = energy(&run(&SlidingRef::build(&p), &y0, t1 * k as f64 / 4.0));
        assert!(e < last, "energy rose while sliding: {last} -> {e}");
        last = e;
    }
}
