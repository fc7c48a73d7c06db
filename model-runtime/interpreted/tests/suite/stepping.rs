//! What a caller shapes of the steps ([`Stepping`]): the largest and the first step, and each
//! step's dense output, which gives back, anywhere in a step, what sampling there during the
//! run gives.

use crate::{compile, model, OSCILLATOR};
use model_interpreted::{
    solve, solve_stepped, Control, DenseStep, EventRequest, Solution, SolveRequest, Stepping,
    DENSE_NODES,
};
use model_runtime::Direction;
use std::sync::atomic::AtomicBool;

fn stepped(request: &SolveRequest, stepping: Stepping) -> Solution {
    let file = compile("oscillator.dsl", OSCILLATOR);
    let never = AtomicBool::new(false);
    let control = Control { interrupt: &never };
    solve_stepped(model(&file), request, &control, &stepping).unwrap()
}

fn from_one(t_end: f64) -> SolveRequest {
    SolveRequest {
        state: vec![("x".to_string(), 1.0)],
        ..SolveRequest::new(t_end)
    }
}

#[test]
fn the_largest_and_the_first_step_bound_the_steps() {
    let free = stepped(&from_one(2.0), Stepping::default());
    let bounded = stepped(
        &from_one(2.0),
        Stepping {
            max_step: Some(0.01),
            first_step: Some(1e-6),
            ..Stepping::default()
        },
    );
    let widest = |s: &Solution| {
        (s.times().windows(2))
            .map(|w| w[1] - w[0])
            .fold(0.0, f64::max)
    };
    assert!(widest(&free) > 0.05, "{}", widest(&free));
    assert!(widest(&bounded) <= 0.01 + 1e-12, "{}", widest(&bounded));
    assert_eq!(bounded.times()[1], 1e-6);
    assert!(free.dense.is_empty());
}

/// The step's polynomial through its nodes (barycentric, Chebyshev–Lobatto weights), at `t`.
fn through_nodes(step: &DenseStep, n: usize, i: usize, t: f64) -> f64 {
    let nodes = DenseStep::nodes(step.t0, step.t1);
    let (mut num, mut den) = (0.0, 0.0);
    for (k, node) in nodes.iter().enumerate() {
        if t == *node {
            return step.values[k * n + i];
        }
        let ends = if k == 0 || k == DENSE_NODES - 1 {
            0.5
        } else {
            1.0
        };
        let w = if k % 2 == 0 { ends } else { -ends } / (t - node);
        num += w * step.values[k * n + i];
        den += w;
    }
    num / den
}

#[test]
fn each_steps_dense_output_gives_what_sampling_gives() {
    let dense = stepped(
        &from_one(2.0),
        Stepping {
            dense: true,
            ..Stepping::default()
        },
    );
    assert_eq!(dense.dense.len() as u64, dense.stats.steps);
    let times: Vec<f64> = (0..=200).map(|k| k as f64 * 0.01).collect();
    let sampled = stepped(
        &SolveRequest {
            times: Some(times.clone()),
            ..from_one(2.0)
        },
        Stepping::default(),
    );
    for (row, t) in sampled.trajectory.rows().zip(&times) {
        let step = (dense.dense.iter())
            .find(|s| s.t0 <= *t && *t <= s.t1)
            .unwrap();
        for i in 0..2 {
            let back = through_nodes(step, 2, i, *t);
            assert!(
                (back - row[1 + i]).abs() < 1e-12,
                "t = {t}: {back} {}",
                row[1 + i]
            );
        }
    }
}

#[test]
fn a_switched_model_keeps_its_steps_dense_output_too() {
    let file = compile("held_ball.dsl", include_str!("../held_ball.dsl"));
    let request = SolveRequest::new(1.0);
    let never = AtomicBool::new(false);
    let control = Control { interrupt: &never };
    let keep = Stepping {
        dense: true,
        ..Stepping::default()
    };
    let solution = solve_stepped(model(&file), &request, &control, &keep).unwrap();
    assert_eq!(solution.dense.len() as u64, solution.stats.steps);
}

#[test]
fn a_smooth_models_event_says_which_request_it_answers() {
    let file = compile("oscillator.dsl", OSCILLATOR);
    let event = |direction| EventRequest {
        name: "x".to_string(),
        direction,
        stop: false,
    };
    let request = SolveRequest {
        events: vec![event(Direction::Up), event(Direction::Down)],
        ..from_one(2.0)
    };
    let solution = solve(model(&file), &request).unwrap();
    // x = cos 3t falls through zero first, at pi/6.
    let asked: Vec<Option<usize>> = solution.events.iter().map(|e| e.request).collect();
    assert_eq!(&asked[..2], &[Some(1), Some(0)]);
}
