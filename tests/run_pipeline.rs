//! The run pipeline in-process: a short run of the paper's scene streams finite samples, the
//! collector keeps both windows, and the summary reads the paper's first period.

use std::sync::atomic::AtomicBool;

use eulerdisk::eval::Backend;
use eulerdisk::run::provenance::Provenance;
use eulerdisk::run::{run_scene, Ending, ProgressStyle, RunOptions};
use eulerdisk::scene::{self, Override};

fn short_run(t_end: f64, backend: Backend) -> (tempfile::TempDir, eulerdisk::run::RunReport) {
    let dir = tempfile::tempdir().unwrap();
    let overrides = [Override::new("run", "t_end", t_end)];
    let scene = scene::load("tangent-toy", &overrides).unwrap();
    let opts = RunOptions {
        out_dir: dir.path().to_path_buf(),
        progress: ProgressStyle::Quiet,
        backend,
        figures: false,
        provenance: Provenance::new(&scene, "tangent-toy", &overrides),
    };
    let report = run_scene(&scene, &opts, &AtomicBool::new(false)).unwrap();
    (dir, report)
}

#[test]
fn paper_scene_first_seconds_match_the_paper() {
    let (_dir, report) = short_run(1.5, Backend::Generated);
    assert_eq!(report.ending, Ending::Completed);
    let s = &report.summary;
    assert_eq!(s.stop_reason, "end_time");
    assert_eq!(s.t_end, 1.5);
    assert_eq!(s.start_mode.map(|m| m.as_str()), Some("sliding"));
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
