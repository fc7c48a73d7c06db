//! Axis ranges, tick labels and time ranges in titles: the numbers around a chart's data.
//!
//! They are pure functions so that what a figure prints can be tested without drawing it:
//! a tick at a float-noise distance from zero reads `0`, a time axis spans the time the figure
//! covers (not only the instants where it happens to have points), and every title writes a
//! time range the same way.

use std::ops::Range;

/// A tick value closer to zero than this fraction of the axis span is zero: tick positions are
/// sums of float steps, so a zero tick arrives as e.g. `-5.6e-17`.
const ZERO_TICK: f64 = 1e-9;

/// The largest magnitude an axis bound may have: the span of an axis between `-AXIS_MAX` and
/// `AXIS_MAX` (and the steps of its ticks) stays finite. Values beyond it are clipped.
const AXIS_MAX: f64 = f64::MAX / 8.0;

/// The range of the finite values of `values`, padded by 5% (or by 1 when flat). On a
/// logarithmic axis only positive values count, and the range is widened by a factor 1.5.
/// Without any such value: `0..1`, or `1e-6..1` on a logarithmic axis. The bounds lie within
/// `±f64::MAX / 8` whatever the values, so that the span is finite (an infinite one never
/// finishes drawing).
pub fn padded_range(values: impl Iterator<Item = f64>, log: bool) -> Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .map(|v| v.clamp(-AXIS_MAX, AXIS_MAX))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
    if !lo.is_finite() {
        return if log { 1e-6..1.0 } else { 0.0..1.0 };
    }
    if log {
        return lo / 1.5..(hi * 1.5).min(AXIS_MAX);
    }
    let pad = if hi > lo {
        0.05 * (hi - lo)
    } else {
        1.0f64.max(hi.abs() * 0.1)
    };
    (lo - pad).max(-AXIS_MAX)..(hi + pad).min(AXIS_MAX)
}

/// The extent of `values` without padding (for a time axis drawn edge to edge), or `None`
/// without any finite value. A single instant `t` becomes `t - 0.5..t + 0.5`.
pub fn data_range(values: impl Iterator<Item = f64>) -> Option<Range<f64>> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
    lo.is_finite().then(|| usable_span(lo, hi))
}

/// `start..end` if it is a usable axis (finite, `start < end`); a degenerate or reversed span
/// becomes one unit wide around its start.
pub fn usable_span(start: f64, end: f64) -> Range<f64> {
    if start.is_finite() && end.is_finite() && start < end {
        start..end
    } else {
        let s = if start.is_finite() { start } else { 0.0 };
        s - 0.5..s + 0.5
    }
}

/// A tick label on an axis spanning `span`: exponent notation on a logarithmic axis and for
/// extreme magnitudes, the shortest plain form otherwise (no `0.30000000000000004`), and `0`
/// for a tick that is zero up to float noise (below 1e-9 of the span).
pub fn tick_label(v: f64, log: bool, span: f64) -> String {
    let a = v.abs();
    if v == 0.0 || (!log && a <= ZERO_TICK * span.abs()) {
        "0".to_string()
    } else if log || !(1e-3..1e5).contains(&a) {
        let text = format!("{v:.1e}");
        text.replace(".0e", "e")
    } else {
        trimmed(v, 6)
    }
}

/// `v` with at most `decimals` decimals, trailing zeros removed (`-0` reads `0`).
fn trimmed(v: f64, decimals: usize) -> String {
    let text = format!("{v:.decimals$}");
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.')
    } else {
        &text
    };
    if text == "-0" {
        "0".to_string()
    } else {
        text.to_string()
    }
}

/// A time range as every figure title writes it: `[0, 2] s`, `[99.0004, 100] s` (at most four
/// decimals, no trailing zeros).
pub fn time_range_label(t0: f64, t1: f64) -> String {
    format!("[{}, {}] s", trimmed(t0, 4), trimmed(t1, 4))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(tick_label(9.999999999e-6, true, 1.0), "1e-5");
        assert_eq!(tick_label(3e-5, true, 1.0), "3e-5");
        assert_eq!(tick_label(0.30000000000000004, false, 1.0), "0.3");
        assert_eq!(tick_label(1400.0, false, 1e4), "1400");
        assert_eq!(tick_label(2.5e6, false, 1e7), "2.5e6");
        assert_eq!(tick_label(0.0, false, 1.0), "0");
    }

    #[test]
    fn a_tick_at_float_noise_from_zero_reads_zero() {
        // The ticks of -1..1 in steps of 0.2 arrive with the zero as -5.6e-17.
        assert_eq!(tick_label(-5.551115123125783e-17, false, 2.0), "0");
        assert_eq!(tick_label(1.1e-16, false, 2.0), "0");
        // A genuinely small value on a small axis keeps its value.
        assert_eq!(tick_label(-5.6e-17, false, 1e-15), "-5.6e-17");
        // Logarithmic axes have no zero.
        assert_eq!(tick_label(1e-17, true, 1.0), "1e-17");
        // Rounding to six decimals never prints a negative zero.
        assert_eq!(tick_label(-1e-7, false, 1e-6), "-1e-7");
        assert_eq!(trimmed(-1e-9, 6), "0");
    }

    #[test]
    fn time_ranges_are_written_one_way() {
        assert_eq!(time_range_label(0.0, 2.0), "[0, 2] s");
        assert_eq!(time_range_label(1.0, 100.0), "[1, 100] s");
        assert_eq!(time_range_label(99.00004, 100.0), "[99, 100] s");
        assert_eq!(time_range_label(99.0004, 99.99996), "[99.0004, 100] s");
        assert_eq!(time_range_label(0.0, 0.07646), "[0, 0.0765] s");
    }

    #[test]
    fn ranges_cover_the_data_and_survive_degenerate_input() {
        assert_eq!(padded_range([1.0, 3.0].into_iter(), false), 0.9..3.1);
        assert_eq!(padded_range([2.0].into_iter(), false), 1.0..3.0);
        assert_eq!(padded_range([0.0, -1.0].into_iter(), true), 1e-6..1.0);
        assert_eq!(padded_range(std::iter::empty(), false), 0.0..1.0);
        assert_eq!(
            data_range([0.05, 0.95, f64::NAN].into_iter()),
            Some(0.05..0.95)
        );
        assert_eq!(data_range([f64::NAN].into_iter()), None);
        assert_eq!(data_range([4.0].into_iter()), Some(3.5..4.5));
        assert_eq!(usable_span(1.0, 0.5), 0.5..1.5);
        assert_eq!(usable_span(0.0, 2.0), 0.0..2.0);
    }

    /// A reference line at `μ_st = f64::MAX` made the ν axis end at infinity, and drawing it
    /// never finished.
    #[test]
    fn ranges_of_extreme_values_have_a_finite_span() {
        for values in [
            vec![0.115, f64::MAX],
            vec![-f64::MAX, f64::MAX],
            vec![f64::MAX],
            vec![-f64::MAX, 0.0],
        ] {
            for log in [false, true] {
                let r = padded_range(values.iter().copied(), log);
                assert!((r.end - r.start).is_finite(), "{values:?} {log}: {r:?}");
                assert!(r.start < r.end, "{values:?} {log}: {r:?}");
            }
        }
    }
}
