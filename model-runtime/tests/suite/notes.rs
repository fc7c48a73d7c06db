//! A transition's note ([`HybridSystem::Note`]) reaches the observer by value, in order, with
//! the record of the event that caused it: in physical time, through regularised time, and
//! ahead of a restart that fails.

use crate::common::ball::{Ball, BallGuard, Flights, Impact};
use model_runtime::Const;
use model_runtime::{
    Clocked, Direction, Dop853, Dopri5, EvalError, EventHit, GuardSpec, HybridError, HybridOptions,
    HybridSolver, HybridSystem, PhysicalTime, Recorder, Regularised, SolveError, StopReason,
    TimeScale, Tolerance, Transition, TransitionKind,
};

/// Regularised time with a clock that runs slower near the ground.
impl TimeScale<2> for Ball {
    fn time_scale(&self, _: (), y: &[f64; 2]) -> f64 {
        (0.1 + y[0]) / 1.1
    }
}

/// Impact `k` (from 1) of the dropped ball in closed form: its time and the speed before it.
fn impact(k: u32) -> (f64, f64) {
    let flights = Flights::of(&Ball::dropped(), 1.0, 0.0);
    (
        flights.impact_times(k as usize)[k as usize - 1],
        flights.speed(k),
    )
}

/// Every record carries the note its transition map produced for that event, in order.
fn check_notes(
    records: &[model_runtime::TransitionRecord<Const<2>, (), BallGuard, Impact>],
    expected: u32,
) {
    assert_eq!(records.len(), expected as usize);
    for (i, r) in records.iter().enumerate() {
        let k = i as u32 + 1;
        let (t, speed) = impact(k);
        assert_eq!(r.note.number, k);
        assert_eq!(r.kind, TransitionKind::Continue);
        // The note was computed from this record's event state.
        assert_eq!(r.note.speed, -r.hit.y[1]);
        assert_eq!(r.note.label, format!("impact {k} at t = {:.3}", r.hit.t));
        assert!(
            (r.hit.t - t).abs() < 1e-8,
            "impact {k}: {} against {t}",
            r.hit.t
        );
        assert!(
            (r.note.speed - speed).abs() < 1e-7,
            "impact {k}: {}",
            r.note.speed
        );
    }
}

#[test]
fn notes_reach_the_observer_in_physical_time() {
    let mut solver = HybridSolver::new(
        Dopri5::new(),
        Tolerance::scalar(1e-10, 1e-12),
        HybridOptions::default(),
    )
    .unwrap();
    let mut seen = Recorder::new();
    let mut ball = Ball::dropped();
    let out = solver
        .run(&mut ball, (), 0.0, &[1.0, 0.0], 2.5, &mut seen)
        .unwrap();
    assert_eq!(out.stop, StopReason::EndTime);
    // Impacts at 0.452, 1.264, 1.996 s; the fourth is at 2.654 s.
    assert!(impact(3).0 < 2.5 && impact(4).0 > 2.5);
    check_notes(&seen.transitions, 3);
    assert_eq!(out.transitions, 3);
}

#[test]
fn notes_pass_through_regularised_time() {
    let mut ball = Ball::dropped();
    let mut clocked = Regularised::<_, 2, 3>::new(&mut ball, &[()], 0.0, 2.5);
    let tol = clocked.tolerance(&Tolerance::scalar(1e-10, 1e-12), (1e-10, 1e-12));
    let mut solver = HybridSolver::new(Dop853::new(), tol, HybridOptions::default()).unwrap();
    let mut seen = Recorder::new();
    let mut physical = PhysicalTime::<_, 2, 3>::new(&mut seen, 0.0, None);
    let z0 = Regularised::<Ball, 2, 3>::start(&[1.0, 0.0]);
    let out = solver
        .run(&mut clocked, (), 0.0, &z0, f64::MAX, &mut physical)
        .unwrap();
    assert_eq!(out.stop, StopReason::User(Clocked::EndTime));
    check_notes(&seen.transitions, 3);
}

/// Switches once, into a mode whose right-hand side fails at the state it starts from.
struct Doomed;
#[derive(Clone, Copy, Debug, PartialEq)]
enum Leg {
    First,
    Broken,
}
const AT_ONE: [GuardSpec<()>; 1] = [GuardSpec {
    id: (),
    direction: Direction::Up,
}];

impl HybridSystem<Const<1>> for Doomed {
    type Mode = Leg;
    type Guard = ();
    type Stop = ();
    type Note = &'static str;
    fn rhs(&self, leg: Leg, _t: f64, _y: &[f64; 1], dy: &mut [f64; 1]) -> Result<(), EvalError> {
        match leg {
            Leg::First => {
                dy[0] = 1.0;
                Ok(())
            }
            Leg::Broken => Err(EvalError::NonFinite {
                model: "doomed".into(),
                quantity: "der(y)".into(),
                value: f64::INFINITY,
            }),
        }
    }
    fn guards(&self, _: Leg) -> &[GuardSpec<()>] {
        &AT_ONE
    }
    fn guard_values(
        &self,
        _: Leg,
        t: f64,
        _y: &[f64; 1],
        _dy: &[f64; 1],
        g: &mut [f64],
    ) -> Result<(), EvalError> {
        g[0] = t - 1.0;
        Ok(())
    }
    fn on_event(
        &mut self,
        _: Leg,
        hit: &EventHit<Const<1>, ()>,
    ) -> Result<Transition<Const<1>, Leg, (), &'static str>, EvalError> {
        Ok(Transition::Switch {
            to: Leg::Broken,
            y: hit.y,
            note: "into the broken leg",
        })
    }
}

#[test]
fn a_failed_restart_still_reports_the_transition_before_it() {
    let mut solver = HybridSolver::new(
        Dopri5::new(),
        Tolerance::scalar(1e-8, 1e-8),
        HybridOptions::default(),
    )
    .unwrap();
    let mut seen = Recorder::new();
    let err = solver
        .run(&mut Doomed, Leg::First, 0.0, &[0.0], 2.0, &mut seen)
        .unwrap_err();
    match err {
        HybridError::Solve {
            mode: Leg::Broken,
            error: SolveError::Eval { t, .. },
        } => assert!((t - 1.0).abs() < 1e-12, "failed at {t}"),
        other => panic!("{other:?}"),
    }
    assert_eq!(seen.transitions.len(), 1);
    let record = &seen.transitions[0];
    assert_eq!(record.note, "into the broken leg");
    assert_eq!(record.kind, TransitionKind::Switch { to: Leg::Broken });
    assert!((record.hit.t - 1.0).abs() < 1e-12);
}
