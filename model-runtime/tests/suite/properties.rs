//! Properties over random configurations: event times of random bouncing balls, and the
//! error of adaptive runs following the requested tolerance.

use crate::common::ball::{Ball, Flights};
use crate::common::{dist, ClockGuards, Forced};
use model_runtime::Const;
use model_runtime::{
    integrate, Direction, Dop853, Dopri5, EvalError, EventHit, GuardSpec, HybridOptions,
    HybridSolver, HybridSystem, Recorder, StepOptions, Stepper, Tolerance, Transition,
};
use proptest::prelude::*;

fn check_ball<S: Stepper<Const<2>>>(
    stepper: S,
    h0: f64,
    v0: f64,
    e: f64,
    rtol: f64,
) -> Result<(), TestCaseError> {
    let mut ball = Ball::new(9.81, e);
    let flights = Flights::of(&ball, h0, v0);
    let times = flights.impact_times(6);
    let mut solver = HybridSolver::new(
        stepper,
        Tolerance::scalar(rtol, rtol * 1e-2),
        HybridOptions::default(),
    )
    .unwrap();
    let mut rec = Recorder::new();
    solver
        .run(
            &mut ball,
            (),
            0.0,
            &[h0, v0],
            // Halfway through the seventh flight (flights shrink geometrically: a later end
            // could lie beyond their accumulation point).
            times[5] + e.powi(6) * flights.v1 / flights.g,
            &mut rec,
        )
        .unwrap();
    prop_assert_eq!(rec.transitions.len(), 6);
    for (tr, t) in rec.transitions.iter().zip(&times) {
        // Parabolas are integrated and interpolated exactly: only round-off remains.
        prop_assert!(
            (tr.hit.t - t).abs() < 1e-12 * t.max(1.0),
            "{} vs {}",
            tr.hit.t,
            t
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_balls_bounce_on_time(
        h0 in 0.05f64..10.0,
        v0 in -3.0f64..3.0,
        e in 0.3f64..0.95,
        log_rtol in -12.0f64..-5.0,
    ) {
        let rtol = 10f64.powf(log_rtol);
        check_ball(Dop853::new(), h0, v0, e, rtol)?;
        check_ball(Dopri5::new(), h0, v0, e, rtol)?;
    }

    #[test]
    fn global_error_follows_the_tolerance(log_rtol in -12.0f64..-4.0, t_end in 0.5f64..8.0) {
        let rtol = 10f64.powf(log_rtol);
        let tol = Tolerance::scalar(rtol, rtol);
        for (name, err) in [
            ("DOP853", dist(&integrate(&Forced, Dop853::new(), tol, StepOptions::default(), 0.0, &Forced::Y0, t_end).unwrap().y, &Forced::exact(t_end))),
            ("DOPRI5", dist(&integrate(&Forced, Dopri5::new(), tol, StepOptions::default(), 0.0, &Forced::Y0, t_end).unwrap().y, &Forced::exact(t_end))),
        ] {
            // The solution's components are O(1..e): the error stays within a modest multiple
            // of the tolerance (global errors accumulate over the ~t_end/h steps).
            prop_assert!(err < 100.0 * rtol * t_end.max(1.0), "{name}: error {err:e} at rtol {rtol:e}");
        }
    }
}

/// The harmonic oscillator `x = cos(t + phase)` with a guard `x - level` in both directions.
struct Level {
    level: f64,
}
const BOTH: [GuardSpec<()>; 1] = [GuardSpec {
    id: (),
    direction: Direction::Both,
}];
impl HybridSystem<Const<2>> for Level {
    type Mode = ();
    type Guard = ();
    type Stop = ();
    type Note = ();
    fn rhs(&self, _: (), _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
        *dy = [y[1], -y[0]];
        Ok(())
    }
    fn guards(&self, _: ()) -> &[GuardSpec<()>] {
        &BOTH
    }
    fn guard_values(
        &self,
        _: (),
        _t: f64,
        y: &[f64; 2],
        _dy: &[f64; 2],
        g: &mut [f64],
    ) -> Result<(), EvalError> {
        g[0] = y[0] - self.level;
        Ok(())
    }
    fn on_event(
        &mut self,
        _: (),
        hit: &EventHit<Const<2>, ()>,
    ) -> Result<Transition<Const<2>, (), ()>, EvalError> {
        Ok(Transition::Continue { y: hit.y, note: () })
    }
}

/// Times in `(0, t_end]` at which `cos(t + phase) = level`, in order.
fn level_times(phase: f64, level: f64, t_end: f64) -> Vec<f64> {
    let a = level.acos();
    let two_pi = 2.0 * std::f64::consts::PI;
    let mut times = Vec::new();
    for k in -1..=((t_end / two_pi) as i64 + 2) {
        for base in [a, two_pi - a] {
            let t = base + k as f64 * two_pi - phase;
            if t > 1e-9 && t <= t_end {
                times.push(t);
            }
        }
    }
    times.sort_by(f64::total_cmp);
    times
}

fn check_levels<S: Stepper<Const<2>>>(
    stepper: S,
    phase: f64,
    level: f64,
) -> Result<(), TestCaseError> {
    let t_end = 20.0;
    let expected = level_times(phase, level, t_end);
    let mut solver = HybridSolver::new(
        stepper,
        Tolerance::scalar(1e-11, 1e-11),
        HybridOptions::default(),
    )
    .unwrap();
    let mut rec = Recorder::new();
    let y0 = [phase.cos(), -phase.sin()];
    solver
        .run(&mut Level { level }, (), 0.0, &y0, t_end, &mut rec)
        .unwrap();
    let found: Vec<f64> = rec.transitions.iter().map(|r| r.hit.t).collect();
    prop_assert_eq!(found.len(), expected.len(), "{:?} vs {:?}", found, expected);
    for (f, e) in found.iter().zip(&expected) {
        // Near the turning points (level close to ±1) the crossing is ill-conditioned: the
        // time error is the state error divided by |x'| = sqrt(1 - level²).
        let slope = (1.0 - level * level).sqrt();
        prop_assert!(
            (f - e).abs() < 1e-8 / slope,
            "{} vs {} (level {})",
            f,
            e,
            level
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn level_crossings_of_an_oscillator_match_the_arccos(phase in 0.0f64..std::f64::consts::TAU, level in -0.95f64..0.95) {
        check_levels(Dop853::new(), phase, level)?;
        check_levels(Dopri5::new(), phase, level)?;
    }
}

fn direction(k: u8) -> Direction {
    match k % 3 {
        0 => Direction::Up,
        1 => Direction::Down,
        _ => Direction::Both,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn the_earliest_admitted_guard_fires(
        guards in proptest::collection::vec((0.01f64..2.0, any::<bool>(), 0u8..3), 1..8),
        h in 0.05f64..3.0,
    ) {
        let sys_guards: Vec<GuardSpec<usize>> = guards
            .iter()
            .enumerate()
            .map(|(i, g)| GuardSpec { id: i, direction: direction(g.2) })
            .collect();
        // Guard i is s_i (x - r_i): it crosses up (s_i = 1) or down (s_i = -1) at t = r_i.
        let mut sys = ClockGuards {
            specs: sys_guards,
            value: |i: usize, x: f64| if guards[i].1 { x - guards[i].0 } else { guards[i].0 - x },
        };
        // The brute-force answer: the smallest admitted root, the first listed on ties.
        let expected = guards
            .iter()
            .enumerate()
            .filter(|(_, g)| {
                let crossed = if g.1 { model_runtime::Crossed::Up } else { model_runtime::Crossed::Down };
                direction(g.2).admits(crossed)
            })
            .min_by(|a, b| a.1 .0.total_cmp(&b.1 .0).then(a.0.cmp(&b.0)))
            .map(|(i, g)| (i, g.0));
        let options = HybridOptions {
            step: StepOptions { h_initial: Some(h), h_max: h, ..StepOptions::default() },
            ..HybridOptions::default()
        };
        let mut solver = HybridSolver::new(Dopri5::new(), Tolerance::scalar(1e-9, 1e-9), options).unwrap();
        let out = solver.run(&mut sys, (), 0.0, &[0.0], 2.5, &mut ()).unwrap();
        match (out.stop, expected) {
            (model_runtime::StopReason::User(i), Some((j, r))) => {
                // Equal roots are the same event: the first listed must win. The time is
                // exact up to the round-off of x(t) = t accumulated over the steps.
                prop_assert!(i == j || guards[i].0 == r, "fired {} at {}, expected {} at {}", i, out.t, j, r);
                prop_assert!((out.t - r).abs() <= 1e-14, "t {} vs {}", out.t, r);
            }
            (model_runtime::StopReason::EndTime, None) => {}
            (stop, exp) => prop_assert!(false, "stop {:?}, expected {:?}", stop, exp),
        }
    }
}
