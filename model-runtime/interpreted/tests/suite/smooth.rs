//! Smooth models: the interpreted disk steps exactly like the compiled one, events on states
//! and outputs at closed-form times, any state the request names.

use crate::{compile, model, tight, OSCILLATOR};
use equations::models::rolling;
use equations::{DiskParams, InitialState};
use model_interpreted::{solve, EventKind, EventRequest, SolveRequest, Stop};
use model_runtime::{Direction, Method, Problem};

/// The rolling disk from its own source file, interpreted in its own 12 states (a run-time
/// size), against the same model compiled by `model!` (a compile-time size): the same
/// integrator code on both, so the same steps and the same trajectory.
#[test]
fn the_interpreted_disk_steps_like_the_compiled_one() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../equations/src/models/box1_rolling.rs"
    );
    let models = model_dsl::Source::read(std::path::Path::new(path))
        .unwrap()
        .compile()
        .unwrap();
    let file = model_interpreted::ModelFile::Smooth(models);
    let p = DiskParams::paper();
    let y0 = InitialState::paper(&p).state.y;
    let names = &file.smooth(None).unwrap().params;
    let params: Vec<(String, f64)> = (names.iter().map(|(n, _)| n.clone()))
        .zip(p.to_array())
        .collect();
    let states = &file.smooth(None).unwrap().states;
    for method in [Method::Dopri5, Method::Dop853, Method::Rodas4] {
        let request = SolveRequest {
            method,
            rtol: 1e-9,
            atol: 1e-11,
            params: params.clone(),
            state: states.iter().cloned().zip(y0).collect(),
            ..SolveRequest::new(0.3)
        };
        let solved = solve(model(&file), &request).unwrap();
        let compiled = Problem::new(&rolling::Model::new(p.to_array()), y0, (0.0, 0.3))
            .method(method)
            .tolerances(1e-9, 1e-11)
            .solve::<{ rolling::N_OUTPUTS }>()
            .unwrap();
        assert_eq!(solved.stats.steps, compiled.stats.steps, "{method:?}");
        assert_eq!(solved.stats.rejected, compiled.stats.rejected, "{method:?}");
        let last = solved.last_row().unwrap();
        let want = compiled.last().unwrap();
        for (k, (got, want)) in last[1..=12].iter().zip(want).enumerate() {
            assert!(
                (got - want).abs() <= 1e-9 * want.abs().max(1.0),
                "{method:?} {}: {got} vs {want}",
                rolling::STATE_NAMES[k]
            );
        }
        assert_eq!(solved.columns.len(), 1 + 12 + rolling::N_OUTPUTS);
        assert_eq!(solved.state_names(), &states[..]);
        assert_eq!(solved.stop, Stop::EndTime);
    }
}

/// An output equal to a state crosses zero where the state does: the output's event,
/// evaluated by the interpreter from `(t, y, dy)`, is located at the same times (to the root
/// finder's few ulps), and both at the analytic zeros of `cos(3 t)`.
#[test]
fn an_event_on_an_output_is_located_where_the_equal_state_crosses() {
    let file = compile("oscillator.dsl", OSCILLATOR);
    let times = |event: &str| -> Vec<f64> {
        let request = SolveRequest {
            t_end: 4.0,
            state: vec![("x".into(), 1.0)],
            events: vec![EventRequest {
                name: event.into(),
                direction: Direction::Both,
                stop: false,
            }],
            ..tight(SolveRequest::new(4.0))
        };
        let solved = solve(model(&file), &request).unwrap();
        assert!(solved.events.iter().all(|e| e.name == event));
        assert!(solved.events.iter().all(|e| e.kind == EventKind::Crossing));
        solved.events.iter().map(|e| e.t()).collect()
    };
    let (state, output) = (times("x"), times("position"));
    assert_eq!(state.len(), 4, "{state:?}");
    assert_eq!(state.len(), output.len());
    for (k, (a, b)) in state.iter().zip(&output).enumerate() {
        let want = (k as f64 + 0.5) * std::f64::consts::PI / 3.0;
        assert!((a - b).abs() < 1e-13, "{a} vs {b}");
        assert!((a - want).abs() < 1e-9, "{a} vs {want}");
    }
}

/// A terminal event ends the run there: the last row is the event's, the stop names it, and
/// the outputs by name follow the closed form (`speed = -3 sin 3t`).
#[test]
fn a_terminal_event_closes_the_trajectory_and_outputs_read_by_name() {
    let file = compile("oscillator.dsl", OSCILLATOR);
    let request = SolveRequest {
        dt: Some(0.05),
        state: vec![("x".into(), 1.0)],
        params: vec![("w".into(), 3.0)],
        events: vec![EventRequest {
            name: "v".into(),
            direction: Direction::Up,
            stop: true,
        }],
        ..tight(SolveRequest::new(10.0))
    };
    let solved = solve(model(&file), &request).unwrap();
    // v = -3 sin(3t) first crosses zero upwards at t = pi/3.
    let t_stop = std::f64::consts::PI / 3.0;
    assert_eq!(solved.events.len(), 1);
    assert!((solved.events[0].t() - t_stop).abs() < 1e-9);
    assert_eq!(
        solved.stop,
        Stop::Event {
            name: "v".into(),
            kind: EventKind::Crossing
        }
    );
    assert_eq!(solved.last_row().as_ref(), Some(&solved.events[0].row));
    let (t, speed) = (solved.column("t").unwrap(), solved.column("speed").unwrap());
    for (t, speed) in t.iter().zip(speed) {
        assert!((speed + 3.0 * (3.0 * t).sin()).abs() < 1e-9, "{t}: {speed}");
    }
    assert_eq!(solved.output_names(), ["speed", "position"]);
    assert!(solved.column("nothing").is_none());
}
