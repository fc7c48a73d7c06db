//! Switched models through the front end: modes and events parsed, checked, compiled, and
//! every mistake in the new constructs located at its token.

use crate::common::{compile_switched as compile, messages, switched_errors as errors};
use crate::common::{find, underlined};
use model_algebra::Inputs;
use model_dsl::{Action, Crossing, Source};

const BALL: &str = include_str!("../../../examples/bouncing_ball.dsl");

fn eval(program: &model_algebra::Program, y: &[f64], dy: &[f64], p: &[f64], n: usize) -> Vec<f64> {
    let inputs = Inputs {
        t: 0.0,
        states: y,
        params: p,
        ders: dy,
    };
    program.eval(&inputs).unwrap().outputs(n)
}

#[test]
fn the_ball_compiles_to_two_modes_with_its_event_and_its_rest() {
    let ball = compile(BALL);
    assert_eq!(ball.name, "bouncing_ball");
    assert_eq!(ball.states(), ["h", "v"]);
    assert_eq!(ball.initial, [Some(1.0), Some(0.0)]);
    let names: Vec<&str> = ball.modes.iter().map(|m| m.model.name.as_str()).collect();
    assert_eq!(names, ["flying", "resting"]);
    let flying = &ball.modes[0];
    assert_eq!(flying.model.outputs, ["energy"]);
    assert_eq!(flying.events.len(), 1);
    let impact = &flying.events[0];
    assert_eq!(
        (impact.name.as_str(), impact.crossing),
        ("impact", Crossing::Down)
    );
    assert_eq!(impact.guard, "h");
    let Action::Jump(jump) = &impact.action else {
        panic!("{:?}", impact.action)
    };
    assert_eq!((jump.to, jump.states.as_slice()), (None, &[1usize][..]));
    assert_eq!(jump.texts, ["-v*e"]);
    let p = [9.81, 0.8];
    // The guard reads h; the reset gives -e v from the state before the impact.
    assert_eq!(
        eval(&flying.guards, &[0.25, -3.0], &[-3.0, -9.81], &p, 1),
        [0.25]
    );
    assert_eq!(
        eval(&jump.program, &[0.0, -3.0], &[-3.0, -9.81], &p, 1),
        [2.4000000000000004]
    );
    let rest = impact.accumulation.as_ref().expect("the rule");
    assert_eq!(
        (rest.to, rest.states.as_slice()),
        (Some(1), &[0usize, 1][..])
    );
    assert_eq!(
        eval(&rest.program, &[1e-12, -3e-6], &[0.0, 0.0], &p, 2),
        [0.0, 0.0]
    );
    // The user's outputs alone in the mode's own outputs program.
    assert_eq!(
        eval(
            &flying.model.outputs_program,
            &[1.0, 2.0],
            &[2.0, -9.81],
            &p,
            1
        ),
        [9.81 + 2.0]
    );
    assert!(
        !flying.model.explanation.markdown.contains("when:"),
        "{}",
        flying.model.explanation.markdown
    );
    assert!(ball.modes[1].events.is_empty());
}

#[test]
fn a_model_with_events_and_no_modes_is_its_own_mode_and_guards_may_read_derivatives() {
    let text = "mod drop { params { g = 9.81 } states { h = 2, v }
        equations { der(h) = v; der(v) = -g; }
        outputs { speed = abs(v); }
        when apex: der(h) < 0;
        when fast: speed > 3 -> stop;
        when floor: h <= 0 { v = -v; } }";
    let model = compile(text);
    assert_eq!(model.modes.len(), 1);
    assert_eq!(model.modes[0].model.name, "drop");
    assert_eq!(model.initial, [Some(2.0), None]);
    let events = &model.modes[0].events;
    let summary: Vec<(&str, Crossing, bool)> = events
        .iter()
        .map(|e| {
            (
                e.name.as_str(),
                e.crossing,
                matches!(e.action, Action::Record),
            )
        })
        .collect();
    assert_eq!(
        summary,
        [
            ("apex", Crossing::Down, true),
            ("fast", Crossing::Up, false),
            ("floor", Crossing::Down, false)
        ]
    );
    assert!(matches!(events[1].action, Action::Stop));
    // The guards in one program: der(h), speed - 3, h.
    let values = eval(
        &model.modes[0].guards,
        &[0.5, -4.0],
        &[-4.0, -9.81],
        &[9.81],
        3,
    );
    assert_eq!(values, [-4.0, 1.0, 0.5]);
}

