//! Major peaks of the normal force: the "knocks" that make the rattle.
//!
//! Every local maximum of `N/mg` is not a knock: while the disk slides, `N` wiggles by tiny
//! amounts, and numerically each wiggle is a maximum. The sound comes from the large, short
//! rises of `N` when the inclination is small. So a **major peak** is a sample `i` with
//!
//! 1. a local maximum: `x[i−1] < x[i] ≥ x[i+1]` (a plateau counts once, at its first sample);
//! 2. a large enough rise above its local baseline. Walking left from `i` until a sample higher
//!    than `x[i]` or the edge of the window `[t_i − w, t_i]` is met, the smallest value seen
//!    is the left minimum; likewise on the right. The *baseline* is the higher of the two
//!    minima and the *prominence* is `x[i] − baseline` (topographic prominence within a
//!    window; a side cut short by the end of the data does not count, so a knock just before
//!    the run's end is judged by its left side). It must reach both `min_prominence`
//!    (absolute, in `N/mg`) and `min_relative_prominence · |baseline|`;
//! 3. a rise comparable with its neighbours': at least `min_share_of_strongest` of the largest
//!    prominence of the peaks passing 1–2 within `±neighbourhood`. When the disk stands
//!    steep, `N` falls to ~0.2 mg between knocks and shows a second, shallow bump there
//!    (a rise of ~0.07 mg, a third of its baseline, beside knocks of 50 mg): rule 2 alone
//!    would count it and double the rate;
//! 4. no higher major peak within the refractory time: candidates are accepted from the
//!    highest down and a candidate closer than `refractory` to an accepted one is dropped.
//!
//! The trace carries the located extrema of `N` among its samples (`super::trace`), so a
//! peak is normally a located maximum: its time and height are exact, and its baseline is a
//! located minimum or, where the window's edge cuts a slope, a sample there. A peak that is a
//! sample (a trace without located extrema, as in the tests' synthetic signals) has its time
//! and height refined by the parabola through its three samples, so the rate measured from
//! peak intervals is not quantised by the sampling step.

use std::collections::BTreeSet;

use super::trace::ForceTrace;

/// The definition of a major peak (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeakRule {
    /// Half-width `w` of the window in which the baseline is searched (s).
    pub window: f64,
    /// Smallest prominence, in `N/mg`.
    pub min_prominence: f64,
    /// Smallest prominence relative to the baseline's magnitude.
    pub min_relative_prominence: f64,
    /// Half-width of the neighbourhood whose strongest peak sets the scale of rule 3 (s).
    pub neighbourhood: f64,
    /// Smallest prominence as a share of the strongest in the neighbourhood.
    pub min_share_of_strongest: f64,
    /// Shortest time between two major peaks (s).
    pub refractory: f64,
}

impl Default for PeakRule {
    /// Settings for the paper's disk: the knocks come 7–25 times per second (so the
    /// neighbourhood spans at least three of them) and rise by tens to thousands of `mg`;
    /// sliding wiggles and the bumps between knocks rise by less than 0.1 `mg`.
    fn default() -> Self {
        PeakRule {
            window: 0.05,
            min_prominence: 0.05,
            min_relative_prominence: 0.2,
            neighbourhood: 0.25,
            min_share_of_strongest: 0.02,
            refractory: 0.01,
        }
    }
}

/// Why a peak rule is unusable.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("peak rule: `{name}` = {value} must be finite and {requirement}")]
pub struct PeakRuleError {
    /// The setting.
    pub name: &'static str,
    /// Its value.
    pub value: f64,
    /// What it must be.
    pub requirement: &'static str,
}

impl PeakRule {
    /// Checks every setting.
    pub fn validate(&self) -> Result<(), PeakRuleError> {
        let checks = [
            ("window", self.window, self.window > 0.0, "positive"),
            (
                "min_prominence",
                self.min_prominence,
                self.min_prominence > 0.0,
                "positive",
            ),
            (
                "min_relative_prominence",
                self.min_relative_prominence,
                self.min_relative_prominence >= 0.0,
                "non-negative",
            ),
            (
                "neighbourhood",
                self.neighbourhood,
                self.neighbourhood >= 0.0,
                "non-negative",
            ),
            (
                "min_share_of_strongest",
                self.min_share_of_strongest,
                (0.0..=1.0).contains(&self.min_share_of_strongest),
                "within [0, 1]",
            ),
            (
                "refractory",
                self.refractory,
                self.refractory >= 0.0,
                "non-negative",
            ),
        ];
        for (name, value, ok, requirement) in checks {
            if !(value.is_finite() && ok) {
                return Err(PeakRuleError {
                    name,
                    value,
                    requirement,
                });
            }
        }
        Ok(())
    }
}

