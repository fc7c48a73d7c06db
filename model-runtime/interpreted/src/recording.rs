//! What a solve keeps as the run streams it: the recorded points with the mode and the
//! discrete values in force at each, the transitions with the values on both sides, and
//! whether the run must stop (the work bound, an interrupt).
//!
//! Why an observer of its own rather than the runtime's one-call drivers: a model's outputs
//! read the discrete values of their own time, not those of the run's end, so each point
//! carries the values in force when it was recorded; a run that fails, goes over its work
//! bound or is interrupted still hands back everything computed until then; and the smooth
//! and the switched model share this one piece instead of two copies.

use crate::request::Times;
use crate::solution::DenseStep;
use crate::trajectory::Trajectory;
use model_runtime::{Dyn, Observed, Sample, StepView};
use model_runtime::{WorkBound, WorkExceeded, WorkMeter};
use std::cell::RefCell;
use std::ops::ControlFlow;
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, Ordering};

/// What a recorded row's outputs are evaluated with: the mode in force (by index) and the
/// discrete values (by index into [`Recording::snapshots`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Point {
    pub(crate) mode: u32,
    pub(crate) discrete: u32,
}

/// Why the observer ended a run early.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Halt {
    /// The steps outran the work bound.
    Work(WorkExceeded),
    /// The caller's interrupt flag was set.
    Interrupted,
}

/// Where to record: at every accepted step (and the start), at the runtime's samples (a
/// rate, [`model_runtime::HybridOptions::sample_rate`]), or at given times read off each
/// step's dense output.
#[derive(Clone, Debug)]
pub(crate) enum Grid<'a> {
    /// Every accepted step.
    Steps,
    /// The runtime's samples.
    Rate,
    /// Exactly these times (in the run's order).
    Times {
        /// The times.
        times: Times<'a>,
        /// The next one not yet recorded.
        next: usize,
    },
}

/// Whether `a` comes before `b` in a run's direction (`backward`: decreasing time).
fn before(a: f64, b: f64, backward: bool) -> bool {
    if backward {
        a > b
    } else {
        a < b
    }
}

/// The discrete values as the model sets them (shared with it: written at each reset, read
/// here at each recorded point).
pub(crate) type SharedValues = Rc<RefCell<Vec<f64>>>;

/// The points and the state of a run being recorded.
pub(crate) struct Recording<'a> {
    pub(crate) grid: Grid<'a>,
    /// Each row's mode and discrete values.
    pub(crate) points: Vec<Point>,
    /// The rows: `t`, the state and the discrete values written as they are recorded, the
    /// outputs' columns left for the end ([`crate::tables::Tables::finish`]).
    pub(crate) table: Trajectory,
    /// A state interpolated at a given time, before it is recorded.
    sample: Vec<f64>,
    /// Each distinct set of discrete values met, in order.
    pub(crate) snapshots: Vec<Vec<f64>>,
    discrete: SharedValues,
    meter: WorkMeter,
    interrupt: &'a AtomicBool,
    pub(crate) halt: Option<Halt>,
    pub(crate) steps: u64,
    /// Each accepted step's dense output, when the caller asked to keep it.
    pub(crate) dense: Option<Vec<DenseStep>>,
    /// Whether the run goes backward in time (its points come in decreasing time).
    backward: bool,
}

impl<'a> Recording<'a> {
    pub(crate) fn new(
        grid: Grid<'a>,
        discrete: SharedValues,
        (t0, bound): (f64, WorkBound),
        interrupt: &'a AtomicBool,
        width: usize,
    ) -> Self {
        let first = discrete.borrow().clone();
        // Room for every row where the grid says how many (given times): a million samples
        // then grow nothing.
        let rows = match &grid {
            Grid::Times { times, .. } => times.len(),
            Grid::Steps | Grid::Rate => 0,
        };
        Recording {
            grid,
            points: Vec::with_capacity(rows),
            table: Trajectory::with_capacity(width, rows),
            sample: Vec::new(),
            snapshots: vec![first],
            discrete,
            meter: WorkMeter::new(bound, t0),
            interrupt,
            halt: None,
            steps: 0,
            dense: None,
            backward: false,
        }
    }

    /// The recording of a run backward in time when `backward`.
    pub(crate) fn with_direction(mut self, backward: bool) -> Self {
        self.backward = backward;
        self
    }

    /// The recording, keeping every accepted step's dense output when `keep`.
    pub(crate) fn with_dense(mut self, keep: bool) -> Self {
        self.dense = keep.then(Vec::new);
        self
    }

