//! The limits of a run, hit from the command line: each names itself and the key that moves
//! it, a run that fails on one exits 1 with its work and complete files, and a value no run
//! can use is refused before anything is written.

use std::path::Path;

use super::cli_run::{csv, rejected, run};

/// A disk of radius 1e-12 m started at θ = 3 rad: its time scale `sqrt(a/g)` is 3e-7 s and it
/// takes about 2e8 steps per simulated second; the one second asked for would run for hours.
const TINY_DISK: [&str; 4] = ["--set", "disk.a=1e-12", "--set", "initial.theta=3.0"];

/// Runs the tiny disk under `max_steps_per_s` into `out`, expecting the work bound.
fn over_the_work_bound(out: &Path, max_steps_per_s: f64) -> serde_json::Value {
    let bound = format!("solver.max_steps_per_s={max_steps_per_s}");
    let mut args = TINY_DISK.to_vec();
    args.extend(["--t-end", "1", "--quiet", "--no-figures", "--set", &bound]);
    args.extend(["--out", out.to_str().unwrap()]);
    let o = run(&args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("the work bound was reached"), "{err}");
    assert!(err.contains("raise `solver.max_steps_per_s`"), "{err}");
    let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// The run fails at the first step over `rate × (t + 0.1 s)`: a tenth of the rate's steps
/// were taken (the simulated time is a few µs, far below the allowance), the work is in
/// `summary.json`, and the files end where the run did, every value finite.
#[test]
fn a_collapsing_step_size_meets_the_work_bound_said_by_its_key() {
    let dir = tempfile::tempdir().unwrap();
    let mut steps_at = Vec::new();
    for rate in [1e5, 2e5] {
        let out = dir.path().join(format!("out-{rate}"));
        let summary = over_the_work_bound(&out, rate);
        assert_eq!(summary["stop_reason"], "error");
        let detail = summary["stop_detail"].as_str().unwrap();
        assert!(detail.contains("solver.max_steps_per_s"), "{detail}");
        let steps = summary["steps"].as_u64().unwrap() as f64;
        let t_fail = summary["t_end"].as_f64().unwrap();
        assert!(t_fail > 0.0 && t_fail < 1e-3, "{t_fail}");
        // The budget at the failure, in steps; the driver stops at the first step over it.
        let budget = rate * (t_fail + 0.1);
        assert!(
            steps > 0.1 * rate && steps < budget * 1.01 + 10.0,
            "{steps} vs {budget}"
        );
        assert!(summary["rhs_evals"].as_u64().unwrap() as f64 > steps);
        // Where it got: the end of its last accepted step, by the state names.
        let last = &summary["last_state"];
        let t_last = last["t"].as_f64().unwrap();
        assert!(t_last > 0.0 && t_last <= t_fail, "{t_last} {t_fail}");
        let state = last["state"].as_object().unwrap();
        assert_eq!(state.len(), 12, "{state:?}");
        assert!(state
            .values()
            .all(|v| v.as_f64().is_some_and(f64::is_finite)));
        steps_at.push(steps);
        for name in ["trajectory.csv", "extrema.csv"] {
            let (header, rows) = csv(&out.join(name));
            for row in &rows {
                assert_eq!(row.len(), header.len(), "{name}: {row:?}");
            }
        }
        for name in ["trajectory.csv", "events.csv", "extrema.csv"] {
            let text = std::fs::read_to_string(out.join(name)).unwrap();
            assert!(!text.to_lowercase().contains("nan"), "{name}");
        }
        // The stop is the last event, dated when the bound was reached: after every decision
        // the run made, and after the trajectory's last row.
        let (_, events) = csv(&out.join("events.csv"));
        let (stop, decisions) = events.split_last().unwrap();
        assert_eq!(stop[2..4], ["stop", "error"]);
        let t_stop: f64 = stop[0].parse().unwrap();
        let t_decided: f64 = decisions.last().unwrap()[0].parse().unwrap();
        assert!(t_stop >= t_decided, "{t_stop} < {t_decided}");
        assert_eq!(t_stop, t_fail);
        let (_, rows) = csv(&out.join("trajectory.csv"));
        assert!(t_stop >= rows.last().unwrap()[0].parse::<f64>().unwrap());
    }
    // Twice the rate, twice the steps before the bound.
    let ratio = steps_at[1] / steps_at[0];
    assert!((ratio - 2.0).abs() < 0.05, "{steps_at:?}");
}

#[test]
fn a_work_bound_no_run_can_meet_is_refused_by_its_key() {
    for value in ["0", "-1", "nan", "inf"] {
        rejected(
            &["--set", &format!("solver.max_steps_per_s={value}")],
            "solver.max_steps_per_s",
        );
    }
}

/// `friction.mu_st = 1.8e308` (the largest finite number): static friction never gives way.
/// The friction guard `T − mu_st N` overflowed to −inf at the first step and the run failed;
/// the ν figure's reference line at 1.8e308 hung the plotting library. The run now rolls to
/// its end, as with any coefficient friction never reaches, with every figure drawn.
#[test]
fn the_largest_static_friction_rolls_to_the_end() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = run(&[
        "--set",
        "friction.mu_st=1.7976931348623157e308",
        "--t-end",
        "5",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    let (_, events) = csv(&out.join("events.csv"));
    let modes: Vec<&str> = events.iter().map(|e| e[2].as_str()).collect();
    assert_eq!(modes, ["stop"], "it never slides: {events:?}");
    let (header, rows) = csv(&out.join("trajectory.csv"));
    assert_eq!(rows.len(), 5001);
    assert!(rows
        .iter()
        .all(|r| r[1] == "rolling" && r.len() == header.len()));
    for stem in eulerdisk::FIGURE_STEMS {
        assert!(out.join(format!("{stem}.png")).is_file(), "{stem}");
    }
}

/// One Ctrl-C while the figures are drawn: the figures being drawn are finished, no other is
/// started, and the run exits at once as interrupted with its data files and `summary.json`
/// complete; the summary lists the figures left undrawn, and every figure present is whole.
#[test]
fn one_ctrl_c_while_drawing_stops_the_figures_and_keeps_the_files() {
    use std::io::{BufRead, BufReader};
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};

    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut child = Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .args(["run", "--set", "friction.mu_st=1.7976931348623157e308"])
        .args(["--out", out.to_str().unwrap()])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
    let mut said = Vec::new();
    for line in lines.by_ref() {
        let line = line.unwrap();
        let drawing = line.contains("drawing the figures");
        said.push(line);
        if drawing {
            break;
        }
    }
    let sent = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let interrupted = Instant::now();
    said.extend(lines.map(|l| l.unwrap()));
    let status = child.wait().unwrap();
    let said = said.join("\n");
    assert!(interrupted.elapsed() < Duration::from_secs(5), "{said}");
    assert_eq!(status.code(), Some(130), "{said}");
    assert!(
        said.contains("interrupted while drawing the figures"),
        "{said}"
    );

    let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
    let summary: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(summary["stop_reason"], "end_time");
    let not_drawn: Vec<&str> = summary["figures_not_drawn"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert!(
        !not_drawn.is_empty(),
        "the interrupt came after every figure"
    );
    for stem in eulerdisk::FIGURE_STEMS {
        let present = ["png", "svg"].map(|ext| out.join(format!("{stem}.{ext}")).is_file());
        if not_drawn.contains(&stem) {
            assert_eq!(present, [false, false], "{stem}");
        } else {
            assert_eq!(present, [true, true], "{stem}");
            let svg = std::fs::read_to_string(out.join(format!("{stem}.svg"))).unwrap();
            assert!(
                svg.trim_end().ends_with("</svg>"),
                "{stem}.svg is cut short"
            );
        }
    }
    let (_, rows) = csv(&out.join("trajectory.csv"));
    assert_eq!(rows.len(), 100_001);
    let (_, events) = csv(&out.join("events.csv"));
    assert_eq!(events.last().unwrap()[2..4], ["stop", "end_time"]);
    let names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        names.iter().all(|n| !n.starts_with(".partial-")),
        "{names:?}"
    );
}

/// A disk rolling under friction that never gives way (`μ_st = 1e300`), spun fast enough to
/// leave the floor while rolling: at the located loss of contact `N` is zero to round-off and
/// `T/N` was `−9.8e15` (or `0/0`, NaN). ν there is the law's bound `μ_st`; no column of any
/// file holds a NaN or an infinity.
#[test]
fn a_rolling_loss_of_contact_writes_only_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = run(&[
        "--set",
        "friction.mu_st=1e300",
        "--set",
        "initial.Omega_x=100",
        "--t-end",
        "2",
        "--quiet",
        "--no-figures",
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(3), "{err}");
    assert!(
        err.contains("contact_lost") && err.contains("while rolling"),
        "{err}"
    );
    let (header, rows) = csv(&out.join("trajectory.csv"));
    let last = rows.last().unwrap();
    assert_eq!(last[1], "rolling");
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let normal: f64 = last[column("N_N")].parse().unwrap();
    assert!(normal.abs() < 1e-12, "{normal}");
    assert_eq!(last[column("nu_ratio")], "1e300");
    for name in ["trajectory.csv", "events.csv", "extrema.csv"] {
        let (header, rows) = csv(&out.join(name));
        for row in &rows {
            for (cell, name) in row.iter().zip(&header) {
                let lower = cell.to_lowercase();
                assert!(
                    !lower.contains("nan") && !lower.contains("inf"),
                    "{name}: {row:?}"
                );
            }
        }
    }
}

/// `initial.V_Y = 1e300` gives an infinite energy: a scene error naming the key, for the
/// generated and the reference models alike (the reference ran and wrote `energy_J = inf`).
#[test]
fn a_start_with_an_infinite_energy_is_refused_by_its_key() {
    for backend in [&[][..], &["--reference"][..]] {
        let mut args = vec!["--set", "initial.V_Y=1e300"];
        args.extend_from_slice(backend);
        crate::cli_run::rejected(&args, "initial.V_Y");
    }
}
