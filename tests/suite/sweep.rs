//! `eulerdisk sweep`: rows identical to `run`, sharding + merging, resuming, kills, failures
//! and bad sweep files. Every sweep here is short (t_end well under a second of simulated
//! time) so the file stays fast on two cores.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use eulerdisk::{
    load_scene, load_sweep, merge, plan, read_manifest, read_rows, run_arguments, run_options,
    run_scene, run_sweep, scalar_entries, split_fields, sweep_dir, ExecOptions, ExecReport, Keep,
    LoadedSweep, Override, Plan, PlanError, ProgressStyle, Row, Shard, Status, BUILTIN_SWEEPS,
    ROWS_DIR, TABLE_FILE, TIMING_COLUMNS,
};

const BIN: &str = env!("CARGO_BIN_EXE_eulerdisk");

/// Six points: mu_d x integrator, 0.3 s of the paper's scene each.
const SMALL: &str = r#"
scene = "tangent-toy-pruned"
[set]
run.t_end = 0.3
[[axis]]
key = "friction.mu_d"
values = [0.1, 0.115, 0.13]
[[axis]]
key = "solver.integrator"
values = ["dopri5", "dop853"]
[error]
against = "friction.mu_d"
keys = ["transitions", "n_over_mg_max"]
[figures]
keys = ["n_over_mg_max", "err_n_over_mg_max"]
"#;

fn sweep_file(dir: &Path, text: &str) -> LoadedSweep {
    let path = dir.join("s.toml");
    fs::write(&path, text).unwrap();
    load_sweep(path.to_str().unwrap()).unwrap()
}

fn small_plan(dir: &Path) -> Plan {
    plan(&sweep_file(dir, SMALL), &[]).unwrap()
}

fn opts(jobs: usize, shard: Option<Shard>) -> ExecOptions {
    ExecOptions {
        jobs,
        progress: ProgressStyle::Quiet,
        shard,
    }
}

fn go(plan: &Plan, out: &Path, jobs: usize, shard: Option<Shard>) -> ExecReport {
    run_sweep(plan, out, &opts(jobs, shard), &AtomicBool::new(false))
        .unwrap()
        .exec
}

/// `sweep.csv` with the timing columns blanked: what must not depend on how it was run.
fn untimed_table(dir: &Path) -> Vec<Vec<String>> {
    let text = fs::read_to_string(dir.join(TABLE_FILE)).unwrap();
    let mut lines = text.lines();
    let header = split_fields(lines.next().unwrap());
    let mut names = header.clone();
    names.sort();
    names.dedup();
    assert_eq!(
        names.len(),
        header.len(),
        "a column named twice: {header:?}"
    );
    let timing: Vec<usize> = header
        .iter()
        .enumerate()
        .filter(|(_, h)| TIMING_COLUMNS.contains(&h.as_str()))
        .map(|(i, _)| i)
        .collect();
    std::iter::once(header.clone())
        .chain(lines.map(|l| {
            let mut f = split_fields(l);
            assert_eq!(
                f.len(),
                header.len(),
                "a row with the wrong number of fields: {l}"
            );
            for &i in &timing {
                f[i].clear();
            }
            f
        }))
        .collect()
}

fn without_timing(
    mut summary: serde_json::Map<String, serde_json::Value>,
) -> serde_json::Map<String, serde_json::Value> {
    for k in TIMING_COLUMNS {
        summary.remove(*k);
    }
    summary
}

