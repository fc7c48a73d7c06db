//! Every unusable request is a typed error found before integration, pointing at the value,
//! the event or the setting by its position in what was given.

use crate::{compile, model, OSCILLATOR};
use model_interpreted::{
    solve, EventRequest, LoadError, RequestError, SolveFailure, SolveRequest, ValueError,
};
use model_runtime::Direction;

fn request_error(text: &str, request: SolveRequest) -> RequestError {
    let file = compile("model.dsl", text);
    match solve(model(&file), &request) {
        Err(SolveFailure::Request(error)) => error,
        other => panic!("{other:?}"),
    }
}

fn named(pairs: &[(&str, f64)]) -> Vec<(String, f64)> {
    pairs.iter().map(|&(n, v)| (n.to_string(), v)).collect()
}

#[test]
fn values_are_checked_by_name_and_located_by_position() {
    let with = |params: &[(&str, f64)], state: &[(&str, f64)]| {
        let request = SolveRequest {
            params: named(params),
            state: named(state),
            ..SolveRequest::new(1.0)
        };
        request_error(OSCILLATOR, request)
    };
    let unknown = with(&[("w", 2.0), ("k", 1.0)], &[]);
    assert!(
        matches!(&unknown, RequestError::Params(ValueError::Unknown { index: 1, name, names })
            if name == "k" && names == "`w`"),
        "{unknown}"
    );
    let twice = with(&[], &[("x", 1.0), ("v", 0.0), ("x", 2.0)]);
    assert!(matches!(
        &twice,
        RequestError::State(ValueError::Twice { index: 2, .. })
    ));
    let nan = with(&[], &[("v", f64::NAN)]);
    assert!(matches!(
        &nan,
        RequestError::State(ValueError::NotFinite { index: 0, .. })
    ));
    let missing = request_error(
        "mod m { params { k } states { x } equations { der(x) = -k * x; } }",
        SolveRequest::new(1.0),
    );
    assert!(
        matches!(&missing, RequestError::Params(ValueError::Missing { name }) if name == "k"),
        "{missing}"
    );
}

#[test]
fn events_name_a_state_or_an_output_of_a_smooth_model_only() {
    let event = |name: &str| EventRequest {
        name: name.into(),
        direction: Direction::Both,
        stop: false,
    };
    let request = SolveRequest {
        events: vec![event("x"), event("speed"), event("y")],
        ..SolveRequest::new(1.0)
    };
    let RequestError::UnknownEvent(unknown) = request_error(OSCILLATOR, request) else {
        panic!("`y` is unknown")
    };
    assert_eq!((unknown.index, unknown.name.as_str()), (2, "y"));
    assert_eq!(unknown.states, "`x`, `v`");
    let request = SolveRequest {
        events: vec![event("h")],
        ..SolveRequest::new(1.0)
    };
    let switched =
        "mod s { states { h = 1 } equations { der(h) = -1; } when hit: h < 0 { h = 1; } }";
    assert!(matches!(
        request_error(switched, request),
        RequestError::EventsOfSwitched { name } if name == "h"
    ));
    let file = compile("s.dsl", switched);
    assert!(matches!(
        file.model(Some("chart")),
        Err(LoadError::ChartOfSwitched { .. })
    ));
    assert!(matches!(file.smooth(None), Err(LoadError::Switched { .. })));
}

#[test]
fn settings_are_input_errors() {
    let with_dt = |dt| SolveRequest {
        dt: Some(dt),
        ..SolveRequest::new(1.0)
    };
    assert!(matches!(
        request_error(OSCILLATOR, with_dt(-0.1)),
        RequestError::SampleStep { .. }
    ));
    assert!(matches!(
        request_error(OSCILLATOR, with_dt(1e-12)),
        RequestError::SampleCount { .. }
    ));
    let with_times = |times: &[f64]| SolveRequest {
        times: Some(times.to_vec()),
        ..SolveRequest::new(1.0)
    };
    let time_error = |times: &[f64]| match request_error(OSCILLATOR, with_times(times)) {
        RequestError::Time { index, problem, .. } => (index, problem),
        other => panic!("{other}"),
    };
    assert_eq!(time_error(&[0.1, 0.3, 0.2]).0, 2);
    assert!(time_error(&[0.1, 0.1]).1.contains("after"));
    assert!(time_error(&[0.5, 1.5]).1.contains("outside"));
    assert!(time_error(&[f64::NAN]).1.contains("finite"));
    let both = SolveRequest {
        dt: Some(0.1),
        ..with_times(&[0.5])
    };
    assert!(matches!(
        request_error(OSCILLATOR, both),
        RequestError::StepAndTimes
    ));
    let switched =
        "mod s { states { h = 1 } equations { der(h) = -1; } when hit: h < 0 { h = 1; } }";
    assert!(matches!(
        request_error(switched, with_times(&[0.5])),
        RequestError::TimesOfSwitched { .. }
    ));
    let not_finite = request_error(OSCILLATOR, SolveRequest::new(f64::INFINITY));
    assert!(matches!(&not_finite, RequestError::Settings(text) if text.contains("[0, inf]")));
}
