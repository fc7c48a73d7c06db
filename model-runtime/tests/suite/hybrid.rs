//! The hybrid driver's contract: switches, immediate switch-backs, projection, typed errors.

use crate::common;
use crate::common::OneGuard;
use model_runtime::Const;

use model_runtime::{
    Crossed, Direction, Dopri5, EvalError, EventHit, GuardSpec, HybridError, HybridOptions,
    HybridSolver, HybridSystem, Recorder, Rodas4, SolveError, Stepper, StopReason, Tolerance,
    Transition, TransitionKind,
};

/// DP5 at rtol = atol = 1e-8 with default options: the solver most tests here need.
fn dp5<const N: usize>() -> HybridSolver<Dopri5<Const<N>>, Const<N>> {
    HybridSolver::new(
        Dopri5::new(),
        Tolerance::scalar(1e-8, 1e-8),
        HybridOptions::default(),
    )
    .unwrap()
}

/// A toy stick–slip: in `Stick` the speed stays 0 until the drive `t - 1` turns positive; in
/// `Slide` the speed follows `v' = a` and sliding ends when `v` falls back to 0. With `a < 0`
/// sliding wants to end the instant it starts.
struct StickSlip {
    a: f64,
    fail_on_event: bool,
}
#[derive(Clone, Copy, Debug, PartialEq)]
enum Phase {
    Stick,
    Slide,
}
#[derive(Clone, Copy, Debug, PartialEq)]
enum Why {
    Drive,
    Stopped,
}
const STICK: [GuardSpec<Why>; 1] = [GuardSpec {
    id: Why::Drive,
    direction: Direction::Up,
}];
const SLIDE: [GuardSpec<Why>; 1] = [GuardSpec {
    id: Why::Stopped,
    direction: Direction::Down,
}];
impl HybridSystem<Const<2>> for StickSlip {
    type Mode = Phase;
    type Guard = Why;
    type Stop = (Phase, f64);
    type Note = ();
    fn rhs(&self, m: Phase, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
        // y = (position, speed)
        *dy = match m {
            Phase::Stick => [0.0, 0.0],
            Phase::Slide => [y[1], self.a],
        };
        Ok(())
    }
    fn guards(&self, m: Phase) -> &[GuardSpec<Why>] {
        match m {
            Phase::Stick => &STICK,
            Phase::Slide => &SLIDE,
        }
    }
    fn guard_values(
        &self,
        m: Phase,
        t: f64,
        y: &[f64; 2],
        _dy: &[f64; 2],
        g: &mut [f64],
    ) -> Result<(), EvalError> {
        g[0] = match m {
            Phase::Stick => t - 1.0,
            Phase::Slide => y[1],
        };
        Ok(())
    }
    fn on_event(
        &mut self,
        m: Phase,
        hit: &EventHit<Const<2>, Why>,
    ) -> Result<Transition<Const<2>, Phase, (Phase, f64)>, EvalError> {
        if self.fail_on_event {
            return Err(EvalError::NonFinite {
                model: "stick_slip".into(),
                quantity: "drive".into(),
                value: f64::NAN,
            });
        }
        Ok(match m {
            Phase::Stick => Transition::Switch {
                to: Phase::Slide,
                y: [hit.y[0], 0.0],
                note: (),
            },
            Phase::Slide => Transition::Stop((m, hit.t)),
        })
    }
}

/// The outcome of a stick-slip run and what it recorded.
type StickSlipRun = (
    model_runtime::HybridOutcome<Const<2>, Phase, (Phase, f64)>,
    Recorder<Const<2>, Phase, Why>,
);

fn stick_slip<S: Stepper<Const<2>>>(stepper: S, a: f64) -> StickSlipRun {
    let mut solver = HybridSolver::new(
        stepper,
        Tolerance::scalar(1e-10, 1e-12),
        HybridOptions::default(),
    )
    .unwrap();
    let mut rec = Recorder::new();
    let out = solver
        .run(
            &mut StickSlip {
                a,
                fail_on_event: false,
            },
            Phase::Stick,
            0.0,
            &[0.0, 0.0],
            10.0,
            &mut rec,
        )
        .unwrap();
    (out, rec)
}

#[test]
fn an_immediate_switch_back_is_reported_at_the_switch_instant() {
    for (out, rec) in [
        stick_slip(Dopri5::new(), -1.0),
        stick_slip(Rodas4::new(), -1.0),
    ] {
        // The switch into sliding at t = 1 ...
        assert_eq!(rec.transitions.len(), 1);
        let first = &rec.transitions[0];
        assert_eq!(first.kind, TransitionKind::Switch { to: Phase::Slide });
        assert!((first.hit.t - 1.0).abs() <= 4.0 * f64::EPSILON);
        // ... is followed at once by the end of sliding: v leaves 0 downwards.
        match out.stop {
            StopReason::User((Phase::Slide, t)) => assert_eq!(t, first.hit.t),
            other => panic!("{other:?}"),
        }
        assert_eq!(out.t, first.hit.t);
        assert_eq!(out.y, [0.0, 0.0]);
    }
}

