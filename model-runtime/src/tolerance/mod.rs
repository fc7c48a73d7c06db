//! The mixed relative/absolute error norm shared by every adaptive method.
//!
//! One norm for all methods keeps their tolerances comparable: a step is acceptable when the
//! root-mean-square of `err_i / scale_i` is at most one, with
//! `scale_i = atol_i + rtol_i * max(m_i(y0), m_i(y1))`. By default `m_i(y) = |y_i|`, each
//! component's own magnitude. Components declared as one vector ([`Tolerance::with_group`])
//! use the vector's Euclidean length instead: `m_i(y) = |y_G|` for every `i` in the group `G`
//! (`atol_i` and `rtol_i` stay per component). With equal tolerances across a group, its
//! contribution to the norm is then `|err_G|² / scale_G²`, unchanged by a rotation of the
//! vector and its error, i.e. independent of the frame the vector is written in
//! ([`groups`] explains why that matters).
//!
//! The component with the largest scaled error is remembered, so a failing run can name it;
//! on request ([`Tolerance::tracking_limiting`]) it is also determined for accepted steps, so a
//! driver can count which component limits the step size.

mod groups;

use crate::dim::{Const, Dim, Vector};
use crate::error::InputError;
pub use groups::{ComponentGroup, VectorGroups};
use std::ops::Range;

/// Whether the norm names the worst component of accepted steps too.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LimitingComponent {
    /// Only rejected steps name it (the common path does not search for it).
    #[default]
    Untracked,
    /// Every estimate names it, and the integrator counts it per accepted step
    /// ([`crate::Stats::limiting`]).
    Tracked,
}

/// Relative and absolute tolerances, one pair per state component, and the components that
/// form vectors.
#[derive(Clone, Debug, PartialEq)]
pub struct Tolerance<D: Dim> {
    /// Relative tolerances.
    pub rtol: Vector<D>,
    /// Absolute tolerances.
    pub atol: Vector<D>,
    groups: VectorGroups<D>,
    limiting: LimitingComponent,
}

/// A tolerance of a size known at compile time is a plain value.
impl<const N: usize> Copy for Tolerance<Const<N>> {}

impl<const N: usize> Tolerance<Const<N>> {
    /// The same tolerances for every component.
    pub fn scalar(rtol: f64, atol: f64) -> Self {
        Self::scalar_in(Const, rtol, atol)
    }
}

impl<D: Dim> Tolerance<D> {
    /// The same tolerances for every component of a state of size `dim`.
    pub fn scalar_in(dim: D, rtol: f64, atol: f64) -> Self {
        Self::per_component(dim.filled(rtol), dim.filled(atol))
    }

    /// Per-component tolerances.
    pub fn per_component(rtol: Vector<D>, atol: Vector<D>) -> Self {
        Tolerance {
            groups: VectorGroups::none(D::of(&rtol)),
            rtol,
            atol,
            limiting: LimitingComponent::Untracked,
        }
    }

    /// The same tolerances, with the components `range` scaled as one vector (see the module
    /// docs), in addition to the groups declared before. Fails with
    /// [`InputError::ComponentGroup`] on an empty or out-of-range group, or one that overlaps
    /// an earlier group.
    pub fn with_group(mut self, range: Range<usize>) -> Result<Self, InputError> {
        self.groups.push(range)?;
        Ok(self)
    }

    /// The same tolerances, naming the worst component of every estimate (a small cost per
    /// step) so that [`crate::Integrator`] counts it in [`crate::Stats::limiting`].
    pub fn tracking_limiting(self) -> Self {
        Tolerance {
            limiting: LimitingComponent::Tracked,
            ..self
        }
    }

    /// The size of the states this tolerance measures.
    #[inline(always)]
    pub fn dim(&self) -> D {
        D::of(&self.rtol)
    }

    /// The declared vector groups.
    pub fn groups(&self) -> &VectorGroups<D> {
        &self.groups
    }

    /// Whether accepted steps name their worst component.
    pub fn limiting(&self) -> LimitingComponent {
        self.limiting
    }

