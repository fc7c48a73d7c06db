//! `model solve` runs a model as its file says, or says why not: outputs read the discrete
//! values of their own time, a value that is not finite is an error, a run is bounded by the
//! work bound `run` has, a failed or interrupted run keeps what it computed (complete files
//! whose last event row says why), an accumulation has one time everywhere, and the files
//! carry the mode, the discrete values and the state on both sides of a reset.

use crate::cli_model::{arg, file, model};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The lines of a CSV file, each split at its commas (a quoted field holds none here but in
/// the `phase` of a `stop` row); none for a file that was not written.
fn lines(path: &Path) -> Vec<Vec<String>> {
    (std::fs::read_to_string(path).unwrap_or_default().lines())
        .map(|line| line.split(',').map(str::to_string).collect())
        .collect()
}

/// A table as lines of fields.
type Lines = Vec<Vec<String>>;

/// `model solve FILE ARGS --out traj.csv --events events.csv`: the exit code, the two
/// tables and standard error.
fn solve(text: &str, extra: &[&str]) -> (Option<i32>, Lines, Lines, String) {
    let (dir, path) = file(text);
    let traj = dir.path().join("traj.csv");
    let events = dir.path().join("events.csv");
    let mut args = vec![
        "solve",
        arg(&path),
        "--out",
        arg(&traj),
        "--events",
        arg(&events),
    ];
    args.extend_from_slice(extra);
    let out = model(&args);
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!stderr.contains("panicked"), "{stderr}");
    (out.status.code(), lines(&traj), lines(&events), stderr)
}

/// The column `name` of a table with a header, as numbers.
fn column(table: &[Vec<String>], name: &str) -> Vec<f64> {
    let k = table[0].iter().position(|c| c == name).unwrap();
    table[1..]
        .iter()
        .map(|row| row[k].parse().unwrap())
        .collect()
}

/// The case: `rate = der(x)` reads `d`, which an event sets to 2 at t = 0.5; every
/// row says the `d` of its own time (it said the end's, 2, everywhere).
#[test]
fn outputs_read_the_discrete_values_of_their_own_time() {
    let (code, traj, events, stderr) = solve(
        "mod step {
            discrete { d = 1 }
            states { x }
            equations { der(x) = d; }
            when step: t > 0.5 { d = 2; }
            outputs { rate = der(x); }
        }",
        &["--t-end", "1", "--dt", "0.1"],
    );
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(traj[0], ["t", "mode", "x", "d", "rate"]);
    let (t, d, rate) = (
        column(&traj, "t"),
        column(&traj, "d"),
        column(&traj, "rate"),
    );
    for k in 0..t.len() {
        // The sample at t = 0.5 is the one before the event there.
        let want = if t[k] <= 0.5 { 1.0 } else { 2.0 };
        assert_eq!((d[k], rate[k]), (want, want), "t = {}", t[k]);
    }
    assert!(traj[1..].iter().all(|row| row[1] == "step"), "{traj:?}");
    // The event's row before its reset reads d = 1, the one after d = 2.
    assert_eq!(events[0], ["event", "phase", "t", "mode", "x", "d", "rate"]);
    let (before, after) = (&events[1], &events[2]);
    assert_eq!((before[0].as_str(), before[1].as_str()), ("step", "before"));
    assert_eq!((after[0].as_str(), after[1].as_str()), ("step", "after"));
    assert_eq!((before[5].as_str(), before[6].as_str()), ("1", "1"));
    assert_eq!((after[5].as_str(), after[6].as_str()), ("2", "2"));
    let t_event: f64 = before[2].parse().unwrap();
    assert!((t_event - 0.5).abs() < 1e-9, "{t_event}");
}

/// The ball's first impact: the row before it has the falling velocity, the row after the
/// reset `v = -e v`.
#[test]
fn event_rows_hold_the_state_before_and_after_the_reset() {
    let (code, _, events, stderr) = solve(
        "mod ball { params { g = 9.81, e = 0.8 } states { h = 1, v }
            equations { der(h) = v; der(v) = -g; }
            when impact: h < 0 { v = -e * v; } }",
        &["--t-end", "0.5", "--rtol", "1e-12", "--atol", "1e-14"],
    );
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(events[0], ["event", "phase", "t", "mode", "h", "v"]);
    let v1 = -(2.0f64 * 9.81).sqrt();
    let v = |row: &Vec<String>| row[5].parse::<f64>().unwrap();
    // A model without modes runs in one, named after the model.
    assert_eq!(
        events[1][..4],
        ["impact", "before", events[1][2].as_str(), "ball"]
    );
    assert!((v(&events[1]) - v1).abs() < 1e-9, "{events:?}");
    assert_eq!(events[2][1], "after");
    assert!((v(&events[2]) + 0.8 * v1).abs() < 1e-9, "{events:?}");
    assert_eq!(events[1][2], events[2][2]);
    assert_eq!(
        events.last().unwrap()[..2],
        ["stop", "reached the end time"]
    );
}

/// `o = sqrt(x - 1)` at x = 0 is NaN: the error `model eval` gives, exit 1, not a NaN
/// written with exit 0.
#[test]
fn an_output_that_is_not_finite_is_an_error() {
    let text = "mod m { states { x } equations { der(x) = 0; } outputs { o = sqrt(x - 1); } }";
    let (code, traj, _, stderr) = solve(text, &["--t-end", "1"]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("at t = 0: `m`: o = NaN is not finite"),
        "{stderr}"
    );
    assert!(traj.is_empty(), "no NaN is written: {traj:?}");
    let (_dir, path) = file(text);
    let eval = model(&["eval", arg(&path)]);
    assert!(String::from_utf8_lossy(&eval.stderr).contains("`m`: o = NaN is not finite"));
}

