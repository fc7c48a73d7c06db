//! The paper's scene on the hybrid driver: the start, the transition sequence, its agreement
//! between integrators, charts and thresholds, and that no event is skipped.

use equations::DiskParams;
use equations::{
    simulate, DiskRecorder, GeneratedModels, ReferenceModels, RunOutcome, StopReason,
    TransitionRecord, Trigger,
};
use equations::{DiskConfig, InitialState, Integrator, TimeVariable};
use equations::{Mode, SlipChart};
use std::f64::consts::PI;

use crate::common::assert_same_decisions;

/// Runs the paper's scene on the generated models.
fn run(config: &DiskConfig, chart: SlipChart) -> (RunOutcome, DiskRecorder) {
    let params = DiskParams::paper();
    let models = GeneratedModels::generated(params, chart).unwrap();
    let mut rec = DiskRecorder::default();
    let out = simulate(&models, config, &InitialState::paper(&params), &mut rec).unwrap();
    (out, rec)
}

/// Runs the paper's scene on the hand-written reference.
fn run_reference(config: &DiskConfig, chart: SlipChart) -> (RunOutcome, DiskRecorder) {
    let params = DiskParams::paper();
    let models = ReferenceModels::reference(params, chart).unwrap();
    let mut rec = DiskRecorder::default();
    let out = simulate(&models, config, &InitialState::paper(&params), &mut rec).unwrap();
    (out, rec)
}

fn tight(integrator: Integrator, t_end: f64) -> DiskConfig {
    DiskConfig {
        integrator,
        rtol: 1e-11,
        atol: 1e-13,
        t_end,
        ..DiskConfig::paper()
    }
}

/// The event-driven decisions (the initial one excluded).
fn events(rec: &DiskRecorder) -> Vec<TransitionRecord> {
    rec.transitions
        .iter()
        .filter(|r| !matches!(r.trigger, Trigger::InitialFriction { .. }))
        .copied()
        .collect()
}

#[test]
fn the_paper_scene_slides_from_the_start_along_minus_x() {
    let config = DiskConfig {
        t_end: 1e-4,
        ..DiskConfig::paper()
    };
    let (out, rec) = run(&config, SlipChart::Cartesian);
    let first = rec.transitions[0];
    assert_eq!(first.t, 0.0);
    assert_eq!((first.from, first.to), (Mode::Rolling, Mode::Sliding));
    let Trigger::InitialFriction { ratio } = first.trigger else {
        panic!("{first:?}")
    };
    // docs/physics.md §11: rolling would need nu = 0.8355 > mu_st = 0.2.
    assert!((ratio - 0.8355).abs() < 5e-5, "{ratio}");
    // By symmetry the consistent direction is exactly pi (friction along -E_X).
    assert_eq!(first.slip_direction, Some(PI));
    assert_eq!(out.stop, StopReason::EndTime);
    assert_eq!(out.last.mode, Mode::Sliding);
    assert_eq!(out.transitions, 0);
    // The slip grows along +E_X at about 4.239 m/s² (docs/physics.md §11).
    let u = out.last.state.slip.vector();
    assert!(u[0] > 0.0 && u[1].abs() < 1e-3 * u[0], "{u:?}");
    assert!((u[0] / 1e-4 - 4.239).abs() < 5e-3, "{}", u[0] / 1e-4);
}

#[test]
fn the_first_twenty_transitions_agree_between_dp5_and_dop853() {
    let (_, a) = run(&tight(Integrator::Dopri5, 1.6), SlipChart::Cartesian);
    let (_, b) = run(&tight(Integrator::Dop853, 1.6), SlipChart::Cartesian);
    let (a, b) = (events(&a), events(&b));
    assert!(a.len() >= 20 && b.len() >= 20, "{} {}", a.len(), b.len());
    let worst = a
        .iter()
        .zip(&b)
        .take(20)
        .map(|(x, y)| (x.t - y.t).abs())
        .fold(0.0, f64::max);
    eprintln!("largest DP5/DOP853 difference of the first 20 transition times: {worst:e} s");
    for (k, (x, y)) in a.iter().zip(&b).take(20).enumerate() {
        assert_eq!((x.from, x.to), (y.from, y.to), "transition {k}");
        assert!(
            (x.t - y.t).abs() < 1e-9,
            "transition {k}: {} vs {} (diff {:e})",
            x.t,
            y.t,
            x.t - y.t
        );
    }
}