#[test]
fn a_switch_into_a_consistent_mode_runs_on() {
    // With a > 0 sliding continues: v = a (t - 1) never returns to 0 before t_end.
    let (out, rec) = stick_slip(Dopri5::new(), 2.0);
    assert_eq!(out.stop, StopReason::EndTime);
    assert_eq!(out.mode, Phase::Slide);
    assert_eq!(rec.transitions.len(), 1);
    assert!((out.y[1] - 2.0 * 9.0).abs() < 1e-9);
    assert!((out.y[0] - 81.0).abs() < 1e-8);
    assert_eq!(rec.transitions[0].hit.direction, Crossed::Up);
}

#[test]
fn transition_map_failures_are_typed() {
    let mut solver = dp5();
    let err = solver
        .run(
            &mut StickSlip {
                a: 1.0,
                fail_on_event: true,
            },
            Phase::Stick,
            0.0,
            &[0.0, 0.0],
            10.0,
            &mut (),
        )
        .unwrap_err();
    match err {
        HybridError::Transition { mode, t, source } => {
            assert_eq!(mode, Phase::Stick);
            assert!((t - 1.0).abs() < 1e-12);
            assert!(matches!(
                source,
                EvalError::NonFinite { quantity, .. } if quantity == "drive"
            ));
        }
        other => panic!("{other:?}"),
    }
}

/// Rotation on the unit circle with a projection back onto it.
struct Circle {
    project: bool,
    bad_guard: bool,
}
impl HybridSystem<Const<2>> for Circle {
    type Mode = ();
    type Guard = ();
    type Stop = ();
    type Note = ();
    fn rhs(&self, _: (), _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
        *dy = [-y[1], y[0]];
        Ok(())
    }
    fn guards(&self, _: ()) -> &[GuardSpec<()>] {
        &[GuardSpec {
            id: (),
            direction: Direction::Both,
        }]
    }
    fn guard_values(
        &self,
        _: (),
        t: f64,
        _y: &[f64; 2],
        _dy: &[f64; 2],
        g: &mut [f64],
    ) -> Result<(), EvalError> {
        g[0] = if self.bad_guard && t > 2.0 {
            f64::NAN
        } else {
            1.0
        };
        Ok(())
    }
    fn on_event(
        &mut self,
        _: (),
        _: &EventHit<Const<2>, ()>,
    ) -> Result<Transition<Const<2>, (), ()>, EvalError> {
        Ok(Transition::Stop(()))
    }
    fn project(&self, _: (), _t: f64, y: &mut [f64; 2]) -> bool {
        if !self.project {
            return false;
        }
        let r = (y[0] * y[0] + y[1] * y[1]).sqrt();
        y[0] /= r;
        y[1] /= r;
        true
    }
}

#[test]
fn projection_keeps_the_state_on_its_constraint() {
    let radius_error = |project: bool| {
        let mut solver = HybridSolver::new(
            Dopri5::new(),
            Tolerance::scalar(1e-4, 1e-4),
            HybridOptions::default(),
        )
        .unwrap();
        let out = solver
            .run(
                &mut Circle {
                    project,
                    bad_guard: false,
                },
                (),
                0.0,
                &[1.0, 0.0],
                200.0,
                &mut (),
            )
            .unwrap();
        ((out.y[0] * out.y[0] + out.y[1] * out.y[1]).sqrt() - 1.0).abs()
    };
    let free = radius_error(false);
    let projected = radius_error(true);
    println!("radius drift: free {free:e}, projected {projected:e}");
    assert!(free > 1e-5, "the test needs a drifting solution: {free:e}");
    assert!(projected < 1e-15, "{projected:e}");
}

#[test]
fn a_non_finite_guard_is_a_typed_error_naming_the_mode() {
    let mut solver = dp5();
    let err = solver
        .run(
            &mut Circle {
                project: false,
                bad_guard: true,
            },
            (),
            0.0,
            &[1.0, 0.0],
            5.0,
            &mut (),
        )
        .unwrap_err();
    assert!(
        matches!(
            err,
            HybridError::Solve {
                mode: (),
                error: SolveError::GuardNotFinite { guard: 0, t, .. }
            } if t > 2.0
        ),
        "{err:?}"
    );
}

