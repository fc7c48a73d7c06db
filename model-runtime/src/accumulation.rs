//! Accumulation (Zeno) detection: a reset event that fires again and again after ever shorter
//! intervals, such as a bouncing ball coming to rest.
//!
//! Left alone, such a run takes one segment per firing until the intervals fall below what
//! the clock can resolve, and ends in the chattering limit or a step-size collapse: an error
//! for what is, physically, a well-defined limit. The intervals of such a sequence typically
//! shrink geometrically (the ball's flight times by its restitution), so the limit is known
//! long before it is reached: with intervals `d_k = d_1 r^(k-1)`, the firings accumulate at
//! `t_inf = t_last + d_last r / (1 - r)`.
//!
//! [`AccumulationDetector`] is fed the times of successive firings of one event and declares
//! an accumulation when, by its [`AccumulationRule`], the latest `events` intervals all shrink
//! (every ratio of successive intervals is below 1) and the time left to the accumulation
//! point is at most `tail`:
//!
//! * at one steady ratio `r` (the ratios agree within `ratio_spread`, relative to the
//!   largest), the time left is extrapolated geometrically, `d_last r / (1 - r)`;
//! * at ratios that wobble (a ball on a moving floor: each flight's ratio to the one before
//!   depends on the floor's phase at the bounce), the time left is bounded by the slowest ratio
//!   seen, `d_last r_max / (1 - r_max)`, and the accumulation point extrapolated with the
//!   ratios' geometric mean. The bound assumes the intervals keep shrinking at least that
//!   fast; by the time it is below `tail` the intervals are far below anything a run resolves.
//!
//! The tail is what the accumulation skips: the (infinitely many) firings the run will not
//! take, all within `tail` of the last one taken. It is a time, in the model's unit, small
//! against anything the run should resolve and large against the event times' own error
//! (a few ulps of `t`), so that the ratios the rule compares are still meaningful.
//!
//! A sequence whose intervals do not all shrink is never declared: it goes on firing, and if
//! it truly accumulates, the driver's chattering limit still ends it.

use crate::error::InputError;

/// When a run of firings counts as an accumulation; see the module docs of
/// [`AccumulationDetector`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AccumulationRule {
    /// How many of the latest intervals between firings must shrink at one ratio: `events + 1`
    /// firings are needed and `events - 1` ratios compared. At least 2.
    pub events: usize,
    /// How far the compared ratios may spread, `max - min <= ratio_spread * max`, for the
    /// accumulation point to be extrapolated from the last ratio (ratios that spread more are
    /// bounded by the largest, see the module docs). Finite and positive.
    pub ratio_spread: f64,
    /// The largest remaining time `d_last r / (1 - r)` that is declared an accumulation (in
    /// the model's time unit). Finite and positive.
    pub tail: f64,
}

impl Default for AccumulationRule {
    /// Four intervals (three ratios) agreeing to 1 %, and a tail of at most 1e-9 time units.
    fn default() -> Self {
        AccumulationRule {
            events: 4,
            ratio_spread: 1e-2,
            tail: 1e-9,
        }
    }
}

impl AccumulationRule {
    /// The default rule with a tail of `1e-7` of the run's span (`t_end - t0`, never less than
    /// the default's `1e-9`): what the model language's runs use. A tail fixed in time units
    /// is too short for long runs at the default tolerances: the intervals' ratios are
    /// meaningful only while the event times' errors are small against the intervals, and a
    /// rocking block at rtol `1e-8`, atol `1e-10` keeps its ratio to 1 % down to intervals of
    /// `1e-7` s and turns to noise below `1e-8` s, where a `1e-9` tail is never reached
    /// (it rocked on for a million impacts). Skipping `1e-7` of the span is far below anything
    /// the run resolves.
    pub fn for_span(span: f64) -> Self {
        let default = AccumulationRule::default();
        AccumulationRule {
            tail: (1e-7 * span.abs()).max(default.tail),
            ..default
        }
    }

    /// The rule if its numbers are usable, else an error naming the first field that is not.
    pub fn validate(self) -> Result<Self, InputError> {
        let bad = |field, value| Err(InputError::AccumulationRule { field, value });
        if self.events < 2 {
            return bad("events", self.events as f64);
        }
        for (field, value) in [("ratio_spread", self.ratio_spread), ("tail", self.tail)] {
            if !(value.is_finite() && value > 0.0) {
                return bad(field, value);
            }
        }
        Ok(self)
    }
}

