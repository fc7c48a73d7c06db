//! The one linear-combination kernel every Runge–Kutta-type stepper uses: `y + h * Σ a_j k_j`
//! with the nonzero coefficients listed as `(stage, coefficient)` pairs, so each method's file
//! reads like its Butcher tableau.

/// `out = y + h * Σ a_j k[j]` over the listed terms.
#[inline(always)]
pub(crate) fn combine<const N: usize>(
    y: &[f64; N],
    h: f64,
    terms: &[(usize, f64)],
    k: &[[f64; N]],
    out: &mut [f64; N],
) {
    let mut acc = [0.0; N];
    sum(terms, k, &mut acc);
    for i in 0..N {
        out[i] = y[i] + h * acc[i];
    }
}

/// `out = Σ a_j k[j]` over the listed terms.
#[inline(always)]
pub(crate) fn sum<const N: usize>(terms: &[(usize, f64)], k: &[[f64; N]], out: &mut [f64; N]) {
    // Stage by stage over whole vectors: contiguous, bounds-checked once per stage.
    *out = [0.0; N];
    for &(j, a) in terms {
        let kj = &k[j];
        for i in 0..N {
            out[i] += a * kj[i];
        }
    }
}