#[test]
fn shared_equations_and_events_join_every_mode() {
    let text = "mod belt { params { k = 10, vb = 0.5 } states { x, v }
        equations { kinematics: der(x) = v; }
        when broken: x > 100 -> stop;
        mode stuck { equations { der(v) = 0; } when slip: k*x > 6 -> sliding; }
        mode sliding { equations { der(v) = -k*x; } when stick: v > vb -> stuck { v = vb; } } }";
    let model = compile(text);
    let events: Vec<Vec<&str>> = (model.modes.iter())
        .map(|m| m.events.iter().map(|e| e.name.as_str()).collect())
        .collect();
    assert_eq!(events, [vec!["slip", "broken"], vec!["stick", "broken"]]);
    let Action::Jump(slip) = &model.modes[0].events[0].action else {
        panic!()
    };
    assert_eq!((slip.to, slip.states.len()), (Some(1), 0));
    assert_eq!(
        model.modes[0]
            .model
            .explanation
            .markdown
            .matches("der(x) = v")
            .count(),
        1
    );
}

#[test]
fn mistakes_in_switching_are_located_and_name_the_culprit() {
    let text = "mod m { params { e = 0.5 } states { h, v }
        mode a { equations { der(h) = v; der(v) = -1; }
            when hit: h < 0 -> nowhere;
            when bounce: h < 0 { w = -e*v; } }
        mode b { equations { der(h) = v; der(v) = 1; } } }";
    let found = errors(text);
    let unknown = find(&found, "unknown mode `nowhere`");
    assert!(
        unknown.message.contains("the modes are `a`, `b`"),
        "{}",
        unknown.message
    );
    assert_eq!(underlined(unknown, 7), "nowhere");
    let reset = find(&found, "resets `w`, which is not a state");
    assert!(reset.message.contains("the states are `h`, `v`"));
    assert_eq!(underlined(reset, 1), "w");
    assert_eq!(found.len(), 2, "{:#?}", messages(&found));

    // What only the compiler sees: a guard that never changes, a mode short of an equation.
    let text = "mod m { params { e = 0.5 } states { h, v }
        mode a { equations { der(h) = v; der(v) = -1; } when never: e < 1 { v = 0; } }
        mode b { equations { der(h) = v; } } }";
    let found = errors(text);
    let constant = find(&found, "the guard of `never` reads no state");
    assert_eq!(underlined(constant, 5), "e < 1");
    let missing = find(&found, "in mode `b`");
    assert!(missing.message.contains("`v`"), "{}", missing.message);
    assert_eq!(found.len(), 2, "{:#?}", messages(&found));
}

