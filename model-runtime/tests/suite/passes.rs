//! Events that pass ([`Transition::Pass`]): located and reported exactly, at no cost to the
//! run: the steps, samples and final state are bit for bit those of the run without them.

use crate::common::log::RunLog;
use model_runtime::Const;
use model_runtime::{
    ChatterLimit, Clocked, Crossed, Direction, Dop853, EvalError, EventHit, GuardSpec,
    HybridOptions, HybridOutcome, HybridSolver, HybridSystem, InteriorChecks, PhysicalTime,
    Regularised, StopReason, TimeScale, Tolerance, Transition, TransitionKind,
};
use proptest::prelude::*;
use std::f64::consts::PI;
use std::rc::Rc;

/// What a watched guard does when it fires.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Action {
    Pass,
    Stop,
}

/// A guard of the oscillator: its value at `(t, y)` and its action.
type Watch = (GuardSpec<usize>, Rc<dyn Fn(f64, &[f64; 2]) -> f64>, Action);

/// A watch of guard `id` with `direction` and `value`.
fn watch(
    id: usize,
    direction: Direction,
    value: impl Fn(f64, &[f64; 2]) -> f64 + 'static,
    action: Action,
) -> Watch {
    (GuardSpec { id, direction }, Rc::new(value), action)
}

/// The harmonic oscillator `x' = v, v' = -x` from `(1, 0)`, i.e. `x = cos t`, watched by some
/// guards.
struct Watched {
    specs: Vec<GuardSpec<usize>>,
    watches: Vec<Watch>,
}

impl Watched {
    fn new(watches: Vec<Watch>) -> Watched {
        Watched {
            specs: watches.iter().map(|w| w.0).collect(),
            watches,
        }
    }
}

impl HybridSystem<Const<2>> for Watched {
    type Mode = ();
    type Guard = usize;
    type Stop = usize;
    type Note = ();
    fn rhs(&self, _: (), _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
        *dy = [y[1], -y[0]];
        Ok(())
    }
    fn guards(&self, _: ()) -> &[GuardSpec<usize>] {
        &self.specs
    }
    fn guard_values(
        &self,
        _: (),
        t: f64,
        y: &[f64; 2],
        _dy: &[f64; 2],
        g: &mut [f64],
    ) -> Result<(), EvalError> {
        for (v, w) in g.iter_mut().zip(&self.watches) {
            *v = (w.1)(t, y);
        }
        Ok(())
    }
    fn on_event(
        &mut self,
        _: (),
        hit: &EventHit<Const<2>, usize>,
    ) -> Result<Transition<Const<2>, (), usize>, EvalError> {
        Ok(match self.watches[hit.index].2 {
            Action::Pass => Transition::Pass { note: () },
            Action::Stop => Transition::Stop(hit.guard),
        })
    }
}

/// The zeros of `x = cos t` (both ways, at π/2 + kπ) and the upward zeros of the fast
/// `sin(50 t)` (at kπ/25, several in one step of the oscillator, never at a zero of `x`),
/// passing.
fn passing_watches() -> Vec<Watch> {
    vec![
        watch(0, Direction::Both, |_, y| y[0], Action::Pass),
        watch(1, Direction::Up, |t, _| (50.0 * t).sin(), Action::Pass),
    ]
}

type Log = RunLog<2, (), usize, ()>;
type Outcome = HybridOutcome<Const<2>, (), usize>;

/// DOP853 at 1e-10 with 10 samples per unit and the given interior checks, to `t_end`; a
/// chattering limit of one transition per unit time that passes must not trip.
fn run(sys: &mut Watched, checks: InteriorChecks, t_end: f64) -> (Outcome, Log) {
    let options = HybridOptions {
        sample_rate: Some(10.0),
        guard_checks: checks,
        chatter: ChatterLimit {
            max_transitions: 1,
            window: 1.0,
        },
        ..HybridOptions::default()
    };
    let mut solver =
        HybridSolver::new(Dop853::new(), Tolerance::scalar(1e-10, 1e-12), options).unwrap();
    let mut log = RunLog::new();
    let out = solver
        .run(sys, (), 0.0, &[1.0, 0.0], t_end, &mut log)
        .unwrap();
    (out, log)
}

/// The closed-form times of the passing events up to `t_end`, in order: `(t, guard, how)`.
fn expected_passes(t_end: f64) -> Vec<(f64, usize, Crossed)> {
    let mut events = Vec::new();
    for k in 0.. {
        let t = PI / 2.0 + k as f64 * PI;
        if t > t_end {
            break;
        }
        let how = if k % 2 == 0 {
            Crossed::Down
        } else {
            Crossed::Up
        };
        events.push((t, 0, how));
    }
    // sin(50 t) starts on zero at t = 0: a run's start is quiet.
    for k in 1.. {
        let t = k as f64 * PI / 25.0;
        if t > t_end {
            break;
        }
        events.push((t, 1, Crossed::Up));
    }
    events.sort_by(|a, b| a.0.total_cmp(&b.0));
    events
}

