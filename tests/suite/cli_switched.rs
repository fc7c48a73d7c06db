//! `eulerdisk model show|solve` on switched DSL files, as a user runs them: the example ball,
//! belt and block shown and solved from their files, every event in `events.csv` at its
//! closed-form time, an accumulation said on the terminal, a chatter that no rule resolves
//! named with the work done, and mistakes in the new constructs located.

use crate::cli_model::{arg, file, model};
use std::path::Path;

fn example(name: &str) -> String {
    format!(
        "{}/model-macros/examples/{name}.dsl",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// Runs `model solve` on `file` into a temporary folder: (trajectory rows, events, stderr).
fn solve(file: &str, extra: &[&str]) -> (Vec<Vec<String>>, Vec<(String, f64)>, String) {
    let dir = tempfile::tempdir().unwrap();
    let traj = dir.path().join("traj.csv");
    let events = dir.path().join("events.csv");
    let mut args = vec!["solve", file, "--out", arg(&traj), "--events", arg(&events)];
    args.extend_from_slice(extra);
    let out = model(&args);
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    // A run ended by a `stop` exits with 3 ("stopped early"), one to its end with 0.
    let expected = if stderr.contains("stopped by event") {
        3
    } else {
        0
    };
    assert_eq!(out.status.code(), Some(expected), "{args:?}: {stderr}");
    let table = |path: &Path| -> Vec<Vec<String>> {
        (std::fs::read_to_string(path).unwrap().lines())
            .map(|line| line.split(',').map(str::to_string).collect())
            .collect()
    };
    // The trajectory without its `mode` column (checked on its own below).
    let rows = (table(&traj).into_iter())
        .map(|mut row| {
            row.remove(1);
            row
        })
        .collect();
    // Each event once, at the state before it (not its `after` row, nor the `stop` row).
    let events = (table(&events).into_iter().skip(1))
        .filter(|row| row[1] != "after" && row[0] != "stop")
        .map(|row| (row[0].clone(), row[2].parse().unwrap()))
        .collect();
    (rows, events, stderr)
}

#[test]
fn the_ball_from_its_file_bounces_at_the_closed_form_times_and_rests() {
    let (rows, events, stderr) = solve(
        &example("bouncing_ball"),
        &[
            "--t-end",
            "6",
            "--dt",
            "0.01",
            "--integrator",
            "dop853",
            "--rtol",
            "1e-10",
            "--atol",
            "1e-12",
        ],
    );
    assert_eq!(rows[0], ["t", "h", "v", "energy"]);
    let (g, e, h0) = (9.81f64, 0.8f64, 1.0f64);
    let v1 = (2.0 * g * h0).sqrt();
    let mut expected = (2.0 * h0 / g).sqrt();
    let impacts: Vec<f64> = events
        .iter()
        .filter(|(n, _)| n == "impact")
        .map(|(_, t)| *t)
        .collect();
    assert!(impacts.len() > 50, "{events:?}");
    for (k, t) in impacts.iter().enumerate() {
        assert!(
            (t - expected).abs() < 1e-9,
            "impact {}: {t} vs {expected}",
            k + 1
        );
        expected += 2.0 * e.powi(k as i32 + 1) * v1 / g;
    }
    let t_inf = (2.0 * h0 / g).sqrt() + 2.0 * e * v1 / (g * (1.0 - e));
    let (name, rest) = events.last().unwrap();
    assert_eq!(name, "impact accumulates");
    assert!((rest - t_inf).abs() < 1e-9, "{rest} vs {t_inf}");
    assert!(
        stderr.contains("the firings of `impact` accumulate at t = 4.0637"),
        "{stderr}"
    );
    assert!(stderr.contains("the run goes on in `resting`"), "{stderr}");
    // Never through the floor; at rest on it to the end.
    for row in &rows[1..] {
        let (t, h): (f64, f64) = (row[0].parse().unwrap(), row[1].parse().unwrap());
        assert!(h >= -1e-12, "h = {h} at t = {t}");
        if t > t_inf + 1e-6 {
            assert_eq!((row[1].as_str(), row[2].as_str()), ("0", "0"), "at t = {t}");
        }
    }
    assert_eq!(rows.last().unwrap()[0], "6");
}

#[test]
fn the_belt_and_the_block_from_their_files_name_every_event() {
    let tight = [
        "--t-end",
        "5",
        "--integrator",
        "dop853",
        "--rtol",
        "1e-11",
        "--atol",
        "1e-13",
    ];
    let (_, events, _) = solve(&example("stick_slip"), &tight);
    let names: Vec<&str> = events.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["slip_back", "stick", "slip_back", "stick"]);
    let t1 = 0.6 * 9.81 / (10.0 * 0.5);
    assert!((events[0].1 - t1).abs() < 1e-9, "{events:?}");
    let omega = 10f64.sqrt();
    let c = 0.2 * 9.81 / 10.0;
    let slipping = 2.0 * (std::f64::consts::PI - (c * omega / 0.5).atan()) / omega;
    assert!((events[1].1 - t1 - slipping).abs() < 1e-9, "{events:?}");

    let (_, events, stderr) = solve(&example("rocking_block"), &tight);
    assert!(
        events.iter().filter(|(n, _)| n == "impact").count() > 30,
        "{events:?}"
    );
    assert_eq!(events.last().unwrap().0, "impact accumulates");
    assert!(stderr.contains("the run goes on in `standing`"), "{stderr}");
}

/// The shipped rocking block, and variants of it, come to rest at the default tolerances (and
/// at a loose rtol) where the closed form says. Linearised, a rock that starts at `theta = 0`
/// with speed `w` returns after `(2/p) atanh(w / (p alpha))` with speed `w`; the first impact,
/// from rest at `theta0`, comes at `acosh(alpha / (alpha - theta0)) / p` with speed
/// `p sqrt(alpha^2 - (alpha - theta0)^2)`, and each impact keeps `r` of the speed. Before the
/// accumulation rule took the run's span into account, the shipped file at its defaults
/// rocked on for a million impacts (its ratios turn to noise below 1e-8 s, a 1e-9 s tail was
/// never reached): a low work bound makes that a failure here, not a hang.
#[test]
fn the_rocking_block_comes_to_rest_where_the_closed_form_says() {
    let (p, alpha) = (2.0f64, 0.2f64);
    for (r, theta0, rtol) in [
        (0.7f64, 0.1f64, "1e-8"),
        (0.7, 0.1, "1e-6"),
        (0.5, 0.05, "1e-6"),
        (0.85, 0.15, "1e-8"),
        (0.85, 0.15, "1e-11"),
        (0.9, 0.1, "1e-7"),
    ] {
        let t1 = (alpha / (alpha - theta0)).acosh() / p;
        let w1 = p * (alpha * alpha - (alpha - theta0).powi(2)).sqrt();
        let rests = t1
            + (1..2000)
                .map(|k| 2.0 / p * (w1 * r.powi(k) / (p * alpha)).atanh())
                .sum::<f64>();
        let (r_arg, theta_arg) = (format!("r={r}"), format!("theta={theta0}"));
        let args = [
            "--t-end",
            "10",
            "--rtol",
            rtol,
            "--set",
            &r_arg,
            "--state",
            &theta_arg,
            "--max-steps-per-s",
            "20000",
        ];
        let (rows, events, stderr) = solve(&example("rocking_block"), &args);
        let (name, t) = events.last().unwrap();
        assert_eq!(name, "impact accumulates", "r = {r}, rtol {rtol}: {stderr}");
        // The event times carry the tolerance's error, summed over the impacts; the
        // accumulation point is extrapolated from ratios that the absolute tolerance
        // (1e-10 on speeds of 1e-7) blurs, within the rule's tail, 1e-7 of the 10 s span.
        let rtol: f64 = rtol.parse().unwrap();
        let bound = 1e2 * rtol * rests + 1e-6;
        assert!(
            (t - rests).abs() < bound,
            "r = {r}, rtol {rtol}: {t} vs {rests}"
        );
        assert_eq!(rows.last().unwrap()[0], "10", "r = {r}");
    }
}

#[test]
fn a_terminal_event_and_an_unresolved_accumulation_end_the_run_by_name() {
    let (_, events, stderr) = solve(
        &example("rocking_block"),
        &["--t-end", "5", "--state", "omega=0.3"],
    );
    assert_eq!(events.last().unwrap().0, "overturns", "{events:?}");
    assert!(stderr.contains("stopped by event `overturns`"), "{stderr}");
    let (_dir, path) = file(
        "mod ball { params { g = 9.81 } states { h = 1, v }
            equations { der(h) = v; der(v) = -g; }
            when impact: h < 0 { v = -0.5 * v; } }",
    );
    let (rows, events, stderr) = solve(arg(&path), &["--t-end", "10"]);
    assert_eq!(events.last().unwrap().0, "impact accumulates", "{events:?}");
    assert!(stderr.contains("the run stops there"), "{stderr}");
    assert!(
        stderr.contains("stopped by event `impact accumulates`"),
        "{stderr}"
    );
    let t_end: f64 = rows.last().unwrap()[0].parse().unwrap();
    assert!(t_end < 2.0, "{t_end}");
}

