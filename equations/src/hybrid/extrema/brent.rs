//! Brent's minimisation on a bracket, with the stopping width the extrema are located to:
//! apart from the scan so that the scan's file holds only the choice of brackets.

use super::X_TOL;

/// Brent's minimisation of `f` on `[a, c]`, starting from `b` inside with `f(b) = fb` below
/// both ends; stops when the bracket is [`X_TOL`] of its width (or a few ulps of `t`).
/// Returns the best point and its value.
pub fn brent(a: f64, b: f64, c: f64, fb: f64, mut f: impl FnMut(f64) -> f64) -> (f64, f64) {
    const GOLD: f64 = 0.381_966_011_250_105_1;
    let (mut lo, mut hi) = (a, c);
    let tol_abs = X_TOL * (c - a) + 4.0 * f64::EPSILON * b.abs();
    let (mut x, mut w, mut v) = (b, b, b);
    let (mut fx, mut fw, mut fv) = (fb, fb, fb);
    let (mut d, mut e) = (0.0f64, 0.0f64);
    for _ in 0..100 {
        let m = 0.5 * (lo + hi);
        let tol = tol_abs;
        if (x - m).abs() <= 2.0 * tol - 0.5 * (hi - lo) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol {
            // A parabola through x, w, v.
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            if p.abs() < (0.5 * q * e).abs() && p > q * (lo - x) && p < q * (hi - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - lo < 2.0 * tol || hi - u < 2.0 * tol {
                    d = if x < m { tol } else { -tol };
                }
                golden = false;
            }
        }
        if golden {
            e = if x >= m { lo - x } else { hi - x };
            d = GOLD * e;
        }
        let u = if d.abs() >= tol {
            x + d
        } else {
            x + tol.copysign(d)
        };
        let fu = f(u);
        if fu.is_nan() {
            break;
        }
        if fu <= fx {
            if u >= x {
                lo = x;
            } else {
                hi = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                lo = u;
            } else {
                hi = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    (x, fx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brent_finds_a_sharp_peak_to_the_curvature() {
        // A peak of width 1e-4 at an irrational time: N-like, 1/(w² + (t − t*)²).
        let (t_star, width) = (0.123_456_789_012_345, 1e-4);
        let peak = |t: f64| 1.0 / (width * width + (t - t_star).powi(2));
        let (a, c) = (0.1234, 0.1236);
        let b = 0.12345;
        let mut evals = 0;
        let (t, f) = brent(a, b, c, -peak(b), |t| {
            evals += 1;
            -peak(t)
        });
        // The time to the stopping width (X_TOL of the bracket); the value, flat at the top, to
        // the curvature times that width squared: round-off.
        assert!((t - t_star).abs() <= X_TOL * (c - a), "t = {t}");
        assert!(((-f) - peak(t_star)).abs() <= 1e-12 * peak(t_star), "{f}");
        assert!(evals < 60, "{evals} evaluations");
    }
}
