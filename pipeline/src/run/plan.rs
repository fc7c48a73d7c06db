//! Which instants of a run are recorded, decided before it starts.
//!
//! The trajectory file wants a coarse grid over the whole run; the figures of the first and
//! the last simulated second want a fine one (the normal force peaks last milliseconds). The
//! simulation is asked for exactly those samples and no others: a sample costs an
//! interpolation and a model evaluation, and a 100 s run sampled finely throughout spent more
//! time producing samples than integrating. All grids are one fine grid `t0 + k / fine_rate`
//! (the coarse rate divides it), so a sample's place in the plan follows from its time alone.
//!
//! A scene may also name windows of its own (`[output] windows`) where the trajectory file is
//! sampled finer, at a whole multiple of its rate: the fine grid is then the least common
//! multiple of all the rates, and each window keeps every so-many of its points.

use std::ops::Range;

use crate::scene::schema::SampleWindow;

/// Length of the two finely sampled windows (s).
pub const WINDOW: f64 = 1.0;
/// Highest fine sampling rate used for the windows (1/s).
pub const FINE_RATE_MAX: f64 = 20_000.0;
/// Most points the fine grid may have over a run: the simulation visits each of them.
pub const MAX_GRID_POINTS: f64 = 1e9;
/// The lowest trajectory rate that scene windows can refine (1/s): below it the fine grid
/// holds more than 1e12 points per trajectory point, past where its whole-number arithmetic
/// (the multiples, their least common multiple) is exact.
pub const MIN_RATE_WITH_WINDOWS: f64 = FINE_RATE_MAX / 1e12;

/// Which of the two fine windows a sample falls in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Window {
    /// The first simulated second.
    First,
    /// The last simulated second.
    Last,
}

/// The samples a run records: every `every`-th point of the fine grid everywhere (the
/// trajectory), and every point inside the windows (the figures).
#[derive(Clone, Debug, PartialEq)]
pub struct SamplePlan {
    /// Start of the run (s): the grids' origin.
    pub t0: f64,
    /// The trajectory's rate (1/s).
    pub rate: f64,
    /// Fine grid points per trajectory point.
    pub every: u64,
    /// Whether the coarse grid is recorded at all (the last second before an early stop,
    /// sampled after the run, is not).
    pub coarse: bool,
    /// The first second (fine), if recorded.
    pub first: Option<Range<f64>>,
    /// The last second (fine), if recorded.
    pub last: Option<Range<f64>>,
    /// Fine grid points per sample of the first and the last second.
    pub figure_every: u64,
    /// The scene's own windows: where, and the fine grid points per sample there.
    pub windows: Vec<(Range<f64>, u64)>,
}

impl SamplePlan {
    /// The plan of a run over `[t0, t_end]` whose trajectory is sampled at `rate`: the fine
    /// grid as fine as `FINE_RATE_MAX` allows (never coarser than the trajectory), finely
    /// sampled in the first and the last `WINDOW`.
    pub fn new(t0: f64, t_end: f64, rate: f64) -> SamplePlan {
        let every = (FINE_RATE_MAX / rate).floor().max(1.0) as u64;
        SamplePlan {
            t0,
            rate,
            every,
            coarse: true,
            first: Some(t0..t0 + WINDOW),
            last: Some(t_end - WINDOW..t_end),
            figure_every: 1,
            windows: Vec::new(),
        }
    }

    /// How many times `rate` holds `base` when it is a whole multiple of it (to 1e-9), else
    /// `None`.
    pub fn multiple(rate: f64, base: f64) -> Option<u64> {
        let m = (rate / base).round();
        ((1.0..1e12).contains(&m) && (rate / base - m).abs() <= 1e-9 * m).then_some(m as u64)
    }

    /// This plan with the scene's `windows` sampled at their own rates too (each a whole
    /// multiple of the trajectory's rate, as the scene's validation checks; one that is not
    /// is left out). The fine grid becomes the least common multiple of all the rates.
    pub fn with_windows(self, windows: &[SampleWindow]) -> SamplePlan {
        let multiples: Vec<(Range<f64>, u64)> = windows
            .iter()
            .filter_map(|w| {
                Some((
                    w.from..w.to,
                    SamplePlan::multiple(w.sample_rate, self.rate)?,
                ))
            })
            .collect();
        let every = multiples.iter().fold(self.every, |l, (_, m)| lcm(l, *m));
        SamplePlan {
            figure_every: (every / self.every).saturating_mul(self.figure_every),
            windows: multiples
                .into_iter()
                .map(|(range, m)| (range, every / m))
                .collect(),
            every,
            ..self
        }
    }

    /// The plan that records only the last second before `t_stop`: a run that stopped before
    /// its end time, whose last second was not known in advance, samples it from the steps it
    /// kept.
    pub fn last_second_before(&self, t_stop: f64) -> SamplePlan {
        SamplePlan {
            coarse: false,
            first: None,
            last: Some(t_stop - WINDOW..t_stop),
            windows: Vec::new(),
            ..self.clone()
        }
    }

