//! The run pipeline in-process: a short run of the paper's scene streams finite samples, the
//! collector keeps both windows, and the summary reads the paper's first period; a run that
//! stops early still gets its finely sampled last second; an interrupt stops the simulation.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use crate::quiet_run::{run_quietly, Quiet};
use equations::record::StopKind;
use eulerdisk::{load_scene, simulate_scene, Backend, Ending, Override};

fn short_run(t_end: f64, backend: Backend) -> (tempfile::TempDir, eulerdisk::RunReport) {
    let overrides = [Override::new("run", "t_end", t_end)];
    run_in_tempdir(&overrides, backend, &AtomicBool::new(false))
}

/// Runs the paper's scene with `overrides` into a temporary directory.
fn run_in_tempdir(
    overrides: &[Override],
    backend: Backend,
    interrupt: &AtomicBool,
) -> (tempfile::TempDir, eulerdisk::RunReport) {
    let scene = load_scene("tangent-toy", overrides).unwrap();
    let how = Quiet {
        backend,
        trajectory: true,
        ..Quiet::default()
    };
    run_quietly(&scene, overrides, how, interrupt)
}

#[test]
fn paper_scene_first_seconds_match_the_paper() {
    let (_dir, report) = short_run(1.5, Backend::Generated);
    assert_eq!(report.ending, Ending::Completed);
    let s = &report.summary;
    assert_eq!(s.stop_reason.map(StopKind::name), Some("end_time"));
    assert_eq!(s.t_end, 1.5);
    assert_eq!(s.start_mode.map(|m| m.name()), Some("sliding"));
    // Paper: period 0.14 s, 2π/T = 44 1/s in the first second.
    let period = s.theta_period_first_s.unwrap();
    assert!((period - 0.14).abs() < 0.005, "{period}");
    assert!((s.nu_sliding.unwrap() - 0.115).abs() < 1e-12);
    assert!(s.nu_max.unwrap() <= 0.2 + 1e-9);
    assert!(s.n_over_mg_min.unwrap() > 0.0);
    assert!(s.transitions > 5);
}

#[test]
fn generated_and_reference_runs_agree() {
    let (_a, g) = short_run(0.5, Backend::Generated);
    let (_b, r) = short_run(0.5, Backend::Reference);
    assert_eq!(g.summary.transitions, r.summary.transitions);
    let (pg, pr) = (
        g.summary.theta_period_first_s,
        r.summary.theta_period_first_s,
    );
    assert_eq!(pg.is_some(), pr.is_some());
    if let (Some(pg), Some(pr)) = (pg, pr) {
        assert!((pg - pr).abs() < 1e-6, "{pg} {pr}");
    }
}

/// The run in memory (another front end's entry point) is the run `eulerdisk run` writes:
/// the same samples, transitions, steps and stop.
#[test]
fn a_scene_simulated_in_memory_is_the_run_written_to_files() {
    let overrides = [Override::new("run", "t_end", 0.3)];
    let scene = load_scene("tangent-toy", &overrides).unwrap();
    let run = simulate_scene(&scene, Backend::Generated, &AtomicBool::new(false)).unwrap();
    let (dir, report) = short_run(0.3, Backend::Generated);
    let data = &run.data;
    let csv = std::fs::read_to_string(dir.path().join("trajectory.csv")).unwrap();
    assert_eq!(data.samples.len(), csv.lines().count() - 1);
    assert_eq!(data.samples.last().map(|s| s.t), Some(0.3));
    assert_eq!(data.work.steps, report.summary.steps);
    let stop = data.stop.as_ref().map(|stop| (stop.kind, stop.t));
    assert_eq!(
        stop,
        report
            .summary
            .stop_reason
            .map(|k| (k, report.summary.t_end))
    );
    assert_eq!(run.ending, report.ending);
    assert_eq!(data.work.rhs_evals, report.summary.rhs_evals);
}

