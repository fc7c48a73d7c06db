//! `eulerdisk run` as a user runs it: a short run writes every file with the right columns
//! and no NaN; a bad scene writes nothing and names the key; Ctrl-C keeps what was complete.

use std::fs;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use equations::record::Quantity;
use eulerdisk::EVENTS_HEADER;

/// `eulerdisk run ARGS`, waited for.
pub(crate) fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .arg("run")
        .args(args)
        .output()
        .unwrap()
}

/// A CSV file's header and rows, split at commas.
pub(crate) fn csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (header, rows)
}

#[test]
fn short_run_writes_every_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = run(&["--t-end", "0.2", "--quiet", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));

    let (header, rows) = csv(&out.join("trajectory.csv"));
    let scene = eulerdisk::load_scene("tangent-toy", &[]).unwrap();
    let mut expected = vec!["t_s".to_string(), "mode".to_string()];
    expected.extend(scene.quantities.iter().map(|q| q.column()));
    assert_eq!(header, expected);
    assert_eq!(rows.len(), 201, "0.2 s at 1000 samples/s, both ends");
    for row in &rows {
        assert_eq!(row.len(), header.len());
        assert!(row[1] == "rolling" || row[1] == "sliding", "{row:?}");
        for v in row.iter().skip(2).chain([&row[0]]) {
            let x: f64 = v.parse().unwrap();
            assert!(x.is_finite(), "{row:?}");
        }
    }
    let theta = header
        .iter()
        .position(|h| *h == Quantity::Theta.column())
        .unwrap();
    assert_eq!(
        rows[0][theta].parse::<f64>().unwrap(),
        std::f64::consts::FRAC_PI_2 - 1.0
    );

    let (header, rows) = csv(&out.join("events.csv"));
    assert_eq!(header.join(","), EVENTS_HEADER);
    assert_eq!(rows[0][1..4], ["rolling", "sliding", "initial_friction"]);
    assert!((rows[0][4].parse::<f64>().unwrap() - 0.8355).abs() < 5e-4);
    let last = rows.last().unwrap();
    assert_eq!(last[2..4], ["stop", "end_time"]);
    assert_eq!(last[0], "0.2");
    for w in rows.windows(2) {
        let (a, b): (f64, f64) = (w[0][0].parse().unwrap(), w[1][0].parse().unwrap());
        assert!(a <= b, "events out of order");
        if w[1][2] != "stop" {
            assert_eq!(
                w[0][2], w[1][1],
                "mode after one event is the mode before the next"
            );
        }
    }

    let summary: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["start_mode"], "sliding");
    assert_eq!(summary["stop_reason"], "end_time");
    assert_eq!(summary["t_end"], 0.2);
    assert_eq!(
        summary["nu_sliding"]
            .as_f64()
            .map(|v| (v - 0.115).abs() < 1e-12),
        Some(true)
    );
    for stem in [
        "fig01a_theta",
        "fig01b_theta",
        "fig02_theta_envelope",
        "fig03a_theta_dot",
        "fig03b_theta_dot",
        "fig04_theta_dot_over_psi_dot",
        "fig05a_nu",
        "fig05b_nu",
        "fig06a_slip_speed",
        "fig06b_slip_speed",
        "fig07_slip_speed_envelope",
        "fig08a_normal_force",
        "fig08b_normal_force",
        "fig09_normal_force_vs_theta",
        "fig10_normal_force_last_second",
    ] {
        let png = fs::read(out.join(format!("{stem}.png"))).unwrap();
        assert_eq!(&png[1..4], b"PNG", "{stem}");
        let svg = fs::read_to_string(out.join(format!("{stem}.svg"))).unwrap();
        assert!(svg.contains("<svg") && svg.contains("Fig. "), "{stem}");
    }
    let leftovers: Vec<_> = fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".partial"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

/// `eulerdisk run ARGS` exits 2 naming `key`, and writes nothing.
pub(crate) fn rejected(args: &[&str], key: &str) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut all = args.to_vec();
    all.extend(["--quiet", "--out", out.to_str().unwrap()]);
    let o = run(&all);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.contains(key), "{key} not named: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!out.exists(), "a rejected scene must write nothing");
}

