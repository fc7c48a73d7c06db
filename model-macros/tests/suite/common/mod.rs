//! Checks shared by the end-to-end model tests.
#![allow(dead_code)]

use model_runtime::{EvalError, Model};

/// `|a - b| <= rel * max(|a|, |b|, 1)`, with a message naming the quantity.
pub fn assert_close(a: f64, b: f64, rel: f64, what: &str) {
    let scale = a.abs().max(b.abs()).max(1.0);
    assert!(
        (a - b).abs() <= rel * scale,
        "{what}: {a:e} vs {b:e} (difference {:e})",
        (a - b).abs()
    );
}

/// Compares two derivative vectors entry by entry at 1e-12 relative.
pub fn assert_same_derivatives<const N: usize>(
    generated: &[f64; N],
    hand: &[f64; N],
    names: &[&str],
) {
    for i in 0..N {
        assert_close(generated[i], hand[i], 1e-12, &format!("der({})", names[i]));
    }
}

/// The symbolic Jacobian against central finite differences of `rhs`.
pub fn assert_jacobian_matches_differences<const N: usize>(
    model: &impl Model<N>,
    t: f64,
    y: &[f64; N],
) {
    let mut jac = [[0.0; N]; N];
    model.jacobian(t, y, &mut jac).unwrap();
    let names = &model.info().state_names;
    for j in 0..N {
        let h = 1e-6 * y[j].abs().max(1.0);
        let (mut yp, mut ym) = (*y, *y);
        yp[j] += h;
        ym[j] -= h;
        let (mut fp, mut fm) = ([0.0; N], [0.0; N]);
        model.rhs(t, &yp, &mut fp).unwrap();
        model.rhs(t, &ym, &mut fm).unwrap();
        for i in 0..N {
            let difference = (fp[i] - fm[i]) / (2.0 * h);
            let what = format!("d der({}) / d {}", &names[i], &names[j]);
            assert_close(jac[i][j], difference, 1e-6, &what);
        }
    }
}

/// `rhs` fails with a singular pivot that `INFO` lists, and writes no NaN into `dy`.
pub fn assert_singular<const N: usize>(model: &impl Model<N>, t: f64, y: &[f64; N]) -> EvalError {
    let mut dy = [0.0; N];
    let error = model.rhs(t, y, &mut dy).unwrap_err();
    match &error {
        EvalError::SingularPivot {
            model: name,
            pivot,
            value,
        } => {
            assert_eq!(*name, model.info().name);
            assert!(
                model.info().pivots.contains(pivot) || model.info().numeric_blocks.contains(pivot),
                "`{pivot}` is not among the pivots {:?}",
                model.info().pivots
            );
            assert!(*value == 0.0 || !value.is_finite());
        }
        other => panic!("expected a singular pivot, got {other}"),
    }
    assert!(
        dy.iter().all(|v| !v.is_nan()),
        "a NaN leaked into dy: {dy:?}"
    );
    error
}