    /// Whether the last window of this plan covers the second before `t_stop`. A stop past
    /// the last window's end is at its end: a run in regularised time reaches its end time
    /// on its clock, which may read a few ulps more.
    pub fn covers_last_second(&self, t_stop: f64) -> bool {
        let t_stop = self.last.as_ref().map_or(t_stop, |w| t_stop.min(w.end));
        let before = (t_stop - WINDOW).max(self.t0);
        let within = |w: &Range<f64>| w.start <= before && t_stop <= w.end;
        self.last.as_ref().is_some_and(within) || self.first.as_ref().is_some_and(within)
    }

    /// The fine grid's rate (1/s): the rate the simulation is asked to sample at.
    pub fn fine_rate(&self) -> f64 {
        self.rate * self.every as f64
    }

    /// The rate of the first and the last second's samples (1/s).
    pub fn figure_rate(&self) -> f64 {
        self.fine_rate() / self.figure_every as f64
    }

    /// The index of the fine grid point at `t` (the simulation samples exactly at
    /// `t0 + k / fine_rate`, so rounding recovers `k`).
    fn index(&self, t: f64) -> u64 {
        ((t - self.t0) * self.fine_rate()).round().max(0.0) as u64
    }

    /// Whether the sample at `t` belongs on the trajectory's grid.
    pub fn is_coarse(&self, t: f64) -> bool {
        self.coarse && self.index(t).is_multiple_of(self.every)
    }

    /// The fine window the sample at `t` falls in, if any.
    pub fn window(&self, t: f64) -> Option<Window> {
        let inside =
            |w: &Option<Range<f64>>| w.as_ref().is_some_and(|w| w.start <= t && t <= w.end);
        if !self.index(t).is_multiple_of(self.figure_every) {
            None
        } else if inside(&self.first) {
            Some(Window::First)
        } else if inside(&self.last) {
            Some(Window::Last)
        } else {
            None
        }
    }

    /// Whether the sample at `t` belongs in the trajectory file: on its grid, or on the grid
    /// of one of the scene's windows.
    pub fn is_written(&self, t: f64) -> bool {
        self.is_coarse(t)
            || self.windows.iter().any(|(w, every)| {
                w.start <= t && t <= w.end && self.index(t).is_multiple_of(*every)
            })
    }

    /// Whether the sample at `t` is recorded at all.
    pub fn wants(&self, t: f64) -> bool {
        self.is_written(t) || self.window(t).is_some()
    }

    /// A time at or before the first sample after `t` that [`SamplePlan::wants`]: the
    /// earliest of the next trajectory point, the next point of a window's own grid for a
    /// window around `t`, and the start of each window after `t`, each less half a fine grid
    /// step (the grid's times are rounded, and the bound must not pass the point it stands
    /// for). Infinite when no sample after `t` is wanted. What lets the run skip the fine
    /// grid between the points it keeps instead of asking about each.
    pub fn next_wanted(&self, t: f64) -> f64 {
        let fine = self.fine_rate();
        let half = 0.5 / fine;
        let before_point = |every: u64| {
            let point = self.index(t).div_ceil(every).saturating_mul(every);
            self.t0 + (point as f64 - 0.5) / fine
        };
        let figures = (self.first.iter().chain(&self.last)).map(|w| (w, self.figure_every));
        let windows = figures.chain(self.windows.iter().map(|(w, every)| (w, *every)));
        let mut next = f64::INFINITY;
        for (w, every) in windows {
            if t < w.start - half {
                next = next.min(w.start - half);
            } else if t <= w.end + half {
                next = next.min(before_point(every));
            }
        }
        if self.coarse {
            next = next.min(before_point(self.every));
        }
        next.max(t)
    }
}