#[test]
fn bad_scenes_write_nothing_and_name_the_key() {
    rejected(&["--t-end", "-1"], "run.t_end");
    rejected(&["--rtol", "1e-20"], "solver.rtol");
    rejected(&["--atol", "0"], "solver.atol");
    rejected(&["--set", "solver.integrator=euler"], "solver.integrator");
    // The flag's values are checked, and listed, by the command line itself.
    rejected(&["--integrator", "euler"], "dopri5, dop853, rodas4");
    rejected(&["--set", "disk.mass=1"], "disk.mass");
    rejected(&["--set", "friction.mu_st=0.01"], "friction.mu_st");
    rejected(&["--set", "initial.theta=0"], "initial.theta");
    rejected(&["--set", "initial.Z=1"], "initial.Z");
    rejected(&["--set", "disk.a=nan"], "disk.a");
    rejected(&["--set", "nodot=1"], "nodot");
    rejected(&["no-such-scene"], "no-such-scene");
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.toml");
    let text = include_str!("../../scenes/tangent-toy.toml")
        .replace("mu_st = 0.2", "mu_st = 0.2\nmu_s = 1");
    fs::write(&file, text).unwrap();
    rejected(&[file.to_str().unwrap()], "friction.mu_s");
}

#[test]
fn every_integrator_finds_the_same_first_transitions() {
    let dir = tempfile::tempdir().unwrap();
    let times = |integrator: &str| -> Vec<f64> {
        let out = dir.path().join(integrator);
        let o = run(&[
            "--t-end",
            "0.3",
            "--quiet",
            "--no-figures",
            "--integrator",
            integrator,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let (_, rows) = csv(&out.join("events.csv"));
        rows.iter()
            .filter(|r| r[2] != "stop")
            .map(|r| r[0].parse().unwrap())
            .collect()
    };
    let reference = times("dop853");
    assert!(reference.len() >= 3, "{reference:?}");
    for integrator in ["dopri5", "rodas4"] {
        let t = times(integrator);
        assert_eq!(t.len(), reference.len(), "{integrator}: {t:?}");
        for (a, b) in t.iter().zip(&reference) {
            // rtol 1e-8: the transition times agree to ~1e-8 s (BENCHMARKS.md §2).
            assert!((a - b).abs() < 1e-6, "{integrator}: {a} vs {b}");
        }
    }
}

#[test]
fn forbidden_mode_stops_the_run_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = run(&[
        "--t-end",
        "0.3",
        "--quiet",
        "--no-figures",
        "--set",
        "modes.allowed=[\"sliding\"]",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let (_, rows) = csv(&out.join("events.csv"));
    let last = rows.last().unwrap();
    assert_eq!(
        last[1..4],
        ["rolling", "stop", "mode_not_allowed"],
        "{last:?}"
    );
    // The reason is on the terminal and in the summary, not only in the last row of events.csv.
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("mode_not_allowed") && stderr.contains("modes.allowed"),
        "{stderr}"
    );
    let summary = read_summary(&out);
    assert_eq!(summary["stop_reason"], "mode_not_allowed");
    let detail = summary["stop_detail"].as_str().unwrap();
    assert!(
        detail.contains("entered rolling") && detail.contains("modes.allowed"),
        "{detail}"
    );
    // The simulation stopped itself at the forbidden transition and reports its work up to
    // there.
    assert!(
        summary["steps"].as_u64().is_some_and(|n| n > 0),
        "{summary}"
    );
    assert!(summary["rhs_evals"].as_u64().is_some_and(|n| n > 0));
    assert!(summary["not_computed"].get("steps").is_none());
    assert!((summary["t_end"].as_f64().unwrap() - 0.0722).abs() < 1e-4);
}

fn read_summary(out: &Path) -> serde_json::Value {
    serde_json::from_str(&fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn the_summary_records_how_it_was_produced_and_a_rerun_leaves_no_stale_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let out_s = out.to_str().unwrap();
    let o = run(&[
        "--t-end",
        "0.1",
        "--rtol",
        "1e-9",
        "--set",
        "solver.guard_checks=exact:4",
        "--quiet",
        "--out",
        out_s,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary = read_summary(&out);
    let by = &summary["produced_by"];
    assert!(
        by["program"].as_str().unwrap().starts_with("eulerdisk "),
        "{by}"
    );
    assert!(!by["git_revision"].as_str().unwrap().is_empty(), "{by}");
    // The engine that ran, named by the crate that holds it: the main job's run of the paper's
    // scene goes through the DSL's mode graph (`equations::simulate_graph`) unless asked for
    // the hand-written system.
    assert_eq!(by["engine"], equations::GRAPH_ENGINE);
    assert_eq!(by["engine"], "dsl mode graph");
    let hand = dir.path().join("hand-written");
    let h = run(&[
        "--t-end",
        "0.1",
        "--engine",
        "hand-written",
        "--no-figures",
        "--quiet",
        "--out",
        hand.to_str().unwrap(),
    ]);
    assert!(h.status.success(), "{}", String::from_utf8_lossy(&h.stderr));
    let produced_by = &read_summary(&hand)["produced_by"];
    assert_eq!(produced_by["engine"], equations::ENGINE);
    assert_eq!(produced_by["engine"], "hand-written hybrid system");
    assert_eq!(by["scene"], "tangent-toy");
    assert_eq!(by["scene_file"], "built-in scenes/tangent-toy.toml");
    let overrides: Vec<&str> = by["overrides"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(overrides.len(), 3, "{overrides:?}");
    assert!(overrides[0].starts_with("run.t_end=") && overrides[1].starts_with("solver.rtol="));
    assert_eq!(overrides[2], "solver.guard_checks=\"exact:4\"");
    let solver = &by["settings"]["solver"];
    assert_eq!(solver["rtol"], 1e-9);
    assert_eq!(solver["atol"], 1e-10);
    assert_eq!(solver["guard_checks"], "exact:4");
    for key in ["integrator", "error_norm", "step_control"] {
        assert!(solver[key].is_string(), "{solver}");
    }
    assert!(by["derived"]["stick_threshold"].as_f64().unwrap() > 0.0);
    assert_eq!(summary["compared_with_paper"], true);
    let figures = names_in(&out)
        .iter()
        .filter(|n| n.starts_with("fig"))
        .count();
    assert_eq!(figures, 30);

    // Rerun another scene without figures into the same directory, beside a file of the user's.
    fs::write(out.join("notes.txt"), "mine").unwrap();
    let o = run(&[
        "pure-rolling",
        "--t-end",
        "0.1",
        "--quiet",
        "--no-figures",
        "--out",
        out_s,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        names_in(&out),
        [
            "events.csv",
            "extrema.csv",
            "notes.txt",
            "summary.json",
            "trajectory.csv"
        ],
        "the first run's figures are gone, the user's file stays"
    );
    let summary = read_summary(&out);
    assert_eq!(summary["produced_by"]["scene"], "pure-rolling");
    assert_eq!(summary["produced_by"]["overrides"][0], "run.t_end=0.1");
    // Not the paper's scene: no paper column.
    assert_eq!(summary["compared_with_paper"], false);
}

#[test]
fn quiet_says_it_hides_the_summary_too() {
    let o = Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .args(["run", "--help"])
        .output()
        .unwrap();
    let help = String::from_utf8_lossy(&o.stdout);
    let quiet = help
        .lines()
        .skip_while(|l| !l.contains("--quiet"))
        .take(3)
        .collect::<String>();
    assert!(quiet.contains("summary"), "{help}");
}

#[test]
fn ctrl_c_keeps_what_was_complete() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let child = Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .args([
            "run",
            "--quiet",
            "--no-figures",
            "--rtol",
            "1e-13",
            "--atol",
            "1e-15",
        ])
        .args(["--out", out.to_str().unwrap()])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The output directory appears once the interrupt handler is installed and the run has
    // started; interrupt a little later.
    let waiting = Instant::now();
    while !out.exists() && waiting.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(500));
    let sent = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let start = Instant::now();
    let o = child.wait_with_output().unwrap();
    assert!(start.elapsed() < Duration::from_secs(60));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(130), "{err}");
    assert!(err.contains("interrupted"), "{err}");
    let (_, rows) = csv(&out.join("events.csv"));
    let last = rows.last().unwrap();
    assert_eq!(last[2..4], ["stop", "interrupted"], "{last:?}");
    let t_stop: f64 = last[0].parse().unwrap();
    assert!(t_stop > 0.0 && t_stop < 100.0, "{t_stop}");
    let (_, traj) = csv(&out.join("trajectory.csv"));
    let t_last: f64 = traj.last().unwrap()[0].parse().unwrap();
    assert!(
        (t_last - t_stop).abs() < 1e-9,
        "trajectory ends where the run stopped"
    );
    let summary = fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(
        summary.contains("\"stop_reason\": \"interrupted\""),
        "{summary}"
    );
}

/// SIGTERM (what a service manager or `timeout` sends) stops the run as Ctrl-C does: the
/// files are completed and renamed, none is left under its temporary `.partial-*` name.
#[test]
fn a_termination_signal_keeps_what_was_complete() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let child = Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .args(["run", "--quiet", "--rtol", "1e-13", "--atol", "1e-15"])
        .args(["--out", out.to_str().unwrap()])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let waiting = Instant::now();
    while !out.exists() && waiting.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(500));
    let sent = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(130), "{err}");
    let names: Vec<String> = fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        names.iter().all(|n| !n.starts_with(".partial-")),
        "{names:?}"
    );
    let summary = fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"stop_reason\": \"interrupted\""));
}

