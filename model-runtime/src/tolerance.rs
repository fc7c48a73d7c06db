//! The mixed relative/absolute error norm shared by every adaptive method.
//!
//! One norm for all methods keeps their tolerances comparable: a step is acceptable when the
//! root-mean-square of `err_i / (atol_i + rtol_i * max(|y0_i|, |y1_i|))` is at most one.
//! The component with the largest scaled error is remembered, so a failing run can name it.

use crate::error::InputError;

/// Relative and absolute tolerances, one pair per state component.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance<const N: usize> {
    /// Relative tolerances.
    pub rtol: [f64; N],
    /// Absolute tolerances.
    pub atol: [f64; N],
}

impl<const N: usize> Tolerance<N> {
    /// The same tolerances for every component.
    pub fn scalar(rtol: f64, atol: f64) -> Self {
        Tolerance {
            rtol: [rtol; N],
            atol: [atol; N],
        }
    }

    /// Per-component tolerances.
    pub fn per_component(rtol: [f64; N], atol: [f64; N]) -> Self {
        Tolerance { rtol, atol }
    }

    /// Checks that every tolerance is finite and non-negative and that no component has both
    /// zero (which would demand an exact solution).
    pub fn validate(&self) -> Result<(), InputError> {
        for i in 0..N {
            let (r, a) = (self.rtol[i], self.atol[i]);
            let ok = r.is_finite() && a.is_finite() && r >= 0.0 && a >= 0.0 && (r > 0.0 || a > 0.0);
            if !ok {
                return Err(InputError::Tolerance {
                    component: i,
                    rtol: r,
                    atol: a,
                });
            }
        }
        Ok(())
    }

    /// The error scale of component `i` between two states of magnitude `a` and `b`.
    #[inline]
    pub fn scale(&self, i: usize, a: f64, b: f64) -> f64 {
        self.atol[i] + self.rtol[i] * a.abs().max(b.abs())
    }

    /// The root-mean-square scaled norm of `v` with scales taken from `y0` and `y1`.
    pub fn norm(&self, v: &[f64; N], y0: &[f64; N], y1: &[f64; N]) -> ErrorEstimate {
        let scaled = |i: usize| v[i] / self.scale(i, y0[i], y1[i]);
        let mut sum = 0.0;
        for i in 0..N {
            let s = scaled(i);
            sum += s * s;
        }
        let norm = if N == 0 { 0.0 } else { (sum / N as f64).sqrt() };
        if norm <= 1.0 {
            // Accepted: which component is worst matters only for reports of failures, so the
            // common path does not search for it.
            return ErrorEstimate { norm, worst: 0 };
        }
        // Rejected (or NaN, which counts as infinitely bad): name the worst component.
        ErrorEstimate {
            norm: if norm.is_nan() { f64::INFINITY } else { norm },
            worst: self.worst(v, y0, y1),
        }
    }

    /// The component of `v` with the largest scaled magnitude (a NaN one first).
    pub fn worst(&self, v: &[f64; N], y0: &[f64; N], y1: &[f64; N]) -> usize {
        let scaled = |i: usize| v[i] / self.scale(i, y0[i], y1[i]);
        (0..N).find(|&i| scaled(i).is_nan()).unwrap_or_else(|| {
            (0..N)
                .max_by(|&a, &b| scaled(a).abs().total_cmp(&scaled(b).abs()))
                .unwrap_or(0)
        })
    }
}

/// The scaled size of a local error estimate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorEstimate {
    /// Scaled norm: the step is acceptable when it is at most one. Never NaN (a NaN error is
    /// reported as infinite).
    pub norm: f64,
    /// The component with the largest scaled error; only determined when `norm > 1` (zero
    /// otherwise).
    pub worst: usize,
}

impl ErrorEstimate {
    /// The estimate of a method without error control: always acceptable.
    pub const NONE: ErrorEstimate = ErrorEstimate {
        norm: 0.0,
        worst: 0,
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn norm_names_the_worst_component_and_maps_nan_to_infinity() {
        let tol = Tolerance::<3>::scalar(0.0, 1.0);
        let e = tol.norm(&[1.0, -3.0, 2.0], &[0.0; 3], &[0.0; 3]);
        assert_eq!(e.worst, 1);
        assert!((e.norm - (14.0f64 / 3.0).sqrt()).abs() < 1e-15);
        let e = tol.norm(&[1.0, f64::NAN, 2.0], &[0.0; 3], &[0.0; 3]);
        assert_eq!(e.worst, 1);
        assert_eq!(e.norm, f64::INFINITY);
    }

    #[test]
    fn validation_names_the_component() {
        let mut tol = Tolerance::<2>::scalar(1e-6, 1e-9);
        assert!(tol.validate().is_ok());
        tol.atol[1] = -1.0;
        assert_eq!(
            tol.validate(),
            Err(InputError::Tolerance {
                component: 1,
                rtol: 1e-6,
                atol: -1.0
            })
        );
        tol.atol[1] = 0.0;
        tol.rtol[1] = 0.0;
        assert!(matches!(
            tol.validate(),
            Err(InputError::Tolerance { component: 1, .. })
        ));
    }
}