    /// The discrete values in force now, by index into [`Recording::snapshots`].
    pub(crate) fn values_now(&mut self) -> usize {
        let now = self.discrete.borrow();
        let last = self.snapshots.len() - 1;
        if self.snapshots[last] == *now {
            return last;
        }
        self.snapshots.push(now.clone());
        last + 1
    }

    /// Records `(t, mode, y)` with the discrete values in force.
    pub(crate) fn push(&mut self, t: f64, mode: usize, y: &[f64]) {
        let discrete = self.values_now();
        (self.table).push(&[&[t], y, &self.snapshots[discrete]]);
        self.points.push(Point {
            mode: mode as u32,
            discrete: discrete as u32,
        });
    }

    /// The time of the last row recorded.
    fn last_t(&self) -> Option<f64> {
        self.table.last_first()
    }

    /// The next of the given times reached by `t1` (at or before it, in the run's direction),
    /// taken off the grid.
    fn next_time(&mut self, t1: f64) -> Option<f64> {
        let backward = self.backward;
        let Grid::Times { times, next } = &mut self.grid else {
            return None;
        };
        let t = times.get(*next).filter(|&t| !before(t1, t, backward))?;
        *next += 1;
        Some(t)
    }

    /// The start, where a grid records it.
    pub(crate) fn start(&mut self, t0: f64, mode: usize, y0: &[f64]) {
        match &mut self.grid {
            Grid::Steps => self.push(t0, mode, y0),
            Grid::Rate => {}
            Grid::Times { times, next } => {
                let backward = self.backward;
                let mut count = 0;
                while times.get(*next).is_some_and(|t| !before(t0, t, backward)) {
                    *next += 1;
                    count += 1;
                }
                for _ in 0..count {
                    self.push(t0, mode, y0);
                }
            }
        }
    }

    /// Whether the grid needs each step's dense output.
    pub(crate) fn wants_dense(&self) -> bool {
        self.dense.is_some() || matches!(self.grid, Grid::Times { .. })
    }

    /// An accepted step in mode `mode`: its points, and the work it adds.
    pub(crate) fn step(&mut self, mode: usize, step: &StepView<'_, Dyn, impl Copy>) -> Observed {
        self.steps += 1;
        if let Some(over) = self.meter.step(step.t0, step.t1) {
            self.halt.get_or_insert(Halt::Work(over));
        }
        if let (Some(kept), Some(dense)) = (&mut self.dense, step.dense) {
            if step.t1 != step.t0 {
                kept.push(DenseStep::sampled(
                    step.t0,
                    step.t1,
                    step.y0.len(),
                    |t, y| dense.at(t, y),
                ));
            }
        }
        let backward = self.backward;
        match &mut self.grid {
            Grid::Steps => {
                if self.last_t().is_none_or(|t| before(t, step.t0, backward)) {
                    self.push(step.t0, mode, step.y0);
                }
                self.push(step.t1, mode, step.y1);
            }
            Grid::Rate => {}
            Grid::Times { .. } => {
                // Each time due is interpolated into one reused vector, then recorded.
                let mut sample = std::mem::take(&mut self.sample);
                while let Some(t) = self.next_time(step.t1) {
                    sample.clone_from(step.y1);
                    if t != step.t1 {
                        // Always present: `wants_dense` asks the driver for it.
                        if let Some(dense) = step.dense {
                            dense.at(t, &mut sample);
                        }
                    }
                    self.push(t, mode, &sample);
                }
                self.sample = sample;
            }
        }
        Ok(())
    }

    /// A sample of the runtime's rate.
    pub(crate) fn sample(&mut self, mode: usize, sample: &Sample<'_, Dyn, impl Copy>) -> Observed {
        self.push(sample.t, mode, sample.y);
        Ok(())
    }

    /// Whether the run goes on: not once the work bound is reached or the caller interrupts.
    pub(crate) fn proceed(&mut self) -> ControlFlow<()> {
        if self.halt.is_none() && self.interrupt.load(Ordering::Relaxed) {
            self.halt = Some(Halt::Interrupted);
        }
        match self.halt {
            Some(_) => ControlFlow::Break(()),
            None => ControlFlow::Continue(()),
        }
    }

    /// Closes the trajectory at the run's last point `(t, mode, y)` unless it is recorded.
    pub(crate) fn close(&mut self, t: f64, mode: usize, y: &[f64]) {
        if self
            .last_t()
            .is_none_or(|last| before(last, t, self.backward))
        {
            self.push(t, mode, y);
        }
    }
}