#[test]
fn each_row_is_the_run_of_its_point_bit_for_bit() {
    let tmp = tempfile::tempdir().unwrap();
    let plan = small_plan(tmp.path());
    let out = tmp.path().join("out");
    assert_eq!(go(&plan, &out, 2, None).ran, 6);
    let rows = read_rows(&out, &plan.definition).unwrap();
    let d = &plan.definition;
    // Every point against the library's `run` of the same scene and overrides ...
    for (point, row) in &rows {
        let sets = run_arguments(d, &d.points[*point]);
        let overrides: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
        let scene = load_scene(&d.scene_name, &overrides).unwrap();
        let dir = tmp.path().join(format!("lib{point}"));
        let report = run_scene(
            &scene,
            &run_options(&scene, &dir, Keep::None),
            &AtomicBool::new(false),
        )
        .unwrap();
        assert_eq!(row.status, Status::Completed);
        assert_eq!(
            without_timing(row.summary.clone()),
            without_timing(scalar_entries(&report.summary)),
            "point {point}"
        );
    }
    // ... and one point against the command `eulerdisk run` itself, through summary.json.
    let point = 3;
    let run_dir = tmp.path().join("cli");
    let mut cmd = Command::new(BIN);
    cmd.args(["run", &d.scene_name, "--quiet", "--no-figures", "--out"])
        .arg(&run_dir);
    for s in run_arguments(d, &d.points[point]) {
        cmd.args(["--set", &s]);
    }
    assert!(cmd.status().unwrap().success());
    let json: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(run_dir.join("summary.json")).unwrap()).unwrap();
    let row = &rows[&point];
    let mut compared = 0;
    for (k, v) in json.as_object().unwrap() {
        if let Some(mine) = row
            .summary
            .get(k)
            .filter(|_| !TIMING_COLUMNS.contains(&k.as_str()))
        {
            assert_eq!(mine, v, "key {k}");
            compared += 1;
        }
    }
    assert!(compared >= 15, "{compared}");
    assert!(row.summary["transitions"].as_u64().unwrap() > 0);
}

#[test]
fn sharded_and_merged_equals_unsharded_row_for_row() {
    let tmp = tempfile::tempdir().unwrap();
    let plan = small_plan(tmp.path());
    let whole = tmp.path().join("whole");
    go(&plan, &whole, 2, None);
    let sharded = tmp.path().join("sharded");
    let mut ran = 0;
    for index in 0..4 {
        let r = go(&plan, &sharded, 1, Some(Shard { index, count: 4 }));
        assert_eq!(r.points, if index < 2 { 2 } else { 1 });
        ran += r.ran;
        // A shard's folder holds its own points only.
        let shard_dir = sweep_dir(&sharded, Some(Shard { index, count: 4 }));
        assert!(read_rows(&shard_dir, &plan.definition)
            .unwrap()
            .keys()
            .all(|p| p % 4 == index));
    }
    assert_eq!(ran, 6);
    let merged = tmp.path().join("merged");
    let (_, rows, report) = merge(std::slice::from_ref(&sharded), &merged).unwrap();
    assert!(report.complete(), "{report:?}");
    assert_eq!((report.inputs.len(), rows.len()), (4, 6));
    let table = untimed_table(&merged);
    assert_eq!(table.len(), 7);
    assert_eq!(table, untimed_table(&whole));
    assert!(merged.join("sweep_n_over_mg_max_map.png").is_file());

    // A lost shard is listed as missing; a shard given twice as a duplicate that agrees.
    let lost = sweep_dir(&sharded, Some(Shard { index: 1, count: 4 }));
    let copy = tmp.path().join("copy-of-0");
    copy_dir(
        &sweep_dir(&sharded, Some(Shard { index: 0, count: 4 })),
        &copy,
    );
    fs::remove_dir_all(&lost).unwrap();
    let (_, _, report) = merge(&[sharded.clone(), copy], &tmp.path().join("m2")).unwrap();
    let missing: Vec<usize> = report.missing.iter().map(|p| p.0).collect();
    assert_eq!(missing, [1, 5]);
    let dups: Vec<(usize, bool)> = report
        .duplicates
        .iter()
        .map(|d| (d.point.0, d.agree))
        .collect();
    assert_eq!(dups, [(0, true), (4, true)]);
    assert!(!report.complete());
    // The command says so, and fails.
    let out = Command::new(BIN)
        .args(["sweep", "merge"])
        .arg(&sharded)
        .arg("--out")
        .arg(tmp.path().join("m3"))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(text.contains("missing (2): r000001 r000005"), "{text}");
}