/// The paper's slip reading loses contact while sliding at t = 18.159 s, a run stopped early by
/// the physics (exit code 3, distinct from a run to the end and from a failure). At
/// the located instant N is zero to round-off, and T/N of the computed forces was 0/0 (NaN) or
/// −μ_d; ν is the friction law's μ_d on every sliding row, the last one included.
#[test]
fn the_friction_ratio_at_contact_loss_is_the_laws() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .args(["run", "--quiet", "--no-figures", "--t-end", "20"])
        .args([
            "--set",
            "run.slip_sign=paper",
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(3), "{err}");
    assert!(err.contains("contact_lost"), "{err}");
    let (header, rows) = csv(&out.join("trajectory.csv"));
    let nu = header.iter().position(|h| h == "nu_ratio").unwrap();
    for row in rows.iter().filter(|r| r[1] == "sliding") {
        assert_eq!(row[nu], "0.115", "{row:?}");
    }
    let text = fs::read_to_string(out.join("trajectory.csv")).unwrap();
    assert!(!text.to_lowercase().contains("nan"));
}

#[test]
fn every_builtin_scene_is_listed() {
    let o = Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .arg("scenes")
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    for (name, _) in eulerdisk::BUILTIN_SCENES {
        assert!(text.contains(name), "{name}");
    }
}