/// One major peak.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Peak {
    /// Time (s), refined between samples.
    pub t: f64,
    /// Height `N/mg`, refined between samples.
    pub n_over_mg: f64,
    /// Rise above the local baseline, in `N/mg`.
    pub prominence: f64,
    /// Whether the peak is a located extremum (exact) rather than a refined sample.
    pub located: bool,
}

/// The lowest value on one side of a peak.
#[derive(Clone, Copy, Debug, PartialEq)]
struct SideMinimum {
    /// The smallest value met.
    min: f64,
    /// The walk ran into the end of the data before the window's edge or a higher sample.
    cut: bool,
}

/// Walks from `i` to the left (or right) while within `half_width` of `t[i]` and not above
/// `x[i]`, and returns the smallest value met.
fn side_minimum(t: &[f64], x: &[f64], i: usize, left: bool, half_width: f64) -> SideMinimum {
    let mut min = x[i];
    let mut j = i;
    loop {
        j = match (left, j) {
            (true, 0) => return SideMinimum { min, cut: true },
            (true, _) => j - 1,
            (false, _) if j + 1 >= x.len() => return SideMinimum { min, cut: true },
            (false, _) => j + 1,
        };
        if (t[j] - t[i]).abs() > half_width || x[j] > x[i] {
            return SideMinimum { min, cut: false };
        }
        min = min.min(x[j]);
    }
}

/// The baseline of a peak: the higher of its two side minima, ignoring a side cut short by
/// the end of the data (unless both are).
fn baseline(left: SideMinimum, right: SideMinimum) -> f64 {
    match (left.cut, right.cut) {
        (false, true) => left.min,
        (true, false) => right.min,
        _ => left.min.max(right.min),
    }
}

/// Vertex of the parabola through three samples, when it lies between them.
fn refine(t: [f64; 3], x: [f64; 3]) -> (f64, f64) {
    let (h1, h2) = (t[1] - t[0], t[2] - t[1]);
    // Divided differences of the interpolating parabola.
    let d1 = (x[1] - x[0]) / h1;
    let d2 = (x[2] - x[1]) / h2;
    let curvature = (d2 - d1) / (h1 + h2);
    if curvature.is_nan() || curvature >= 0.0 {
        return (t[1], x[1]);
    }
    // p(s) = x1 + b (s − t1) + c (s − t1)², with b the slope at t1.
    let b = d1 + curvature * h1;
    let ds = (-b / (2.0 * curvature)).clamp(-h1, h2);
    (t[1] + ds, x[1] + b * ds + curvature * ds * ds)
}

/// The major peaks of `trace` under `rule`, in time order.
pub fn major_peaks(trace: &ForceTrace, rule: &PeakRule) -> Result<Vec<Peak>, PeakRuleError> {
    rule.validate()?;
    let (t, x) = (trace.t(), trace.n_over_mg());
    let mut candidates = Vec::new();
    let mut i = 1;
    while i + 1 < x.len() {
        if x[i - 1] < x[i] && x[i] >= x[i + 1] {
            // A plateau's first sample stands for the whole plateau: skip its other samples.
            let mut end = i;
            while end + 1 < x.len() && x[end + 1] == x[i] {
                end += 1;
            }
            let is_max = end + 1 >= x.len() || x[end + 1] < x[i];
            if is_max {
                let baseline = baseline(
                    side_minimum(t, x, i, true, rule.window),
                    side_minimum(t, x, end, false, rule.window),
                );
                let prominence = x[i] - baseline;
                let needed = rule
                    .min_prominence
                    .max(rule.min_relative_prominence * baseline.abs());
                if prominence >= needed {
                    let located = trace.is_located(i);
                    let (tp, xp) = if located {
                        (t[i], x[i])
                    } else if end == i {
                        refine([t[i - 1], t[i], t[i + 1]], [x[i - 1], x[i], x[i + 1]])
                    } else {
                        (0.5 * (t[i] + t[end]), x[i])
                    };
                    candidates.push(Peak {
                        t: tp,
                        n_over_mg: xp,
                        prominence,
                        located,
                    });
                }
            }
            i = end + 1;
        } else {
            i += 1;
        }
    }
    let candidates = keep_comparable(candidates, rule.neighbourhood, rule.min_share_of_strongest);
    Ok(apply_refractory(candidates, rule.refractory))
}