/// `y' = 1`, singular beyond `y = 2`, with a stop guard at `y = 1.9`.
fn cliff() -> impl HybridSystem<Const<1>, Mode = (), Guard = (), Stop = ()> {
    OneGuard {
        model: common::Fragile,
        guard: |y: &[f64; 1], _: &[f64; 1]| y[0] - 1.9,
        on_event: common::stop::<1>,
    }
}

#[test]
fn a_step_overshooting_into_a_singular_region_is_retried_and_the_guard_found() {
    let options = HybridOptions {
        step: model_runtime::StepOptions {
            h_initial: Some(1.5),
            ..Default::default()
        },
        ..HybridOptions::default()
    };
    let mut solver =
        HybridSolver::new(Dopri5::new(), Tolerance::scalar(1e-8, 1e-8), options).unwrap();
    let out = solver
        .run(&mut cliff(), (), 0.0, &[0.0], 5.0, &mut ())
        .unwrap();
    assert_eq!(out.stop, StopReason::User(()));
    assert!((out.t - 1.9).abs() < 1e-14, "{}", out.t);
    assert!(out.stats.rejected >= 1, "{:?}", out.stats);
}

/// `y' = 1` whose transition map at `y = 1` returns a NaN state.
fn broken() -> impl HybridSystem<Const<1>, Mode = (), Guard = (), Stop = ()> {
    OneGuard {
        model: common::Ramp,
        guard: |y: &[f64; 1], _: &[f64; 1]| y[0] - 1.0,
        on_event: |_: &EventHit<Const<1>, ()>| Transition::Continue {
            y: [f64::NAN],
            note: (),
        },
    }
}

#[test]
fn a_non_finite_state_from_the_transition_map_is_named() {
    let mut solver = dp5();
    let err = solver
        .run(&mut broken(), (), 0.0, &[0.0], 10.0, &mut ())
        .unwrap_err();
    match err {
        HybridError::Solve {
            mode: (),
            error:
                SolveError::TransitionState {
                    t,
                    component: 0,
                    value,
                },
        } => {
            assert!((t - 1.0).abs() < 1e-12);
            assert!(value.is_nan());
        }
        other => panic!("{other:?}"),
    }
}

/// The stick–slip toy with a first-step hint for sliding segments.
struct Hinted(StickSlip);
impl HybridSystem<Const<2>> for Hinted {
    type Mode = Phase;
    type Guard = Why;
    type Stop = (Phase, f64);
    type Note = ();
    fn rhs(&self, m: Phase, t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
        self.0.rhs(m, t, y, dy)
    }
    fn guards(&self, m: Phase) -> &[GuardSpec<Why>] {
        self.0.guards(m)
    }
    fn guard_values(
        &self,
        m: Phase,
        t: f64,
        y: &[f64; 2],
        dy: &[f64; 2],
        g: &mut [f64],
    ) -> Result<(), EvalError> {
        self.0.guard_values(m, t, y, dy, g)
    }
    fn on_event(
        &mut self,
        m: Phase,
        hit: &EventHit<Const<2>, Why>,
    ) -> Result<Transition<Const<2>, Phase, (Phase, f64)>, EvalError> {
        self.0.on_event(m, hit)
    }
    fn first_step(&self, m: Phase, _t: f64, _y: &[f64; 2]) -> Option<f64> {
        (m == Phase::Slide).then_some(1e-3)
    }
}

/// Records the first step of every segment.
#[derive(Default)]
struct FirstSteps {
    expect_first: bool,
    first: Vec<(Phase, f64)>,
}
impl model_runtime::Observer<Const<2>, Phase, Why> for FirstSteps {
    fn on_step(
        &mut self,
        s: &model_runtime::StepView<'_, Const<2>, Phase>,
    ) -> model_runtime::Observed {
        if self.expect_first {
            self.first.push((s.mode, s.t1 - s.t0));
            self.expect_first = false;
        }
        Ok(())
    }
    fn on_transition(
        &mut self,
        _: model_runtime::TransitionRecord<Const<2>, Phase, Why>,
    ) -> model_runtime::Observed {
        self.expect_first = true;
        Ok(())
    }
}

#[test]
fn a_first_step_hint_starts_the_segment() {
    let mut solver = dp5();
    let mut obs = FirstSteps::default();
    let mut sys = Hinted(StickSlip {
        a: 2.0,
        fail_on_event: false,
    });
    solver
        .run(&mut sys, Phase::Stick, 0.0, &[0.0, 0.0], 3.0, &mut obs)
        .unwrap();
    // t1 - t0 is the hinted step up to the rounding of t0 + h (t0 ≈ 1).
    assert_eq!(obs.first.len(), 1);
    assert_eq!(obs.first[0].0, Phase::Slide);
    assert!((obs.first[0].1 - 1e-3).abs() < 1e-15, "{:?}", obs.first);
}
