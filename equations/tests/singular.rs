//! Singular and bad states give typed errors naming the pivot, never NaN: the flat disk
//! (`sin θ = 0`), zero slip in the slip charts, the sliding determinant `β0 = 0`, and
//! non-finite input. Bad parameters are rejected by name before any model is built.

mod common;

use common::subject::{
    eval, CartesianGen, CartesianRef, Family, RollingGen, RollingRef, SlidingGen, SlidingRef,
};
use equations::formulas;
use equations::reference::{RollingReference, SlidingPolarReference, Slip};
use equations::{DiskParams, ParamError};
use model_runtime::{EvalError, Model};
use std::f64::consts::PI;

fn a_state() -> [f64; 12] {
    let p = DiskParams::paper();
    let theta: f64 = 0.6;
    [
        0.1,
        -0.2,
        p.a * theta.sin(),
        0.3,
        -0.1,
        0.05,
        0.4,
        theta,
        1.0,
        2.0,
        -1.5,
        7.0,
    ]
}

fn pivot_of<M: Model<12>>(model: &M, y: &[f64; 12]) -> String {
    let mut dy = [0.0; 12];
    match model.rhs(0.0, y, &mut dy) {
        Err(EvalError::SingularPivot { pivot, value, .. }) => {
            assert!(
                value == 0.0 || !value.is_finite() || value.abs() < 1e-12,
                "{pivot} = {value}"
            );
            pivot.to_string()
        }
        other => panic!(
            "{}: expected a singular pivot at {y:?}, got {other:?} with {dy:?}",
            model.info().name
        ),
    }
}

#[test]
fn a_flat_disk_is_singular_in_every_model() {
    let p = DiskParams::paper();
    let mut y = a_state();
    y[7] = 0.0;
    assert_eq!(pivot_of(&RollingRef::build(&p), &y), "sin(theta)");
    assert_eq!(pivot_of(&SlidingRef::build(&p), &y), "sin(theta)");
    assert_eq!(pivot_of(&CartesianRef::build(&p), &y), "sin(theta)");
    assert!(pivot_of(&RollingGen::build(&p), &y).contains("sin(theta)"));
    assert!(pivot_of(&SlidingGen::build(&p), &y).contains("sin(theta)"));
    assert!(pivot_of(&CartesianGen::build(&p), &y).contains("sin(theta)"));
}

#[test]
fn zero_slip_is_singular_in_the_slip_charts() {
    let p = DiskParams::paper();
    let mut y = a_state();
    y[3] = 0.0;
    y[4] = 0.0;
    assert_eq!(pivot_of(&SlidingRef::build(&p), &y), "v_C");
    assert_eq!(pivot_of(&CartesianRef::build(&p), &y), "v_C");
    assert!(pivot_of(&SlidingGen::build(&p), &y).contains("v_C"));
    // The generated Cartesian model divides by |u| inside its coefficients (the chain rule of
    // `v_C` and `alpha`), not at a solve pivot: it must refuse the state, by either error.
    let mut dy = [0.0; 12];
    match CartesianGen::build(&p).rhs(0.0, &y, &mut dy) {
        Err(EvalError::SingularPivot { pivot, .. }) => {
            assert!(pivot.contains("u_X") || pivot.contains("u_Y"), "{pivot}")
        }
        Err(EvalError::NonFinite { quantity, .. }) => {
            assert!(quantity.contains("der("), "{quantity}")
        }
        Ok(()) => panic!("generated cartesian model accepted u = 0: {dy:?}"),
    }
    // The onset helper stays regular there.
    let onset = SlidingPolarReference::new(p)
        .unwrap()
        .slip_acceleration(
            &y,
            Slip {
                speed: 0.0,
                alpha: 1.0,
            },
        )
        .unwrap();
    assert!(onset.along.is_finite() && onset.across.is_finite());
}