/// A detected accumulation: where the firings converge and how fast.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Accumulation {
    /// The extrapolated accumulation point `t_last + d_last r / (1 - r)`.
    pub t_inf: f64,
    /// The ratio `r` of the last two intervals (steady ratios), or the geometric mean of the
    /// compared ratios (ratios that wobble).
    pub ratio: f64,
}

/// Watches the firing times of one event for a geometric accumulation (see the module docs).
#[derive(Clone, Debug)]
pub struct AccumulationDetector {
    rule: AccumulationRule,
    /// The latest firing times, oldest first: at most `rule.events + 1`.
    times: Vec<f64>,
}

impl AccumulationDetector {
    /// A detector with an empty history; the rule is checked here.
    pub fn new(rule: AccumulationRule) -> Result<Self, InputError> {
        let rule = rule.validate()?;
        Ok(AccumulationDetector {
            rule,
            times: Vec::with_capacity(rule.events + 1),
        })
    }

    /// Its rule.
    pub fn rule(&self) -> AccumulationRule {
        self.rule
    }

    /// Firings in the history.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether the history is empty.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// Forgets every firing (something else happened in between).
    pub fn reset(&mut self) {
        self.times.clear();
    }

    /// Records a firing at `t` and returns the accumulation if the history now shows one. A
    /// time that is not after the last one starts the history afresh; one that is not finite
    /// leaves it empty.
    pub fn fire(&mut self, t: f64) -> Option<Accumulation> {
        if !t.is_finite() {
            self.times.clear();
            return None;
        }
        if self.times.last().is_some_and(|&last| t <= last) {
            self.times.clear();
        }
        if self.times.len() == self.rule.events + 1 {
            self.times.remove(0);
        }
        self.times.push(t);
        self.accumulation()
    }

    /// The accumulation the full history (finite, increasing times) shows, if any.
    fn accumulation(&self) -> Option<Accumulation> {
        if self.times.len() < self.rule.events + 1 {
            return None;
        }
        let intervals = self.times.windows(2).map(|w| w[1] - w[0]);
        let ratios: Vec<f64> = intervals
            .clone()
            .zip(intervals.skip(1))
            .map(|(d0, d1)| d1 / d0)
            .collect();
        let (lo, hi) = ratios.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &r| {
            (lo.min(r), hi.max(r))
        });
        if !(hi < 1.0 && lo > 0.0) {
            return None;
        }
        let n = self.times.len();
        let (t_last, d_last) = (self.times[n - 1], self.times[n - 1] - self.times[n - 2]);
        let tail = |r: f64| d_last * r / (1.0 - r);
        let accumulation = if hi - lo <= self.rule.ratio_spread * hi {
            // Steady: the geometric extrapolation from the last ratio.
            let ratio = *ratios.last()?;
            (tail(ratio) <= self.rule.tail).then_some(Accumulation {
                t_inf: t_last + tail(ratio),
                ratio,
            })
        } else {
            // Shrinking, but not at one ratio: bounded by the slowest ratio seen, and
            // extrapolated with their geometric mean.
            let mean = ratios.iter().map(|r| r.ln()).sum::<f64>() / ratios.len() as f64;
            let ratio = mean.exp();
            (tail(hi) <= self.rule.tail).then_some(Accumulation {
                t_inf: t_last + tail(ratio),
                ratio,
            })
        };
        accumulation
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Firing `k` (from 0) of a geometric sequence from `t0` with first interval `d` and ratio
    /// `r`, and its accumulation point.
    fn geometric(t0: f64, d: f64, r: f64, k: i32) -> f64 {
        t0 + d * (1.0 - r.powi(k)) / (1.0 - r)
    }

    #[test]
    fn an_exact_geometric_sequence_is_detected_once_its_tail_is_short_enough() {
        let (t0, d, r) = (2.0, 0.5, 0.8);
        let t_inf = t0 + d / (1.0 - r);
        let rule = AccumulationRule::default();
        let mut det = AccumulationDetector::new(rule).unwrap();
        let mut found = None;
        for k in 0..200 {
            let t = geometric(t0, d, r, k);
            if let Some(acc) = det.fire(t) {
                // Detected as soon as the extrapolated tail is within the rule's, not later.
                let remaining = t_inf - t;
                assert!(remaining <= rule.tail * (1.0 + 1e-4), "{remaining:e}");
                assert!(remaining > rule.tail * r * (1.0 - 1e-4), "{remaining:e}");
                found = Some(acc);
                break;
            }
        }
        let acc = found.expect("an accumulation");
        assert!(
            (acc.t_inf - t_inf).abs() <= 1e-12 * t_inf,
            "{acc:?} {t_inf}"
        );
        assert!((acc.ratio - r).abs() < 1e-4, "{acc:?}");
    }

