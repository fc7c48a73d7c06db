//! What a mode may carry besides its equations, through the front end: discrete values held
//! between events, a mode's own coordinates in some state slots, and a first step; each
//! mistake located at its token.

use crate::common::{compile_switched as compile, find, switched_errors as errors, underlined};
use model_algebra::Inputs;
use model_dsl::Action;

/// A ball that counts its bounces in a discrete value, and falls in its own coordinate: the
/// downward speed `w` in the slot of the velocity `v`.
const BALL: &str = "mod ball {
    params { g = 9.81, e = 0.8 }
    states { h = 1.0, v = 0.0 }
    discrete { bounces = 0, t_last = -1 }
    mode rising {
        equations { der(h) = v; der(v) = -g; }
        first_step = abs(v / der(v)) / 100;
        when apex: v < 0 -> falling { w = -v; }
    }
    mode falling {
        states { w } replace { v }
        equations { der(h) = -w; der(w) = g; }
        when impact: h < 0 -> rising { v = e * w; bounces = bounces + 1; t_last = t; }
    }
}";

#[test]
fn discrete_values_follow_the_parameters_and_resets_assign_them() {
    let ball = compile(BALL);
    assert_eq!(
        ball.discrete,
        [("bounces".into(), 0.0), ("t_last".into(), -1.0)]
    );
    assert_eq!(ball.n_params(), 2);
    // Every mode's model reads them as parameters after the model's own.
    for mode in &ball.modes {
        let names: Vec<&str> = mode.model.params.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["g", "e", "bounces", "t_last"]);
    }
    let falling = &ball.modes[1];
    let Action::Jump(jump) = &falling.events[0].action else {
        panic!()
    };
    // Slots: the target mode's states (h, v), then the discrete values (2, 3).
    assert_eq!(jump.states, [1, 2, 3]);
    let names: Vec<&str> = (jump.states.iter())
        .map(|&s| ball.value_name(0, s))
        .collect();
    assert_eq!(names, ["v", "bounces", "t_last"]);
    let inputs = Inputs {
        t: 0.45,
        states: &[-1e-9, 4.0],
        params: &[9.81, 0.8, 2.0, 0.1],
        ders: &[-4.0, 9.81],
    };
    let values = jump.program.eval(&inputs).unwrap().outputs(3);
    assert_eq!(values, [0.8 * 4.0, 3.0, 0.45]);
}

#[test]
fn a_mode_carries_its_own_coordinates_in_the_slots_it_replaces() {
    let ball = compile(BALL);
    assert_eq!(ball.modes[0].model.states, ["h", "v"]);
    assert_eq!(ball.modes[1].model.states, ["h", "w"]);
    assert_eq!(ball.slot_names(), ["h", "v/w"]);
    // The reset into `falling` assigns its `w`, read from `rising`'s `v`.
    let Action::Jump(apex) = &ball.modes[0].events[0].action else {
        panic!()
    };
    assert_eq!((apex.to, apex.states.as_slice()), (Some(1), &[1usize][..]));
    assert_eq!(ball.value_name(1, 1), "w");
    let shown = model_dsl::switching_markdown(&ball);
    assert!(
        shown.contains("States: `w` in the slots of `v`."),
        "{shown}"
    );
    assert!(shown.contains("Discrete values"), "{shown}");
    assert!(shown.contains("`w := -v`"), "{shown}");
    assert!(
        shown.contains("`bounces := bounces + 1`") || shown.contains("bounces :="),
        "{shown}"
    );
}

#[test]
fn a_first_step_may_read_the_derivatives() {
    let ball = compile(BALL);
    let step = ball.modes[0].first_step.as_ref().expect("declared");
    let inputs = Inputs {
        t: 0.0,
        states: &[1.0, 3.0],
        params: &[9.81, 0.8, 0.0, -1.0],
        ders: &[3.0, -9.81],
    };
    let h = step.program.eval(&inputs).unwrap().outputs(1)[0];
    assert!((h - 3.0 / 9.81 / 100.0).abs() < 1e-15, "{h}");
    assert!(ball.modes[1].first_step.is_none());
    let shown = model_dsl::switching_markdown(&ball);
    assert!(shown.contains("First step when the mode starts"), "{shown}");
}

#[test]
fn mistakes_in_held_values_and_mode_states_are_located() {
    let text = "mod m { params { e = 0.5 } states { h, v } discrete { n = 0 }
        mode a { states { w, x } replace { v }
            equations { der(h) = v; der(v) = -1; }
            when hit: h < 0 -> b { q = 1; } }
        mode b { states { u } replace { z }
            equations { der(h) = v; der(v) = 1; } } }";
    let found = errors(text);
    let count = find(&found, "brings 2 states in for 1 replaced");
    assert_eq!(underlined(count, 6), "states");
    let unknown = find(&found, "replaces `z`, which is not a state of the model");
    assert_eq!(underlined(unknown, 1), "z");
    let reset = find(
        &found,
        "resets `q`, which is not a state or a discrete value of mode `b`",
    );
    assert!(reset.message.contains("`h`, `v`, `n`"), "{}", reset.message);
    assert_eq!(found.len(), 3, "{found:#?}");

    // What only the compiler sees: an output that reads a held value.
    let found = errors(
        "mod m { states { h } discrete { n = 0 } outputs { seen = n + h; }
         equations { der(h) = 1; } when w: h > 1 { n = n + 1; } }",
    );
    let output = find(&found, "output `seen` reads the discrete value `n`");
    assert_eq!(underlined(output, 4), "seen");

    // A discrete value needs its starting value; a mode cannot be called `discrete`.
    let found = errors("mod m { states { h } discrete { n } equations { der(h) = 1; } }");
    let value = find(&found, "expected `= VALUE` after `n`");
    assert_eq!(underlined(value, 1), "}");
    let found = errors(
        "mod m { states { h } mode discrete { equations { der(h) = 1; } when w: h > 1 -> stop; } }",
    );
    let reserved = find(&found, "a mode cannot be called `discrete`");
    assert_eq!(underlined(reserved, 8), "discrete");
    let found = errors(
        "mod m { states { h } mode a { equations { der(h) = 1; } first_step = 1; first_step = 2; } }",
    );
    let twice = find(&found, "`first_step` is written twice");
    assert_eq!(underlined(twice, 10), "first_step");
}

#[test]
fn a_mode_like_another_takes_its_rows_and_keeps_its_own_events() {
    let model = compile(
        "mod m { params { g = 9.81 } states { h = 1, v }
            mode up { states { w } replace { v } equations { der(h) = w; der(w) = -g; }
                first_step = 1e-3; when top: w < 0 -> down; }
            mode down like up { when floor: h < 0 -> up { w = -w; } } }",
    );
    let (up, down) = (&model.modes[0], &model.modes[1]);
    assert_eq!(down.model.states, up.model.states);
    assert_eq!(
        down.model.explanation.markdown,
        up.model.explanation.markdown.replace("`up`", "`down`")
    );
    assert!(down.first_step.is_some());
    let names: Vec<&str> = down.events.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(names, ["floor"]);
    let found = errors(
        "mod m { states { h } mode a like b { when w: h > 1 -> stop; }
            mode c like a { when x: h > 2 -> stop; } }",
    );
    let unknown = find(&found, "mode `a` is like `b`, which is not a mode");
    assert_eq!(underlined(unknown, 1), "b");
    let chained = find(
        &found,
        "mode `c` is like `a`, which does not write its own equations",
    );
    assert_eq!(underlined(chained, 1), "a");
}
