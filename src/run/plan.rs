//! Which instants of a run are recorded, decided before it starts.
//!
//! The trajectory file wants a coarse grid over the whole run; the figures of the first and
//! the last simulated second want a fine one (the normal force peaks last milliseconds). The
//! simulation is asked for exactly those samples and no others: a sample costs an
//! interpolation and a model evaluation, and a 100 s run sampled finely throughout spent more
//! time producing samples than integrating. All grids are one fine grid `t0 + k / fine_rate`
//! (the coarse rate divides it), so a sample's place in the plan follows from its time alone.

use std::ops::Range;

/// Length of the two finely sampled windows (s).
pub const WINDOW: f64 = 1.0;
/// Highest fine sampling rate used for the windows (1/s).
pub const FINE_RATE_MAX: f64 = 20_000.0;

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
    /// Whether the coarse grid is recorded at all (a replay of the last second is not).
    pub coarse: bool,
    /// The first second (fine), if recorded.
    pub first: Option<Range<f64>>,
    /// The last second (fine), if recorded.
    pub last: Option<Range<f64>>,
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
        }
    }

    /// The plan of a replay that records only the last second before `t_stop` (for a run that
    /// stopped before its end time, whose last second was not known in advance).
    pub fn last_second_before(&self, t_stop: f64) -> SamplePlan {
        SamplePlan {
            coarse: false,
            first: None,
            last: Some(t_stop - WINDOW..t_stop),
            ..self.clone()
        }
    }

    /// Whether the last window of this plan covers the second before `t_stop`.
    pub fn covers_last_second(&self, t_stop: f64) -> bool {
        let before = (t_stop - WINDOW).max(self.t0);
        let within = |w: &Range<f64>| w.start <= before && t_stop <= w.end;
        self.last.as_ref().is_some_and(within) || self.first.as_ref().is_some_and(within)
    }

    /// The fine grid's rate (1/s): the rate the simulation is asked to sample at.
    pub fn fine_rate(&self) -> f64 {
        self.rate * self.every as f64
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
        if inside(&self.first) {
            Some(Window::First)
        } else if inside(&self.last) {
            Some(Window::Last)
        } else {
            None
        }
    }

    /// Whether located extrema are kept: in a full run all of them, in a replay of the last
    /// second none (the first pass, which ran through the same motion, kept them).
    pub fn keeps_extrema(&self) -> bool {
        self.coarse
    }

    /// Whether the sample at `t` is recorded at all.
    pub fn wants(&self, t: f64) -> bool {
        self.is_coarse(t) || self.window(t).is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn a_replay_records_only_the_last_second_before_the_stop() {
        let plan = SamplePlan::new(0.0, 100.0, 1000.0);
        assert!(plan.covers_last_second(100.0));
        assert!(plan.covers_last_second(0.7), "a run shorter than a second");
        assert!(!plan.covers_last_second(18.2));
        let replay = plan.last_second_before(18.2);
        assert!(replay.covers_last_second(18.2));
        assert!(!replay.wants(10.0));
        assert!(!replay.is_coarse(17.5));
        assert_eq!(replay.window(17.5), Some(Window::Last));
    }
}
