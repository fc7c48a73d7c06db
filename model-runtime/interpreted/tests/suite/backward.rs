//! A smooth model backward in time (`t_end < t0`): closed forms, decreasing rows and
//! sampling times, events fired along the run, each step's dense output; a switched model
//! refused, by name and reason.

use crate::{compile, model, tight, OSCILLATOR};
use model_interpreted::{
    solve, solve_stepped, Control, EventRequest, RequestError, SolveFailure, SolveRequest,
    Stepping, Stop,
};
use model_runtime::Direction;
use std::sync::atomic::AtomicBool;

/// The oscillator (`w = 3`) on `x = cos 3t`, from `t0` to `t_end`.
fn on_cosine(t0: f64, t_end: f64) -> SolveRequest {
    SolveRequest {
        t0,
        state: vec![
            ("x".to_string(), (3.0 * t0).cos()),
            ("v".to_string(), -3.0 * (3.0 * t0).sin()),
        ],
        ..tight(SolveRequest::new(t_end))
    }
}

#[test]
fn a_smooth_model_runs_backward_to_its_closed_form() {
    let file = compile("oscillator.dsl", OSCILLATOR);
    let request = SolveRequest {
        dt: Some(0.25),
        ..on_cosine(2.0, -1.0)
    };
    let solution = solve(model(&file), &request).unwrap();
    let t = solution.column("t").unwrap();
    // Every 0.25 from 2 down to -1, the end included.
    let want: Vec<f64> = (0..=12).map(|k| 2.0 - 0.25 * k as f64).collect();
    assert_eq!(t, want);
    for row in solution.trajectory.rows() {
        assert!((row[1] - (3.0 * row[0]).cos()).abs() < 1e-10, "{row:?}");
    }
    assert_eq!(solution.stop, Stop::EndTime);
    // Every step: the rows decrease, from t0 to t_end.
    let steps = solve(model(&file), &on_cosine(2.0, -1.0)).unwrap();
    let t = steps.column("t").unwrap();
    assert_eq!((t[0], *t.last().unwrap()), (2.0, -1.0));
    assert!(t.windows(2).all(|w| w[1] < w[0]));
}

#[test]
fn events_fire_along_a_backward_run() {
    // From t = 1 back to 0, x = cos 3t goes from -0.99 up through zero at pi/6: an up
    // crossing as the run proceeds (SciPy's direction), though dx/dt < 0 there.
    let file = compile("oscillator.dsl", OSCILLATOR);
    let event = |direction, stop| EventRequest {
        name: "x".to_string(),
        direction,
        stop,
    };
    let request = SolveRequest {
        events: vec![event(Direction::Down, false), event(Direction::Up, true)],
        ..on_cosine(1.0, 0.0)
    };
    let solution = solve(model(&file), &request).unwrap();
    assert_eq!(solution.events.len(), 1);
    let up = &solution.events[0];
    assert_eq!(up.request, Some(1));
    assert!(
        (up.t() - std::f64::consts::PI / 6.0).abs() < 1e-10,
        "{}",
        up.t()
    );
    assert!(matches!(&solution.stop, Stop::Event { name, .. } if name == "x"));
    assert_eq!(solution.stop_time(), Some(up.t()));
    assert_eq!(solution.t_end(), Some(up.t()));
}

#[test]
fn decreasing_times_and_dense_steps_of_a_backward_run() {
    let file = compile("oscillator.dsl", OSCILLATOR);
    let times: Vec<f64> = (0..=30).map(|k| 1.5 - 0.05 * k as f64).collect();
    let sampled = solve(
        model(&file),
        &SolveRequest {
            times: Some(times.clone()),
            ..on_cosine(1.5, 0.0)
        },
    )
    .unwrap();
    assert_eq!(sampled.column("t").unwrap(), times);
    let never = AtomicBool::new(false);
    let keep = Stepping {
        dense: true,
        ..Stepping::default()
    };
    let control = Control { interrupt: &never };
    let dense = solve_stepped(model(&file), &on_cosine(1.5, 0.0), &control, &keep).unwrap();
    assert_eq!(dense.dense.len() as u64, dense.stats.steps);
    assert!(dense.dense.iter().all(|s| s.t1 < s.t0));
    assert_eq!(dense.dense[0].t0, 1.5);
    assert_eq!(dense.dense.last().unwrap().t1, 0.0);
    // Increasing times are out of a backward run's order.
    let refused = solve(
        model(&file),
        &SolveRequest {
            times: Some(vec![0.5, 1.0]),
            ..on_cosine(1.5, 0.0)
        },
    );
    match refused {
        Err(SolveFailure::Request(RequestError::Time { index, problem, .. })) => {
            assert_eq!(index, 1);
            assert!(problem.contains("decreasing"), "{problem}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_switched_model_runs_forward_only() {
    let file = compile("held_ball.dsl", include_str!("../held_ball.dsl"));
    let request = SolveRequest {
        t0: 1.0,
        ..SolveRequest::new(0.0)
    };
    match solve(model(&file), &request) {
        Err(SolveFailure::Request(error @ RequestError::BackwardOfSwitched { .. })) => {
            let text = error.to_string();
            assert!(text.contains("forward in time only"), "{text}");
            assert!(text.contains("inverse"), "{text}");
        }
        other => panic!("{other:?}"),
    }
}