fn copy_dir(from: &Path, to: &Path) {
    fs::create_dir_all(to).unwrap();
    for e in fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        if e.file_type().unwrap().is_dir() {
            copy_dir(&e.path(), &to.join(e.file_name()));
        } else {
            fs::copy(e.path(), to.join(e.file_name())).unwrap();
        }
    }
}

/// Every file in the rows folder (temporary ones included), sorted.
fn all_row_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = fs::read_dir(dir.join(ROWS_DIR))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    v.sort();
    v
}

fn is_partial(p: &Path) -> bool {
    p.file_name()
        .unwrap()
        .to_string_lossy()
        .starts_with(".partial")
}

/// The finished row files.
fn row_files(dir: &Path) -> Vec<PathBuf> {
    all_row_files(dir)
        .into_iter()
        .filter(|p| !is_partial(p))
        .collect()
}

#[test]
fn resume_runs_only_the_points_without_a_row() {
    let tmp = tempfile::tempdir().unwrap();
    let small = small_plan(tmp.path());
    let plan = &small;
    let out = tmp.path().join("out");
    let first = go(plan, &out, 2, None);
    assert_eq!((first.ran, first.skipped), (6, 0));
    let before: Vec<(PathBuf, Vec<u8>)> = row_files(&out)
        .into_iter()
        .map(|p| (p.clone(), fs::read(&p).unwrap()))
        .collect();
    let table = untimed_table(&out);
    // Nothing to do: nothing runs, nothing changes.
    let again = go(plan, &out, 2, None);
    assert_eq!((again.ran, again.skipped), (0, 6));
    // Two rows lost: exactly those two run again; the others keep their files, timing included.
    fs::remove_file(&before[1].0).unwrap();
    fs::remove_file(&before[4].0).unwrap();
    let resumed = go(plan, &out, 2, None);
    assert_eq!(
        (resumed.ran, resumed.skipped, resumed.interrupted),
        (2, 4, false)
    );
    for (i, (path, bytes)) in before.iter().enumerate() {
        if i != 1 && i != 4 {
            assert_eq!(&fs::read(path).unwrap(), bytes, "{}", path.display());
        }
    }
    assert_eq!(untimed_table(&out), table);
    // Another sweep is refused in the same folder instead of being mixed in.
    let other =
        eulerdisk::plan(&sweep_file(tmp.path(), &SMALL.replace("0.3", "0.2")), &[]).unwrap();
    let err = run_sweep(&other, &out, &opts(1, None), &AtomicBool::new(false)).unwrap_err();
    assert!(err.to_string().contains("another sweep"), "{err}");
}

