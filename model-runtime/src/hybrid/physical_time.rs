//! The observer side of regularised time: [`PhysicalTime`] turns what the driver reports in
//! `τ` for a [`crate::Regularised`] system back into physical time for an observer of the inner
//! system — samples on the physical grid (the roots of the clock on each step's dense output),
//! steps (with their dense output in physical time, when the observer asks for it) and
//! transitions with physical times and rates, the transition's note passed on.
//! Apart from the system so that each file holds one side of the transformation.

use super::regularised::{head, physical_hit, physical_rate, ClockGuard};
use crate::dense::{Interpolant, StoredInterpolant};
use crate::dim::Const;
use crate::observer::{
    first_sample_from, Observed, Observer, Sample, StepView, TransitionKind, TransitionRecord,
};
use crate::root::find_crossing;

/// An observer of `H` (in physical time) fed by a run of [`crate::Regularised`] (in `τ`).
pub struct PhysicalTime<'o, O, const N: usize, const M: usize> {
    inner: &'o mut O,
    rate: Option<f64>,
    t_first: f64,
    next_sample: u64,
    t_seg: f64,
}

impl<'o, O, const N: usize, const M: usize> PhysicalTime<'o, O, N, M> {
    /// Feeds `inner`, with samples at `t0 + k / rate` (none for `None`) for a run starting at
    /// physical time `t0`.
    pub fn new(inner: &'o mut O, t0: f64, rate: Option<f64>) -> Self {
        PhysicalTime {
            inner,
            rate,
            t_first: t0,
            next_sample: 0,
            t_seg: t0,
        }
    }

    fn sample_time(&self) -> Option<f64> {
        self.rate
            .map(|r| self.t_first + self.next_sample as f64 / r)
    }
}

impl<O, Md, G, Nt, const N: usize, const M: usize> Observer<Const<M>, Md, ClockGuard<G>, Nt>
    for PhysicalTime<'_, O, N, M>
where
    O: Observer<Const<N>, Md, G, Nt>,
    Md: Copy,
    G: Copy,
{
    fn wants_dense(&self) -> bool {
        self.rate.is_some() || self.inner.wants_dense()
    }

    fn on_step(&mut self, step: &StepView<'_, Const<M>, Md>) -> Observed {
        let (t0, t1) = (self.t_seg + step.y0[N], self.t_seg + step.y1[N]);
        // Round-off in the located end of a run leaves its clock an ulp or so short of a
        // sample due exactly there.
        let slack = 8.0 * f64::EPSILON * t1.abs().max(1.0);
        let mut z = [0.0; M];
        while let (Some(ts), Some(dense), Some(rate)) = (self.sample_time(), step.dense, self.rate)
        {
            if ts > t1 + slack {
                break;
            }
            self.next_sample += 1;
            if !self.inner.wants_sample(ts) {
                let from = self.inner.next_wanted_sample(ts);
                self.next_sample = first_sample_from(self.t_first, rate, self.next_sample, from);
                continue;
            }
            let tau = grid_tau::<_, N, M>(dense, (step.t0, step.t1), (t0, t1), self.t_seg, ts);
            dense.at(tau, &mut z);
            self.inner.on_sample(&Sample {
                t: ts,
                mode: step.mode,
                y: &head(&z),
            })?;
        }
        let (y0, y1) = (head(step.y0), head(step.y1));
        let physical = match step.dense {
            Some(dense) if self.inner.wants_dense() => Some(InPhysicalTime::<_, N, M> {
                dense,
                tau: (step.t0, step.t1),
                clock: (step.y0[N], step.y1[N]),
                t_seg: self.t_seg,
            }),
            _ => None,
        };
        self.inner.on_step(&StepView {
            mode: step.mode,
            t0,
            t1,
            y0: &y0,
            y1: &y1,
            f0: &physical_rate(step.f0),
            dense: physical.as_ref().map(|d| d as &dyn Interpolant<Const<N>>),
        })
    }

    fn on_transition(
        &mut self,
        record: TransitionRecord<Const<M>, Md, ClockGuard<G>, Nt>,
    ) -> Observed {
        let ClockGuard::Inner(guard) = record.hit.guard else {
            return Ok(());
        };
        let t = self.t_seg + record.hit.y[N];
        // A pass restarts nothing: the clock keeps counting from the same segment start.
        if !matches!(record.kind, TransitionKind::Pass) {
            self.t_seg = t;
        }
        self.inner.on_transition(TransitionRecord {
            hit: physical_hit(&record.hit, guard, t),
            from: record.from,
            kind: match record.kind {
                TransitionKind::Switch { to } => TransitionKind::Switch { to },
                TransitionKind::Continue => TransitionKind::Continue,
                TransitionKind::Pass => TransitionKind::Pass,
            },
            y_after: head(&record.y_after),
            note: record.note,
        })
    }

    fn proceed(&mut self) -> std::ops::ControlFlow<()> {
        self.inner.proceed()
    }
}