    #[test]
    fn unsteady_ratios_are_an_accumulation_bounded_by_the_slowest() {
        // Ratios alternating 0.5 and 0.7: shrinking fast, but not geometrically.
        let rule = AccumulationRule::default();
        let mut det = AccumulationDetector::new(rule).unwrap();
        let (mut t, mut d) = (0.0, 1.0);
        let mut times = vec![t];
        let acc = loop {
            if let Some(acc) = det.fire(t) {
                break acc;
            }
            d *= if times.len() % 2 == 0 { 0.5 } else { 0.7 };
            t += d;
            times.push(t);
            assert!(times.len() < 400);
        };
        // The true accumulation point, summed to the end; the last interval at detection is
        // short enough that the slowest ratio's tail is within the rule's.
        let (mut t_inf, mut dd) = (t, d);
        for k in 0..200 {
            dd *= if (times.len() + k) % 2 == 0 { 0.5 } else { 0.7 };
            t_inf += dd;
        }
        assert!(d * 0.7 / 0.3 <= rule.tail, "{d:e}");
        assert!(t_inf - t <= rule.tail);
        assert!((acc.t_inf - t_inf).abs() <= rule.tail, "{acc:?} {t_inf}");
        // The geometric mean of three alternating ratios (of intervals of ~1e-10 between
        // times of ~1.6: each known to ~1e-6).
        let means = [0.5f64 * 0.7 * 0.5, 0.7 * 0.5 * 0.7].map(|p| p.cbrt());
        assert!(
            means.iter().any(|m| (acc.ratio - m).abs() < 1e-4),
            "{acc:?}"
        );
    }

    #[test]
    fn a_single_interval_that_grows_is_never_an_accumulation() {
        // Shrinking at ratio 0.5 but for one interval in every four that grows.
        let mut det = AccumulationDetector::new(AccumulationRule::default()).unwrap();
        let (mut t, mut d) = (0.0, 1e-6);
        for k in 0..400 {
            assert_eq!(det.fire(t), None, "firing {k}");
            d *= if k % 4 == 3 { 8.0 } else { 0.5 };
            t += d;
        }
    }

    #[test]
    fn intervals_that_do_not_shrink_are_never_an_accumulation() {
        for r in [1.0, 1.01, 2.0] {
            let mut det = AccumulationDetector::new(AccumulationRule {
                tail: 1e9,
                ..AccumulationRule::default()
            })
            .unwrap();
            for k in 0..50 {
                assert_eq!(det.fire(geometric(0.0, 1e-12, r, k)), None, "ratio {r}");
            }
        }
    }

    #[test]
    fn a_reset_or_a_step_back_in_time_starts_the_history_afresh() {
        let rule = AccumulationRule {
            tail: 1.0,
            ..AccumulationRule::default()
        };
        let mut det = AccumulationDetector::new(rule).unwrap();
        let times: Vec<f64> = (0..5).map(|k| geometric(0.0, 1.0, 0.5, k)).collect();
        for &t in &times[..4] {
            assert_eq!(det.fire(t), None);
        }
        assert!(det.clone().fire(times[4]).is_some());
        det.reset();
        assert!(det.is_empty());
        for &t in &times[..4] {
            assert_eq!(det.fire(t), None);
        }
        // Not after the last firing: the history restarts there; not finite: it is emptied.
        assert_eq!(det.fire(times[2]), None);
        assert_eq!(det.len(), 1);
        assert_eq!(det.fire(f64::NAN), None);
        assert!(det.is_empty());
        assert_eq!(det.fire(times[2]), None);
        det.reset();
        let acc = (0..5).filter_map(|k| det.fire(10.0 + geometric(0.0, 1.0, 0.5, k)));
        assert_eq!(acc.count(), 1);
    }

    #[test]
    fn a_bad_rule_is_named_by_its_field() {
        let field = |rule: AccumulationRule| match rule.validate() {
            Err(InputError::AccumulationRule { field, .. }) => field,
            other => panic!("{other:?}"),
        };
        let ok = AccumulationRule::default();
        assert_eq!(ok.validate(), Ok(ok));
        assert_eq!(field(AccumulationRule { events: 1, ..ok }), "events");
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(
                field(AccumulationRule {
                    ratio_spread: bad,
                    ..ok
                }),
                "ratio_spread"
            );
            assert_eq!(field(AccumulationRule { tail: bad, ..ok }), "tail");
        }
        let e = AccumulationDetector::new(AccumulationRule { tail: -1.0, ..ok }).unwrap_err();
        assert!(e.to_string().contains("tail"), "{e}");
    }
}