/// Regularised time changes the variable the integrator steps in, not the motion: over the
/// first 5 s at tight tolerances both charts and both methods make the decisions of a run in
/// physical time at the same times, and sample the same states at the same physical times.
#[test]
fn regularised_time_reproduces_the_run_in_physical_time() {
    let physical = tight(Integrator::Dop853, 5.0);
    let regularised = |integrator| DiskConfig {
        time: TimeVariable::Regularised,
        sample_rate: Some(50.0),
        ..tight(integrator, 5.0)
    };
    let (out_p, a) = run(
        &DiskConfig {
            sample_rate: Some(50.0),
            ..physical
        },
        SlipChart::Cartesian,
    );
    for (integrator, chart) in [
        (Integrator::Dop853, SlipChart::Cartesian),
        (Integrator::Dopri5, SlipChart::Cartesian),
        (Integrator::Dop853, SlipChart::Polar),
    ] {
        let (out_r, b) = run(&regularised(integrator), chart);
        assert_eq!(out_r.stop, StopReason::EndTime);
        assert_eq!(out_r.last.t, 5.0);
        assert!(events(&a).len() > 40, "{}", events(&a).len());
        assert_same_decisions(&events(&a), &events(&b), 1e-8);
        assert_eq!(a.samples.len(), b.samples.len());
        for (x, y) in a.samples.iter().zip(&b.samples) {
            assert_eq!(x.t, y.t);
            let theta = equations::layout::THETA;
            assert!(
                (x.state.y[theta] - y.state.y[theta]).abs() < 1e-8,
                "{integrator:?} {chart:?}: theta at t = {}: {} against {}",
                x.t,
                x.state.y[theta],
                y.state.y[theta]
            );
        }
        assert!(
            out_r.stats.steps < out_p.stats.steps || integrator == Integrator::Dopri5,
            "{integrator:?}: {} regularised steps against {} in physical time",
            out_r.stats.steps,
            out_p.stats.steps
        );
    }
}

#[test]
fn polar_and_cartesian_charts_give_the_same_transitions() {
    let config = DiskConfig {
        rtol: 1e-10,
        atol: 1e-12,
        ..tight(Integrator::Dop853, 1.0)
    };
    let (_, a) = run(&config, SlipChart::Cartesian);
    let (_, b) = run(&config, SlipChart::Polar);
    assert_same_decisions(&events(&a), &events(&b), 1e-8);
}

#[test]
fn generated_and_reference_models_switch_at_the_same_times() {
    let config = DiskConfig {
        t_end: 1.2,
        ..DiskConfig::paper()
    };
    for chart in [SlipChart::Cartesian, SlipChart::Polar] {
        let (out_g, g) = run(&config, chart);
        let (out_r, r) = run_reference(&config, chart);
        assert_eq!(g.transitions.len(), r.transitions.len(), "{chart:?}");
        for (x, y) in g.transitions.iter().zip(&r.transitions) {
            assert_eq!((x.from, x.to), (y.from, y.to));
            assert!((x.t - y.t).abs() < 1e-9, "{chart:?}: {} vs {}", x.t, y.t);
        }
        let (eg, er) = (out_g.last.energy, out_r.last.energy);
        assert!(
            (eg - er).abs() < 1e-9 * er,
            "{chart:?}: energy {eg} vs {er}"
        );
    }
}

#[test]
fn the_stick_threshold_does_not_move_the_events() {
    // The approach to zero slip is bridged exactly, so the threshold is only a detection level.
    let coarse = tight(Integrator::Dop853, 0.8);
    let fine = DiskConfig {
        stick_threshold: 1e-10,
        ..coarse
    };
    let (_, a) = run(&coarse, SlipChart::Cartesian);
    let (_, b) = run(&fine, SlipChart::Cartesian);
    let (a, b) = (events(&a), events(&b));
    assert_eq!(a.len(), b.len());
    for (k, (x, y)) in a.iter().zip(&b).enumerate() {
        assert!(
            (x.t - y.t).abs() < 1e-9,
            "transition {k}: {} vs {}",
            x.t,
            y.t
        );
    }
}