#[test]
fn a_chatter_no_rule_resolves_fails_naming_the_modes_and_the_work() {
    // A relay: each mode drives x back through zero at once.
    let (_dir, path) = file(
        "mod relay { states { x = 1 }
            mode down { equations { der(x) = -1; } when low: x < 0 -> up; }
            mode up { equations { der(x) = 1; } when high: x > 0 -> down; } }",
    );
    let out = model(&["solve", arg(&path), "--t-end", "3"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("chattering at t = 1"), "{stderr}");
    assert!(stderr.contains("between modes `down`, `up`"), "{stderr}");
    assert!(stderr.contains("after 3 steps and 100 events"), "{stderr}");
}

#[test]
fn show_prints_the_modes_and_events_in_markdown_and_latex() {
    let out = model(&["show", &example("stick_slip")]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    assert!(
        text.starts_with("# `stick_slip`: modes and events"),
        "{text}"
    );
    assert!(text.contains("## Mode `stuck`"), "{text}");
    assert!(
        text.contains(
            "| `slip_back` | `x*k - mu_s*m*g` crosses 0 upwards | `s := -1`, go to `slipping` |"
        ),
        "{text}"
    );
    assert!(
        text.contains("# `slipping`: the solved equations"),
        "{text}"
    );
    let out = model(&["show", &example("bouncing_ball"), "--format", "latex"]);
    let latex = String::from_utf8_lossy(&out.stdout);
    assert!(latex.starts_with("\\begin{align*}"), "{latex}");
    assert!(
        latex.contains("h &\\downarrow 0 \\;\\Rightarrow\\; v^{+} = "),
        "{latex}"
    );
}

#[test]
fn a_mistake_in_a_switched_file_is_located_and_exits_2() {
    let (_dir, path) = file(
        "mod m { states { h, v }
            mode a { equations { der(h) = v; der(v) = -1; } when hit: h < 0 -> nowhere; } }",
    );
    let out = model(&["solve", arg(&path), "--t-end", "1"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("model.dsl:2:80: unknown mode `nowhere`: the modes are `a`"),
        "{stderr}"
    );
    let out = model(&[
        "solve",
        &example("bouncing_ball"),
        "--t-end",
        "1",
        "--event",
        "h",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("declares its events in the file"));
}

#[test]
fn a_file_that_calls_rust_is_refused_under_the_function_s_name() {
    let (_dir, path) = file(
        "mod m { states { h, v } equations { der(h) = v; der(v) = -1; }
            when hit: h < 0 -> m | stop by land; }",
    );
    for args in [
        vec!["solve", arg(&path), "--t-end", "1"],
        vec!["show", arg(&path)],
    ] {
        let command = args[0];
        let out = model(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{command}: {stderr}");
        assert!(
            stderr.contains("model.dsl:2:44: `land` is a Rust function (`by land`)"),
            "{command}: {stderr}"
        );
        assert!(stderr.contains("runs only compiled"), "{stderr}");
    }
}

#[test]
fn show_prints_a_declared_time_scale_under_its_mode() {
    let (_dir, path) = file(
        "mod m { params { c = 0.1 } states { h, v } equations { der(h) = v; der(v) = -1; }
            time_scale = h^2 / (h^2 + c);
            when hit: h < 0 { v = -v; } }",
    );
    let out = model(&["show", arg(&path)]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("Time scale (regularised time, `dt = s dτ`): `s = h^2/(h^2 + c)`."),
        "{stdout}"
    );
}