#[test]
fn a_killed_sweep_leaves_whole_rows_and_resumes() {
    let tmp = tempfile::tempdir().unwrap();
    // Twelve runs of 0.2 s, one at a time, so the kill lands in the middle.
    let text = SMALL.replace("0.3", "0.2").replace(
        "values = [0.1, 0.115, 0.13]",
        "values = [0.1, 0.105, 0.11, 0.115, 0.12, 0.13]",
    );
    let loaded = sweep_file(tmp.path(), &text);
    let out = tmp.path().join("out");
    let mut child = Command::new(BIN)
        .args(["sweep", "--quiet", "--jobs", "1", "--out"])
        .arg(&out)
        .arg(tmp.path().join("s.toml"))
        .spawn()
        .unwrap();
    let started = Instant::now();
    while (!out.join(ROWS_DIR).is_dir() || row_files(&out).len() < 3)
        && started.elapsed() < Duration::from_secs(120)
    {
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap(); // SIGKILL: no handler runs
    child.wait().unwrap();
    let plan = plan(&loaded, &[]).unwrap();
    let kept = read_rows(&out, &plan.definition).unwrap();
    assert!(
        kept.len() >= 3 && kept.len() < 12,
        "{} rows: the kill should land mid-sweep",
        kept.len()
    );
    for row in kept.values() {
        assert!(row.summary.contains_key("transitions"));
    }
    // Every line of the table that was on disk at the kill is whole.
    if out.join(TABLE_FILE).is_file() {
        untimed_table(&out);
    }
    // A half-written row file (what a kill during a write leaves) is removed on resume.
    fs::write(
        out.join(ROWS_DIR).join(".partial-1-r000011.json"),
        b"{\"point\":11,\"val",
    )
    .unwrap();
    let resumed = go(&plan, &out, 2, None);
    assert_eq!(resumed.skipped, kept.len());
    assert_eq!(resumed.ran + resumed.skipped, 12);
    assert!(!all_row_files(&out).iter().any(|p| is_partial(p)));
    let fresh = tmp.path().join("fresh");
    go(&plan, &fresh, 2, None);
    assert_eq!(untimed_table(&out), untimed_table(&fresh));
}

#[test]
fn failing_and_slow_runs_are_rows_with_their_reason() {
    let tmp = tempfile::tempdir().unwrap();
    // Sliding only: the disk soon wants to roll, which the scene forbids (a failed run).
    // 100 s: stopped by the timeout. 0.05 s: completes.
    let text = r#"
scene = "tangent-toy-pruned"
combine = "zip"
timeout_s = 0.4
keep = "events"
[set]
solver.integrator = "dopri5"
[[axis]]
key = "modes.allowed"
values = [["sliding"], ["rolling", "sliding"], ["rolling", "sliding"]]
[[axis]]
key = "run.t_end"
values = [1.0, 100.0, 0.05]
"#;
    let plan = plan(&sweep_file(tmp.path(), text), &[]).unwrap();
    let out = tmp.path().join("out");
    let report = go(&plan, &out, 2, None);
    assert_eq!((report.ran, report.failed), (3, 2));
    let rows = read_rows(&out, &plan.definition).unwrap();
    let r: Vec<&Row> = rows.values().collect();
    assert_eq!(
        (r[0].status, r[0].stop_reason.name()),
        (Status::Failed, "mode_not_allowed")
    );
    assert!(
        r[0].stop_detail.contains("modes.allowed"),
        "{}",
        r[0].stop_detail
    );
    assert_eq!(
        (r[1].status, r[1].stop_reason.name()),
        (Status::Timeout, "timeout")
    );
    assert!(
        r[1].stop_detail.contains("timeout_s = 0.4"),
        "{}",
        r[1].stop_detail
    );
    assert_eq!(
        (r[2].status, r[2].stop_reason.name()),
        (Status::Completed, "end_time")
    );
    // `keep = "events"` keeps the summary and the events, not the trajectory.
    let run2 = out.join("runs").join("r000002");
    assert!(run2.join("events.csv").is_file() && run2.join("summary.json").is_file());
    assert!(!run2.join("trajectory.csv").exists());
    let table = fs::read_to_string(out.join(TABLE_FILE)).unwrap();
    assert!(
        table.contains("r000001,\"[\"\"rolling\"\", \"\"sliding\"\"]\",100,timeout,timeout"),
        "{table}"
    );
    // Without `keys`, every summary key is a column, but `stop_detail` only once: the row's.
    let header = split_fields(table.lines().next().unwrap());
    let detail: Vec<usize> = (0..header.len())
        .filter(|&i| header[i] == "stop_detail")
        .collect();
    assert_eq!(detail.len(), 1, "{header:?}");
    let timed_out = split_fields(table.lines().nth(2).unwrap());
    assert!(
        timed_out[detail[0]].contains("timeout_s = 0.4"),
        "{timed_out:?}"
    );
    // The folder's lock is held while the sweep runs, and gone after it.
    assert!(!out.join("sweep.lock").exists());
}

/// A sweep file with `axis` tables replaced; the key and the word its error must name.
fn rejected(text: &str) -> PlanError {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("bad.toml");
    fs::write(&path, text).unwrap();
    match load_sweep(path.to_str().unwrap()) {
        Err(e) => PlanError::Spec(e),
        Ok(l) => plan(&l, &[]).map(|_| ()).unwrap_err(),
    }
}

#[test]
fn bad_sweep_files_are_rejected_by_key_and_value() {
    let base = "scene = \"tangent-toy\"\n";
    let axis = |key: &str, gen: &str| format!("{base}[[axis]]\nkey = \"{key}\"\n{gen}\n");
    let cases: Vec<(String, &str, &str)> = vec![
        (format!("{base}axes = 3\n"), "axes", "unknown field"),
        (
            axis("friction.mu", "values = [0.1]"),
            "friction.mu",
            "unknown field",
        ),
        (
            axis("friction.mu_st", "values = [0.3, 0.1]"),
            "friction.mu_st",
            "got 0.1",
        ),
        (
            axis(
                "initial.theta",
                "linspace = { from = 1.0, to = 4.0, num = 2 }",
            ),
            "initial.theta",
            "4",
        ),
        (
            axis("solver.integrator", "values = [\"euler\"]"),
            "solver.integrator",
            "euler",
        ),
        (
            axis(
                "solver.rtol",
                "logspace = { from = 0.0, to = 1e-6, num = 3 }",
            ),
            "axis[0].logspace.from",
            "got 0",
        ),
        (axis("mu_d", "values = [0.1]"), "axis[0].key", "mu_d"),
        (
            axis(
                "friction.mu_d",
                "linspace = { from = 0.1, to = 0.2, num = -1 }",
            ),
            "axis[0].linspace.num",
            "-1",
        ),
        (
            format!("{}keys = [\"transitionz\"]\n", base),
            "keys",
            "transitionz",
        ),
        (format!("{}timeout_s = -1.0\n", base), "timeout_s", "-1"),
        (
            format!(
                "{}combine = \"zip\"\n{}",
                base,
                &axis("friction.mu_d", "values = [0.1, 0.11]")[base.len()..]
            ) + "[[axis]]\nkey = \"friction.mu_st\"\nvalues = [0.2]\n",
            "axis[1]",
            "equally long",
        ),
        (
            axis("friction.mu_d", "values = [0.1]")
                + "[error]\nagainst = \"solver.rtol\"\nkeys = [\"transitions\"]\n",
            "error.against",
            "solver.rtol",
        ),
        (
            axis("friction.mu_d", "values = [0.1]") + "[figures]\nkeys = [\"speed\"]\n",
            "figures.keys",
            "speed",
        ),
        (
            format!("{base}[set]\nfriction.mu_d = -1.0\n"),
            "friction.mu_d",
            "-1",
        ),
    ];
    for (text, key, word) in cases {
        let err = rejected(&text);
        let message = err.to_string();
        assert!(
            err.keys().iter().any(|k| k == key),
            "expected key `{key}` in {:?}: {message}\n{text}",
            err.keys()
        );
        assert!(
            message.contains(word),
            "expected `{word}` in: {message}\n{text}"
        );
    }
    // A bad point names its values and its number; nothing is written by the command.
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("bad.toml");
    fs::write(&path, axis("friction.mu_st", "values = [0.3, 0.1]")).unwrap();
    let out = tmp.path().join("out");
    let o = Command::new(BIN)
        .arg("sweep")
        .arg(&path)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("point 1 (friction.mu_st = 0.1)"),
        "{stderr}"
    );
    assert!(!out.exists());
}