#[test]
fn passing_events_leave_steps_samples_and_state_bit_for_bit_unchanged() {
    let t_end = 7.0;
    let (plain, plain_log) = run(&mut Watched::new(Vec::new()), InteriorChecks::None, t_end);
    assert!(plain_log.records.is_empty());
    // Several passes in one step: the fast guard's period is shorter than most steps, and
    // only interior checks see all its crossings (screening assumes guards slower than a
    // step, so it is not used here).
    assert!(plain_log.steps.iter().any(|s| s.1 - s.0 > 2.0 * PI / 50.0));
    let slow_only = || passing_watches()[..1].to_vec();
    for (checks, watches) in [
        (InteriorChecks::Exact(8), passing_watches()),
        (InteriorChecks::None, slow_only()),
    ] {
        let guards = watches.len();
        let (out, log) = run(&mut Watched::new(watches), checks, t_end);
        assert_eq!(log.steps, plain_log.steps, "{checks}");
        assert_eq!(log.samples, plain_log.samples, "{checks}");
        assert_eq!(
            (out.t, out.y, out.stop),
            (plain.t, plain.y, StopReason::EndTime)
        );
        assert_eq!(out.stats.steps, plain.stats.steps);
        let expected: Vec<_> = expected_passes(t_end)
            .into_iter()
            .filter(|e| e.1 < guards)
            .collect();
        assert_eq!((out.transitions, out.passes), (0, expected.len() as u64));
        assert_eq!(log.records.len(), expected.len(), "{checks}");
        for (r, &(t, guard, how)) in log.records.iter().zip(&expected) {
            assert_eq!(
                (r.kind, r.hit.guard, r.hit.direction),
                (TransitionKind::Pass, guard, how)
            );
            assert_eq!(r.y_after, r.hit.y);
            // The fast guard reads only `t`: exact to ulps; the oscillator's zeros are as
            // exact as its solution.
            let tol = if guard == 1 { 1e-13 } else { 1e-9 };
            assert!((r.hit.t - t).abs() < tol, "{checks}: {r:?} against {t}");
        }
    }
}

#[test]
fn a_stop_after_passes_in_one_step_cuts_that_step_at_the_stop() {
    let t_stop = 2.0;
    let mut watches = passing_watches();
    watches.push(watch(2, Direction::Up, |t, _| t - 2.0, Action::Stop));
    let (out, log) = run(&mut Watched::new(watches), InteriorChecks::Exact(8), 7.0);
    let (_, plain_log) = run(&mut Watched::new(Vec::new()), InteriorChecks::None, 7.0);
    assert_eq!(out.stop, StopReason::User(2));
    assert_eq!((out.t, out.transitions), (t_stop, 0));
    assert!((out.y[0] - t_stop.cos()).abs() < 1e-9);
    let expected = expected_passes(t_stop);
    assert_eq!(out.passes, expected.len() as u64);
    let times: Vec<f64> = log.records.iter().map(|r| r.hit.t).collect();
    assert!(times
        .iter()
        .zip(expected.iter())
        .all(|(t, e)| (t - e.0).abs() < 1e-9));
    // The steps before the stop are the plain run's; the last one is cut at the stop.
    let n = log.steps.len();
    assert_eq!(log.steps[..n - 1], plain_log.steps[..n - 1]);
    let (last, plain_last) = (log.steps[n - 1], plain_log.steps[n - 1]);
    assert_eq!((last.0, last.1), (plain_last.0, t_stop));
    assert!(plain_last.0 < t_stop && t_stop < plain_last.1);
    // The passes inside that step before the stop were all reported.
    let inside = |t: f64| t > last.0;
    assert_eq!(
        times.iter().filter(|&&t| inside(t)).count(),
        expected.iter().filter(|e| inside(e.0)).count()
    );
}

#[test]
fn guards_that_pass_at_the_same_time_are_reported_in_priority_order() {
    let at_one = |id| watch(id, Direction::Up, |t, _| t - 1.0, Action::Pass);
    let (out, log) = run(
        &mut Watched::new(vec![at_one(0), at_one(1)]),
        InteriorChecks::None,
        2.0,
    );
    assert_eq!((out.passes, out.t), (2, 2.0));
    let (first, second) = (&log.records[0].hit, &log.records[1].hit);
    assert_eq!((first.guard, second.guard), (0, 1));
    // The second is found on the rest of the step, a few ulps after the first at most.
    assert!(
        first.t <= second.t && second.t - 1.0 <= 8.0 * f64::EPSILON,
        "{first:?} {second:?}"
    );
    assert!((first.t - 1.0).abs() <= 4.0 * f64::EPSILON);
}

