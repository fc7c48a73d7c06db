//! What `model show` and `model solve` say about a file that is legal but likely not what
//! its author meant (warnings, each at its token, the run going on), and about mistakes
//! (one error each, in the user's names, with a suggestion where one is close).

use crate::cli_model::{arg, file, model};

/// `model ARGS` on `text`: the exit code and standard error.
fn run(command: &str, text: &str, extra: &[&str]) -> (Option<i32>, String) {
    let (_dir, path) = file(text);
    let mut args = vec![command, arg(&path)];
    args.extend_from_slice(extra);
    let out = model(&args);
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!stderr.contains("panicked"), "{stderr}");
    (out.status.code(), stderr)
}

#[test]
fn a_guard_that_cannot_change_sign_and_modes_without_a_way_in_or_out_are_warned_of() {
    let text = "mod m { states { h = 1, v }
        mode a { equations { der(h) = v; der(v) = -1; }
            when never: h^2 < 0 { v = 0; }
            when land: h < 0 -> b { v = 0; } }
        mode b { equations { der(h) = 0; der(v) = 0; } when tick: t > 5 { v = 0; } }
        mode c { equations { der(h) = 0; der(v) = 0; } } }";
    for (command, extra) in [("show", vec![]), ("solve", vec!["--t-end", "1"])] {
        let (code, stderr) = run(command, text, &extra);
        assert_eq!(code, Some(0), "{command}: {stderr}");
        assert!(
            stderr.contains("model.dsl:3:25: warning: event `never` can never fire"),
            "{command}: {stderr}"
        );
        assert!(
            stderr.contains("warning: mode `b` has events but none leaves it"),
            "{stderr}"
        );
        assert!(
            stderr.contains("warning: mode `c` is never entered"),
            "{stderr}"
        );
    }
}

/// `when apex: der(h) < 0` from v = 0: the guard starts on its threshold and departs from
/// it, which is not a crossing: a warning says so.
#[test]
fn a_guard_on_a_derivative_that_starts_on_its_threshold_is_warned_of() {
    let (code, stderr) = run(
        "solve",
        "mod m { states { h = 1, v } equations { der(h) = v; der(v) = -1; }
            when apex: der(h) < 0 -> stop; }",
        &["--t-end", "1"],
    );
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        stderr.contains("warning: event `apex`: its guard `der(h)` reads a derivative"),
        "{stderr}"
    );
}

/// An event declared twice: one error, naming the event, nothing internal.
#[test]
fn a_duplicated_event_is_one_error_in_the_user_s_names() {
    let (code, stderr) = run(
        "show",
        "mod m { states { h = 1, v } equations { der(h) = v; der(v) = -1; }
            when impact: h < 0 { v = -v; }
            when impact: h < 0 { v = -v; } }",
        &[],
    );
    assert_eq!(code, Some(2), "{stderr}");
    assert_eq!(
        stderr.matches(": event `impact` is declared twice").count(),
        1,
        "{stderr}"
    );
    assert_eq!(stderr.matches("model.dsl:").count(), 1, "{stderr}");
    assert!(
        !stderr.contains("when:") && !stderr.contains("reset:"),
        "{stderr}"
    );
}

#[test]
fn mistakes_get_a_suggestion_or_a_hint() {
    let ball = |event: &str| {
        format!(
            "mod m {{ discrete {{ bounces = 0 }} states {{ h = 1, v }}
            mode flying {{ equations {{ der(h) = v; der(v) = -1; }} {event} }}
            mode resting {{ equations {{ der(h) = 0; der(v) = 0; }} }} }}"
        )
    };
    for (event, needle) in [
        (
            "when land: h < 0 -> Resting { v = 0; }",
            "unknown mode `Resting` (did you mean `resting`?)",
        ),
        (
            "when land: h < 0 -> resting { v = -pre(v); }",
            "there is no `pre`: a reset already reads every value as it was just before the event, so write `v`",
        ),
        (
            "when land: h < 0 -> resting { bounces += 1; }",
            "`+=` is not an assignment of the DSL: write `bounces = bounces + EXPR`",
        ),
    ] {
        let (code, stderr) = run("show", &ball(event), &[]);
        assert_eq!(code, Some(2), "{event}: {stderr}");
        assert!(stderr.contains(needle), "{event}: {stderr}");
        assert!(stderr.contains("model.dsl:2:"), "{event}: {stderr}");
    }
}
