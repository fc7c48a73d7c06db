//! The trajectory API on models written in the DSL: recorded points against closed forms, events
//! located exactly with their states, every method, and failures that name the state.

use model_runtime::{
    Crossed, Direction, Event, Method, Output, Problem, SolveFailure, Termination, Tolerance,
};

model_macros::model! {
    /// A harmonic oscillator: x = cos(w t), v = -w sin(w t) from (1, 0).
    mod oscillator {
        params { w = 2.0 }
        states { x, v }
        equations {
            der(x) = v;
            der(v) = -w^2 * x;
        }
        outputs { energy = (v^2 + w^2 * x^2) / 2; }
    }
}

model_macros::model! {
    /// y' = y^2 from y(0) = 1 blows up at t = 1.
    mod blowup {
        states { y }
        equations { der(y) = y^2; }
    }
}

fn model() -> oscillator::Model {
    oscillator::Model::default()
}

#[test]
fn output_times_follow_the_closed_form_with_every_method() {
    let times: Vec<f64> = (0..=50).map(|k| 0.1 * k as f64).collect();
    for (method, tol) in [
        (Method::Dopri5, 1e-7),
        (Method::Dop853, 1e-9),
        (Method::Rodas4, 1e-5),
        (Method::Rk4 { h: 1e-3 }, 1e-9),
    ] {
        let sol = Problem::new(&model(), [1.0, 0.0], (0.0, 5.0))
            .method(method)
            .tolerances(1e-10, 1e-12)
            .output(Output::Times(times.clone()))
            .solve()
            .unwrap();
        assert_eq!(sol.t, times, "{method:?}");
        assert_eq!(sol.stop, Termination::EndTime);
        for (t, y) in sol.t.iter().zip(&sol.y) {
            assert!((y[0] - (2.0 * t).cos()).abs() < tol, "{method:?} t = {t}");
            assert!(
                (y[1] + 2.0 * (2.0 * t).sin()).abs() < 2.0 * tol,
                "{method:?} t = {t}"
            );
        }
        // The outputs are evaluated at the recorded points: energy 2 throughout.
        let energy = sol.column("energy").unwrap();
        assert!(
            energy.iter().all(|e| (e - 2.0).abs() < 4.0 * tol),
            "{method:?}"
        );
    }
}

#[test]
fn steps_are_recorded_from_start_to_end() {
    let sol = Problem::new(&model(), [1.0, 0.0], (0.5, 3.0))
        .solve()
        .unwrap();
    assert_eq!(sol.t[0], 0.5);
    assert_eq!(sol.y[0], [1.0, 0.0]);
    assert_eq!(*sol.t.last().unwrap(), 3.0);
    assert_eq!(sol.t.len() as u64, sol.stats.steps + 1);
    assert!(sol.t.windows(2).all(|w| w[0] < w[1]));
    assert_eq!(sol.column("v").unwrap().len(), sol.t.len());
    assert_eq!(sol.column("nothing"), None);
}

#[test]
fn events_are_located_with_their_exact_states() {
    // x = cos(2t) crosses zero at t = π/4 + kπ/2: downwards for even k, upwards for odd k;
    // v = -2 sin(2t) rises through zero at t = π/2 + kπ (at t = 0 it starts on zero, which
    // is no event).
    let sol = Problem::new(&model(), [1.0, 0.0], (0.0, 10.0))
        .method(Method::Dop853)
        .tolerances(1e-12, 1e-12)
        .event(Event::new("x = 0", |_t, y, _dy| y[0]))
        .event(Event::new("v rising", |_t, y, _dy| y[1]).direction(Direction::Up))
        .solve()
        .unwrap();
    let quarter = std::f64::consts::FRAC_PI_4;
    let all: Vec<_> = sol.events.iter().filter(|e| e.index == 0).collect();
    let rising: Vec<_> = sol.events.iter().filter(|e| e.index == 1).collect();
    // Crossings before t = 10: k = 0..=5 (π/4 + 5π/2 = 8.64; the next is 10.2).
    assert_eq!(all.len(), 6);
    assert_eq!(rising.len(), 3);
    for (k, event) in all.iter().enumerate() {
        let exact = quarter + k as f64 * std::f64::consts::FRAC_PI_2;
        assert!(
            (event.t - exact).abs() < 1e-10,
            "{k}: {} vs {exact}",
            event.t
        );
        assert!(event.y[0].abs() < 1e-10);
        assert!((event.y[1].abs() - 2.0).abs() < 1e-9);
        let expected = if k % 2 == 0 {
            Crossed::Down
        } else {
            Crossed::Up
        };
        assert_eq!(event.crossed, expected);
        assert_eq!(event.der[0], event.y[1]);
    }
    for (k, event) in rising.iter().enumerate() {
        let exact = (2 * k + 1) as f64 * std::f64::consts::FRAC_PI_2;
        assert!(
            (event.t - exact).abs() < 1e-10,
            "{k}: {} vs {exact}",
            event.t
        );
        assert!((event.y[0] + 1.0).abs() < 1e-10);
        assert_eq!(event.crossed, Crossed::Up);
    }
    assert!(sol.events.windows(2).all(|w| w[0].t <= w[1].t));
    assert_eq!(sol.stop, Termination::EndTime);
}

