//! Oscillations of a sampled signal: crossing times, period, per-cycle extremes.
//!
//! The paper reads the nutation period off θ (0.14 s at the start, 0.042 s at the end) and
//! draws envelopes of θ, v_C and N per oscillation. Both need the cycle boundaries, which we
//! take at the upward zero crossings of θ̇ (the minima of θ), located by cubic interpolation
//! through the four samples around each crossing. A Schmitt trigger (the signal must first
//! fall below −hysteresis) keeps noise near zero from counting extra cycles.

/// One sampled series: times (increasing) and values.
#[derive(Clone, Copy, Debug)]
pub struct Series<'a> {
    /// Times (s), increasing.
    pub t: &'a [f64],
    /// Values at those times.
    pub v: &'a [f64],
}

/// Where a cubic through four samples crosses zero between its middle two samples.
fn cubic_crossing(t: &[f64; 4], v: &[f64; 4]) -> f64 {
    let lagrange = |x: f64| {
        let mut sum = 0.0;
        for i in 0..4 {
            let mut w = v[i];
            for j in 0..4 {
                if i != j {
                    w *= (x - t[j]) / (t[i] - t[j]);
                }
            }
            sum += w;
        }
        sum
    };
    // Bisection on the bracket [t1, t2] (v1 < 0 <= v2 by construction); the cubic may have
    // other roots outside it, bisection cannot wander there.
    let (mut lo, mut hi) = (t[1], t[2]);
    let mut f_lo = lagrange(lo);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let f_mid = lagrange(mid);
        if (f_mid < 0.0) == (f_lo < 0.0) {
            lo = mid;
            f_lo = f_mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Times where the series crosses zero upwards, with hysteresis: after a crossing the signal
/// must fall below `-hysteresis` before the next counts.
pub fn upward_crossings(s: Series, hysteresis: f64) -> Vec<f64> {
    let n = s.t.len().min(s.v.len());
    let mut out = Vec::new();
    let mut armed = false;
    for i in 0..n.saturating_sub(1) {
        if s.v[i] < -hysteresis {
            armed = true;
        }
        if armed && s.v[i] < 0.0 && s.v[i + 1] >= 0.0 {
            let t = if i >= 1 && i + 2 < n {
                cubic_crossing(
                    &[s.t[i - 1], s.t[i], s.t[i + 1], s.t[i + 2]],
                    &[s.v[i - 1], s.v[i], s.v[i + 1], s.v[i + 2]],
                )
            } else {
                let f = s.v[i] / (s.v[i] - s.v[i + 1]);
                s.t[i] + f * (s.t[i + 1] - s.t[i])
            };
            out.push(t);
            armed = false;
        }
    }
    out
}

/// The mean period of the oscillation of `s` within `[t0, t1]`: the span between the first
/// and the last upward crossing divided by the number of cycles between them. `None` when
/// fewer than two crossings lie in the window. The hysteresis is 5% of the largest |value|
/// in the window.
pub fn mean_period(s: Series, t0: f64, t1: f64) -> Option<f64> {
    let lo = s.t.partition_point(|&t| t < t0);
    let hi = s.t.partition_point(|&t| t <= t1);
    if hi <= lo + 2 {
        return None;
    }
    let window = Series {
        t: &s.t[lo..hi],
        v: &s.v[lo..hi],
    };
    let peak = window.v.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let crossings = upward_crossings(window, 0.05 * peak);
    if crossings.len() < 2 {
        return None;
    }
    let cycles = (crossings.len() - 1) as f64;
    Some((crossings[crossings.len() - 1] - crossings[0]) / cycles)
}

/// The extremes of one cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CycleExtremes {
    /// Time of the cycle's largest value.
    pub t_max: f64,
    /// The largest value.
    pub max: f64,
    /// Time of the cycle's smallest value.
    pub t_min: f64,
    /// The smallest value.
    pub min: f64,
}

/// For each cycle between consecutive boundaries (`bounds`, increasing), the sample extremes
/// of `values` (sampled at `t`). Cycles without samples are skipped.
pub fn cycle_extremes(t: &[f64], values: &[f64], bounds: &[f64]) -> Vec<CycleExtremes> {
    let mut out = Vec::with_capacity(bounds.len());
    for w in bounds.windows(2) {
        let lo = t.partition_point(|&x| x < w[0]);
        let hi = t.partition_point(|&x| x < w[1]);
        let mut e: Option<CycleExtremes> = None;
        for i in lo..hi.min(values.len()) {
            let v = values[i];
            let c = e.get_or_insert(CycleExtremes {
                t_max: t[i],
                max: v,
                t_min: t[i],
                min: v,
            });
            if v > c.max {
                c.max = v;
                c.t_max = t[i];
            }
            if v < c.min {
                c.min = v;
                c.t_min = t[i];
            }
        }
        out.extend(e);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn damped(period: f64, rate: f64, t_end: f64, phase: f64) -> (Vec<f64>, Vec<f64>) {
        let omega = 2.0 * PI / period;
        let t: Vec<f64> = (0..=(t_end * rate) as usize)
            .map(|k| k as f64 / rate)
            .collect();
        let v = t
            .iter()
            .map(|&t| (-0.7 * t).exp() * (omega * t + phase).sin())
            .collect();
        (t, v)
    }

    #[test]
    fn period_of_a_damped_oscillation_is_exact() {
        // The zeros of exp(-λt) sin(ωt + φ) are exactly spaced by π/ω whatever λ is; what
        // remains is the cubic interpolation error, O((ωh)^4): about 1e-10 relative at 40+
        // samples per period of the run's sampling, 3e-8 at a coarse 97 Hz for 0.5 s.
        for (period, rate, tol) in [
            (0.14, 1000.0, 1e-9),
            (0.042, 1000.0, 1e-9),
            (0.042, 5000.0, 1e-11),
            (0.5, 97.0, 1e-7),
        ] {
            for phase in [0.0, 0.3, 2.0] {
                let (t, v) = damped(period, rate, 3.0, phase);
                let got = mean_period(Series { t: &t, v: &v }, 0.0, 3.0).unwrap();
                let rel = (got - period).abs() / period;
                assert!(
                    rel < tol,
                    "period {period} rate {rate}: got {got} ({rel:e})"
                );
            }
        }
    }

    #[test]
    fn crossings_are_the_zeros() {
        let (t, v) = damped(0.2, 1000.0, 1.0, 0.0);
        let c = upward_crossings(Series { t: &t, v: &v }, 0.01);
        // sin(ωt) rises through zero at t = k·period, k >= 1 (t = 0 is not armed).
        assert_eq!(c.len(), 4);
        for (k, tc) in c.iter().enumerate() {
            assert!((tc - 0.2 * (k + 1) as f64).abs() < 1e-10, "{tc}");
        }
    }

    #[test]
    fn hysteresis_ignores_noise_at_zero() {
        let t: Vec<f64> = (0..100).map(|k| k as f64).collect();
        let v: Vec<f64> = (0..100)
            .map(|k| if k % 2 == 0 { -1e-6 } else { 1e-6 })
            .collect();
        assert!(upward_crossings(Series { t: &t, v: &v }, 1e-3).is_empty());
    }

    #[test]
    fn too_short_windows_have_no_period() {
        let (t, v) = damped(0.5, 100.0, 0.6, 0.0);
        assert_eq!(mean_period(Series { t: &t, v: &v }, 0.0, 0.6), None);
        assert_eq!(mean_period(Series { t: &[], v: &[] }, 0.0, 1.0), None);
    }

    #[test]
    fn cycle_extremes_follow_the_decay() {
        let (t, v) = damped(0.1, 2000.0, 1.0, 0.0);
        let bounds: Vec<f64> = (0..=10).map(|k| k as f64 * 0.1).collect();
        let e = cycle_extremes(&t, &v, &bounds);
        assert_eq!(e.len(), 10);
        for w in e.windows(2) {
            assert!(w[1].max < w[0].max);
            assert!(w[1].min > w[0].min);
        }
        // First maximum near t = T/4 with value close to exp(-0.7 T/4).
        assert!((e[0].t_max - 0.025).abs() < 2e-3);
        assert!((e[0].max - (-0.7f64 * 0.025).exp()).abs() < 1e-3);
    }
}
