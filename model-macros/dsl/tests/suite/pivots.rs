//! The relative singular-pivot test: a pivot that has cancelled to round-off is refused, a pivot
//! that is merely small is not.

use crate::common::model;
use model_algebra::CompiledModel;
use model_algebra::{compile, CompileOptions, PIVOT_TOLERANCE};
use model_algebra::{EvalFailure, Inputs};

const MODEL: &str = "
mod m {
    params { eps = 1e-3 }
    states { x, y }
    equations {
        a: (x - y)*der(x) = 1;
        b: eps*der(y) = 1;
    }
}
";

fn rhs(m: &CompiledModel, x: f64, y: f64, eps: f64) -> Result<Vec<f64>, EvalFailure> {
    let inputs = Inputs {
        t: 0.0,
        states: &[x, y],
        params: &[eps],
        ders: &[],
    };
    Ok(m.rhs.eval(&inputs)?.ders(2))
}

#[test]
fn a_cancelled_difference_is_singular_and_a_small_parameter_is_not() {
    let m = compile(&model(MODEL), &CompileOptions::default()).unwrap();
    assert_eq!(m.pivots, vec!["x - y", "eps"]);
    // x - y keeps 1 digit in 16: its value is round-off, not a pivot.
    let y = 1.0 + 4.0 * f64::EPSILON;
    assert!((1.0 - y) != 0.0);
    assert_eq!(
        rhs(&m, 1.0, y, 1e-3),
        Err(EvalFailure::SingularPivot {
            text: "x - y".into(),
            value: 1.0 - y
        })
    );
    // A difference of 1e-9 has seven digits left: a large but honest derivative.
    let d = rhs(&m, 1.0, 1.0 + 1e-9, 1e-3).unwrap();
    assert!((d[0] * -1e-9 - 1.0).abs() < 1e-6, "{d:?}");
    // A pivot that is a tiny parameter is exact, however small.
    let d = rhs(&m, 1.0, 2.0, 1e-300).unwrap();
    assert_eq!(d[0], -1.0);
    assert!((d[1] / 1e300 - 1.0).abs() < 1e-15, "{d:?}");
    // Either side of the boundary |x - y| = tolerance * (|x| + |y|) ≈ 2 tolerance.
    let (just_in, just_out) = (1.0 + 3.0 * PIVOT_TOLERANCE, 1.0 + PIVOT_TOLERANCE);
    assert!(rhs(&m, 1.0, just_in, 1e-3).is_ok());
    assert!(rhs(&m, 1.0, just_out, 1e-3).is_err());
}

#[test]
fn a_zero_tolerance_tests_exact_zero_only() {
    let options = CompileOptions {
        pivot_tolerance: 0.0,
        ..CompileOptions::default()
    };
    let m = compile(&model(MODEL), &options).unwrap();
    let y = 1.0 + 4.0 * f64::EPSILON;
    assert!(rhs(&m, 1.0, y, 1e-3).unwrap()[0].abs() > 1e15);
    assert!(matches!(
        rhs(&m, 1.0, 1.0, 1e-3),
        Err(EvalFailure::SingularPivot { value, .. }) if value == 0.0
    ));
    // No cancellation tests are emitted, so they cost nothing.
    let default = compile(&model(MODEL), &CompileOptions::default()).unwrap();
    let (with, without) = (default.rhs.ops(), m.rhs.ops());
    assert_eq!((with.add - without.add, with.mul - without.mul), (1, 1));
}

#[test]
fn sums_of_one_sign_and_factors_are_tested_where_they_can_cancel() {
    // The pivot `k*(x^2 + y^2)*(x - y)` can only cancel in its last factor.
    let m = compile(
        &model("mod m { params { k = 2 } states { x } equations { a: k*(x^2 + 1)*(x - 3)*der(x) = 1; } }"),
        &CompileOptions::default(),
    )
    .unwrap();
    let text = m.rhs.to_string();
    assert_eq!(
        text.matches('|').count(),
        2,
        "one cancellation test:\n{text}"
    );
    let run = |x: f64| {
        m.rhs.eval(&Inputs {
            t: 0.0,
            states: &[x],
            params: &[2.0],
            ders: &[],
        })
    };
    assert!(run(3.0 * (1.0 + f64::EPSILON)).is_err());
    assert!(run(3.001).is_ok());
}

/// The double pendulum in mass-matrix form, with a massless upper rod.
const DOUBLE_PENDULUM: &str = "
pub mod dp {
    params { m1 = 0.0, m2 = 0.7, l1 = 1.0, l2 = 0.6, g = 9.81 }
    states { th1, th2, om1, om2 }
    let d = th1 - th2;
    equations {
        der(th1) = om1;
        der(th2) = om2;
        (m1 + m2)*l1^2*der(om1) + m2*l1*l2*cos(d)*der(om2)
            = -m2*l1*l2*sin(d)*om2^2 - (m1 + m2)*g*l1*sin(th1);
        m2*l1*l2*cos(d)*der(om1) + m2*l2^2*der(om2) = m2*l1*l2*sin(d)*om1^2 - m2*g*l2*sin(th2);
    }
}
";

#[test]
fn a_determinant_cancelled_by_a_zero_mass_is_singular() {
    // The pivot is emitted as `m1 + m2*(1 - cos(d)^2)` (`m2` pulled out): with `m1 = 0` the
    // cancellation is inside the term, and is measured against the terms before the factoring.
    let m = compile(&model(DOUBLE_PENDULUM), &CompileOptions::default()).unwrap();
    assert_eq!(m.pivots[1], "l1^2*(m1 + m2 - m2*cos(th1 - th2)^2)");
    let run = |m1: f64, th1: f64| {
        m.rhs.eval(&Inputs {
            t: 0.0,
            states: &[th1, 0.5, 0.0, 0.0],
            params: &[m1, 0.7, 1.0, 0.6, 9.81],
            ders: &[],
        })
    };
    // At th1 - th2 = 1e-7 the determinant's `1 - cos(d)^2` has 2 digits left of 16.
    assert!(
        matches!(run(0.0, 0.5000001), Err(EvalFailure::SingularPivot { ref text, .. }) if *text == m.pivots[1]),
        "{:?}",
        run(0.0, 0.5000001)
    );
    assert!(run(0.0, 0.5001).is_ok());
    // With a massive upper rod the determinant is `m1` plus a round-off-sized term: accurate,
    // however aligned the rods (exactly aligned included).
    for th1 in [0.5000001, 0.5] {
        assert!(run(1.0, th1).is_ok(), "{th1}: {:?}", run(1.0, th1));
    }
}
