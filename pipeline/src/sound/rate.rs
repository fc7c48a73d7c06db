//! How fast the knocks come.
//!
//! Counting peaks in a window quantises the rate by one peak per window (14% at 7 peaks per
//! second in a 1 s window), so the rate is measured from the intervals instead: with `k`
//! peaks in a window, first at `t_1` and last at `t_k`, the rate is `(k − 1)/(t_k − t_1)`,
//! exact for an evenly spaced train whatever its phase.
//!
//! The paper quotes the knocks as "frequencies" of 44 s⁻¹ (period 0.14 s) and 149 s⁻¹
//! (period 0.042 s): 2π/0.14 = 44.9 and 2π/0.042 = 149.6, so those numbers are *angular*
//! frequencies, `2π · rate`, and they are compared here as such.

use std::f64::consts::TAU;

use serde::Serialize;

use super::peaks::Peak;
use super::trace::TimeSpan;

/// The rate of the peaks within one window.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PeakRate {
    /// Start of the window (s).
    pub from: f64,
    /// End of the window (s).
    pub to: f64,
    /// Peaks within the window.
    pub peaks: usize,
    /// Peaks per second, from the intervals; `None` with fewer than two peaks.
    pub per_second: Option<f64>,
}

impl PeakRate {
    /// The window's centre (s).
    pub fn centre(&self) -> f64 {
        0.5 * (self.from + self.to)
    }

    /// `2π ·` the rate: the "frequency" in the paper's sense (s⁻¹).
    pub fn angular(&self) -> Option<f64> {
        self.per_second.map(|r| TAU * r)
    }

    /// The mean period between peaks (s).
    pub fn period(&self) -> Option<f64> {
        self.per_second.map(|r| 1.0 / r)
    }
}

/// The rate of the `peaks` (in time order) lying within `[from, to]`.
pub fn rate_between(peaks: &[Peak], from: f64, to: f64) -> PeakRate {
    let lo = peaks.partition_point(|p| p.t < from);
    let hi = peaks.partition_point(|p| p.t <= to);
    let inside = &peaks[lo..hi.max(lo)];
    let per_second = match inside {
        [first, .., last] if last.t > first.t => {
            Some((inside.len() - 1) as f64 / (last.t - first.t))
        }
        _ => None,
    };
    PeakRate {
        from,
        to,
        peaks: inside.len(),
        per_second,
    }
}

/// Rates in windows of `width` seconds whose starts step by `step` across `span` (the last
/// window ends at the span's end). Empty when the span is shorter than one window.
pub fn sliding_rates(peaks: &[Peak], span: TimeSpan, width: f64, step: f64) -> Vec<PeakRate> {
    if !(width > 0.0 && step > 0.0) || span.length() < width {
        return Vec::new();
    }
    let count = ((span.length() - width) / step).floor() as usize + 1;
    (0..count)
        .map(|k| {
            let from = span.start + k as f64 * step;
            rate_between(peaks, from, from + width)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn train(rate: f64, phase: f64, until: f64) -> Vec<Peak> {
        (0..)
            .map(|k| phase + k as f64 / rate)
            .take_while(|&t| t <= until)
            .map(|t| Peak {
                t,
                n_over_mg: 2.0,
                prominence: 1.0,
                located: true,
            })
            .collect()
    }

    #[test]
    fn interval_rate_is_exact_whatever_the_phase() {
        for phase in [0.0, 0.013, 0.07] {
            let peaks = train(7.0, phase, 10.0);
            let r = rate_between(&peaks, 2.0, 3.0);
            assert!((r.per_second.unwrap() - 7.0).abs() < 1e-9, "{r:?}");
            assert!((r.angular().unwrap() - TAU * 7.0).abs() < 1e-8);
        }
    }

    #[test]
    fn too_few_peaks_give_no_rate() {
        let peaks = train(1.0, 0.5, 10.0);
        assert_eq!(rate_between(&peaks, 0.0, 1.0).per_second, None);
        assert_eq!(rate_between(&peaks, 0.6, 1.4).peaks, 0);
        assert_eq!(rate_between(&peaks, 3.0, 1.0).peaks, 0);
    }

    #[test]
    fn sliding_windows_cover_the_span() {
        let peaks = train(20.0, 0.0, 5.0);
        let span = TimeSpan {
            start: 0.0,
            end: 5.0,
        };
        let rates = sliding_rates(&peaks, span, 1.0, 0.5);
        assert_eq!(rates.len(), 9);
        assert_eq!(rates[8].to, 5.0);
        assert!(rates
            .iter()
            .all(|r| (r.per_second.unwrap() - 20.0).abs() < 1e-9));
        assert!(sliding_rates(
            &peaks,
            TimeSpan {
                start: 0.0,
                end: 0.5
            },
            1.0,
            0.5
        )
        .is_empty());
    }
}