/// The numbers in `text` as written: `7419`, `471,084`, `0.04204`, `3.9e-3`.
fn quoted_numbers(text: &str) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let starts = chars[i].is_ascii_digit() && (i == 0 || !chars[i - 1].is_alphanumeric());
        if !starts {
            i += 1;
            continue;
        }
        let mut j = i;
        while j < chars.len() {
            let c = chars[j];
            let next_digit = chars.get(j + 1).is_some_and(|n| n.is_ascii_digit());
            let exponent = c == 'e'
                && chars
                    .get(j + 1)
                    .is_some_and(|n| n.is_ascii_digit() || *n == '-');
            let sign = c == '-' && chars[j - 1] == 'e';
            if c.is_ascii_digit() || ((c == '.' || c == ',') && next_digit) || exponent || sign {
                j += 1;
            } else {
                break;
            }
        }
        out.push(chars[i..j].iter().collect());
        i = j;
    }
    out
}

/// `value` written the way `quoted` is (same decimals, or same exponent form) equals `quoted`.
fn same_as_printed(quoted: &str, value: f64) -> bool {
    let plain = quoted.replace(',', "");
    let printed = match plain.split_once('e') {
        Some((mantissa, _)) => {
            let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len());
            format!("{value:.decimals$e}")
        }
        None => {
            let decimals = plain.split_once('.').map_or(0, |(_, d)| d.len());
            format!("{value:.decimals$}")
        }
    };
    printed == plain
}

/// The "ours" cell of the README's comparison row `label`.
fn readme_cell<'a>(readme: &'a str, label: &str) -> &'a str {
    let line = readme
        .lines()
        .find(|l| l.starts_with(&format!("| {label} |")))
        .unwrap_or_else(|| panic!("README has no row `{label}`"));
    line.split('|').nth(2).unwrap().trim()
}

#[test]
fn quoted_numbers_are_read_as_printed() {
    assert_eq!(
        quoted_numbers("7419 (471,084 steps, 8.23 M, 3.9e-3 m/s at 50.2 s; x2)"),
        ["7419", "471,084", "8.23", "3.9e-3", "50.2"]
    );
    assert!(same_as_printed("0.04204", 0.042042));
    assert!(!same_as_printed("0.04204", 0.04206));
    assert!(same_as_printed("3.9e-3", 3.8665e-3));
    assert!(same_as_printed("471,084", 471_084.0));
    assert!(!same_as_printed("2438", 2437.4));
}

