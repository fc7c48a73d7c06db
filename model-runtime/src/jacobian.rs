//! The Jacobian by central differences: the default of [`crate::Model::jacobian`] and of
//! [`crate::HybridSystem::jacobian`] for models and systems without a symbolic one.
//!
//! A leaf (it needs only [`EvalError`]), so that the model contract and the hybrid driver can
//! both fall back on it without depending on each other.

use crate::dim::{Dim, Matrix, Vector};
use crate::error::EvalError;

/// The model name a non-finite entry is reported under; [`crate::Model::jacobian`] replaces it
/// with the model's own.
pub(crate) const FD_MODEL: &str = "finite differences";

/// Central-difference Jacobian of `f` at `y`. An entry that is not finite (the right-hand
/// sides at `y ± h` overflow, or their difference does) is an [`EvalError::NonFinite`], never
/// an `Ok` with an infinite or NaN Jacobian.
pub fn finite_difference_jacobian<D: Dim>(
    mut f: impl FnMut(&Vector<D>, &mut Vector<D>) -> Result<(), EvalError>,
    y: &Vector<D>,
    jac: &mut Matrix<D>,
) -> Result<(), EvalError> {
    let dim = D::of(y);
    let mut yp = y.clone();
    let mut fp = dim.zeros();
    let mut fm = dim.zeros();
    for j in 0..dim.size() {
        let h = f64::EPSILON.cbrt() * y[j].abs().max(1.0);
        yp[j] = y[j] + h;
        f(&yp, &mut fp)?;
        yp[j] = y[j] - h;
        f(&yp, &mut fm)?;
        yp[j] = y[j];
        for i in 0..dim.size() {
            let entry = (fp[i] - fm[i]) / (2.0 * h);
            if !entry.is_finite() {
                return Err(EvalError::NonFinite {
                    model: FD_MODEL.into(),
                    quantity: "an entry of the Jacobian".into(),
                    value: entry,
                });
            }
            jac[i][j] = entry;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dim::Const;

    #[test]
    fn a_jacobian_that_overflows_is_an_error() {
        // Finite values on both sides whose difference overflows to -inf.
        let f = |y: &[f64; 1], dy: &mut [f64; 1]| {
            dy[0] = if y[0] > 0.0 { -f64::MAX } else { f64::MAX };
            Ok(())
        };
        let mut jac = [[0.0; 1]; 1];
        let result = finite_difference_jacobian::<Const<1>>(f, &[0.0], &mut jac);
        assert!(
            matches!(result, Err(EvalError::NonFinite { value, .. }) if value == f64::NEG_INFINITY),
            "{result:?}"
        );
        let linear = |y: &[f64; 1], dy: &mut [f64; 1]| {
            dy[0] = 3.0 * y[0];
            Ok(())
        };
        finite_difference_jacobian::<Const<1>>(linear, &[1.0], &mut jac).unwrap();
        assert!((jac[0][0] - 3.0).abs() < 1e-9);
    }
}