#[test]
fn builtin_sweeps_validate_and_record_their_definition() {
    for (name, _) in BUILTIN_SWEEPS {
        let p = plan(&load_sweep(name).unwrap(), &["run.t_end=0.1".to_string()]).unwrap();
        assert!(p.definition.points.len() >= 9, "{name}");
    }
    // A `--set` that every point's axis value replaces does not reject the sweep.
    let p = plan(
        &load_sweep("speed-accuracy").unwrap(),
        &["solver.rtol=3".to_string()],
    )
    .unwrap();
    assert_eq!(p.scenes[0].config.rtol, 1e-4);
    // The definition written first is the one read back.
    let tmp = tempfile::tempdir().unwrap();
    let plan = plan(
        &load_sweep("paper-friction").unwrap(),
        &["run.t_end=0.05".to_string()],
    )
    .unwrap();
    let out = tmp.path().join("out");
    let shard = Shard { index: 0, count: 6 };
    assert_eq!(go(&plan, &out, 2, Some(shard)).ran, 2);
    let m = read_manifest(&sweep_dir(&out, Some(shard)))
        .unwrap()
        .unwrap();
    assert_eq!(m.definition, plan.definition);
    assert_eq!(m.shard, Some(shard));
}

#[test]
fn shard_auto_takes_its_share_from_the_job_array() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let status = Command::new(BIN)
        .args([
            "sweep",
            "paper-friction",
            "--quiet",
            "--jobs",
            "2",
            "--shard",
            "auto",
            "--set",
            "run.t_end=0.05",
            "--out",
        ])
        .arg(&out)
        .env("SLURM_ARRAY_TASK_ID", "2")
        .env("SLURM_ARRAY_TASK_MIN", "1")
        .env("SLURM_ARRAY_TASK_COUNT", "6")
        .status()
        .unwrap();
    assert!(status.success());
    let shard_dir = out.join("shard-1-of-6");
    let names: Vec<String> = row_files(&shard_dir)
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["r000001.json", "r000007.json"]);
    assert!(!shard_dir.join(".scratch").exists());
}

