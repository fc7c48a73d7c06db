//! The one linear-combination kernel every Runge–Kutta-type stepper uses: `y + h * Σ a_j k_j`
//! with the nonzero coefficients listed as `(stage, coefficient)` pairs, so each method's file
//! reads like its Butcher tableau.

use crate::dim::{Dim, Vector};

/// `out = y + h * Σ a_j k[j]` over the listed terms.
#[inline(always)]
pub(crate) fn combine<D: Dim>(
    y: &Vector<D>,
    h: f64,
    terms: &[(usize, f64)],
    k: &[Vector<D>],
    out: &mut Vector<D>,
) {
    sum::<D>(terms, k, out);
    let (y, out) = (y.as_ref(), out.as_mut());
    for i in 0..out.len() {
        out[i] = y[i] + h * out[i];
    }
}

/// `out = Σ a_j k[j]` over the listed terms.
#[inline(always)]
pub(crate) fn sum<D: Dim>(terms: &[(usize, f64)], k: &[Vector<D>], out: &mut Vector<D>) {
    // Stage by stage over whole vectors: contiguous, bounds-checked once per stage.
    let out = out.as_mut();
    out.fill(0.0);
    for &(j, a) in terms {
        let kj = k[j].as_ref();
        for (o, &kji) in out.iter_mut().zip(kj) {
            *o += a * kji;
        }
    }
}
