//! The finiteness check every function `model-macros` emits ends with.
//!
//! An emitted right-hand side, Jacobian or output function must never hand back a NaN or an
//! infinity as a result: the first value that is not finite becomes an
//! [`EvalError::NonFinite`] naming it. The check is the same loop for all three, so it lives
//! here once and the emitted code calls it; it is public only for the emitted code.

use crate::error::EvalError;

/// `Ok` if every value is finite; otherwise [`EvalError::NonFinite`] for the first one that is
/// not, named by its entry in `names` (which runs parallel to `values`) and the model's `model`.
///
/// ```
/// use model_runtime::{check_finite, EvalError};
/// assert!(check_finite("m", &["der(x)", "der(v)"], &[1.0, 2.0]).is_ok());
/// let error = check_finite("m", &["der(x)", "der(v)"], &[1.0, f64::NAN]).unwrap_err();
/// assert!(matches!(error, EvalError::NonFinite { quantity, .. } if quantity == "der(v)"));
/// ```
#[doc(hidden)]
#[inline(always)]
pub fn check_finite(
    model: &'static str,
    names: &[&'static str],
    values: &[f64],
) -> Result<(), EvalError> {
    for (&quantity, value) in names.iter().zip(values) {
        if !value.is_finite() {
            return Err(EvalError::non_finite(model, quantity, *value));
        }
    }
    Ok(())
}