/// `docs/check-slurm-sweep.sh` on a machine whose Slurm controller is up refuses before it
/// touches anything: no package installed, no daemon started or stopped, no configuration
/// written (stand-ins for the Slurm commands record any call).
#[cfg(unix)]
#[test]
fn the_slurm_check_leaves_a_running_cluster_alone() {
    use std::os::unix::fs::PermissionsExt;
    let tmp = tempfile::tempdir().unwrap();
    let calls = tmp.path().join("calls");
    let stand_in = |name: &str, body: &str| {
        let path = tmp.path().join(name);
        fs::write(
            &path,
            format!(
                "#!/bin/sh\necho {name} \"$@\" >> '{}'\n{body}\n",
                calls.display()
            ),
        )
        .unwrap();
        fs::set_permissions(&path, fs::Permissions::from_mode(0o755)).unwrap();
    };
    stand_in(
        "scontrol",
        "[ \"$1\" = ping ] && echo 'Slurmctld(primary) at node is UP'",
    );
    for name in [
        "apt-get",
        "slurmctld",
        "slurmd",
        "munged",
        "sbatch",
        "runuser",
    ] {
        stand_in(name, "");
    }
    let path = format!(
        "{}:{}",
        tmp.path().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/check-slurm-sweep.sh");
    let out = Command::new("bash")
        .arg(&script)
        .arg(BIN)
        .env("PATH", path)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("Slurm controller is up"), "{err}");
    let called = fs::read_to_string(&calls).unwrap();
    assert_eq!(
        called.trim(),
        "scontrol ping",
        "only asked, nothing done: {called}"
    );
}