/// Checks the mode sequence of a run and that, between events, every guard kept its sign on
/// a dense sampling: an event skipped inside a step would show up as a sample on the wrong
/// side of a guard.
fn check_sequence_and_guards(rec: &DiskRecorder, mu_st: f64) {
    let mut mode = Mode::Rolling;
    for (k, r) in rec.transitions.iter().enumerate() {
        assert_eq!(
            r.from, mode,
            "transition {k} starts from the wrong mode: {r:?}"
        );
        match r.trigger {
            Trigger::FrictionLimit { ratio } => {
                assert_eq!((r.from, r.to), (Mode::Rolling, Mode::Sliding));
                assert!((ratio - mu_st).abs() < 1e-9, "{r:?}");
            }
            Trigger::SlipStopped { rolling_ratio, .. } => {
                assert_eq!(r.from, Mode::Sliding);
                assert_eq!(r.to == Mode::Rolling, rolling_ratio < mu_st, "{r:?}");
            }
            Trigger::InitialFriction { .. } => assert_eq!(k, 0),
        }
        if k > 0 {
            assert!(
                r.t > rec.transitions[k - 1].t,
                "transition {k} does not advance time"
            );
        }
        mode = r.to;
    }
    let times: Vec<f64> = rec.transitions.iter().map(|r| r.t).collect();
    for s in &rec.samples {
        // Samples within a few ns of an event may sit on the bridge or the event itself.
        if times.iter().any(|&t| (s.t - t).abs() < 1e-8) {
            continue;
        }
        assert!(s.force.normal > 0.0, "N <= 0 at t = {}", s.t);
        match s.mode {
            Mode::Rolling => assert!(s.force.ratio() < mu_st, "nu >= mu_st at t = {}", s.t),
            Mode::Sliding => assert!(s.state.slip.speed > 0.0, "v_C <= 0 at t = {}", s.t),
        }
    }
}

#[test]
fn two_seconds_alternate_correctly_with_no_event_skipped() {
    let mu_st = DiskParams::paper().mu_st;
    let loose = DiskConfig {
        t_end: 2.0,
        sample_rate: Some(20_000.0),
        ..DiskConfig::paper()
    };
    let strict = DiskConfig {
        rtol: 1e-10,
        atol: 1e-12,
        ..loose
    };
    let (out_a, a) = run(&loose, SlipChart::Cartesian);
    let (_, b) = run(&strict, SlipChart::Cartesian);
    assert_eq!(out_a.stop, StopReason::EndTime);
    check_sequence_and_guards(&a, mu_st);
    check_sequence_and_guards(&b, mu_st);
    assert_eq!(a.transitions.len(), b.transitions.len());
    assert!(out_a.transitions >= 20, "{}", out_a.transitions);
    for (x, y) in a.transitions.iter().zip(&b.transitions) {
        assert_eq!((x.from, x.to), (y.from, y.to));
        assert!((x.t - y.t).abs() < 1e-5, "{} vs {}", x.t, y.t);
    }
    assert_eq!(a.samples.len(), 40_001);
}

#[test]
fn the_inclination_floor_stops_the_run_exactly_there() {
    let config = DiskConfig {
        t_end: 1.0,
        min_inclination: 0.3,
        ..DiskConfig::paper()
    };
    let (out, _) = run(&config, SlipChart::Cartesian);
    let StopReason::InclinationReachedFloor { t, theta } = out.stop else {
        panic!("{:?}", out.stop)
    };
    assert!((theta - 0.3).abs() < 1e-12, "{theta}");
    assert!(t > 0.0 && t < 0.5, "{t}");
    assert_eq!(out.last.t, t);
}

#[test]
fn chattering_is_reported_with_a_named_reason() {
    // Two mode decisions within one second exceed a limit of one: the run stops at the second.
    let config = DiskConfig {
        t_end: 1.0,
        chatter: equations::ChatterLimit {
            max_transitions: 1,
            window: 1.0,
        },
        ..DiskConfig::paper()
    };
    let (out, rec) = run(&config, SlipChart::Cartesian);
    let StopReason::Chattering { t, transitions, .. } = out.stop else {
        panic!("{:?}", out.stop)
    };
    assert_eq!(transitions, 2);
    assert!((t - 0.0769).abs() < 1e-3, "{t}");
    assert_eq!(events(&rec).len(), 1);
}