/// The least common multiple of `a` and `b` (both > 0), `u64::MAX` where it does not fit
/// (a grid that fine is refused by the scene's validation, `MAX_GRID_POINTS`, long before).
fn lcm(a: u64, b: u64) -> u64 {
    let gcd = |mut a: u64, mut b: u64| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    (a / gcd(a, b)).saturating_mul(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A trajectory rate of 1e-300 with a window: no overflow in the grid's arithmetic (it
    /// panicked with overflow checks, and wrapped without).
    #[test]
    fn a_tiny_rate_with_a_window_does_not_overflow() {
        let window = SampleWindow {
            from: 0.0,
            to: 1.0,
            sample_rate: 1e-299,
        };
        let plan = SamplePlan::new(0.0, 10.0, 1e-300).with_windows(&[window]);
        assert_eq!(plan.every, u64::MAX);
        assert!(plan.figure_every >= 1);
        assert!(lcm(u64::MAX, 10) == u64::MAX && lcm(4, 6) == 12);
    }

    #[test]
    fn a_scene_window_refines_the_grid_and_keeps_the_others() {
        let window = SampleWindow {
            from: 5.0,
            to: 5.01,
            sample_rate: 200_000.0,
        };
        let base = SamplePlan::new(0.0, 10.0, 1000.0);
        let plan = base.clone().with_windows(&[window]);
        assert_eq!(plan.fine_rate(), 200_000.0);
        assert_eq!((plan.every, plan.figure_every), (200, 10));
        let grid: Vec<f64> = (0..=2_000_000).map(|k| k as f64 / 200_000.0).collect();
        let written: Vec<f64> = grid
            .iter()
            .copied()
            .filter(|&t| plan.is_written(t))
            .collect();
        // 10 001 coarse points, and 2001 in the window of which 11 are coarse already.
        assert_eq!(written.len(), 10_001 + 2001 - 11);
        assert!(written.windows(2).all(|w| w[0] < w[1]));
        // The figures' windows and the coarse grid are those of the plan without the window.
        for &t in grid.iter().step_by(10) {
            assert_eq!(plan.window(t), base.window(t), "{t}");
            assert_eq!(plan.is_coarse(t), base.is_coarse(t), "{t}");
        }
        assert_eq!(plan.window(0.5 + 1.0 / 200_000.0), None);
        assert!(!plan.wants(5.02 + 1.0 / 200_000.0));
        assert_eq!(SamplePlan::multiple(200_000.0, 1000.0), Some(200));
        assert_eq!(SamplePlan::multiple(1500.0, 1000.0), None);
        assert_eq!(SamplePlan::multiple(500.0, 1000.0), None);
        assert_eq!(lcm(20, 200), 200);
        assert_eq!(lcm(20, 30), 60);
    }

    #[test]
    fn the_plan_keeps_the_coarse_grid_and_both_windows() {
        let plan = SamplePlan::new(0.0, 10.0, 100.0);
        assert_eq!(plan.every, 200);
        assert_eq!(plan.fine_rate(), 20_000.0);
        let grid: Vec<f64> = (0..=200_000).map(|k| k as f64 / 20_000.0).collect();
        let wanted: Vec<f64> = grid.iter().copied().filter(|&t| plan.wants(t)).collect();
        // 20 001 + 20 001 fine points in the windows, 801 coarse points between them.
        assert_eq!(wanted.len(), 20_001 + 20_001 + 799);
        let coarse = grid.iter().filter(|&&t| plan.is_coarse(t)).count();
        assert_eq!(coarse, 1001);
        assert_eq!(plan.window(0.5), Some(Window::First));
        assert_eq!(plan.window(9.5), Some(Window::Last));
        assert_eq!(plan.window(5.0), None);
        assert!(!plan.wants(5.0 + 1.0 / 20_000.0));
    }

    /// The samples a run gets when it skips to [`SamplePlan::next_wanted`] after each declined
    /// one, and how many it asked about, on the grid `k / fine_rate` up to `t_end`.
    fn skipping(plan: &SamplePlan, t_end: f64) -> (Vec<f64>, usize) {
        let (mut kept, mut asked, mut k) = (Vec::new(), 0, 0u64);
        let time = |k: u64| k as f64 / plan.fine_rate();
        while time(k) <= t_end {
            let t = time(k);
            asked += 1;
            k += 1;
            if plan.wants(t) {
                kept.push(t);
            } else {
                let from = plan.next_wanted(t);
                assert!(from >= t, "{from} before {t}");
                if from > t_end {
                    break;
                }
                while time(k) < from {
                    k += 1;
                }
            }
        }
        (kept, asked)
    }

    #[test]
    fn skipping_to_the_next_wanted_sample_keeps_every_wanted_one() {
        let window = SampleWindow {
            from: 5.0,
            to: 5.01,
            sample_rate: 200_000.0,
        };
        let plain = SamplePlan::new(0.0, 10.0, 100.0);
        for (plan, t_end) in [
            (plain.clone(), 10.0),
            (
                SamplePlan::new(0.0, 10.0, 1000.0).with_windows(&[window]),
                10.0,
            ),
            (plain.last_second_before(7.3), 10.0),
            (SamplePlan::new(0.0, 10.0, 30_000.0), 10.0),
        ] {
            let grid = (0..).map(|k| k as f64 / plan.fine_rate());
            let wanted: Vec<f64> = grid
                .take_while(|&t| t <= t_end)
                .filter(|&t| plan.wants(t))
                .collect();
            let (kept, asked) = skipping(&plan, t_end);
            assert_eq!(kept, wanted, "{plan:?}");
            // Between two wanted samples the run asks about one declined sample at most.
            assert!(
                asked <= 2 * wanted.len() + 1,
                "{asked} asked, {}",
                wanted.len()
            );
        }
    }

    #[test]
    fn a_replay_records_only_the_last_second_before_the_stop() {
        let plan = SamplePlan::new(0.0, 100.0, 1000.0);
        assert!(plan.covers_last_second(100.0));
        assert!(plan.covers_last_second(0.7), "a run shorter than a second");
        assert!(!plan.covers_last_second(18.2));
        // The regularised clock ends an ulp or two past the end time.
        assert!(plan.covers_last_second(100.00000000000011));
        let replay = plan.last_second_before(18.2);
        assert!(replay.covers_last_second(18.2));
        assert!(!replay.wants(10.0));
        assert!(!replay.is_coarse(17.5));
        assert_eq!(replay.window(17.5), Some(Window::Last));
    }
}