/// `sweep merge` brings each kept run's folder (`runs/<id>/`) along with its row.
#[test]
fn merge_brings_the_kept_run_folders() {
    let tmp = tempfile::tempdir().unwrap();
    let text = r#"
scene = "tangent-toy-pruned"
keep = "summary"
[set]
run.t_end = 0.05
[[axis]]
key = "friction.mu_d"
values = [0.1, 0.115, 0.13]
"#;
    let plan = plan(&sweep_file(tmp.path(), text), &[]).unwrap();
    let out = tmp.path().join("out");
    for index in 0..2 {
        go(&plan, &out, 1, Some(Shard { index, count: 2 }));
    }
    let merged = tmp.path().join("merged");
    let (_, rows, report) = merge(std::slice::from_ref(&out), &merged).unwrap();
    assert!(report.complete() && rows.len() == 3, "{report:?}");
    for row in &rows {
        let shard = Shard {
            index: row.point % 2,
            count: 2,
        };
        let kept = sweep_dir(&out, Some(shard)).join("runs").join(row.id());
        let copied = merged.join("runs").join(row.id());
        assert_eq!(
            fs::read(copied.join("summary.json")).unwrap(),
            fs::read(kept.join("summary.json")).unwrap(),
            "{}",
            row.id()
        );
    }
}

/// Runs that timed out run again when the same sweep comes back with a longer `timeout_s`
/// (the folder is the same sweep, not "another sweep"); with the same timeout they stay.
#[test]
fn a_longer_timeout_reruns_the_timed_out_points() {
    let tmp = tempfile::tempdir().unwrap();
    let with_timeout = |t: f64| {
        format!(
            "scene = \"tangent-toy-pruned\"\ntimeout_s = {t}\n[[axis]]\nkey = \"run.t_end\"\nvalues = [0.01, 20.0]\n"
        )
    };
    let out = tmp.path().join("out");
    // 1 µs: the 20 s run cannot finish (the timeout is watched every 20 ms).
    let short = plan(&sweep_file(tmp.path(), &with_timeout(1e-6)), &[]).unwrap();
    go(&short, &out, 1, None);
    let rows = read_rows(&out, &short.definition).unwrap();
    assert_eq!(rows[&1].status, Status::Timeout, "{:?}", rows[&1]);
    // The same timeout again: nothing to do.
    let again = go(&short, &out, 1, None);
    assert_eq!((again.ran, again.skipped), (0, 2));
    // A longer one: exactly the timed-out runs run again, and complete.
    let long = plan(&sweep_file(tmp.path(), &with_timeout(600.0)), &[]).unwrap();
    let timed_out: Vec<usize> = rows
        .values()
        .filter(|r| r.status == Status::Timeout)
        .map(|r| r.point)
        .collect();
    let report = go(&long, &out, 1, None);
    assert_eq!(report.ran, timed_out.len());
    let rows = read_rows(&out, &long.definition).unwrap();
    assert!(
        rows.values().all(|r| r.status == Status::Completed),
        "{rows:?}"
    );
    let manifest = read_manifest(&out).unwrap().unwrap();
    assert_eq!(manifest.definition.file.timeout_s, Some(600.0));
    // Another sweep still is another sweep.
    let other = with_timeout(600.0).replace("20.0", "19.0");
    let other = plan(&sweep_file(tmp.path(), &other), &[]).unwrap();
    let err = run_sweep(&other, &out, &opts(1, None), &AtomicBool::new(false)).unwrap_err();
    assert!(err.to_string().contains("another sweep"), "{err}");
}

