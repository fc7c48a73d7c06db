//! The latest stretch of a run, kept as its steps' interpolants so that it can be sampled
//! after the run, once the run has decided where it ends.
//!
//! A caller that wants the last second before a stop it could not foresee (a disk that falls,
//! a run that fails) would otherwise sample finely all the time or simulate the run twice.
//! Instead, while the run goes, each accepted step's interpolant is copied
//! ([`model_runtime::Interpolant::stored`]) into a ring that drops the steps older than the
//! span asked for ([`super::DiskObserver::keeps_trailing`]) and skips the steps that hold no
//! point of the run's sample grid (so the ring stays small when the steps get short); at the end the caller samples the
//! ring ([`Trailing::sample`]) on the run's own sample grid ([`Trailing::grid`]). A sample is
//! taken from the step the run would have taken it from (the first kept step ending at or after
//! its time, in that step's mode and with its bridge), so it is the sample the run would have
//! delivered: the same bits in physical time, the same to a few ulps of the clock in
//! regularised time (where the clock's root is found by another iteration).

use std::collections::VecDeque;

use model_runtime::{EvalError, Interpolant, StoredInterpolant};

use super::system::Phase;
use super::DiskSample;
use crate::modes::{Slip, DIM};
use model_runtime::Const;

/// One kept step: its interpolant, its reported ends (cut at an event) and what a sample of it
/// needs besides the state.
#[derive(Clone, Debug)]
struct KeptStep {
    dense: StoredInterpolant<Const<DIM>>,
    t0: f64,
    t1: f64,
    phase: Phase,
    bridge: Option<Slip>,
}

/// The ring of the latest steps, at least `span` seconds of them. With a sample grid, only
/// the steps that hold one of its points are kept: at most `rate · span` (and a few) steps
/// however short the steps get.
#[derive(Clone, Debug)]
pub(super) struct StepRing {
    span: f64,
    /// The run's sample grid: its origin and rate.
    grid: (f64, Option<f64>),
    steps: VecDeque<KeptStep>,
}

/// How far (in grid spacings) a step may miss a grid point and still be kept: a step whose
/// end lies within round-off of a point is kept rather than judged by the last bit.
const GRID_MARGIN: f64 = 1e-6;

impl StepRing {
    /// An empty ring keeping `span` seconds of a run sampled on `grid` (origin, rate).
    pub(super) fn new(span: f64, grid: (f64, Option<f64>)) -> Self {
        StepRing {
            span,
            grid,
            steps: VecDeque::new(),
        }
    }

    /// Whether a point of the grid may lie in `[t0, t1]` (always, without a grid).
    fn holds_grid_point(&self, t0: f64, t1: f64) -> bool {
        let (origin, Some(rate)) = self.grid else {
            return true;
        };
        let first = ((t0 - origin) * rate - GRID_MARGIN).ceil();
        let last = ((t1 - origin) * rate + GRID_MARGIN).floor();
        first <= last
    }

    /// Keeps the step `[t0, t1]` taken in `phase` (on a bridge from `bridge`) if it holds a
    /// grid point, dropping the steps that end more than the span before it.
    pub(super) fn push(
        &mut self,
        dense: &dyn Interpolant<Const<DIM>>,
        (t0, t1): (f64, f64),
        phase: Phase,
        bridge: Option<Slip>,
    ) {
        if !self.holds_grid_point(t0, t1) {
            return;
        }
        while self.steps.front().is_some_and(|s| s.t1 < t1 - self.span) {
            self.steps.pop_front();
        }
        self.steps.push_back(KeptStep {
            dense: dense.stored(),
            t0,
            t1,
            phase,
            bridge,
        });
    }

    /// How many steps it holds.
    pub(super) fn len(&self) -> usize {
        self.steps.len()
    }
}

/// How a kept state becomes a disk sample (the run's own conversion, with its models).
pub(super) type SampleAt<'a> =
    dyn Fn(f64, Phase, Option<Slip>, &[f64; DIM]) -> Result<DiskSample, EvalError> + 'a;

/// The latest steps of a run that has ended, to sample ([`super::DiskObserver::on_trailing`]).
pub struct Trailing<'a> {
    pub(super) ring: &'a StepRing,
    pub(super) sample_at: &'a SampleAt<'a>,
}

impl Trailing<'_> {
    /// Where the kept steps begin and end (s); `None` if no step was kept.
    pub fn span(&self) -> Option<(f64, f64)> {
        let first = self.ring.steps.front()?;
        let last = self.ring.steps.back()?;
        Some((first.t0, last.t1))
    }

    /// The kept steps' spans `(t0, t1)` (s), in time order, bridges included.
    pub fn step_spans(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.ring.steps.iter().map(|s| (s.t0, s.t1))
    }

    /// How many steps are kept.
    pub fn steps(&self) -> usize {
        self.ring.len()
    }

    /// The times of the run's sample grid ([`crate::DiskConfig::sample_rate`], from the run's
    /// start) from `from` to the end of the kept steps, computed as the run computes them.
    pub fn grid(&self, from: f64) -> impl Iterator<Item = f64> + '_ {
        let (t_first, rate) = self.ring.grid;
        let end = self.span().map_or(f64::NEG_INFINITY, |(_, t1)| t1);
        let rate = rate.filter(|_| end >= from);
        let first = rate.map_or(0, |r| ((from - t_first) * r).floor().max(0.0) as u64);
        (first..)
            .map_while(move |k| {
                let ts = t_first + k as f64 / rate?;
                (ts <= end).then_some(ts)
            })
            .filter(move |&ts| ts >= from)
    }

    /// The disk at `t` as the run would have sampled it: from the first kept step that ends
    /// at or after `t`. `None` if `t` lies outside the kept steps (before them, after them,
    /// or off the grid between two of them).
    pub fn sample(&self, t: f64) -> Option<Result<DiskSample, EvalError>> {
        let steps = &self.ring.steps;
        let step = steps.get(steps.partition_point(|s| s.t1 < t))?;
        if t < step.t0 {
            return None;
        }
        let mut y = [0.0; DIM];
        step.dense.sample_at(t, &mut y);
        Some((self.sample_at)(t, step.phase, step.bridge, &y))
    }
}