/// The README's table and its figure are today's: the main job (the paper's scene, 100 s, as
/// `cargo run --release` runs it) must print every number the table quotes, to the digits
/// quoted, and draw the same figure (`same_figure`). When the code changes a result, this test says
/// which number to update; the figure is remade by the command under it in the README.
#[test]
fn the_readmes_numbers_and_figure_are_todays() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = fs::read_to_string(root.join("README.md")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = run(&["--quiet", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = read_summary(&out);
    let num = |key: &str| {
        s[key]
            .as_f64()
            .unwrap_or_else(|| panic!("summary.json has no number `{key}`"))
    };
    let (header, rows) = csv(&out.join("trajectory.csv"));
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let (t, v_c) = (col("t_s"), col(&Quantity::V_C.column()));
    let at = |row: &Vec<String>, i: usize| row[i].parse::<f64>().unwrap();
    let (slip_max, slip_max_t) = rows
        .iter()
        .filter(|r| at(r, t) >= 50.0)
        .map(|r| (at(r, v_c), at(r, t)))
        .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
    let t_end = num("t_end");
    let slip_last = rows
        .iter()
        .filter(|r| at(r, t) >= t_end - 1.0)
        .map(|r| at(r, v_c))
        .fold(0.0, f64::max);
    let (_, events) = csv(&out.join("events.csv"));
    let initial_ratio: f64 = events[0][4].parse().unwrap();
    // The transitions the README quotes to explain the 49 rolling phases per second are rows
    // of today's events.csv, in the order quoted.
    let example = readme
        .split("(e.g. ")
        .nth(1)
        .and_then(|rest| rest.split(", then roll").next())
        .expect("README quotes example transitions `(e.g. slide at .. s, ..., then roll`");
    let quoted_times = quoted_numbers(example);
    assert_eq!(quoted_times.len(), 4, "{example}");
    let times: Vec<f64> = events.iter().filter_map(|r| r[0].parse().ok()).collect();
    let first = times
        .iter()
        .position(|t| same_as_printed(&quoted_times[0], *t))
        .unwrap_or_else(|| panic!("no transition at {} s in events.csv", quoted_times[0]));
    for (q, t) in quoted_times.iter().zip(&times[first..]) {
        assert!(
            same_as_printed(q, *t),
            "README {q} s, events.csv {t} s ({example})"
        );
    }

    let checks: [(&str, Vec<f64>); 12] = [
        ("start mode", vec![initial_ratio]),
        ("stop reason, t_end", vec![t_end]),
        (
            "mode transitions",
            vec![num("transitions"), num("steps"), num("rhs_evals") / 1e6],
        ),
        (
            "θ period, first / last second",
            vec![num("theta_period_first_s"), num("theta_period_last_s")],
        ),
        (
            "2π/period, first / last second",
            vec![num("theta_omega_first"), num("theta_omega_last")],
        ),
        ("θ max after 50 s", vec![num("theta_max_after_50s")]),
        (
            "slip speed max after 50 s",
            vec![num("slip_speed_max_after_50s"), slip_max_t, slip_last],
        ),
        (
            "ν while sliding / ν max",
            vec![num("nu_sliding"), num("nu_max")],
        ),
        (
            "rolling phases per second, last second (all / ≥ 1 ms)",
            vec![
                num("rolling_phases_per_s_last"),
                num("rolling_phases_long_per_s_last"),
            ],
        ),
        (
            "rolling time fraction, last second",
            vec![num("rolling_fraction_last")],
        ),
        (
            "N/mg min / max (max in the last second)",
            vec![
                num("n_over_mg_min"),
                num("n_over_mg_max"),
                num("n_over_mg_max_last_s"),
            ],
        ),
        (
            "energy drift in rolling phases (relative)",
            vec![num("energy_drift_rel")],
        ),
    ];
    let mut stale = Vec::new();
    for (label, values) in checks {
        let quoted = quoted_numbers(readme_cell(&readme, label));
        assert_eq!(quoted.len(), values.len(), "`{label}`: {quoted:?}");
        for (q, v) in quoted.iter().zip(&values) {
            if !same_as_printed(q, *v) {
                stale.push(format!("`{label}`: README {q}, run {v}"));
            }
        }
    }
    let drift = readme
        .lines()
        .find(|l| l.starts_with("| constraint drift max"))
        .unwrap();
    let drift = quoted_numbers(drift.split('|').nth(2).unwrap());
    if !same_as_printed(&drift[0], num("constraint_drift_max")) {
        stale.push(format!(
            "constraint drift: README {}, run {}",
            drift[0],
            num("constraint_drift_max")
        ));
    }
    // The located maximum of the slip is at least the largest sample, and the samples (1 kHz)
    // come within a part in a thousand of it.
    let located = num("slip_speed_max_after_50s");
    assert!(
        located >= slip_max && located - slip_max <= 1e-3 * located,
        "{located} {slip_max}"
    );
    assert_eq!(s["start_mode"], "sliding");
    assert_eq!(s["stop_reason"], "end_time");
    assert!(
        stale.is_empty(),
        "the README quotes another run:\n{}",
        stale.join("\n")
    );

    let hero = "fig08b_normal_force.png";
    if let Err(why) = same_figure(&out.join(hero), &root.join("docs/figures").join(hero)) {
        panic!(
            "docs/figures/{hero} is not today's figure ({why}): remake it with \
             `cargo run --release && cp out/{hero} docs/figures/`"
        );
    }
}

/// Whether two renderings show the same figure: the same size, a plot that is not empty, and
/// the ink (the pixels that are not background) in the same places but for anti-aliased edges
/// and glyphs. Bytes are not compared: an encoder or font rasteriser update changes them
/// without changing the figure.
fn same_figure(today: &Path, kept: &Path) -> Result<(), String> {
    let read = |p: &Path| {
        image::open(p)
            .map(|i| i.to_rgb8())
            .map_err(|e| e.to_string())
    };
    let (a, b) = (read(today)?, read(kept)?);
    if a.dimensions() != b.dimensions() {
        return Err(format!(
            "size {:?} against {:?}",
            a.dimensions(),
            b.dimensions()
        ));
    }
    let ink = |p: &image::Rgb<u8>| p.0.iter().any(|&c| c < 200);
    let pixels = f64::from(a.width()) * f64::from(a.height());
    let inked = a.pixels().filter(|p| ink(p)).count() as f64 / pixels;
    if inked < 0.01 {
        return Err(format!(
            "only {:.2}% of today's figure is drawn",
            100.0 * inked
        ));
    }
    let differ = a
        .pixels()
        .zip(b.pixels())
        .filter(|(p, q)| ink(p) != ink(q))
        .count() as f64;
    if differ / pixels > 0.005 {
        return Err(format!(
            "{:.2}% of the pixels differ in ink",
            100.0 * differ / pixels
        ));
    }
    Ok(())
}

/// The repository's text files (sources, docs, scenes), without build output.
fn repository_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if name.starts_with('.') || name == "target" {
            continue;
        }
        if path.is_dir() {
            repository_files(&path, out);
        } else if ["rs", "md", "toml"]
            .iter()
            .any(|ext| path.extension().is_some_and(|e| e == *ext))
        {
            out.push(path);
        }
    }
}

