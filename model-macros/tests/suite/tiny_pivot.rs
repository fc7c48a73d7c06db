//! A pivot that is not an exact zero but round-off at the state (`sin(x)` at `x = π` is
//! 1.2e-16) is refused like a cancelling sum, under the same `pivot_tolerance`; a pivot that is
//! merely small (`sin(x)` at `x = 1e-20`) is not.

use model_runtime::{EvalError, Model as _};

model_macros::model! {
    mod tiny {
        states { x }
        equations { sin(x) * der(x) = 1; }
    }
}

model_macros::model! {
    mod exact_only {
        states { x }
        equations { sin(x) * der(x) = 1; }
        options { pivot_tolerance = 0 }
    }
}

fn rhs_at(x: f64) -> Result<f64, EvalError> {
    let mut dy = [0.0];
    tiny::Model::new([]).rhs(0.0, &[x], &mut dy)?;
    Ok(dy[0])
}

#[test]
fn sine_at_a_multiple_of_pi_is_a_singular_pivot() {
    for x in [
        std::f64::consts::PI,
        -std::f64::consts::PI,
        3.0 * std::f64::consts::PI,
    ] {
        match rhs_at(x) {
            Err(EvalError::SingularPivot { pivot, value, .. }) => {
                assert_eq!(pivot, "sin(x)");
                assert!(value.abs() < 1e-15, "{value}");
            }
            other => panic!("x = {x}: {other:?}"),
        }
    }
}

#[test]
fn small_but_exact_sines_are_accepted() {
    for x in [1e-20, 1e-300, 1e-6, std::f64::consts::PI - 1e-9] {
        let der = rhs_at(x).unwrap();
        assert!((der - 1.0 / x.sin()).abs() <= 1e-15 * der.abs(), "x = {x}");
    }
}

#[test]
fn zero_tolerance_tests_exact_zero_only() {
    let mut dy = [0.0];
    exact_only::Model::new([])
        .rhs(0.0, &[std::f64::consts::PI], &mut dy)
        .unwrap();
    assert!(dy[0] > 1e15, "{}", dy[0]);
    assert!(matches!(
        exact_only::Model::new([]).rhs(0.0, &[0.0], &mut dy),
        Err(EvalError::SingularPivot { .. })
    ));
}
