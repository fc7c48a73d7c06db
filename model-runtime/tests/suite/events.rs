//! Exact event location and the hybrid driver on systems with closed-form event times.

use crate::common::ball::{Ball, BallGuard, Flights, Impact, G, RESTITUTION};
use crate::common::{dist, stop, up_crossings, ClockGuards, Harmonic, Kepler, OneGuard};
use model_runtime::Const;
use model_runtime::{
    ChatterLimit, Crossed, Direction, Dop853, Dopri5, EvalError, EventHit, GuardSpec, HybridError,
    HybridOptions, HybridSolver, HybridSystem, InteriorChecks, Observer, Recorder, Rk4, Rodas4,
    Sample, Stepper, StopReason, Tolerance, Transition, TransitionKind,
};

fn bounce<S: Stepper<Const<2>>>(stepper: S) {
    let expected = Flights::of(&Ball::dropped(), 1.0, 0.0).impact_times(10);
    let t_end = expected[9] + 0.05;
    let options = HybridOptions {
        sample_rate: Some(20.0),
        ..HybridOptions::default()
    };
    let mut solver = HybridSolver::new(stepper, Tolerance::scalar(1e-10, 1e-12), options).unwrap();
    let mut rec = Recorder::new();
    let out = solver
        .run(&mut Ball::dropped(), (), 0.0, &[1.0, 0.0], t_end, &mut rec)
        .unwrap();
    assert_eq!(out.stop, StopReason::EndTime);
    assert_eq!(out.t, t_end);
    assert_eq!(rec.transitions.len(), 10, "{}", S::NAME);
    for (k, (tr, t)) in rec.transitions.iter().zip(&expected).enumerate() {
        assert!(
            (tr.hit.t - t).abs() < 1e-12,
            "{}: impact {k} at {} instead of {t} (error {:e})",
            S::NAME,
            tr.hit.t,
            tr.hit.t - t
        );
        assert_eq!(tr.hit.direction, Crossed::Down);
        assert_eq!(tr.kind, TransitionKind::Continue);
        // The event state is from the dense output at the event, on the far side of zero.
        assert!(tr.hit.y[0] <= 0.0 && tr.hit.y[0] > -1e-12, "{:?}", tr.hit);
        assert!(
            tr.hit.value == 0.0 || tr.hit.t - tr.hit.before <= 8.0 * f64::EPSILON * tr.hit.t,
            "{:?}",
            tr.hit
        );
    }
    // Samples at 20 Hz on the global grid, across all segments, on the exact parabolas.
    assert_eq!(rec.samples.len(), (t_end * 20.0).floor() as usize + 1);
    for (i, &(t, (), y)) in rec.samples.iter().enumerate() {
        assert!((t - i as f64 / 20.0).abs() < 1e-15);
        let k = expected.iter().filter(|&&ti| ti < t).count();
        let exact_height = if k == 0 {
            1.0 - 0.5 * G * t * t
        } else {
            let v = RESTITUTION.powi(k as i32) * G * expected[0];
            let s = t - expected[k - 1];
            v * s - 0.5 * G * s * s
        };
        assert!(
            (y[0] - exact_height).abs() < 1e-11,
            "{}: sample at {t}",
            S::NAME
        );
    }
    assert_eq!(out.transitions, 10);
    assert_eq!(out.stats.events, 10);
}

#[test]
fn bouncing_ball_impacts_match_the_closed_form_with_every_method() {
    bounce(Dop853::new());
    bounce(Dopri5::new());
    bounce(Rodas4::new());
    bounce(Rk4::new(0.01));
}

#[test]
fn kepler_orbit_crosses_upwards_once_per_period() {
    let e = 0.5;
    let period = 2.0 * std::f64::consts::PI;
    let mut solver = HybridSolver::new(
        Dop853::new(),
        Tolerance::scalar(1e-15, 1e-15),
        HybridOptions::default(),
    )
    .unwrap();
    let mut rec = Recorder::new();
    // Starts exactly on the guard (y = 0): that start does not fire; the next passages do.
    solver
        .run(
            // The Kepler orbit, watched for y crossing upwards (every periapsis passage).
            &mut up_crossings(Kepler, 1),
            (),
            0.0,
            &Kepler::periapsis(e),
            5.5 * period,
            &mut rec,
        )
        .unwrap();
    assert_eq!(rec.transitions.len(), 5);
    for (k, tr) in rec.transitions.iter().enumerate() {
        let expected = (k + 1) as f64 * period;
        let err = tr.hit.t - expected;
        println!("crossing {}: t error {err:e}", k + 1);
        assert!(err.abs() < 1e-12, "crossing {}: error {err:e}", k + 1);
        assert_eq!(tr.hit.direction, Crossed::Up);
        assert!(dist(&tr.hit.y, &Kepler::periapsis(e)) < 1e-11);
    }
}