#[test]
fn syntax_of_events_is_checked_where_written() {
    let cases = [
        ("mod m { states { x } equations { der(x) = 1; } when hit x < 0; }", "expected `:` and a guard"),
        ("mod m { states { x } equations { der(x) = 1; } when hit: x = 0; }", "not `=`"),
        ("mod m { states { x } equations { der(x) = 1; } when hit: x; }", "expected a comparison"),
        ("mod m { states { x } equations { der(x) = 1; } when hit: x < 0 -> stop { x = 1; } }", "stops the run"),
        ("mod m { states { x } equations { der(x) = 1; } when hit: x < 0; when hit accumulates -> m; }", "resets nothing"),
        ("mod m { states { x } equations { der(x) = 1; } when hit: x < 0 { x = 1; } when miss accumulates -> m; }", "no event `miss`"),
        ("mod m { states { x } mode state { equations { der(x) = 1; } } }", "cannot be called `state`"),
        ("mod m { states { x } mode a { equations { der(x) = 1; } } mode a { equations { der(x) = 2; } } }", "declared twice"),
        ("mod m { states { x } mode a { params { k } equations { der(x) = 1; } } }", "belong to the model"),
        ("mod m { states { x } equations { der(x) = 1; } when hit: x < 0 by f { x = 1; } }", "not both"),
        ("mod m { states { x } equations { der(x) = 1; } when hit: x < 0 { x = 1; } by f; }", "not both"),
        ("mod m { states { x } equations { der(x) = 1; } when hit: x < 0 by; }", "name of a Rust function after `by`"),
        ("mod m { states { x } equations { der(x) = 1; } when hit: x < 0 -> stop by f; }", "stops the run"),
        ("mod m { states { x } equations { der(x) = 1; } time_scale = 1; time_scale = 2; }", "`time_scale` is written twice"),
        ("mod m { states { x } mode a { equations { der(x) = 1; } when hit: x < 0 -> a | stop; } }", "a Rust function decides which"),
        ("mod m { states { x } mode a { equations { der(x) = 1; } when hit: x < 0 -> a | b by f; } }", "unknown mode `b`"),
        ("mod m { states { x } mode a { equations { der(x) = 1; } when hit: x < 0 by f; when hit accumulates -> a | stop; } }", "an accumulation goes on in one mode"),
        ("mod m { states { x } mode a { equations { der(x) = 1; } when hit: x < 0 -> a | ; } }", "after `|`"),
        ("mod m { states { x } equations { der(x) = 1; } time_scale 1; }", "expected `=` and an expression after `time_scale`"),
        ("mod m { states { x } mode a { equations { der(x) = 1; } time_scale = x; time_scale = 1; } }", "written twice"),
    ];
    for (text, expected) in cases {
        let found = messages(&errors(text));
        assert!(
            found.iter().any(|m| m.contains(expected)),
            "{text}\n{found:#?}"
        );
    }
}

#[test]
fn an_error_in_a_shared_row_is_reported_once() {
    let text = "mod m { states { x, v } equations { der(x) = vv; }
        mode a { equations { der(v) = 1; } } mode b { equations { der(v) = -1; } } }";
    let found = messages(&errors(text));
    assert_eq!(found.len(), 1, "{found:#?}");
    assert!(found[0].starts_with("unknown name `vv`"), "{found:#?}");
}

#[test]
fn a_model_that_calls_rust_is_refused_from_text_at_each_call() {
    let text = "mod m { states { x, v } equations { der(x) = v; der(v) = -1; }
        when hit: x < 0 by bounce;
        when hit accumulates -> m by rest; }";
    let found = errors(text);
    assert_eq!(found.len(), 2, "{:#?}", messages(&found));
    for (error, name) in found.iter().zip(["bounce", "rest"]) {
        assert!(
            error
                .message
                .starts_with(&format!("`{name}` is a Rust function")),
            "{}",
            error.message
        );
        assert!(
            error.message.contains("runs only compiled"),
            "{}",
            error.message
        );
        assert_eq!(underlined(error, name.len()), name);
    }
    assert_eq!((found[0].line, found[1].line), (2, 3));
}