/// Keeps the candidates (in time order) whose prominence is at least `share` of the largest
/// within `±neighbourhood` of them.
fn keep_comparable(candidates: Vec<Peak>, neighbourhood: f64, share: f64) -> Vec<Peak> {
    if share == 0.0 {
        return candidates;
    }
    let strongest: Vec<f64> = candidates
        .iter()
        .map(|c| {
            let lo = candidates.partition_point(|p| p.t < c.t - neighbourhood);
            let hi = candidates.partition_point(|p| p.t <= c.t + neighbourhood);
            candidates[lo..hi]
                .iter()
                .fold(c.prominence, |m, p| m.max(p.prominence))
        })
        .collect();
    candidates
        .into_iter()
        .zip(strongest)
        .filter(|(c, strongest)| c.prominence >= share * strongest)
        .map(|(c, _)| c)
        .collect()
}

/// Keeps, from the highest down, the candidates no closer than `refractory` to a kept one.
/// `candidates` are in time order, so the kept neighbours in time of a candidate are its
/// nearest kept neighbours by index.
fn apply_refractory(mut candidates: Vec<Peak>, refractory: f64) -> Vec<Peak> {
    if refractory == 0.0 {
        return candidates;
    }
    let mut order: Vec<usize> = (0..candidates.len()).collect();
    order.sort_by(|&a, &b| {
        candidates[b]
            .n_over_mg
            .total_cmp(&candidates[a].n_over_mg)
            .then(a.cmp(&b))
    });
    let mut kept: BTreeSet<usize> = BTreeSet::new();
    for idx in order {
        let t = candidates[idx].t;
        let before = kept.range(..idx).next_back();
        let after = kept.range(idx + 1..).next();
        let too_close = before
            .into_iter()
            .chain(after)
            .any(|&k| (candidates[k].t - t).abs() < refractory);
        if !too_close {
            kept.insert(idx);
        }
    }
    let mut idx = 0;
    candidates.retain(|_| {
        idx += 1;
        kept.contains(&(idx - 1))
    });
    candidates
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trace(f: impl Fn(f64) -> f64, rate: f64, seconds: f64) -> ForceTrace {
        let n = (seconds * rate) as usize;
        let t: Vec<f64> = (0..n).map(|i| i as f64 / rate).collect();
        let x = t.iter().map(|&t| f(t)).collect();
        ForceTrace::new(t, x).unwrap()
    }

    #[test]
    fn parabola_vertex_is_exact_for_a_parabola() {
        let p = |s: f64| 3.0 - 2.0 * (s - 0.37).powi(2);
        let (t, x) = refine([0.0, 0.5, 1.0], [p(0.0), p(0.5), p(1.0)]);
        assert!(
            (t - 0.37).abs() < 1e-12 && (x - 3.0).abs() < 1e-12,
            "{t} {x}"
        );
    }

    #[test]
    fn small_wiggles_are_not_peaks_and_tall_ones_are() {
        // 1% wiggles at 300 Hz on a baseline of 1, and one tall bump at t = 0.5 s.
        let tr = trace(
            |t| {
                1.0 + 0.01 * (2.0 * std::f64::consts::PI * 300.0 * t).sin()
                    + 2.0 * (-((t - 0.5) / 0.002).powi(2)).exp()
            },
            20_000.0,
            1.0,
        );
        let peaks = major_peaks(&tr, &PeakRule::default()).unwrap();
        assert_eq!(peaks.len(), 1, "{peaks:?}");
        assert!((peaks[0].t - 0.5).abs() < 1e-4);
        assert!((peaks[0].prominence - 2.0).abs() < 0.05);
    }

    #[test]
    fn refractory_keeps_the_higher_of_two_close_peaks() {
        let bump = |t: f64, c: f64, h: f64| h * (-((t - c) / 0.0005).powi(2)).exp();
        let tr = trace(
            |t| 1.0 + bump(t, 0.300, 1.0) + bump(t, 0.305, 1.5),
            20_000.0,
            0.6,
        );
        let peaks = major_peaks(&tr, &PeakRule::default()).unwrap();
        assert_eq!(peaks.len(), 1, "{peaks:?}");
        assert!((peaks[0].t - 0.305).abs() < 1e-4);
        let both = PeakRule {
            refractory: 0.001,
            ..PeakRule::default()
        };
        assert_eq!(major_peaks(&tr, &both).unwrap().len(), 2);
    }

    #[test]
    fn a_peak_at_the_end_of_the_data_is_judged_by_its_left_side() {
        // The bump's maximum is 3 samples before the end: the right side is cut short.
        let tr = trace(
            |t| 1.0 + 2.0 * (-((t - 0.49985) / 0.002).powi(2)).exp(),
            20_000.0,
            0.5,
        );
        let peaks = major_peaks(&tr, &PeakRule::default()).unwrap();
        assert_eq!(peaks.len(), 1, "{peaks:?}");
        assert!(peaks[0].prominence > 1.5);
    }

    #[test]
    fn shallow_bumps_between_tall_knocks_are_not_knocks() {
        // Knocks of 50 every 0.14 s on a baseline of 0.2, with a bump of 0.07 halfway.
        let bump = |t: f64, w: f64| (-(t / w).powi(2)).exp();
        let tr = trace(
            |t| {
                let phase = t.rem_euclid(0.14) - 0.07;
                0.2 + 50.0 * bump(phase, 0.003) + 0.07 * bump(phase.abs() - 0.07, 0.01)
            },
            20_000.0,
            1.0,
        );
        let peaks = major_peaks(&tr, &PeakRule::default()).unwrap();
        assert_eq!(peaks.len(), 7, "{peaks:?}");
        assert!(peaks.iter().all(|p| p.n_over_mg > 50.0));
        let every_bump = PeakRule {
            min_share_of_strongest: 0.0,
            ..PeakRule::default()
        };
        assert_eq!(major_peaks(&tr, &every_bump).unwrap().len(), 14);
    }

    #[test]
    fn a_located_peak_keeps_its_height_and_a_sampled_one_is_refined() {
        // A sharp peak of height 3 at 0.5037 s, between the samples 0.5 and 0.51 s.
        let f = |t: f64| 1.0 + 2.0 / (1.0 + ((t - 0.5037) / 0.003).powi(2));
        let sampled = trace(f, 100.0, 1.0);
        let coarse = major_peaks(&sampled, &PeakRule::default()).unwrap();
        assert_eq!(coarse.len(), 1);
        assert!(!coarse[0].located);
        assert!(coarse[0].n_over_mg < 2.5, "{:?}", coarse[0]);
        let exact = sampled.with_extrema(&[(0.5037, f(0.5037))]).unwrap();
        let peaks = major_peaks(&exact, &PeakRule::default()).unwrap();
        assert_eq!(peaks.len(), 1);
        let p = peaks[0];
        assert!(p.located);
        assert_eq!((p.t, p.n_over_mg), (0.5037, 3.0));
        // The baseline: the higher of the samples farthest inside the window, 0.46 and 0.55 s.
        assert_eq!(p.prominence, 3.0 - f(46.0 / 100.0).max(f(55.0 / 100.0)));
    }

    #[test]
    fn bad_rules_are_named() {
        let tr = trace(|_| 1.0, 10.0, 1.0);
        let bad = PeakRule {
            window: f64::NAN,
            ..PeakRule::default()
        };
        let err = major_peaks(&tr, &bad).unwrap_err();
        assert_eq!(err.name, "window");
        let bad = PeakRule {
            refractory: -1.0,
            ..PeakRule::default()
        };
        assert_eq!(major_peaks(&tr, &bad).unwrap_err().name, "refractory");
    }

    #[test]
    fn flat_and_tiny_traces_have_no_peaks() {
        for n in 0..4 {
            let tr =
                ForceTrace::new((0..n).map(f64::from).collect(), vec![1.0; n as usize]).unwrap();
            assert!(major_peaks(&tr, &PeakRule::default()).unwrap().is_empty());
        }
    }
}