/// dx/dt = -sign(x) as two modes: a sliding mode at x = 0 that can only chatter.
struct Relay;
#[derive(Clone, Copy, Debug, PartialEq)]
enum Side {
    Positive,
    Negative,
}
const DOWN: [GuardSpec<()>; 1] = [GuardSpec {
    id: (),
    direction: Direction::Down,
}];
const UP: [GuardSpec<()>; 1] = [GuardSpec {
    id: (),
    direction: Direction::Up,
}];
impl HybridSystem<Const<1>> for Relay {
    type Mode = Side;
    type Guard = ();
    type Stop = ();
    type Note = ();
    fn rhs(&self, m: Side, _t: f64, _y: &[f64; 1], dy: &mut [f64; 1]) -> Result<(), EvalError> {
        dy[0] = if m == Side::Positive { -1.0 } else { 1.0 };
        Ok(())
    }
    fn guards(&self, m: Side) -> &[GuardSpec<()>] {
        if m == Side::Positive {
            &DOWN
        } else {
            &UP
        }
    }
    fn guard_values(
        &self,
        _: Side,
        _t: f64,
        y: &[f64; 1],
        _dy: &[f64; 1],
        g: &mut [f64],
    ) -> Result<(), EvalError> {
        g[0] = y[0];
        Ok(())
    }
    fn on_event(
        &mut self,
        m: Side,
        hit: &EventHit<Const<1>, ()>,
    ) -> Result<Transition<Const<1>, Side, ()>, EvalError> {
        let to = if m == Side::Positive {
            Side::Negative
        } else {
            Side::Positive
        };
        Ok(Transition::Switch {
            to,
            y: hit.y,
            note: (),
        })
    }
}

#[test]
fn relay_chattering_is_detected_not_looped() {
    for start in [1.0, 0.7, 1.0 / 3.0] {
        let mut solver = HybridSolver::new(
            Dopri5::new(),
            Tolerance::scalar(1e-8, 1e-10),
            HybridOptions {
                chatter: ChatterLimit {
                    max_transitions: 50,
                    window: 1e-6,
                },
                ..HybridOptions::default()
            },
        )
        .unwrap();
        let err = solver
            .run(&mut Relay, Side::Positive, 0.0, &[start], 10.0, &mut ())
            .unwrap_err();
        match err {
            HybridError::Chattering {
                t,
                transitions,
                modes,
                ..
            } => {
                assert!((t - start).abs() < 1e-6, "chattering reported at {t}");
                assert_eq!(transitions, 51);
                assert_eq!(modes, vec![Side::Positive, Side::Negative]);
            }
            other => panic!("expected chattering, got {other:?}"),
        }
    }
}

/// Whether an event is `(guard, t)` with `t` within a few ulps of the exact root.
fn is(event: Option<(usize, f64)>, guard: usize, t: f64) -> bool {
    matches!(event, Some((g, te)) if g == guard && (te - t).abs() <= 4.0 * f64::EPSILON)
}

fn first_event(guards: &[(Direction, f64)], checks: InteriorChecks) -> Option<(usize, f64)> {
    // Guard i crosses up at x = r_i; a negative r_i marks a guard positive only on
    // (|r_i|, |r_i| + 0.01): a sign change and back.
    let roots: Vec<f64> = guards.iter().map(|&(_, r)| r).collect();
    let mut sys = ClockGuards {
        specs: guards
            .iter()
            .enumerate()
            .map(|(i, &(direction, _))| GuardSpec { id: i, direction })
            .collect(),
        value: |i: usize, x: f64| {
            let r = roots[i];
            if r >= 0.0 {
                x - r
            } else {
                0.000025 - (x - (-r + 0.005)).powi(2)
            }
        },
    };
    let options = HybridOptions {
        guard_checks: checks,
        step: model_runtime::StepOptions {
            h_initial: Some(1.0),
            ..Default::default()
        },
        ..HybridOptions::default()
    };
    let mut solver =
        HybridSolver::new(Dop853::new(), Tolerance::scalar(1e-9, 1e-9), options).unwrap();
    let out = solver.run(&mut sys, (), 0.0, &[0.0], 1.0, &mut ()).unwrap();
    match out.stop {
        StopReason::User(i) => Some((i, out.t)),
        StopReason::EndTime => None,
        StopReason::Observer => unreachable!("the unit observer never stops a run"),
    }
}

#[test]
fn earliest_guard_wins_and_filters_apply_within_one_step() {
    // Both roots inside the single step [0, 1].
    assert!(is(
        first_event(
            &[(Direction::Up, 0.7), (Direction::Up, 0.3)],
            InteriorChecks::None
        ),
        1,
        0.3
    ));
    // Equal times: the guard listed first wins.
    assert_eq!(
        first_event(
            &[(Direction::Up, 0.5), (Direction::Both, 0.5)],
            InteriorChecks::None
        )
        .map(|e| e.0),
        Some(0)
    );
    // A down-only guard ignores an up-crossing.
    assert!(is(
        first_event(
            &[(Direction::Down, 0.3), (Direction::Up, 0.6)],
            InteriorChecks::None
        ),
        1,
        0.6
    ));
    // A root exactly at the end of the step fires there.
    assert!(is(
        first_event(&[(Direction::Up, 1.0)], InteriorChecks::None),
        0,
        1.0
    ));
}