/// A stiff decay under the default explicit method: the work bound ends it within seconds,
/// names `--max-steps-per-s` and suggests `rodas4`; the files hold what was computed, the
/// last event row saying why; under `rodas4` it runs to its end.
#[test]
fn a_stiff_model_meets_the_work_bound_and_keeps_what_it_computed() {
    let stiff = "mod stiff { states { x } equations { der(x) = 1 - 1e19 * x; } }";
    let started = Instant::now();
    let (code, traj, events, stderr) = solve(stiff, &["--t-end", "1"]);
    assert!(started.elapsed() < Duration::from_secs(60));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("the work bound was reached"), "{stderr}");
    assert!(stderr.contains("raise `--max-steps-per-s`"), "{stderr}");
    assert!(stderr.contains("`rodas4`"), "{stderr}");
    assert_eq!(traj[0], ["t", "x"]);
    assert!(traj.len() > 1000, "{}", traj.len());
    let last = events.last().unwrap().join(",");
    assert!(
        last.starts_with("stop,\"failed: the work bound was reached"),
        "{last}"
    );
    assert!(last.contains("raise `--max-steps-per-s`"), "{last}");
    assert!(
        stderr.contains("`stiff`: 100002 rows, 0 events, failed at t = "),
        "{stderr}"
    );
    let (code, traj, _, stderr) = solve(stiff, &["--t-end", "1", "--integrator", "rodas4"]);
    assert_eq!(code, Some(0), "{stderr}");
    let x = column(&traj, "x");
    assert!(x.last().unwrap().abs() < 1e-9, "{x:?}");
    // The bound is a setting: a low one stops an easy run too.
    let (code, _, _, stderr) = solve(
        "mod m { states { x } equations { der(x) = cos(100 * t); } }",
        &["--t-end", "10", "--max-steps-per-s", "10"],
    );
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("than `--max-steps-per-s` = "), "{stderr}");
    let (code, _, _, stderr) = solve(stiff, &["--t-end", "1", "--max-steps-per-s", "0"]);
    assert_eq!(code, Some(2), "{stderr}");
}

/// A run over its work bound whose steps went mostly to events (a bouncing ball whose
/// intervals the loose tolerances blur, with no accumulation rule): the message says so, not
/// that the model is stiff.
#[test]
fn a_run_spent_on_events_says_so_at_the_work_bound() {
    let ball = "mod ball { states { h = 1, v } equations { der(h) = v; der(v) = -9.81; }
        when impact: h < 0 { v = -0.9 * v; } }";
    let (code, _, _, stderr) = solve(ball, &["--t-end", "100", "--max-steps-per-s", "30"]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("events took most of the steps"), "{stderr}");
    assert!(!stderr.contains("stiff"), "{stderr}");
}

/// A Zeno ball without a rest rule: the accumulation's time is the same in its event row,
/// the `stop` row, the terminal's accumulation line and the summary.
#[test]
fn an_accumulation_has_one_time_everywhere() {
    let (code, _, events, stderr) = solve(
        "mod ball { params { g = 9.81, e = 0.8 } states { h = 1, v }
            equations { der(h) = v; der(v) = -g; }
            when impact: h < 0 { v = -e * v; } }",
        &["--t-end", "10"],
    );
    assert_eq!(code, Some(3), "{stderr}");
    let accumulated = &events[events.len() - 2];
    let stop = events.last().unwrap();
    assert_eq!(accumulated[..2], ["impact accumulates", "at"]);
    assert_eq!(stop[0], "stop");
    assert_eq!(stop[2], accumulated[2]);
    let t = &accumulated[2];
    assert!(
        stderr.contains(&format!("accumulate at t = {t}:")),
        "{stderr}"
    );
    assert!(
        stderr.contains(&format!(
            "stopped by event `impact accumulates` at t = {t},"
        )),
        "{stderr}"
    );
}

/// Ctrl-C stops `model solve` with exit 130 and complete files, the last event row saying
/// `interrupted` at the trajectory's last point.
#[test]
fn ctrl_c_keeps_what_model_solve_computed() {
    let (dir, path) =
        file("mod fast { states { x = 1, v } equations { der(x) = v; der(v) = -1e6 * x; } }");
    let traj = dir.path().join("traj.csv");
    let events = dir.path().join("events.csv");
    let child = Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .args(["model", "solve", arg(&path), "--t-end", "1e7"])
        .args(["--out", arg(&traj), "--events", arg(&events)])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let sent = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    let traj = lines(&traj);
    assert!(traj.len() > 10, "{}", traj.len());
    let last = events.as_path();
    let last = lines(last).pop().unwrap();
    assert_eq!(last[..2], ["stop", "interrupted"], "{last:?}");
    assert_eq!(last[2], traj.last().unwrap()[0]);
}

/// `-f parquet` writes the same tables as Parquet files (to files only).
#[cfg(feature = "parquet")]
#[test]
fn solve_writes_parquet() {
    let (dir, path) = file("mod m { states { x = 1 } equations { der(x) = -x; } }");
    let traj = dir.path().join("traj.parquet");
    let events = dir.path().join("events.parquet");
    let out = model(&[
        "solve",
        arg(&path),
        "--t-end",
        "1",
        "-f",
        "parquet",
        "--out",
        arg(&traj),
        "--events",
        arg(&events),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for file in [&traj, &events] {
        let bytes = std::fs::read(file).unwrap();
        assert!(bytes.starts_with(b"PAR1") && bytes.ends_with(b"PAR1"));
    }
    let out = model(&["solve", arg(&path), "--t-end", "1", "-f", "parquet"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("Parquet is written to files only"));
}