    /// Checks that every tolerance is finite and non-negative and that no component has both
    /// zero (which would demand an exact solution). The groups were checked when declared.
    pub fn validate(&self) -> Result<(), InputError> {
        if self.atol.as_ref().len() != self.rtol.as_ref().len() {
            return Err(InputError::Size {
                what: "absolute tolerance",
                expected: self.rtol.as_ref().len(),
                found: self.atol.as_ref().len(),
            });
        }
        for i in 0..self.dim().size() {
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

    /// The error scale of component `i` alone between two states of magnitude `a` and `b`
    /// (groups are not consulted; see [`Tolerance::scales`]).
    #[inline]
    pub fn scale(&self, i: usize, a: f64, b: f64) -> f64 {
        self.atol[i] + self.rtol[i] * a.abs().max(b.abs())
    }

    /// The error scale of every component between the states `y0` and `y1`, grouped
    /// components taking their vector's magnitude (module docs).
    #[inline]
    pub fn scales(&self, y0: &Vector<D>, y1: &Vector<D>) -> Vector<D> {
        let mut s = self.dim().zeros();
        for i in 0..self.dim().size() {
            s[i] = self.scale(i, y0[i], y1[i]);
        }
        for g in self.groups.iter() {
            let m = g.magnitude(y0.as_ref()).max(g.magnitude(y1.as_ref()));
            for i in g.range() {
                s[i] = self.scale(i, m, 0.0);
            }
        }
        s
    }

    /// The root-mean-square scaled norm of `v` with scales taken from `y0` and `y1`.
    pub fn norm(&self, v: &Vector<D>, y0: &Vector<D>, y1: &Vector<D>) -> ErrorEstimate {
        let s = self.scales(y0, y1);
        let n = self.dim().size();
        let mut sum = 0.0;
        for i in 0..n {
            let x = v[i] / s[i];
            sum += x * x;
        }
        let norm = if n == 0 { 0.0 } else { (sum / n as f64).sqrt() };
        self.estimate(norm, v, &s)
    }

    /// The estimate for a computed `norm` of `v` (scales `s`): NaN is reported as infinite,
    /// and the worst component is named when the step is rejected or when tracked.
    pub fn estimate(&self, norm: f64, v: &Vector<D>, s: &Vector<D>) -> ErrorEstimate {
        if norm <= 1.0 {
            // Accepted: which component is worst matters only for reports of failures and the
            // opt-in count, so the common path does not search for it.
            let worst = match self.limiting {
                LimitingComponent::Untracked => 0,
                LimitingComponent::Tracked => worst_scaled::<D>(v, s),
            };
            return ErrorEstimate { norm, worst };
        }
        // Rejected (or NaN, which counts as infinitely bad): name the worst component.
        ErrorEstimate {
            norm: if norm.is_nan() { f64::INFINITY } else { norm },
            worst: worst_scaled::<D>(v, s),
        }
    }

    /// The component of `v` with the largest scaled magnitude (a NaN one first).
    pub fn worst(&self, v: &Vector<D>, y0: &Vector<D>, y1: &Vector<D>) -> usize {
        worst_scaled::<D>(v, &self.scales(y0, y1))
    }
}

/// The component of `v` with the largest `|v_i / s_i|` (a NaN one first).
fn worst_scaled<D: Dim>(v: &Vector<D>, s: &Vector<D>) -> usize {
    let scaled = |i: usize| v[i] / s[i];
    let n = D::of(v).size();
    (0..n).find(|&i| scaled(i).is_nan()).unwrap_or_else(|| {
        (0..n)
            .max_by(|&a, &b| scaled(a).abs().total_cmp(&scaled(b).abs()))
            .unwrap_or(0)
    })
}

/// The scaled size of a local error estimate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorEstimate {
    /// Scaled norm: the step is acceptable when it is at most one. Never NaN (a NaN error is
    /// reported as infinite).
    pub norm: f64,
    /// The component with the largest scaled error; only determined when `norm > 1` or the
    /// tolerance tracks it ([`Tolerance::tracking_limiting`]); zero otherwise.
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
        let tol = Tolerance::<Const<3>>::scalar(0.0, 1.0);
        let e = tol.norm(&[1.0, -3.0, 2.0], &[0.0; 3], &[0.0; 3]);
        assert_eq!(e.worst, 1);
        assert!((e.norm - (14.0f64 / 3.0).sqrt()).abs() < 1e-15);
        let e = tol.norm(&[1.0, f64::NAN, 2.0], &[0.0; 3], &[0.0; 3]);
        assert_eq!(e.worst, 1);
        assert_eq!(e.norm, f64::INFINITY);
    }

    #[test]
    fn validation_names_the_component() {
        let mut tol = Tolerance::<Const<2>>::scalar(1e-6, 1e-9);
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