#[test]
fn sign_change_and_back_is_seen_only_with_interior_checks() {
    // Guard 0 is positive only on (0.40, 0.41).
    assert_eq!(
        first_event(&[(Direction::Up, -0.40)], InteriorChecks::None),
        None
    );
    let hit = first_event(&[(Direction::Up, -0.40)], InteriorChecks::Exact(200)).unwrap();
    assert_eq!(hit.0, 0);
    assert!((hit.1 - 0.40).abs() < 1e-12, "{hit:?}");
}

/// A spring `x'' = -x` whose guard reads the acceleration from `dy`: `-x - 0.9999` is
/// positive only for a short while around `x = -1` (t = π), a sign change and back inside one
/// step.
fn spring() -> impl HybridSystem<Const<2>, Mode = (), Guard = (), Stop = ()> {
    OneGuard {
        model: Harmonic,
        guard: |_: &[f64; 2], dy: &[f64; 2]| dy[1] - 0.9999,
        on_event: stop::<2>,
    }
}

fn spring_event(checks: InteriorChecks) -> (f64, model_runtime::Stats) {
    let options = HybridOptions {
        guard_checks: checks,
        ..HybridOptions::default()
    };
    let mut solver =
        HybridSolver::new(Dopri5::new(), Tolerance::scalar(1e-6, 1e-9), options).unwrap();
    let out = solver
        .run(&mut spring(), (), 0.0, &[1.0, 0.0], 5.0, &mut ())
        .unwrap();
    assert_eq!(out.stop, StopReason::User(()), "{checks:?}");
    (out.t, out.stats)
}

#[test]
fn screened_checks_find_an_excursion_of_a_derivative_guard_at_the_exact_time() {
    // x = cos t; the guard -cos t - 0.9999 turns positive at t = π - acos(0.9999).
    let exact_root = std::f64::consts::PI - 0.9999f64.acos();
    assert_eq!(
        first_event(&[(Direction::Up, -0.40)], InteriorChecks::Screened(200)).map(|e| e.0),
        Some(0)
    );
    let (t_exact, exact) = spring_event(InteriorChecks::Exact(8));
    let (t_screened, screened) = spring_event(InteriorChecks::Screened(8));
    // Both locate the same crossing on the same dense output.
    assert!(
        (t_exact - t_screened).abs() < 1e-13,
        "{t_exact} {t_screened}"
    );
    // At the located time the exact guard is zero to within the solution's error (rtol 1e-6
    // on |x| ≈ 1): the time itself is 70× more sensitive, the guard's slope being sin t ≈ 0.014.
    let exact_guard = -t_screened.cos() - 0.9999;
    assert!(
        exact_guard.abs() < 1e-5,
        "{t_screened} vs {exact_root}: guard {exact_guard:e}"
    );
    // The screened run evaluated the model only where an estimate fired.
    assert!(screened.guard_estimates > 0);
    assert!(
        screened.rhs_evals < exact.rhs_evals,
        "{screened:?} vs {exact:?}"
    );
    // Without interior checks the excursion (shorter than a step) goes unseen.
    let options = HybridOptions::default();
    let mut solver =
        HybridSolver::new(Dopri5::new(), Tolerance::scalar(1e-6, 1e-9), options).unwrap();
    let out = solver
        .run(&mut spring(), (), 0.0, &[1.0, 0.0], 5.0, &mut ())
        .unwrap();
    assert_eq!(out.stop, StopReason::EndTime);
}

/// Counts on_step calls and checks every sample's mode.
struct Counter {
    steps: u64,
    samples: u64,
}
impl Observer<Const<2>, (), BallGuard, Impact> for Counter {
    fn on_step(
        &mut self,
        s: &model_runtime::StepView<'_, Const<2>, ()>,
    ) -> model_runtime::Observed {
        assert!(s.t1 > s.t0 && s.dense.is_none());
        self.steps += 1;
        Ok(())
    }
    fn on_sample(&mut self, _: &Sample<'_, Const<2>, ()>) -> model_runtime::Observed {
        self.samples += 1;
        Ok(())
    }
}

#[test]
fn observer_sees_every_accepted_step() {
    let mut solver = HybridSolver::new(
        Dopri5::new(),
        Tolerance::scalar(1e-8, 1e-10),
        HybridOptions::default(),
    )
    .unwrap();
    let mut c = Counter {
        steps: 0,
        samples: 0,
    };
    let out = solver
        .run(&mut Ball::dropped(), (), 0.0, &[1.0, 0.0], 3.0, &mut c)
        .unwrap();
    assert_eq!(c.steps, out.stats.steps);
    assert_eq!(c.samples, 0);
}