#[test]
fn a_jump_by_a_rust_function_is_planned_with_its_name_and_no_written_resets() {
    let text = "mod m { params { c = 0 } states { x, v } equations { der(x) = v; der(v) = -1; }
        mode a { when hit: x < c -> b by onset; }
        mode b { when lift: x > 1 -> a { v = 0; } } }";
    let ast = Source::new("m.dsl", text).parse().unwrap();
    let plan = model_dsl::validate_switched(&ast).unwrap();
    let compiled = model_dsl::compile_switched(&plan).unwrap();
    let Action::Jump(jump) = &compiled.modes[0].events[0].action else {
        panic!("{:?}", compiled.modes[0].events[0].action)
    };
    assert_eq!((jump.to, jump.by.as_deref()), (Some(1), Some("onset")));
    assert!(jump.states.is_empty() && jump.texts.is_empty());
    let Action::Jump(back) = &compiled.modes[1].events[0].action else {
        panic!("{:?}", compiled.modes[1].events[0].action)
    };
    assert_eq!((back.to, back.by.as_deref()), (Some(0), None));
    let table = model_dsl::switching_markdown(&compiled);
    assert!(
        table.contains(
            "| `hit` | `x - c` crosses 0 downwards | the state `by onset` (Rust), go to `b` |"
        ),
        "{table}"
    );
    assert_eq!(jump.choice, None);
    let latex = model_dsl::switching_latex(&compiled);
    assert!(
        latex.contains("y^{+} = \\texttt{onset}(t, y, \\dot y),\\ \\to \\text{b}"),
        "{latex}"
    );
}

#[test]
fn a_time_scale_reads_states_and_parameters_only_and_a_mode_s_own_wins() {
    let text = "mod m { params { c = 0.1 } states { x, v } equations { der(x) = v; der(v) = -x; }
        time_scale = x^2 / (x^2 + c);
        mode a { when hit: x < 0 -> b; }
        mode b { time_scale = 1; } }";
    let model = compile(text);
    let clocks: Vec<&str> = (model.modes.iter())
        .map(|m| m.time_scale.as_ref().unwrap().text.as_str())
        .collect();
    assert_eq!(clocks, ["x^2/(x^2 + c)", "1"]);
    let a = &model.modes[0].time_scale.as_ref().unwrap().program;
    assert_eq!(
        eval(a, &[0.3, 5.0], &[f64::NAN, f64::NAN], &[0.1], 1),
        [0.09 / 0.19]
    );
    // Without a declaration there is no clock (the runtime's default is 1).
    assert!(compile(BALL).modes.iter().all(|m| m.time_scale.is_none()));

    let text = "mod m { states { x, v } equations { der(x) = v; der(v) = -x; }
        mode a { time_scale = abs(der(v)); when hit: x < 0 -> b; }
        mode b { time_scale = 1 + t; } }";
    let found = errors(text);
    assert_eq!(found.len(), 2, "{:#?}", messages(&found));
    for error in &found {
        assert!(error
            .message
            .contains("a time scale reads only states and parameters"));
        assert_eq!(underlined(error, 10), "time_scale");
    }
}

#[test]
fn a_choice_of_modes_is_planned_for_its_rust_function() {
    let text = "mod m { states { x, v } equations { der(x) = v; der(v) = -1; }
        mode a { when hit: x < v by land; when miss: x > v -> b | a | stop by land; }
        mode b { } }";
    let ast = Source::new("m.dsl", text).parse().unwrap();
    let model = model_dsl::compile_switched(&model_dsl::validate_switched(&ast).unwrap()).unwrap();
    let Action::Jump(restart) = &model.modes[0].events[0].action else {
        panic!("{:?}", model.modes[0].events[0].action)
    };
    assert_eq!((restart.to, restart.by.as_deref()), (None, Some("land")));
    assert_eq!(restart.choice, None);
    let Action::Jump(jump) = &model.modes[0].events[1].action else {
        panic!("{:?}", model.modes[0].events[1].action)
    };
    assert_eq!(jump.to, None);
    assert_eq!(jump.by.as_deref(), Some("land"));
    assert_eq!(
        jump.choice,
        Some(model_dsl::Choice {
            modes: vec![1, 0],
            stop: true
        })
    );
    let latex = model_dsl::switching_latex(&model);
    assert!(
        latex.contains("\\to \\text{b} \\mid \\text{a} \\mid \\text{stop}"),
        "{latex}"
    );
}