/// `sweep merge` takes the output's lock and refuses an input a running sweep still writes.
#[test]
fn merge_takes_the_sweep_lock() {
    let tmp = tempfile::tempdir().unwrap();
    let text = "scene = \"tangent-toy-pruned\"\n[set]\nrun.t_end = 0.02\n[[axis]]\nkey = \"friction.mu_d\"\nvalues = [0.1, 0.12]\n";
    let plan = plan(&sweep_file(tmp.path(), text), &[]).unwrap();
    let out = tmp.path().join("out");
    for index in 0..2 {
        go(&plan, &out, 1, Some(Shard { index, count: 2 }));
    }
    let merged = tmp.path().join("merged");
    let me = std::process::id().to_string();
    // A running process (this one) holds an input: refused, nothing written.
    let shard = sweep_dir(&out, Some(Shard { index: 1, count: 2 }));
    fs::write(shard.join("sweep.lock"), &me).unwrap();
    let err = merge(std::slice::from_ref(&out), &merged).unwrap_err();
    assert!(err.to_string().contains("another sweep"), "{err}");
    assert!(!merged.join(TABLE_FILE).exists());
    fs::remove_file(shard.join("sweep.lock")).unwrap();
    // ... or the output.
    fs::create_dir_all(&merged).unwrap();
    fs::write(merged.join("sweep.lock"), &me).unwrap();
    assert!(merge(std::slice::from_ref(&out), &merged).is_err());
    fs::remove_file(merged.join("sweep.lock")).unwrap();
    let (_, rows, report) = merge(std::slice::from_ref(&out), &merged).unwrap();
    assert!(report.complete() && rows.len() == 2, "{report:?}");
    assert!(!merged.join("sweep.lock").exists(), "released");
}

/// A sweep with `output.format = "parquet"` writes `sweep.parquet`, typed, and no CSV table.
#[cfg(feature = "parquet")]
#[test]
fn a_parquet_sweep_writes_a_typed_table() {
    eulerdisk_parquet::install();
    let tmp = tempfile::tempdir().unwrap();
    let text = "scene = \"tangent-toy-pruned\"\nkeep = \"events\"\n[set]\nrun.t_end = 0.02\n[[axis]]\nkey = \"friction.mu_d\"\nvalues = [0.1, 0.12]\n";
    let sets = ["output.format=parquet".to_string()];
    let plan = plan(&sweep_file(tmp.path(), text), &sets).unwrap();
    let out = tmp.path().join("out");
    go(&plan, &out, 1, None);
    assert!(!out.join(TABLE_FILE).exists());
    let table = eulerdisk_parquet::read_table(&out.join("sweep.parquet")).unwrap();
    let col = |name: &str| table.header.iter().position(|h| h == name).unwrap();
    assert_eq!(table.rows.len(), 2);
    assert_eq!(
        table.rows[1][col("friction.mu_d")],
        eulerdisk::Cell::Float(0.12)
    );
    assert_eq!(
        table.rows[0][col("status")],
        eulerdisk::Cell::text("completed")
    );
    assert!(matches!(
        table.rows[0][col("transitions")],
        eulerdisk::Cell::Int(_)
    ));
    let run = out.join("runs").join("r000000");
    assert!(run.join("events.parquet").is_file() && !run.join("events.csv").exists());
    assert!(
        !run.join("extrema.parquet").exists(),
        "keep = events keeps the events only"
    );
    // An axis over the format is refused by its key.
    let axis =
        format!("{text}[[axis]]\nkey = \"output.format\"\nvalues = [\"csv\", \"parquet\"]\n");
    let err = plan_err(tmp.path(), &axis);
    assert!(err.contains("axis[1].key"), "{err}");
}

fn plan_err(dir: &Path, text: &str) -> String {
    plan(&sweep_file(dir, text), &[]).unwrap_err().to_string()
}

/// The sweep file the Kubernetes recipe's ConfigMap carries is a valid sweep.
#[test]
fn the_kubernetes_configmap_holds_a_valid_sweep() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let yaml = fs::read_to_string(root.join("docs/k8s-sweep-job.yaml")).unwrap();
    let text: String = yaml
        .lines()
        .skip_while(|l| l.trim() != "sweep.toml: |")
        .skip(1)
        .take_while(|l| l.starts_with("    "))
        .map(|l| format!("{}\n", &l[4..]))
        .collect();
    let tmp = tempfile::tempdir().unwrap();
    let plan = plan(&sweep_file(tmp.path(), &text), &[]).unwrap();
    assert_eq!(plan.definition.points.len(), 8);
}
