//! `eulerdisk model show|eval|solve` as a user runs them on a DSL file: the example heavy top
//! shown, evaluated (against a hand derivation) and solved (its energy kept); a file with a
//! mistake gives `file:line:col: message`, the line and a caret, and exit code 2.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

const HEAVY_TOP: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/model-macros/examples/heavy_top.dsl"
);

pub(crate) fn model(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .arg("model")
        .args(args)
        .output()
        .unwrap()
}

fn ok(args: &[&str]) -> String {
    let out = model(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {stderr}");
    String::from_utf8(out.stdout).unwrap()
}

/// A DSL file in a fresh temporary directory.
pub(crate) fn file(text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("model.dsl");
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

pub(crate) fn arg(path: &Path) -> &str {
    path.to_str().unwrap()
}

#[test]
fn show_prints_the_solved_equations_of_a_file() {
    let text = ok(&["show", HEAVY_TOP]);
    assert!(
        text.starts_with("# `heavy_top`: the solved equations"),
        "{text}"
    );
    for state in ["phi", "theta", "psi", "w_phi", "w_theta", "w_psi"] {
        assert!(
            text.contains(&format!("der({state}) = ")),
            "der({state}):\n{text}"
        );
    }
    // The momenta's block divides by sin(theta): a pivot, named.
    assert!(text.contains("sin(theta)"), "{text}");
    let latex = ok(&["show", HEAVY_TOP, "--format", "latex"]);
    assert!(latex.starts_with("\\begin{align*}"), "{latex}");
    assert!(latex.contains("\\dot{\\theta} &= w_{\\theta}"), "{latex}");
    // A disk model by name still works.
    assert!(ok(&["show", "rolling"]).contains("## At the paper's start"));
}

#[test]
fn a_chart_is_shown_after_its_model_and_evaluated_by_name() {
    let (_dir, path) = file(
        "mod oscillator {
            params { w = 2 }
            states { x, v }
            equations { der(x) = v; der(v) = -w^2 * x; }
            outputs { energy = (v^2 + w^2 * x^2) / 2; }
            chart polar {
                states { r, phi } replace { x, v }
                let x = r * cos(phi);
                let v = -w * r * sin(phi);
            }
        }",
    );
    let text = ok(&["show", arg(&path)]);
    let (at_model, at_chart) = (
        text.find("# `oscillator`").unwrap(),
        text.find("# `polar`").unwrap(),
    );
    assert!(at_model < at_chart, "{text}");
    let out = ok(&[
        "eval",
        arg(&path),
        "--chart",
        "polar",
        "--state",
        "r=1.5",
        "--state",
        "phi=0.3",
    ]);
    let v: Value = serde_json::from_str(&out).unwrap();
    assert!(
        v["derivatives"]["der(r)"].as_f64().unwrap().abs() < 1e-14,
        "{out}"
    );
    assert!(
        (v["derivatives"]["der(phi)"].as_f64().unwrap() - 2.0).abs() < 1e-14,
        "{out}"
    );
    assert!(
        (v["outputs"]["energy"].as_f64().unwrap() - 4.5).abs() < 1e-14,
        "{out}"
    );
    let wrong = model(&["eval", arg(&path), "--chart", "cartesian"]);
    assert_eq!(wrong.status.code(), Some(2));
    let err = String::from_utf8_lossy(&wrong.stderr);
    assert!(
        err.contains(
            "`cartesian` is not a chart of the model; the file defines `oscillator`, `polar`"
        ),
        "{err}"
    );
}

#[test]
fn eval_prints_derivatives_and_outputs_by_name() {
    let (theta, w_phi, w_psi): (f64, f64, f64) = (0.4, 2.0, 150.0);
    let out = ok(&[
        "eval",
        HEAVY_TOP,
        "--state",
        &format!("theta={theta}"),
        "--state",
        &format!("w_phi={w_phi}"),
        "--state",
        &format!("w_psi={w_psi}"),
        "--set",
        "m=1",
    ]);
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["model"], "heavy_top");
    // Printed in the model's order.
    let at = |k: &str| out.find(&format!("\"{k}\":")).unwrap();
    assert!(at("der(phi)") < at("der(theta)") && at("der(theta)") < at("der(w_psi)"));
    assert!(at("energy") < at("momentum_phi"));
    // The nutation equation by hand (w_theta = 0), with m = 1 from --set.
    let (g, l, i1, i3) = (9.81, 0.04, 0.0012, 0.0009);
    let omega3 = w_psi + w_phi * theta.cos();
    let want = (i1 * w_phi * w_phi * theta.sin() * theta.cos() - i3 * omega3 * w_phi * theta.sin()
        + g * l * theta.sin())
        / i1;
    let got = v["derivatives"]["der(w_theta)"].as_f64().unwrap();
    assert!((got - want).abs() <= 1e-12 * want.abs(), "{got} vs {want}");
    let energy =
        i1 / 2.0 * (w_phi * theta.sin()).powi(2) + i3 / 2.0 * omega3 * omega3 + g * l * theta.cos();
    let got = v["outputs"]["energy"].as_f64().unwrap();
    assert!((got - energy).abs() <= 1e-12 * energy, "{got} vs {energy}");
}

