//! Small dense solves for code emitted by `model-macros`.
//!
//! Where the symbolic solution of a coupled block would swell, the compiler emits a call to
//! [`solve_block`] instead: Gaussian elimination with partial pivoting on a fixed-size array, so
//! the emitted right-hand side still allocates nothing. It is public only for the emitted code.

use crate::error::EvalError;

/// Solves `a x = b` by Gaussian elimination with partial pivoting.
///
/// A zero or non-finite pivot (the block is singular at this state) returns
/// [`EvalError::SingularPivot`] naming the block by `block` (its derivatives, e.g.
/// `der(V_X), der(V_Y)`) and carrying the pivot's value; the solution itself is not checked for
/// finiteness (the emitted code checks every derivative before returning).
///
/// ```
/// use model_runtime::solve_block;
/// let x = solve_block([[2.0, 1.0], [1.0, 3.0]], [3.0, 5.0], "demo", "der(a), der(b)").unwrap();
/// assert!((x[0] - 0.8).abs() < 1e-15 && (x[1] - 1.4).abs() < 1e-15);
/// ```
#[doc(hidden)]
#[inline]
pub fn solve_block<const N: usize>(
    mut a: [[f64; N]; N],
    mut b: [f64; N],
    model: &'static str,
    block: &'static str,
) -> Result<[f64; N], EvalError> {
    for col in 0..N {
        let mut best = col;
        for row in col + 1..N {
            if a[row][col].abs() > a[best][col].abs() {
                best = row;
            }
        }
        let pivot = a[best][col];
        if !(pivot != 0.0 && pivot.is_finite()) {
            return Err(EvalError::singular(model, block, pivot));
        }
        a.swap(col, best);
        b.swap(col, best);
        let inverse = 1.0 / pivot;
        for row in col + 1..N {
            let factor = a[row][col] * inverse;
            if factor == 0.0 {
                continue;
            }
            for k in col + 1..N {
                a[row][k] -= factor * a[col][k];
            }
            b[row] -= factor * b[col];
        }
    }
    let mut x = [0.0; N];
    for row in (0..N).rev() {
        let mut sum = b[row];
        for k in row + 1..N {
            sum -= a[row][k] * x[k];
        }
        x[row] = sum / a[row][row];
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn residual<const N: usize>(a: &[[f64; N]; N], x: &[f64; N], b: &[f64; N]) -> f64 {
        (0..N)
            .map(|i| {
                let ax: f64 = (0..N).map(|j| a[i][j] * x[j]).sum();
                (ax - b[i]).abs()
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn solves_a_system_that_needs_a_row_swap() {
        // The first pivot is zero: without pivoting this divides by zero.
        let a = [[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [3.0, 0.0, 1.0]];
        let x_true = [1.0, -2.0, 0.5];
        let b: [f64; 3] = std::array::from_fn(|i| (0..3).map(|j| a[i][j] * x_true[j]).sum());
        let x = solve_block(a, b, "m", "blk").unwrap();
        for i in 0..3 {
            assert!((x[i] - x_true[i]).abs() < 1e-14, "{x:?}");
        }
    }

    #[test]
    fn a_singular_block_is_named_never_nan() {
        let a = [[1.0, 2.0], [2.0, 4.0]];
        let error = solve_block(a, [1.0, 1.0], "m", "der(x), der(y)").unwrap_err();
        assert_eq!(
            error,
            EvalError::SingularPivot {
                model: "m".into(),
                pivot: "der(x), der(y)".into(),
                value: 0.0
            }
        );
    }

    #[test]
    fn a_nan_pivot_is_an_error() {
        let error = solve_block([[f64::NAN]], [1.0], "m", "der(x)").unwrap_err();
        assert!(matches!(error, EvalError::SingularPivot { value, .. } if value.is_nan()));
    }

    proptest! {
        #[test]
        fn residual_is_small_for_well_conditioned_systems(
            entries in proptest::array::uniform16(-1.0f64..1.0),
            rhs in proptest::array::uniform4(-10.0f64..10.0),
            shift in 0usize..4,
        ) {
            // Diagonally dominant, so well conditioned; rotating the rows moves the large
            // entries off the diagonal, so the elimination must pivot.
            let mut a = [[0.0; 4]; 4];
            for i in 0..4 {
                for j in 0..4 {
                    a[i][j] = entries[4 * i + j];
                }
                a[i][i] += if entries[5 * i % 16] < 0.0 { -5.0 } else { 5.0 };
            }
            a.rotate_left(shift);
            let mut rhs = rhs;
            rhs.rotate_left(shift);
            let x = solve_block(a, rhs, "m", "blk").unwrap();
            prop_assert!(residual(&a, &x, &rhs) < 1e-12);
        }
    }
}
