//! Keeps what a run streams: every k-th fine sample for the trajectory, and every fine sample
//! of the first and of the latest second for the figures.
//!
//! The figures of the two windows need finer sampling than the trajectory file (the normal
//! force peaks last milliseconds), but a 100 s run at that rate would not fit in a file
//! anyone wants; so the simulation samples finely and this collector thins out.

use std::collections::VecDeque;

use crate::record::{EventRow, RunData};
use crate::sample::Sample;
use crate::scene::schema::ModeName;

/// Length of the two finely sampled windows (s).
pub const WINDOW: f64 = 1.0;
/// Highest fine sampling rate used for the windows (1/s).
pub const FINE_RATE_MAX: f64 = 20_000.0;

/// The fine sampling: a rate that is a whole multiple of the trajectory's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampling {
    /// The trajectory's rate (1/s).
    pub rate: f64,
    /// Fine samples per trajectory sample.
    pub every: u64,
}

impl Sampling {
    /// The fine sampling for a trajectory rate: as fine as [`FINE_RATE_MAX`] allows, never
    /// coarser than the trajectory.
    pub fn for_rate(rate: f64) -> Sampling {
        let every = (FINE_RATE_MAX / rate).floor().max(1.0) as u64;
        Sampling { rate, every }
    }

    /// The fine rate (1/s).
    pub fn fine_rate(&self) -> f64 {
        self.rate * self.every as f64
    }
}

/// Collects a run's stream.
#[derive(Debug)]
pub struct Collector {
    sampling: Sampling,
    received: u64,
    t0: Option<f64>,
    data: RunData,
    latest: VecDeque<Sample>,
}

/// A mode the scene does not allow was entered.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForbiddenMode {
    /// Time (s).
    pub t: f64,
    /// The mode.
    pub mode: ModeName,
}

impl Collector {
    /// An empty collector.
    pub fn new(sampling: Sampling) -> Collector {
        Collector {
            sampling,
            received: 0,
            t0: None,
            data: RunData::default(),
            latest: VecDeque::new(),
        }
    }

    /// Takes one fine sample.
    pub fn sample(&mut self, s: Sample) {
        let t0 = *self.t0.get_or_insert(s.t);
        if self.received.is_multiple_of(self.sampling.every) {
            self.data.samples.push(s);
        }
        self.received += 1;
        if s.t <= t0 + WINDOW {
            self.data.first_second.push(s);
        }
        self.latest.push_back(s);
        while self.latest.front().is_some_and(|f| f.t < s.t - WINDOW) {
            self.latest.pop_front();
        }
    }

    /// Takes one mode decision; reports it when it enters a mode not in `allowed`.
    pub fn event(&mut self, e: EventRow, allowed: &[ModeName]) -> Option<ForbiddenMode> {
        self.data.events.push(e);
        (!allowed.contains(&e.to)).then_some(ForbiddenMode { t: e.t, mode: e.to })
    }

    /// The time of the latest sample.
    pub fn latest_t(&self) -> Option<f64> {
        self.latest.back().map(|s| s.t)
    }

    /// The mode of the latest sample or event.
    pub fn latest_mode(&self) -> Option<ModeName> {
        let sample = self.latest.back().map(|s| (s.t, s.mode));
        let event = self.data.events.last().map(|e| (e.t, e.to));
        match (sample, event) {
            (Some(s), Some(e)) => Some(if e.0 >= s.0 { e.1 } else { s.1 }),
            (s, e) => s.or(e).map(|x| x.1),
        }
    }

    /// Everything collected; the latest window becomes the last second.
    pub fn finish(mut self) -> RunData {
        if let Some(last) = self.latest.back() {
            // The trajectory ends with the last state, even off the regular grid.
            if self.data.samples.last().map(|s| s.t) != Some(last.t) {
                self.data.samples.push(*last);
            }
        }
        self.data.last_second = self.latest.into_iter().collect();
        self.data
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::synthetic::SyntheticRun;

    #[test]
    fn thins_out_and_keeps_both_windows() {
        let p = equations::params::DiskParams::paper();
        let fine = SyntheticRun {
            period: 0.1,
            t_end: 3.0,
            rate: 2000.0,
        }
        .data(&p)
        .samples;
        let sampling = Sampling::for_rate(100.0);
        assert_eq!(sampling.every, 200);
        let sampling = Sampling {
            rate: 100.0,
            every: 20,
        };
        let mut c = Collector::new(sampling);
        for s in &fine {
            c.sample(*s);
        }
        let d = c.finish();
        assert_eq!(d.samples.len(), 301);
        assert_eq!(d.samples[1].t, fine[20].t);
        assert_eq!(d.first_second.len(), 2001);
        assert_eq!(d.last_second.first().unwrap().t, 2.0);
        assert_eq!(d.last_second.last().unwrap().t, 3.0);
    }

    #[test]
    fn forbidden_modes_are_reported() {
        let mut c = Collector::new(Sampling::for_rate(1000.0));
        let e = EventRow {
            t: 0.5,
            from: ModeName::Rolling,
            to: ModeName::Sliding,
            trigger: crate::record::TriggerKind::FrictionLimit,
            value: 0.2,
            slip_direction: None,
        };
        assert_eq!(c.event(e, &[ModeName::Rolling, ModeName::Sliding]), None);
        assert_eq!(
            c.event(e, &[ModeName::Rolling]),
            Some(ForbiddenMode {
                t: 0.5,
                mode: ModeName::Sliding
            })
        );
    }
}
