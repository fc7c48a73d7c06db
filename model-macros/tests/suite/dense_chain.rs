//! Five rotors whose inertia couples every pair, `M(q) = 2 I + b C(q)` with
//! `C_ij = cos(q_i - q_j)` (a Gram matrix, so `M` is positive definite): one dense 5 x 5 block
//! with state-dependent coefficients, compiled twice: solved symbolically (the compiler's default)
//! and solved numerically at run time (`options { swell_bound = 0 }`). Both are checked against
//! nalgebra's LU, their Jacobians against finite differences.

use crate::common::{assert_jacobian_matches_differences, assert_same_derivatives};
use model_runtime::{EvalError, Model as _};
use nalgebra::{SMatrix, SVector};
use proptest::prelude::*;

/// One model text, compiled twice: with the compiler's default swell bound and with the
/// numeric solve forced.
macro_rules! dense_chain {
    ($name:ident $($options:tt)*) => {
        model_macros::model! {
            pub mod $name {
                params { b = 1.0, k = 2.0, f = 0.5 }
                $($options)*
                states { q1, q2, q3, q4, q5, w1, w2, w3, w4, w5 }
                let c12 = b * cos(q1 - q2);
                let c13 = b * cos(q1 - q3);
                let c14 = b * cos(q1 - q4);
                let c15 = b * cos(q1 - q5);
                let c23 = b * cos(q2 - q3);
                let c24 = b * cos(q2 - q4);
                let c25 = b * cos(q2 - q5);
                let c34 = b * cos(q3 - q4);
                let c35 = b * cos(q3 - q5);
                let c45 = b * cos(q4 - q5);
                let d = 2 + b;
                equations {
                    der(q1) = w1;
                    der(q2) = w2;
                    der(q3) = w3;
                    der(q4) = w4;
                    der(q5) = w5;
                    r1: d * der(w1) + c12 * der(w2) + c13 * der(w3) + c14 * der(w4) + c15 * der(w5) = -k * (q1 - q2) + f * sin(t);
                    r2: c12 * der(w1) + d * der(w2) + c23 * der(w3) + c24 * der(w4) + c25 * der(w5) = -k * (2 * q2 - q1 - q3);
                    r3: c13 * der(w1) + c23 * der(w2) + d * der(w3) + c34 * der(w4) + c35 * der(w5) = -k * (2 * q3 - q2 - q4);
                    r4: c14 * der(w1) + c24 * der(w2) + c34 * der(w3) + d * der(w4) + c45 * der(w5) = -k * (2 * q4 - q3 - q5);
                    r5: c15 * der(w1) + c25 * der(w2) + c35 * der(w3) + c45 * der(w4) + d * der(w5) = -k * (q5 - q4);
                }
            }
        }
    };
}

dense_chain!(dense_chain);
dense_chain!(dense_chain_numeric options { swell_bound = 0 });

fn hand_rhs(p: &[f64; 3], t: f64, y: &[f64; 10]) -> [f64; 10] {
    let [b, k, f] = *p;
    let q = &y[..5];
    let mass = SMatrix::<f64, 5, 5>::from_fn(|i, j| {
        if i == j {
            2.0 + b
        } else {
            b * (q[i] - q[j]).cos()
        }
    });
    let force = SVector::<f64, 5>::from_column_slice(&[
        -k * (q[0] - q[1]) + f * t.sin(),
        -k * (2.0 * q[1] - q[0] - q[2]),
        -k * (2.0 * q[2] - q[1] - q[3]),
        -k * (2.0 * q[3] - q[2] - q[4]),
        -k * (q[4] - q[3]),
    ]);
    let acc = mass
        .lu()
        .solve(&force)
        .expect("the mass matrix is positive definite");
    let mut dy = [0.0; 10];
    dy[..5].copy_from_slice(&y[5..]);
    dy[5..].copy_from_slice(acc.as_slice());
    dy
}

fn check_at(model: &impl model_runtime::Model<10>, p: &[f64; 3], t: f64, y: &[f64; 10]) {
    let mut dy = [0.0; 10];
    model.rhs(t, y, &mut dy).unwrap();
    assert_same_derivatives(&dy, &hand_rhs(p, t, y), &dense_chain::STATE_NAMES);
    assert_jacobian_matches_differences(model, t, y);
}

proptest! {
    #[test]
    fn derivatives_match_an_lu_solve(
        params in (0.0f64..3.0, 0.0f64..5.0, -2.0f64..2.0),
        q in proptest::array::uniform5(-4.0f64..4.0),
        w in proptest::array::uniform5(-3.0f64..3.0),
        t in -10.0f64..10.0,
    ) {
        let p = [params.0, params.1, params.2];
        let mut y = [0.0; 10];
        y[..5].copy_from_slice(&q);
        y[5..].copy_from_slice(&w);
        // The solves order their operations differently; the condition number of M (at most
        // (2 + 5b) / 2) keeps the rounding differences within the 1e-12 relative tolerance.
        check_at(&dense_chain::Model::new(p), &p, t, &y);
        check_at(&dense_chain_numeric::Model::new(p), &p, t, &y);
    }
}

#[test]
fn the_forced_variant_solves_its_block_numerically() {
    assert!(dense_chain::INFO.numeric_blocks.is_empty());
    let numeric = &dense_chain_numeric::INFO;
    assert_eq!(
        numeric.numeric_blocks.len(),
        1,
        "{:?}",
        numeric.numeric_blocks
    );
    for w in ["der(w1)", "der(w5)"] {
        assert!(
            numeric.numeric_blocks[0].contains(w),
            "{:?}",
            numeric.numeric_blocks
        );
    }
}

/// With all angles equal, `M = 2 I + b (ones)`, singular along `(1, ..., 1)` when `b = -2/5`.
#[test]
fn a_singular_mass_matrix_is_reported_never_a_nan() {
    let p = [-0.4, 1.0, 0.0];
    let y = [0.5; 10];
    let mut dy = [0.0; 10];
    for result in [
        dense_chain::Model::new(p).rhs(0.0, &y, &mut dy),
        dense_chain_numeric::Model::new(p).rhs(0.0, &y, &mut dy),
    ] {
        match result {
            Err(EvalError::SingularPivot { .. } | EvalError::NonFinite { .. }) => {}
            other => panic!("expected an error for a singular mass matrix, got {other:?} {dy:?}"),
        }
        assert!(dy.iter().all(|v| !v.is_nan()), "{dy:?}");
    }
}