#[test]
fn projecting_every_step_keeps_the_constraints_and_the_events() {
    let plain = DiskConfig {
        t_end: 1.0,
        ..DiskConfig::paper()
    };
    let projected = DiskConfig {
        project_each_step: true,
        ..plain
    };
    let (out_a, a) = run(&plain, SlipChart::Cartesian);
    let (out_b, b) = run(&projected, SlipChart::Cartesian);
    // Without projection the drift is at the level of the integration error, and measured.
    assert!(
        out_a.max_drift.vertical_speed > 1e-14,
        "{:?}",
        out_a.max_drift
    );
    assert!(out_a.max_drift.max_abs() < 1e-8, "{:?}", out_a.max_drift);
    let r = out_b.last.residuals;
    assert!(
        r.height.abs() < 1e-15 && r.vertical_speed.abs() < 1e-14,
        "{r:?}"
    );
    assert_eq!(a.transitions.len(), b.transitions.len());
    for (x, y) in a.transitions.iter().zip(&b.transitions) {
        assert!((x.t - y.t).abs() < 1e-7, "{} vs {}", x.t, y.t);
    }
}

/// The first sample at which the energy has risen by more than `1e-8` of itself since the
/// previous sample (rolling conserves it exactly; at `rtol = 1e-10` the integration error of
/// the energy stays far below that over the sampling interval).
fn energy_rises(rec: &DiskRecorder) -> Option<f64> {
    rec.samples
        .windows(2)
        .find(|w| w[1].energy > w[0].energy + 1e-8 * w[0].energy)
        .map(|w| w[1].t)
}

#[test]
fn the_physical_reading_never_gains_energy_and_the_papers_reading_does() {
    // Both readings agree until the first zero of the slip where static friction cannot hold:
    // the physical one restarts the slip from zero in a consistent direction, the paper's
    // signed slip speed goes on through zero with α fixed, so friction then pushes the slip
    // (power −T v_C > 0) and the disk gains energy until it leaves the floor.
    let physical = DiskConfig {
        t_end: 20.0,
        rtol: 1e-10,
        atol: 1e-12,
        sample_rate: Some(500.0),
        ..DiskConfig::paper()
    };
    let paper = DiskConfig {
        slip_sign: equations::SlipSign::Paper,
        ..physical
    };
    let (out_phys, phys) = run(&physical, SlipChart::Polar);
    let (out_paper, signed) = run(&paper, SlipChart::Polar);
    assert_eq!(out_phys.stop, StopReason::EndTime);
    assert_eq!(energy_rises(&phys), None);
    let restart = signed
        .transitions
        .iter()
        .position(|r| (r.from, r.to) == (Mode::Sliding, Mode::Sliding))
        .expect("the paper's reading restarts sliding at least once");
    for (x, y) in phys
        .transitions
        .iter()
        .zip(&signed.transitions)
        .take(restart + 1)
    {
        assert_eq!((x.from, x.to), (y.from, y.to));
        assert!((x.t - y.t).abs() < 1e-9, "{} vs {}", x.t, y.t);
    }
    let t_restart = signed.transitions[restart].t;
    let rise = energy_rises(&signed).expect("energy rises under the signed reading");
    assert!(
        rise > t_restart,
        "energy rose at {rise} before the restart at {t_restart}"
    );
    assert!(out_paper.last.energy > out_phys.last.energy);
    assert!(
        matches!(out_paper.stop, StopReason::ContactLost { .. }),
        "{:?}",
        out_paper.stop
    );
}

#[test]
fn sliding_restarts_keep_the_sequence_consistent() {
    // At tight tolerances the slip of the paper's disk reaches zero where static friction cannot
    // hold about 150 times between 10 s and 30 s (docs/physics.md §7.3): sliding
    // restarts from zero slip in a new consistent direction.
    let mu_st = DiskParams::paper().mu_st;
    let config = DiskConfig {
        integrator: Integrator::Dop853,
        rtol: 1e-10,
        atol: 1e-12,
        t_end: 30.0,
        sample_rate: Some(2000.0),
        ..DiskConfig::paper()
    };
    let (out, rec) = run(&config, SlipChart::Cartesian);
    assert_eq!(out.stop, StopReason::EndTime);
    check_sequence_and_guards(&rec, mu_st);
    let restarts: Vec<&TransitionRecord> = rec
        .transitions
        .iter()
        .filter(|r| (r.from, r.to) == (Mode::Sliding, Mode::Sliding))
        .collect();
    assert!(restarts.len() >= 50, "{} restarts", restarts.len());
    for r in restarts {
        let Trigger::SlipStopped {
            rolling_ratio,
            rolling_normal,
        } = r.trigger
        else {
            panic!("{r:?}")
        };
        assert!(rolling_ratio >= mu_st || rolling_normal <= 0.0, "{r:?}");
        assert!(r.slip_direction.is_some_and(f64::is_finite), "{r:?}");
    }
}

