//! A step's interpolant kept after the step ([`StoredInterpolant`]) evaluates to the same bits
//! as the live one did, with every method, and stays so when the integrator moves on.

use crate::common::VanDerPol;
use model_runtime::{
    Const, Dop853, Dopri5, Integrator, Interpolant, Rk4, Rodas4, StepOptions, Stepper, Tolerance,
};

/// Times inside, at and beyond the ends of the step `[t0, t1]`.
fn probes(t0: f64, t1: f64) -> Vec<f64> {
    let h = t1 - t0;
    let mut ts = vec![t0 - h, t0, t1, t1 + h];
    ts.extend((1..16).map(|k| t0 + h * k as f64 / 16.0));
    ts
}

/// Takes a few steps of the stiff-ish Van der Pol oscillator with `stepper`; keeps the third
/// step's interpolant and checks it, bit for bit, against the live one, before and after two
/// more steps.
fn keeps_the_step<S: Stepper<Const<2>>>(stepper: S) {
    let model = VanDerPol { mu: 5.0 };
    let tol = Tolerance::scalar(1e-8, 1e-10);
    let mut it = Integrator::new(stepper, tol, StepOptions::default()).unwrap();
    it.restart(&model, 0.0, &[2.0, 0.0]).unwrap();
    for _ in 0..3 {
        it.step(&model, 10.0).unwrap();
    }
    it.ensure_dense(&model).unwrap();
    let live = it.dense().unwrap();
    let (t0, t1) = (live.t0, live.t1);
    let stored = Interpolant::stored(&live);
    let mut expected = Vec::new();
    for t in probes(t0, t1) {
        let mut y = [0.0; 2];
        live.at(t, &mut y);
        let component = live.component_at(t, 1);
        expected.push((t, y, component));
    }
    for _ in 0..2 {
        it.step(&model, 10.0).unwrap();
    }
    it.ensure_dense(&model).unwrap();
    let copy = stored.clone();
    for (t, y, component) in expected {
        let mut again = [f64::NAN; 2];
        copy.at(t, &mut again);
        assert_eq!(
            again.map(f64::to_bits),
            y.map(f64::to_bits),
            "{} at {t}",
            S::NAME
        );
        assert_eq!(copy.component_at(t, 1).to_bits(), component.to_bits());
    }
    // The live interpolant has moved on: the stored one is not a view of it.
    let mut now = [0.0; 2];
    it.dense().unwrap().at(0.5 * (t0 + t1), &mut now);
    let mut kept = [0.0; 2];
    copy.at(0.5 * (t0 + t1), &mut kept);
    assert_ne!(now, kept);
}

#[test]
fn a_stored_step_evaluates_as_the_live_one_with_every_method() {
    keeps_the_step(Dop853::new());
    keeps_the_step(Dopri5::new());
    keeps_the_step(Rodas4::new());
    keeps_the_step(Rk4::new(1e-3));
}