/// A run that fails (here: out of its step budget) reports the work it did until then, in
/// memory and in `summary.json`, where the steps used to be `null`, and the last state it
/// reached: the end of its last accepted step, every state by its name.
#[test]
fn a_failed_run_reports_its_steps_and_evaluations() {
    let overrides = [Override::new("run", "t_end", 5.0)];
    let mut scene = load_scene("tangent-toy", &overrides).unwrap();
    scene.config.max_steps = 300;
    let (dir, report) = run_quietly(
        &scene,
        &overrides,
        Quiet::default(),
        &AtomicBool::new(false),
    );
    assert_eq!(report.ending, Ending::Failed);
    let s = &report.summary;
    assert_eq!(
        s.stop_reason.map(StopKind::name),
        Some("error"),
        "{}",
        s.stop_detail
    );
    let steps = s.steps.unwrap();
    assert!(steps > 0 && steps <= 300, "{steps}");
    assert!(s.rhs_evals.unwrap() > steps, "{:?}", s.rhs_evals);
    assert!(!s.not_computed.contains_key("steps"));
    let text = std::fs::read_to_string(dir.path().join("summary.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(json["steps"].as_u64(), Some(steps));
    // The last accepted state: before the failure, after the last sample kept, on the
    // constraints of its mode (Z = a sin θ).
    let last = s.last_state.expect("a failed run's last state");
    let latest = report.data.samples.last().unwrap();
    assert!(
        last.t > 0.0 && last.t <= s.t_end && last.t >= latest.t,
        "{} {} {}",
        last.t,
        s.t_end,
        latest.t
    );
    assert_eq!(last.mode, latest.mode);
    let a = scene.params.a;
    assert!((last.state.z - a * last.state.theta.sin()).abs() < 1e-9);
    let written = &json["last_state"];
    assert_eq!(written["t"].as_f64(), Some(last.t));
    assert_eq!(written["mode"].as_str(), Some(last.mode.name()));
    let state = written["state"].as_object().unwrap();
    let names: Vec<&str> = state.keys().map(String::as_str).collect();
    let mut expected = equations::STATE_NAMES.to_vec();
    expected.sort_unstable();
    assert_eq!(names, expected);
    assert_eq!(state["theta"].as_f64(), Some(last.state.theta));
    assert_eq!(state["Omega_z"].as_f64(), Some(last.state.omega_z));
    // A run that ends by itself writes no such key: its final state ends the trajectory.
    let (dir, _) = short_run(0.2, Backend::Generated);
    let text = std::fs::read_to_string(dir.path().join("summary.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert!(json.get("last_state").is_none());
}

/// The paper's reading of the slip sign lifts the disk off the floor at t ≈ 18.16 s: the
/// run stops long before its end time, so its last second was not sampled finely while it
/// ran; it is sampled from the steps the run kept, and the trajectory still ends at the stop.
#[test]
fn a_run_that_stops_early_gets_its_last_second_sampled_finely() {
    let overrides = [
        Override::new("run", "t_end", 30.0),
        Override::new("run", "slip_sign", "paper"),
    ];
    let (_dir, report) = run_in_tempdir(&overrides, Backend::Generated, &AtomicBool::new(false));
    let s = &report.summary;
    assert_eq!(s.stop_reason.map(StopKind::name), Some("contact_lost"));
    assert!((s.t_end - 18.159).abs() < 1e-3, "{}", s.t_end);
    // 20 kHz over the second before the stop; 1 kHz (every 20th) for the trajectory.
    assert!(
        (19_990..=20_001).contains(&s.samples.last_second),
        "{:?}",
        s.samples
    );
    assert_eq!(s.samples.first_second, 20_001);
    assert_eq!(s.samples.trajectory, 18_160 + 1);
    assert!(s.n_over_mg_max_last_s.is_some() && s.theta_period_last_s.is_some());
}

/// The last second a run samples from its kept steps is the one a second pass sampling only
/// that second records (what the run did before): the same times, modes, states and forces,
/// bit for bit, for a run that stops early (in regularised and in physical time) and for one
/// that ends at its end time.
#[test]
fn the_kept_last_second_is_the_one_a_second_pass_samples() {
    let early = [
        Override::new("run", "t_end", 30.0),
        Override::new("run", "slip_sign", "paper"),
    ];
    let physical = [
        Override::new("run", "t_end", 30.0),
        Override::new("run", "slip_sign", "paper"),
        Override::new("solver", "time", "physical"),
    ];
    let to_the_end = [Override::new("run", "t_end", 2.5)];
    for overrides in [&early[..], &physical, &to_the_end] {
        let scene = load_scene("tangent-toy", overrides).unwrap();
        let run = simulate_scene(&scene, Backend::Generated, &AtomicBool::new(false)).unwrap();
        let stop = run.data.stop.clone().unwrap();
        let replayed = replay_last_second(&scene, stop.t);
        let kept = &run.data.last_second;
        assert!(kept.len() > 19_000, "{}", kept.len());
        assert_eq!(kept.len(), replayed.len(), "{overrides:?}");
        for (a, b) in kept.iter().zip(&replayed) {
            assert_eq!((a.t.to_bits(), a.mode), (b.t.to_bits(), b.mode));
            let (ya, yb) = (a.state.to_array(), b.state.to_array());
            let values = ya.into_iter().zip(yb).chain([
                (a.forces.normal, b.forces.normal),
                (a.forces.r_x, b.forces.r_x),
                (a.forces.r_y, b.forces.r_y),
                (a.energy, b.energy),
                (a.slip.speed, b.slip.speed),
            ]);
            for (u, v) in values {
                assert_eq!(u.to_bits(), v.to_bits(), "t = {}: {u} {v}", a.t);
            }
        }
    }
}

/// The last second before `t_stop` of a second run of `scene` that samples only that second.
fn replay_last_second(scene: &eulerdisk::Scene, t_stop: f64) -> Vec<equations::record::Sample> {
    let run = &scene.file.settings.run;
    let plan = eulerdisk::SamplePlan::new(0.0, run.t_end, run.sample_rate)
        .with_windows(&scene.file.cli.output.windows)
        .last_second_before(t_stop);
    let choice = eulerdisk::choose(scene, Backend::Generated, false);
    let mut quiet = eulerdisk::Progress::new(eulerdisk::ProgressStyle::Quiet, run.t_end);
    let stop = AtomicBool::new(false);
    let again = eulerdisk::record_run(scene, &choice, plan, &stop, &mut quiet, None).unwrap();
    again.data.last_second
}

/// An interrupt stops the simulation itself, at its next step: the run reports the work done
/// up to then, long before the 100 s would have taken.
#[test]
fn an_interrupt_stops_the_simulation_and_keeps_its_work() {
    let interrupt = AtomicBool::new(false);
    let (_dir, report) = std::thread::scope(|scope| {
        scope.spawn(|| {
            std::thread::sleep(Duration::from_millis(100));
            interrupt.store(true, Ordering::SeqCst);
        });
        run_in_tempdir(&[], Backend::Generated, &interrupt)
    });
    assert_eq!(report.ending, Ending::Interrupted);
    let s = &report.summary;
    assert_eq!(s.stop_reason.map(StopKind::name), Some("interrupted"));
    assert!(s.t_end > 0.0 && s.t_end < 100.0, "{}", s.t_end);
    assert!(
        s.steps.is_some_and(|n| n > 0) && s.rhs_evals.is_some_and(|n| n > 0),
        "{:?} {:?}",
        s.steps,
        s.rhs_evals
    );
}

/// A disk released at rest leaning 1e-3 rad past upright falls onto its other face: the run
/// stops where θ reaches π minus the floor, and the files say so (`inclination_reached_pi`,
/// the library's reason; the command line once wrote `inclination_reached_0` for both faces).
#[test]
fn a_disk_fallen_past_upright_is_said_to_reach_pi() {
    let overrides = [
        Override::new("run", "t_end", 5.0),
        Override::new("initial", "theta", std::f64::consts::FRAC_PI_2 + 1e-3),
        Override::new("initial", "Omega_x", 0.0),
    ];
    let (dir, report) = run_in_tempdir(&overrides, Backend::Generated, &AtomicBool::new(false));
    let s = &report.summary;
    assert_eq!(
        s.stop_reason,
        Some(StopKind::InclinationReachedPi),
        "{}",
        s.stop_detail
    );
    assert!(s.t_end < 5.0, "{}", s.t_end);
    let last = report.data.samples.last().unwrap();
    assert!(
        last.state.theta > std::f64::consts::PI - 1e-6,
        "{}",
        last.state.theta
    );
    let events = std::fs::read_to_string(dir.path().join("events.csv")).unwrap();
    let stop = events.lines().last().unwrap();
    assert!(stop.contains(",stop,inclination_reached_pi,"), "{stop}");
    let summary = std::fs::read_to_string(dir.path().join("summary.json")).unwrap();
    assert!(summary.contains("\"stop_reason\": \"inclination_reached_pi\""));
}
