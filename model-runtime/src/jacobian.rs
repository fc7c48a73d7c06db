//! The Jacobian by central differences: the default of [`crate::Model::jacobian`] and of
//! [`crate::HybridSystem::jacobian`] for models and systems without a symbolic one.
//!
//! A leaf (it needs only [`EvalError`]), so that the model contract and the hybrid driver can
//! both fall back on it without depending on each other.

use crate::error::EvalError;

/// Central-difference Jacobian of `f` at `y`.
pub fn finite_difference_jacobian<const N: usize>(
    mut f: impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), EvalError>,
    y: &[f64; N],
    jac: &mut [[f64; N]; N],
) -> Result<(), EvalError> {
    let mut yp = *y;
    let mut fp = [0.0; N];
    let mut fm = [0.0; N];
    for j in 0..N {
        let h = f64::EPSILON.cbrt() * y[j].abs().max(1.0);
        yp[j] = y[j] + h;
        f(&yp, &mut fp)?;
        yp[j] = y[j] - h;
        f(&yp, &mut fm)?;
        yp[j] = y[j];
        for i in 0..N {
            jac[i][j] = (fp[i] - fm[i]) / (2.0 * h);
        }
    }
    Ok(())
}