#[test]
fn every_accepted_step_can_be_streamed() {
    #[derive(Default)]
    struct Steps {
        times: Vec<f64>,
        worst_ratio_rolling: f64,
    }
    impl equations::DiskObserver for Steps {
        fn wants_steps(&self) -> bool {
            true
        }
        fn on_step(&mut self, s: &equations::DiskSample) {
            self.times.push(s.t);
            if s.mode == Mode::Rolling {
                self.worst_ratio_rolling = self.worst_ratio_rolling.max(s.force.ratio());
            }
        }
    }
    let params = DiskParams::paper();
    let models = GeneratedModels::generated(params, SlipChart::Cartesian).unwrap();
    let config = DiskConfig {
        t_end: 0.5,
        ..DiskConfig::paper()
    };
    let mut steps = Steps::default();
    let out = simulate(&models, &config, &InitialState::paper(&params), &mut steps).unwrap();
    assert_eq!(steps.times.len() as u64, out.stats.steps);
    assert!(steps.times.windows(2).all(|w| w[1] >= w[0]));
    assert_eq!(*steps.times.last().unwrap(), 0.5);
    // Step ends in rolling never exceed the static limit (event ends sit on it).
    assert!(
        steps.worst_ratio_rolling <= params.mu_st + 1e-9,
        "{}",
        steps.worst_ratio_rolling
    );
}

#[test]
fn slides_that_end_at_once_are_resolved_alike_by_both_integrators() {
    // Near 19 s the slip of the paper's disk reaches zero where rolling would need T/N just
    // above mu_st: sliding restarts, and ~60 µs later the slip is back at zero and the disk
    // rolls. Every one of these switch-backs must be found, at the same times, by DP5 and
    // DOP853 (409 decisions up to 19.5 s).
    let (_, a) = run(&tight(Integrator::Dopri5, 19.5), SlipChart::Cartesian);
    let (_, b) = run(&tight(Integrator::Dop853, 19.5), SlipChart::Cartesian);
    assert_same_decisions(&a.transitions, &b.transitions, 1e-8);
    let short: Vec<(f64, f64)> = a
        .transitions
        .windows(2)
        .filter(|w| w[0].to == Mode::Sliding && w[1].t - w[0].t < 1e-4)
        .map(|w| {
            assert_eq!(
                (w[0].from, w[1].to),
                (Mode::Sliding, Mode::Rolling),
                "{w:?}"
            );
            (w[0].t, w[1].t - w[0].t)
        })
        .collect();
    assert!(short.len() >= 5, "{short:?}");
}

#[test]
fn every_decision_reaches_the_observer_once_and_in_order() {
    // The decisions travel from the transition maps to the observer as the transitions' notes,
    // in physical time and through the clocked system in regularised time alike.
    for time in [TimeVariable::Physical, TimeVariable::Regularised] {
        let config = DiskConfig {
            t_end: 2.0,
            time,
            ..DiskConfig::paper()
        };
        let (out, rec) = run(&config, SlipChart::Cartesian);
        assert_eq!(out.stop, StopReason::EndTime);
        assert!(out.transitions >= 20, "{time:?}: {}", out.transitions);
        // The initial decision is reported first and not counted; every counted one once.
        assert!(matches!(
            rec.transitions[0].trigger,
            Trigger::InitialFriction { .. }
        ));
        assert_eq!(events(&rec).len() as u64, out.transitions, "{time:?}");
        for pair in rec.transitions.windows(2) {
            assert!(pair[0].t <= pair[1].t, "{time:?}: {pair:?}");
            assert_eq!(pair[0].to, pair[1].from, "{time:?}: {pair:?}");
        }
    }
}
