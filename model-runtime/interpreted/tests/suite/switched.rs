//! Switched models: the example ball's impacts at their closed-form times and its
//! accumulation typed, an unresolved accumulation and a chatter said with the work done.

use crate::{compile, model, tight};
use model_interpreted::{solve, AccumulationPoint, EventKind, SolveFailure, SolveRequest, Stop};

#[test]
fn the_ball_bounces_at_the_closed_form_times_and_comes_to_rest_typed() {
    let file = compile(
        "bouncing_ball.dsl",
        include_str!("../../../../model-macros/examples/bouncing_ball.dsl"),
    );
    let solved = solve(model(&file), &tight(SolveRequest::new(6.0))).unwrap();
    let (g, e, h0) = (9.81f64, 0.8f64, 1.0f64);
    let v1 = (2.0 * g * h0).sqrt();
    let t_inf = (2.0 * h0 / g).sqrt() + 2.0 * e * v1 / (g * (1.0 - e));
    let (last, impacts) = solved.events.split_last().unwrap();
    assert!(impacts.len() > 50);
    let mut expected = (2.0 * h0 / g).sqrt();
    for (k, impact) in impacts.iter().enumerate() {
        assert_eq!(
            (impact.name.as_str(), impact.kind),
            ("impact", EventKind::Crossing)
        );
        assert!((impact.t() - expected).abs() < 1e-9, "impact {k}");
        expected += 2.0 * e.powi(k as i32 + 1) * v1 / g;
    }
    assert_eq!(last.kind, EventKind::Accumulation);
    assert_eq!(last.label(), "impact accumulates");
    assert!((last.t() - t_inf).abs() < 1e-9);
    // At rest from there: the state the rule sets.
    assert_eq!(&last.row[1..3], [0.0, 0.0]);
    let [accumulation] = &solved.accumulations[..] else {
        panic!("{:?}", solved.accumulations)
    };
    assert_eq!(accumulation.continued_in.as_deref(), Some("resting"));
    assert_eq!(solved.stop, Stop::EndTime);
    assert_eq!(solved.t_end(), Some(6.0));
}

#[test]
fn an_accumulation_no_rule_continues_stops_the_run_by_name() {
    let file = compile(
        "ball.dsl",
        "mod ball { params { g = 9.81 } states { h = 1, v }
            equations { der(h) = v; der(v) = -g; }
            when impact: h < 0 { v = -0.5 * v; } }",
    );
    let solved = solve(model(&file), &SolveRequest::new(10.0)).unwrap();
    assert_eq!(
        solved.stop,
        Stop::Event {
            name: "impact".into(),
            kind: EventKind::Accumulation
        }
    );
    let [AccumulationPoint {
        continued_in: None,
        t,
        ..
    }] = &solved.accumulations[..]
    else {
        panic!("{:?}", solved.accumulations)
    };
    // h0 = 1, e = 0.5: t_inf = t1 (1 + 2 e / (1 - e)) = 3 t1.
    let t1 = (2.0f64 / 9.81).sqrt();
    assert!((t - 3.0 * t1).abs() < 1e-6, "{t}");
    // The run ends at the last firing it located, just before the extrapolated point.
    let end = solved.t_end().unwrap();
    assert!(end <= *t && *t - end < 1e-6, "{end} vs {t}");
}

#[test]
fn a_chatter_fails_with_the_modes_and_the_work_done() {
    let file = compile(
        "relay.dsl",
        "mod relay { states { x = 1 }
            mode down { equations { der(x) = -1; } when low: x < 0 -> up; }
            mode up { equations { der(x) = 1; } when high: x > 0 -> down; } }",
    );
    let Err(SolveFailure::Run(failure)) = solve(model(&file), &SolveRequest::new(3.0)) else {
        panic!("the relay chatters")
    };
    assert!(
        failure.message.contains("between modes `down`, `up`"),
        "{failure}"
    );
    assert_eq!((failure.steps, failure.events), (Some(3), 100));
}

/// Discrete values and a mode's own coordinates, interpreted: the ball that falls in its
/// downward speed `w` (in the slot of `v`), counts its bounces and records an echo 0.1 s
/// after each, read from the time of the last bounce it holds.
#[test]
fn held_values_and_a_modes_own_coordinates_run_interpreted() {
    let file = compile("held_ball.dsl", include_str!("../held_ball.dsl"));
    let solved = solve(model(&file), &tight(SolveRequest::new(2.0))).unwrap();
    assert_eq!(solved.columns[..3], ["t", "h", "w/v"]);
    let times = |name: &str| -> Vec<f64> {
        (solved.events.iter().filter(|e| e.name == name))
            .map(|e| e.t())
            .collect()
    };
    let (g, e, h0) = (9.81f64, 0.8f64, 1.0f64);
    let v1 = (2.0 * g * h0).sqrt();
    let impacts = times("impact");
    assert!(impacts.len() >= 3, "{impacts:?}");
    let mut expected = (2.0 * h0 / g).sqrt();
    for (k, t) in impacts.iter().enumerate() {
        assert!(
            (t - expected).abs() < 1e-9,
            "impact {k}: {t} against {expected}"
        );
        expected += 2.0 * e.powi(k as i32 + 1) * v1 / g;
    }
    // Each echo 0.1 s after its bounce: the held time of the last bounce, read by a guard.
    let echoes = times("echo");
    assert_eq!(echoes.len(), impacts.len());
    for (echo, impact) in echoes.iter().zip(&impacts) {
        assert!(
            (echo - impact - 0.1).abs() < 1e-9,
            "echo {echo} after {impact}"
        );
    }
    // While falling the slot holds the downward speed: positive, and g t after the apex.
    let w = solved.column("w/v").unwrap();
    assert!(w[1] > 0.0, "{}", w[1]);
}