/// Every reference to the physics write-up names a section it has, and nothing cites a file
/// that is not in the repository.
#[test]
fn every_physics_reference_names_a_section_of_docs_physics() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let physics = fs::read_to_string(root.join("docs/physics.md")).unwrap();
    let sections: Vec<String> = physics
        .lines()
        .filter_map(|l| l.strip_prefix("## ").or_else(|| l.strip_prefix("### ")))
        .filter_map(|h| h.split_whitespace().next())
        .map(|n| n.trim_end_matches('.').to_string())
        .filter(|n| n.chars().next().is_some_and(|c| c.is_ascii_digit()))
        .collect();
    assert!(sections.len() >= 12, "{sections:?}");
    let mut files = Vec::new();
    repository_files(root, &mut files);
    let mut references = 0;
    let mut bad = Vec::new();
    for file in files.iter().filter(|f| !f.ends_with("docs/physics.md")) {
        let text = fs::read_to_string(file).unwrap();
        let shown = file.strip_prefix(root).unwrap().display().to_string();
        if text.contains(&format!("{}.md", "EQUATIONS")) {
            bad.push(format!("{shown}: cites a file outside the repository"));
        }
        for (at, _) in text.match_indices("docs/physics.md") {
            // The reference runs to the end of its parenthesis or sentence, across a line
            // break and the comment marker that continues it.
            let after: String = text[at + "docs/physics.md".len()..]
                .chars()
                .take(70)
                .collect();
            let after = after
                .replace("\n", " ")
                .replace("//!", "")
                .replace("///", "");
            let end = after.find([')', ':', ',']).unwrap_or(after.len());
            let window = &after[..end];
            for part in window.split('§').skip(1) {
                let number: String = part
                    .chars()
                    .take_while(|c| c.is_ascii_digit() || *c == '.')
                    .collect();
                let number = number.trim_end_matches('.');
                references += 1;
                if !sections.iter().any(|s| s == number) {
                    bad.push(format!(
                        "{shown}: the physics write-up has no section {number}"
                    ));
                }
            }
        }
    }
    assert!(
        references > 60,
        "found only {references} section references"
    );
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