/// The `τ` of a step (ends `tau` in `τ`, `t` in physical time, its segment starting at
/// `t_seg`) at which the clock of `dense` reads the physical time `ts`: how a sample on the
/// physical grid is placed, live or from a stored step.
fn grid_tau<I: Interpolant<Const<M>> + ?Sized, const N: usize, const M: usize>(
    dense: &I,
    tau: (f64, f64),
    (t0, t1): (f64, f64),
    t_seg: f64,
    ts: f64,
) -> f64 {
    let target = ts - t_seg;
    if ts >= t1 {
        tau.1
    } else if ts <= t0 {
        tau.0
    } else {
        let clock = |tau: f64| -> Result<f64, std::convert::Infallible> {
            Ok(dense.component_at(tau, N) - target)
        };
        find_crossing(tau.0, t0 - ts, tau.1, t1 - ts, -1.0, clock)
            .unwrap_or_else(|never| match never {})
            .t
    }
}

/// A step's dense output in `τ` (`I`: lent by the run, or stored), evaluated in physical time:
/// each evaluation first finds the `τ` at which the clock reads `t` (the clock rises
/// monotonically, `s > 0`), to a few ulps.
#[derive(Clone)]
struct InPhysicalTime<I, const N: usize, const M: usize> {
    dense: I,
    /// The step's ends in `τ`.
    tau: (f64, f64),
    /// The clock at those ends.
    clock: (f64, f64),
    /// Physical time at the segment's start (the clock's origin).
    t_seg: f64,
}

impl<I: Interpolant<Const<M>>, const N: usize, const M: usize> InPhysicalTime<I, N, M> {
    fn tau_at(&self, t: f64) -> f64 {
        let target = t - self.t_seg;
        let (c0, c1) = self.clock;
        if target <= c0 {
            return self.tau.0;
        }
        if target >= c1 {
            return self.tau.1;
        }
        // The clock is nearly linear over a step: secant steps from the chord converge in a
        // few evaluations; the bracketing finder takes over if they stall.
        let (mut lo, mut hi) = ((self.tau.0, c0 - target), (self.tau.1, c1 - target));
        for _ in 0..4 {
            let tau = lo.0 - lo.1 * (hi.0 - lo.0) / (hi.1 - lo.1);
            if !(tau > lo.0 && tau < hi.0) {
                break;
            }
            let f = self.dense.component_at(tau, N) - target;
            if f.abs() <= 4.0 * f64::EPSILON * t.abs() {
                return tau;
            }
            if f < 0.0 {
                lo = (tau, f);
            } else {
                hi = (tau, f);
            }
        }
        let clock = |tau: f64| -> Result<f64, std::convert::Infallible> {
            Ok(self.dense.component_at(tau, N) - target)
        };
        find_crossing(lo.0, lo.1, hi.0, hi.1, -1.0, clock)
            .unwrap_or_else(|never| match never {})
            .t
    }
}

impl<I: Interpolant<Const<M>>, const N: usize, const M: usize> Interpolant<Const<N>>
    for InPhysicalTime<I, N, M>
{
    fn dim(&self) -> Const<N> {
        Const
    }

    fn at(&self, t: f64, out: &mut [f64; N]) {
        let mut z = [0.0; M];
        self.dense.at(self.tau_at(t), &mut z);
        *out = head(&z);
    }

    fn component_at(&self, t: f64, i: usize) -> f64 {
        self.dense.component_at(self.tau_at(t), i)
    }

    fn sample_at(&self, t: f64, out: &mut [f64; N]) {
        let ends = (self.t_seg + self.clock.0, self.t_seg + self.clock.1);
        let tau = grid_tau::<_, N, M>(&self.dense, self.tau, ends, self.t_seg, t);
        let mut z = [0.0; M];
        self.dense.at(tau, &mut z);
        *out = head(&z);
    }

    /// The fraction in `τ`: the clock is read, not solved for. At the step's own ends `τ` is
    /// known; a span ending elsewhere (a step cut short) has its ends' `τ` found on each call.
    fn at_fraction(&self, (t0, t1): (f64, f64), u: f64, out: &mut [f64; N]) -> f64 {
        let tau_of = |t: f64| {
            if t == self.t_seg + self.clock.0 {
                self.tau.0
            } else if t == self.t_seg + self.clock.1 {
                self.tau.1
            } else {
                self.tau_at(t)
            }
        };
        let (a, b) = (tau_of(t0), tau_of(t1));
        let mut z = [0.0; M];
        self.dense.at(a + u * (b - a), &mut z);
        *out = head(&z);
        self.t_seg + z[N]
    }

    fn stored(&self) -> StoredInterpolant<Const<N>> {
        StoredInterpolant::new(InPhysicalTime::<_, N, M> {
            dense: self.dense.stored(),
            tau: self.tau,
            clock: self.clock,
            t_seg: self.t_seg,
        })
    }
}