/// Regularised time with a clock that runs at half speed where `x = -1`.
impl TimeScale<2> for Watched {
    fn time_scale(&self, _: (), y: &[f64; 2]) -> f64 {
        (3.0 + y[0]) / 4.0
    }
}

#[test]
fn passes_keep_the_segment_clock_of_regularised_time() {
    let t_end = 7.0;
    let mut sys = Watched::new(passing_watches()[..1].to_vec());
    let mut clocked = Regularised::<_, 2, 3>::new(&mut sys, &[()], 0.0, t_end);
    let tol = clocked.tolerance(&Tolerance::scalar(1e-10, 1e-12), (1e-10, 1e-12));
    let mut solver = HybridSolver::new(Dop853::new(), tol, HybridOptions::default()).unwrap();
    let mut log = RunLog::new();
    let mut physical = PhysicalTime::<_, 2, 3>::new(&mut log, 0.0, None);
    let z0 = Regularised::<Watched, 2, 3>::start(&[1.0, 0.0]);
    let out = solver
        .run(&mut clocked, (), 0.0, &z0, f64::MAX, &mut physical)
        .unwrap();
    assert_eq!(out.stop, StopReason::User(Clocked::EndTime));
    // Every pass in physical time, on the one clock the segment started with.
    let expected: Vec<_> = expected_passes(t_end)
        .into_iter()
        .filter(|e| e.1 == 0)
        .collect();
    assert_eq!((out.passes, out.transitions), (expected.len() as u64, 0));
    assert_eq!(log.records.len(), expected.len());
    for (r, &(t, _, how)) in log.records.iter().zip(&expected) {
        assert_eq!((r.kind, r.hit.direction), (TransitionKind::Pass, how));
        assert!((r.hit.t - t).abs() < 1e-8, "{} against {t}", r.hit.t);
        assert!((r.hit.y[0]).abs() < 1e-8 && (r.hit.dy[0] - r.hit.y[1]).abs() < 1e-12);
    }
    let last = log.steps.last().unwrap();
    assert!((last.1 - t_end).abs() < 1e-12, "{last:?}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Any fast guard that passes, checked densely enough to see all its crossings: the run is
    /// the plain one, and the events are the guard's admitted zeros, in order.
    #[test]
    fn any_passing_guard_leaves_the_run_unchanged(
        freq in 2.0..40.0f64,
        phase in 0.1..6.1f64,
        direction in prop::sample::select(vec![Direction::Up, Direction::Down, Direction::Both]),
        points in 4..10u32,
    ) {
        let t_end = 7.0;
        let (plain, plain_log) = run(&mut Watched::new(Vec::new()), InteriorChecks::None, t_end);
        let fast = watch(0, direction, move |t, _| (freq * t + phase).sin(), Action::Pass);
        let zeros_of_x = watch(1, Direction::Both, |_, y| y[0], Action::Pass);
        let mut watched = Watched::new(vec![fast, zeros_of_x]);
        let (out, log) = run(&mut watched, InteriorChecks::Exact(points), t_end);
        prop_assert_eq!(&log.steps, &plain_log.steps);
        prop_assert_eq!(&log.samples, &plain_log.samples);
        prop_assert_eq!((out.t, out.y), (plain.t, plain.y));
        // The fast guard's admitted zeros, at (kπ - phase) / freq in (0, t_end].
        let zeros: Vec<f64> = (0..)
            .map(|k| (k, (k as f64 * PI - phase) / freq))
            .skip_while(|&(_, t)| t <= 0.0)
            .take_while(|&(_, t)| t <= t_end)
            // sin crosses up at even multiples of π, down at odd ones.
            .filter(|&(k, _)| direction.admits(if k % 2 == 0 { Crossed::Up } else { Crossed::Down }))
            .map(|(_, t)| t)
            .collect();
        let fast_hits: Vec<f64> =
            log.records.iter().filter(|r| r.hit.index == 0).map(|r| r.hit.t).collect();
        prop_assert_eq!(fast_hits.len(), zeros.len());
        for (t, zero) in fast_hits.iter().zip(&zeros) {
            prop_assert!((t - zero).abs() < 1e-12, "{} against {}", t, zero);
        }
        let times: Vec<f64> = log.records.iter().map(|r| r.hit.t).collect();
        prop_assert!(times.windows(2).all(|w| w[0] <= w[1]), "{:?}", times);
    }
}