#[test]
fn bad_assignments_and_singular_states_are_named() {
    for (args, needle) in [
        (
            vec!["--state", "thetta=1"],
            "--state `thetta=1`: the model has no `thetta`; the names are `phi`, `theta`",
        ),
        (vec!["--set", "m"], "--set `m`: expected NAME=VALUE"),
        (
            vec!["--set", "m=heavy"],
            "--set `m=heavy`: `heavy` is not a finite number",
        ),
        (
            vec!["--state", "phi=1", "--state", "phi=2"],
            "`phi` is given twice",
        ),
        // theta = 0: the momenta's block divides by sin(theta).
        (
            vec!["--state", "theta=0"],
            "the pivot `I1*sin(theta)^2` is 0 at this state",
        ),
    ] {
        let mut all = vec!["eval", HEAVY_TOP];
        all.extend(args.iter().copied());
        let out = model(&all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(out.stdout.is_empty());
    }
}

#[test]
fn a_mistake_in_the_file_is_located_with_a_caret() {
    let (_dir, path) = file("mod m {\n    states { x }\n    equations { der(x) = -k * x; }\n}\n");
    for (command, extra) in [
        ("show", vec![]),
        ("eval", vec![]),
        ("solve", vec!["--t-end", "1"]),
    ] {
        let mut args = vec![command, arg(&path)];
        args.extend(extra);
        let out = model(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{command:?}: {err}");
        let expected = format!("{}:3:27: unknown name `k`", path.display());
        assert!(err.contains(&expected), "{command:?}: {err}");
        assert!(
            err.contains("3 |     equations { der(x) = -k * x; }\n  |                           ^"),
            "{err}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }
    let (_dir, path) = file("mod m { states { x } equations { der(x) = (x; } }");
    let out = model(&["show", arg(&path)]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains(":1:"));
    let out = model(&["show", "no-such-model"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("neither a model of the disk"));
}

#[test]
fn solve_writes_a_trajectory_that_keeps_the_energy() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("top.csv");
    let out = model(&[
        "solve",
        HEAVY_TOP,
        "--state",
        "theta=0.5",
        "--state",
        "w_psi=150",
        "--t-end",
        "1",
        "--dt",
        "0.01",
        "--rtol",
        "1e-10",
        "--atol",
        "1e-12",
        "--out",
        arg(&csv),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t,phi,theta,psi,w_phi,w_theta,w_psi,energy,momentum_phi,momentum_psi"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 101);
    assert_eq!(rows.last().unwrap()[0], 1.0);
    let energy: Vec<f64> = rows.iter().map(|r| r[7]).collect();
    let drift = energy
        .iter()
        .map(|e| (e - energy[0]).abs())
        .fold(0.0, f64::max);
    assert!(drift < 1e-8 * energy[0].abs(), "energy drift {drift:e}");
    // The top nods: theta moves.
    let theta = rows.iter().map(|r| r[2]);
    let (lo, hi) = theta.fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
    assert!(hi - lo > 1e-4, "{lo} {hi}");
    // A singular start stops with the pivot named, exit 1.
    let out = model(&["solve", HEAVY_TOP, "--state", "theta=0", "--t-end", "1"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("sin(theta)"));
}

/// A body dropped from a height: no outputs, `h` falls as `h0 - g t^2 / 2`.
const DROP: &str = include_str!("../../model-macros/examples/drop.dsl");

/// An oscillator `x = cos(w t)` from `x = 1`, with the threshold `x = 1/2` as an output.
const OSCILLATOR: &str = "mod oscillator {
    params { w = 3 }
    states { x, v }
    equations { der(x) = v; der(v) = -w^2 * x; }
    outputs { e = x - 0.5; }
}";

/// A CSV of numbers under a header (the first `skip` columns dropped).
fn read_csv(text: &str, skip: usize) -> (String, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let header = lines.next().unwrap().to_string();
    let rows = lines
        .map(|l| {
            l.split(',')
                .skip(skip)
                .map(|x| x.parse().unwrap())
                .collect()
        })
        .collect();
    (header, rows)
}

/// `solve` with `args` on `text`, at tight tolerances; the stdout and stderr.
fn solve_events(text: &str, args: &[&str]) -> (String, String) {
    let (_dir, path) = file(text);
    let mut all = vec!["solve", arg(&path), "--rtol", "1e-12", "--atol", "1e-14"];
    all.extend_from_slice(args);
    let out = model(&all);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    // A run a `:stop` event ended exits with 3 ("stopped early"), one to its end with 0.
    let stopped = stderr.contains("stopped by event");
    let expected = if stopped { 3 } else { 0 };
    assert_eq!(out.status.code(), Some(expected), "{args:?}: {stderr}");
    (String::from_utf8(out.stdout).unwrap(), stderr)
}

/// The times of `event `NAME` at t = T` lines on standard error.
fn said_events(stderr: &str, name: &str) -> Vec<f64> {
    let prefix = format!("event `{name}` at t = ");
    (stderr.lines())
        .filter_map(|l| l.strip_prefix(&prefix))
        .map(|t| t.parse().unwrap())
        .collect()
}

#[test]
fn a_terminal_event_stops_a_falling_body_on_the_ground() {
    let (h0, g) = (2.0_f64, 9.81_f64);
    let dir = tempfile::tempdir().unwrap();
    let events = dir.path().join("events.csv");
    let (stdout, stderr) = solve_events(
        DROP,
        &[
            "--state",
            "h=2",
            "--t-end",
            "5",
            "--dt",
            "0.1",
            "--event",
            "h:down:stop",
            "--events",
            arg(&events),
        ],
    );
    let landing = (2.0 * h0 / g).sqrt();
    let (header, rows) = read_csv(&stdout, 0);
    assert_eq!(header, "t,h,v");
    let last = rows.last().unwrap();
    assert!((last[0] - landing).abs() < 1e-9, "{} vs {landing}", last[0]);
    assert!(last[1].abs() < 1e-9, "h = {}", last[1]);
    assert!((last[2] + g * landing).abs() < 1e-9, "v = {}", last[2]);
    // The samples 0, 0.1, ..., 0.6 before the landing, then the landing itself.
    assert_eq!(rows.len(), 8, "{rows:?}");
    assert!((rows[6][0] - 0.6).abs() < 1e-15, "{rows:?}");
    let (header, located) = read_csv(&std::fs::read_to_string(&events).unwrap(), 2);
    assert_eq!(header, "event,phase,t,h,v");
    // The event, then the stop it caused, at the same point.
    assert_eq!(located.len(), 2);
    assert_eq!(located[0], *last);
    assert_eq!(located[1], *last);
    let text = std::fs::read_to_string(&events).unwrap();
    assert!(text.lines().nth(1).unwrap().starts_with("h,at,"), "{text}");
    let stop = text.lines().nth(2).unwrap();
    assert!(stop.starts_with("stop,stopped by event `h`,"), "{text}");
    assert!(
        stderr.contains(&format!("stopped by event `h` at t = {}", last[0])),
        "{stderr}"
    );
    // With `--events`, the events are not said again on standard error.
    assert!(said_events(&stderr, "h").is_empty(), "{stderr}");
}

#[test]
fn an_oscillator_reports_every_zero_crossing_in_both_directions() {
    let (w, t_end) = (3.0_f64, 10.0_f64);
    let (_, stderr) = solve_events(
        OSCILLATOR,
        &["--state", "x=1", "--t-end", "10", "--event", "x"],
    );
    let times = said_events(&stderr, "x");
    // x = cos(w t) is zero at (k + 1/2) pi / w: k = 0..9 before t = 10.
    let want: Vec<f64> = (0..)
        .map(|k| (k as f64 + 0.5) * std::f64::consts::PI / w)
        .take_while(|&t| t <= t_end)
        .collect();
    assert_eq!(want.len(), 10);
    assert_eq!(times.len(), want.len(), "{stderr}");
    for (got, want) in times.iter().zip(&want) {
        assert!((got - want).abs() < 1e-8, "{got} vs {want}");
    }
    assert!(
        stderr.contains("10 events, reached the end time at t = 10"),
        "{stderr}"
    );
}

#[test]
fn an_event_on_an_output_fires_only_in_its_direction() {
    let w = 3.0_f64;
    let dir = tempfile::tempdir().unwrap();
    let events = dir.path().join("events.csv");
    let args = [
        "--state",
        "x=1",
        "--t-end",
        "10",
        "--event",
        "e:up",
        "--events",
        arg(&events),
    ];
    solve_events(OSCILLATOR, &args);
    let (header, mut located) = read_csv(&std::fs::read_to_string(&events).unwrap(), 2);
    assert_eq!(header, "event,phase,t,x,v,e");
    // The last row says how the run ended, at its end.
    assert_eq!(located.pop().unwrap()[0], 10.0);
    // cos(w t) rises through 1/2 at w t = 5 pi / 3 + 2 pi k: k = 0..3 before t = 10 (the
    // falling crossings at w t = pi / 3 + 2 pi k, five of them, do not fire).
    let pi = std::f64::consts::PI;
    let want: Vec<f64> = (0..)
        .map(|k| (5.0 * pi / 3.0 + 2.0 * pi * k as f64) / w)
        .take_while(|&t| t <= 10.0)
        .collect();
    assert_eq!(want.len(), 4);
    assert_eq!(located.len(), want.len(), "{located:?}");
    for (row, want) in located.iter().zip(&want) {
        assert!((row[0] - want).abs() < 1e-8, "{} vs {want}", row[0]);
        assert!(row[3].abs() < 1e-8, "e = {}", row[3]);
        assert!(row[2] > 0.0, "v = {}: x rises", row[2]);
    }
    // The same threshold downwards: the other crossings.
    let (_, stderr) = solve_events(
        OSCILLATOR,
        &["--state", "x=1", "--t-end", "10", "--event", "e:down"],
    );
    let down = said_events(&stderr, "e");
    assert_eq!(down.len(), 5, "{stderr}");
    assert!((down[0] - pi / 3.0 / w).abs() < 1e-8, "{}", down[0]);
}

/// `--method` is the old spelling of `--integrator`: the same run, and a note that says so.
#[test]
fn the_old_method_flag_still_works_with_a_note() {
    let run = |flag: &str| {
        model(&[
            "solve",
            HEAVY_TOP,
            "--state",
            "theta=0.5",
            "--t-end",
            "0.5",
            flag,
            "dopri5",
        ])
    };
    let (new, old) = (run("--integrator"), run("--method"));
    assert!(new.status.success() && old.status.success(), "{old:?}");
    assert_eq!(new.stdout, old.stdout);
    let note = String::from_utf8_lossy(&old.stderr);
    assert!(note.contains("`--method` is deprecated"), "{note}");
    assert!(!String::from_utf8_lossy(&new.stderr).contains("deprecated"));
}

#[test]
fn bad_event_specs_are_input_errors_naming_the_problem() {
    let (_dir, path) = file(OSCILLATOR);
    for (spec, needle) in [
        (
            "y",
            "--event `y`: the model has no state or output `y`; the states are `x`, `v`; the outputs are `e`",
        ),
        ("x:sideways", "`sideways` is neither a direction (`up`, `down`) nor `stop`"),
        ("", "--event ``: the name is empty"),
        (":stop", "--event `:stop`: the name is empty"),
        ("x:up:down", "`down` comes after another direction or twice"),
        ("x:stop:stop", "`stop` comes after another direction or twice"),
    ] {
        let out = model(&["solve", arg(&path), "--t-end", "1", "--event", spec]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{spec:?}: {err}");
        assert!(err.contains(needle), "{spec:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(out.stdout.is_empty(), "{spec:?}");
    }
}

/// Settings `model solve` cannot use are input errors (exit 2) naming the setting, found
/// before any integration: an end time that is not finite, a negative sampling step (read as
/// the step, not as a flag), a negative tolerance, a switched model asked to run backward.
/// The number of states is not one of them (`solve_runs_a_chain_of_forty_states`), nor an
/// end time before the start for a smooth model (`solve_runs_a_smooth_model_backward`).
#[test]
fn unusable_solve_settings_are_input_errors() {
    let (_dir, path) = file(DROP);
    let ball = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/model-macros/examples/bouncing_ball.dsl"
    );
    let out = model(&["solve", ball, "--t0", "1", "--t-end", "0"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("runs forward in time only"), "{err}");
    for args in [
        (&["--t-end", "inf"][..], "time span [0, inf]"),
        (&["--t-end", "1", "--dt", "-0.1"], "dt = -0.1"),
        (&["--t-end", "1", "--rtol", "-1"], "-1"),
    ] {
        let (args, needle) = args;
        let mut all = vec!["solve", arg(&path)];
        all.extend_from_slice(args);
        let out = model(&all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
}

/// `--t-end` before `--t0`: the model integrated backward in time, every `--dt` down from
/// the start, on the closed form, and an event fired as the run proceeds (`x` from negative
/// to positive as `t` decreases is `:up`).
#[test]
fn solve_runs_a_smooth_model_backward() {
    let (_dir, path) = file(OSCILLATOR);
    let (x, v) = ((3.0f64).cos(), -3.0 * (3.0f64).sin());
    let (x, v) = (format!("x={x}"), format!("v={v}"));
    let (header, rows) = solved_csv(&[
        arg(&path),
        "--state",
        &x,
        "--state",
        &v,
        "--t0",
        "1",
        "--t-end",
        "0",
        "--dt",
        "0.25",
        "--rtol",
        "1e-11",
        "--atol",
        "1e-12",
    ]);
    assert_eq!(header, ["t", "x", "v", "e"]);
    let t: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    assert_eq!(t, [1.0, 0.75, 0.5, 0.25, 0.0]);
    for row in &rows {
        assert!((row[1] - (3.0 * row[0]).cos()).abs() < 1e-9, "{row:?}");
    }
    let out = model(&[
        "solve",
        arg(&path),
        "--state",
        &x,
        "--state",
        &v,
        "--t0",
        "1",
        "--t-end",
        "0",
        "--event",
        "x:up:stop",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("stopped by event `x`"), "{err}");
    let at = said_events(&err, "x");
    assert_eq!(at.len(), 1, "{err}");
    assert!((at[0] - std::f64::consts::PI / 6.0).abs() < 1e-8, "{err}");
}

const CHAIN: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/model-macros/examples/pendulum_chain.dsl"
);

/// `model solve` with `args` to standard output: the header and the rows.
fn solved_csv(args: &[&str]) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut all = vec!["solve"];
    all.extend(args);
    let text = ok(&all);
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

/// A model runs in exactly its own states: a chain of 20 links (40 states) keeps its energy.
#[test]
fn solve_runs_a_chain_of_forty_states() {
    let (header, rows) = solved_csv(&[
        CHAIN, "--state", "q1=0.5", "--state", "q7=-0.4", "--state", "q20=1", "--t-end", "0.5",
        "--dt", "0.05", "--rtol", "1e-10", "--atol", "1e-12",
    ]);
    assert_eq!(header.len(), 1 + 40 + 1, "{header:?}");
    assert_eq!((header[1].as_str(), header[40].as_str()), ("q1", "w20"));
    assert_eq!(rows.len(), 11);
    let energy: Vec<f64> = rows.iter().map(|r| r[41]).collect();
    // At rest: the potential alone, -g (20 cos 0.5 + 14 cos 0.4 + cos 1 + the 17 links at 0, 175 in all).
    let potential = -9.81
        * (20.0 * 0.5f64.cos() + 14.0 * 0.4f64.cos() + 1.0f64.cos() + 210.0 - 20.0 - 14.0 - 1.0);
    assert!(
        (energy[0] - potential).abs() < 1e-9 * potential.abs(),
        "{energy:?}"
    );
    let drift = energy
        .iter()
        .map(|e| (e - energy[0]).abs())
        .fold(0.0, f64::max);
    assert!(drift < 1e-8 * energy[0].abs(), "energy drift {drift:e}");
    assert!(rows.last().unwrap()[21..41].iter().any(|w| w.abs() > 0.1));
}

/// A model of three states at its closed form: a rotation and a decay.
#[test]
fn solve_runs_a_model_of_three_states() {
    let (_dir, path) = file(
        "mod three {
            params { w = 2, k = 0.5 }
            states { x, y, z }
            equations { der(x) = -w * y; der(y) = w * x; der(z) = -k * z; }
        }",
    );
    let (header, rows) = solved_csv(&[
        arg(&path),
        "--state",
        "x=1",
        "--state",
        "z=3",
        "--t-end",
        "2",
        "--dt",
        "0.5",
        "--rtol",
        "1e-12",
        "--atol",
        "1e-14",
    ]);
    assert_eq!(header, ["t", "x", "y", "z"]);
    assert_eq!(rows.len(), 5);
    for row in rows {
        let t = row[0];
        let exact = [(2.0 * t).cos(), (2.0 * t).sin(), 3.0 * (-0.5 * t).exp()];
        for (got, want) in row[1..].iter().zip(exact) {
            assert!((got - want).abs() < 1e-10, "t = {t}: {got} vs {want}");
        }
    }
}

/// The decay of the issue: `x = 2 e^-t`, `y = 3` from the values written on the states, in
/// every row; `--state` overrides one, the other keeps the file's. The shipped heavy top
/// starts where its file says, away from its singular point.
#[test]
fn solve_starts_at_the_initial_values_the_file_writes() {
    let (_dir, path) = file(
        "mod decay {
            params { k = 1.0 }
            states { x = 2.0, y = 3.0 }
            equations { der(x) = -k * x; der(y) = 0; }
        }",
    );
    let tight = ["--rtol", "1e-12", "--atol", "1e-14", "--dt", "0.25"];
    let mut args = vec!["solve", arg(&path), "--t-end", "1"];
    args.extend(tight);
    let (header, rows) = read_csv(&ok(&args), 0);
    assert_eq!(header, "t,x,y");
    assert_eq!(rows.len(), 5);
    for row in &rows {
        assert!((row[1] - 2.0 * (-row[0]).exp()).abs() < 1e-11, "{row:?}");
        assert_eq!(row[2], 3.0);
    }
    args.extend(["--state", "x=1"]);
    let (_, rows) = read_csv(&ok(&args), 0);
    let last = rows.last().unwrap();
    assert!((last[1] - (-1.0f64).exp()).abs() < 1e-11, "{last:?}");
    assert_eq!(last[2], 3.0);
    let eval: Value = serde_json::from_str(&ok(&["eval", arg(&path)])).unwrap();
    assert_eq!(eval["derivatives"]["der(x)"], -2.0);
    let (_, rows) = read_csv(&ok(&["solve", HEAVY_TOP, "--t-end", "0.1"]), 0);
    assert_eq!(rows[0][2], 0.3);
    assert_eq!(rows[0][6], 150.0);
}