#[test]
fn a_terminal_event_stops_the_run_at_its_state() {
    let sol = Problem::new(&model(), [1.0, 0.0], (0.0, 10.0))
        .tolerances(1e-10, 1e-12)
        .event(
            Event::new("v = 0 at the far side", |_t, y, _dy| y[1])
                .direction(Direction::Up)
                .terminal(),
        )
        .solve()
        .unwrap();
    // v = -2 sin(2t) rises through zero at t = π/2 (x = -1).
    let end = std::f64::consts::FRAC_PI_2;
    assert_eq!(
        sol.stop,
        Termination::Event {
            name: "v = 0 at the far side".into()
        }
    );
    assert_eq!(sol.events.len(), 1);
    assert!((sol.events[0].t - end).abs() < 1e-9);
    assert!((*sol.t.last().unwrap() - end).abs() < 1e-9);
    assert!((sol.last().unwrap()[0] + 1.0).abs() < 1e-9);
}

#[test]
fn failures_name_the_state() {
    let bad_start = Problem::new(&model(), [1.0, f64::NAN], (0.0, 1.0))
        .solve::<1>()
        .unwrap_err();
    assert_eq!(bad_start.state(), Some("v"));
    assert!(bad_start.to_string().contains("state `v`"), "{bad_start}");

    let bad_tolerance = Problem::new(&model(), [1.0, 0.0], (0.0, 1.0))
        .tolerance(Tolerance::per_component([1e-6, -1.0], [1e-9, 1e-9]))
        .solve::<1>()
        .unwrap_err();
    assert_eq!(bad_tolerance.state(), Some("v"));
    assert!(
        bad_tolerance.to_string().contains("tolerance of state `v`"),
        "{bad_tolerance}"
    );

    let blowup = Problem::new(&blowup::Model::new([]), [1.0], (0.0, 2.0))
        .solve::<0>()
        .unwrap_err();
    let text = blowup.to_string();
    assert!(text.contains("model `blowup`"), "{text}");
    if let SolveFailure::Solve { error, .. } = &blowup {
        if matches!(error, model_runtime::SolveError::StepSizeCollapse { .. }) {
            assert!(text.contains("state `y`"), "{text}");
        }
    } else {
        panic!("{blowup:?}");
    }
}

#[test]
fn bad_output_times_and_budgets_are_errors() {
    let outside = Problem::new(&model(), [1.0, 0.0], (0.0, 1.0))
        .output(Output::Times(vec![0.0, 0.5, 2.0]))
        .solve::<1>()
        .unwrap_err();
    assert!(
        matches!(outside, SolveFailure::OutputTime { index: 2, .. }),
        "{outside:?}"
    );
    let decreasing = Problem::new(&model(), [1.0, 0.0], (0.0, 1.0))
        .output(Output::Times(vec![0.5, 0.25]))
        .solve::<1>()
        .unwrap_err();
    assert!(matches!(
        decreasing,
        SolveFailure::OutputTime { index: 1, .. }
    ));
    let budget = Problem::new(&model(), [1.0, 0.0], (0.0, 100.0))
        .max_steps(10)
        .solve::<1>()
        .unwrap_err();
    assert!(
        matches!(
            budget,
            SolveFailure::Solve {
                error: model_runtime::SolveError::MaxSteps { .. },
                ..
            }
        ),
        "{budget:?}"
    );
}

model_macros::model! {
    /// x decays from its written start, y stays where it is written to be.
    mod decay {
        params { k = 1.0 }
        states { x = 2.0, y = 3.0 }
        equations { der(x) = -k * x; der(y) = 0; }
    }
}

/// A smooth model's initial values as written are its `INITIAL`, and a run from there follows
/// the closed form `x = 2 e^-t`, `y = 3`; a state without a value starts at 0.
#[test]
fn a_smooth_model_starts_at_its_written_initial_values() {
    assert_eq!(decay::INITIAL, [2.0, 3.0]);
    assert_eq!(oscillator::INITIAL, [0.0, 0.0]);
    let sol = Problem::new(&decay::Model::default(), decay::INITIAL, (0.0, 1.0))
        .tolerances(1e-12, 1e-14)
        .solve::<0>()
        .unwrap();
    let last = sol.y.last().unwrap();
    assert!((last[decay::state::x] - 2.0 * (-1.0f64).exp()).abs() < 1e-11);
    assert_eq!(last[decay::state::y], 3.0);
}