/// `β0 = A + m a² cos θ (μ_d cos(α - ψ) sin θ + cos θ)` vanishes only for large friction;
/// find such a state by bisection and check both sliding models refuse it.
#[test]
fn the_painleve_determinant_is_a_named_pivot() {
    let p = DiskParams {
        mu_d: 3.0,
        mu_st: 3.0,
        ..DiskParams::paper()
    };
    // With cos(α - ψ) = -1, β0(θ) / m a² = 1/4 + cos²θ - 3 sin θ cos θ: -3/4 at π/4, 1/4 at π/2.
    let (mut lo, mut hi) = (PI / 4.0, PI / 2.0);
    assert!(formulas::beta0(&p, lo, PI) < 0.0 && formulas::beta0(&p, hi, PI) > 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if formulas::beta0(&p, mid, PI) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let mut y = a_state();
    y[7] = hi;
    y[6] = 0.2;
    y[4] = 0.2 + PI;
    assert_eq!(pivot_of(&SlidingRef::build(&p), &y), "beta0");
    // The generated models test their pivots for exact zero (DSL.md), which a bisected root
    // does not reach; they must at least check β0 among their pivots.
    for info in [
        &equations::models::sliding::INFO,
        &equations::models::sliding_cartesian::INFO,
    ] {
        let beta = info
            .pivots
            .iter()
            .find(|p| p.contains("mu_d") && p.contains("cos(theta)"));
        assert!(
            beta.is_some(),
            "{}: no beta0 pivot among {:?}",
            info.name,
            info.pivots
        );
    }
}

#[test]
fn non_finite_input_is_an_error_not_a_nan() {
    let p = DiskParams::paper();
    // Every slot for the reference (it checks its input); the slots that feed the
    // derivatives for the generated models.
    for k in [0, 3, 7, 9, 11] {
        let mut y = a_state();
        y[k] = f64::NAN;
        let check = |r: Result<(), EvalError>, dy: &[f64; 12], name: &str| match r {
            Err(_) => {}
            Ok(()) => panic!("{name}: NaN in slot {k} gave {dy:?}"),
        };
        let mut dy = [0.0; 12];
        check(
            RollingRef::build(&p).rhs(0.0, &y, &mut dy),
            &dy,
            "rolling reference",
        );
        check(
            SlidingRef::build(&p).rhs(0.0, &y, &mut dy),
            &dy,
            "sliding reference",
        );
        check(
            CartesianRef::build(&p).rhs(0.0, &y, &mut dy),
            &dy,
            "cartesian reference",
        );
        if k == 0 {
            continue;
        }
        check(
            RollingGen::build(&p).rhs(0.0, &y, &mut dy),
            &dy,
            "rolling generated",
        );
        check(
            SlidingGen::build(&p).rhs(0.0, &y, &mut dy),
            &dy,
            "sliding generated",
        );
        check(
            CartesianGen::build(&p).rhs(0.0, &y, &mut dy),
            &dy,
            "cartesian generated",
        );
    }
}

#[test]
fn outputs_never_report_nan() {
    // Zero normal force makes ν = T/N undefined: an error naming `nu`, never a NaN.
    let p = DiskParams::paper();
    let model = RollingReference::new(p).unwrap();
    let y = a_state();
    let e = eval(&model, &y).unwrap();
    assert!(e.out.iter().all(|x| x.is_finite()));
    let mut out = [0.0; 11];
    let mut dy = e.dy;
    dy[5] = -p.g; // free fall: N = m (V̇_Z + g) = 0
    let err = model_runtime::WithOutputs::outputs(&model, 0.0, &y, &dy, &mut out).unwrap_err();
    assert!(
        matches!(err, EvalError::NonFinite { quantity: "nu", .. }),
        "{err:?}"
    );
}

#[test]
fn bad_parameters_are_refused_by_name() {
    let bad = DiskParams {
        a: -0.01,
        ..DiskParams::paper()
    };
    assert_eq!(
        RollingReference::new(bad).unwrap_err(),
        ParamError::NotPositive {
            name: "a",
            value: -0.01
        }
    );
    assert!(SlidingPolarReference::new(DiskParams {
        mu_a: f64::NAN,
        ..DiskParams::paper()
    })
    .is_err());
}

/// Evaluates `rhs` and then `outputs`; any `Ok` must hold only finite numbers.
fn number_or_error<M: model_runtime::WithOutputs<12, K>, const K: usize>(
    model: &M,
    y: &[f64; 12],
) -> Result<(), String> {
    let mut dy = [0.0; 12];
    if model.rhs(0.0, y, &mut dy).is_err() {
        return Ok(());
    }
    if dy.iter().any(|v| !v.is_finite()) {
        return Err(format!("{}: rhs gave {dy:?}", model.info().name));
    }
    let mut out = [0.0; K];
    if model.outputs(0.0, y, &dy, &mut out).is_ok() && out.iter().any(|v| !v.is_finite()) {
        return Err(format!("{}: outputs gave {out:?}", model.info().name));
    }
    Ok(())
}

fn any_number() -> impl proptest::strategy::Strategy<Value = f64> {
    use proptest::prelude::*;
    prop_oneof![
        -10.0..10.0f64,
        -1e3..1e3f64,
        prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO,
    ]
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(3000))]

    /// Any finite state, however absurd: a number or a typed error, never NaN or infinity.
    #[test]
    fn every_model_answers_a_number_or_an_error(y in proptest::array::uniform12(any_number())) {
        let p = DiskParams::paper();
        for result in [
            number_or_error(&RollingRef::build(&p), &y),
            number_or_error(&SlidingRef::build(&p), &y),
            number_or_error(&CartesianRef::build(&p), &y),
            number_or_error(&RollingGen::build(&p), &y),
            number_or_error(&SlidingGen::build(&p), &y),
            number_or_error(&CartesianGen::build(&p), &y),
        ] {
            proptest::prop_assert!(result.is_ok(), "{}", result.unwrap_err());
        }
    }
}
