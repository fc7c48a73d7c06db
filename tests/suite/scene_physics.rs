//! The shipped scenes do what their descriptions say, checked against docs/physics.md §9.

use std::sync::atomic::AtomicBool;

use eulerdisk::{
    load_scene, record_run, ModelChoice, Override, Progress, ProgressStyle, RunData, SamplePlan,
};

/// Runs a built-in scene for `t_end` seconds with the full models (the checks read `X`, `Y`
/// and the energy) and returns what it recorded: every sample at the scene's rate.
fn simulate(name: &str, t_end: f64) -> RunData {
    let scene = load_scene(name, &[Override::new("run", "t_end", t_end)]).unwrap();
    let plan = SamplePlan {
        every: 1,
        first: None,
        last: None,
        ..SamplePlan::new(0.0, t_end, scene.file.settings.run.sample_rate)
    };
    let interrupt = AtomicBool::new(false);
    let mut progress = Progress::new(ProgressStyle::Quiet, t_end);
    let recorded = record_run(
        &scene,
        &ModelChoice::default(),
        plan,
        &interrupt,
        &mut progress,
        None,
    )
    .unwrap();
    let stop = recorded.data.stop.clone().unwrap();
    assert_eq!(stop.kind.name(), "end_time", "{name}: {stop:?}");
    recorded.data
}

fn theta_range(d: &RunData) -> (f64, f64) {
    d.samples
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
            (lo.min(s.state.theta), hi.max(s.state.theta))
        })
}

#[test]
fn spinning_in_place_holds_still() {
    let d = simulate("spinning-in-place", 2.0);
    let (lo, hi) = theta_range(&d);
    assert!(
        (lo - 0.57).abs() < 1e-9 && (hi - 0.57).abs() < 1e-9,
        "{lo} {hi}"
    );
    for s in &d.samples {
        assert!(
            s.state.x.abs() < 1e-9 && s.state.y.abs() < 1e-9,
            "centre moved"
        );
        assert!((s.forces.normal / (0.4387 * 9.81) - 1.0).abs() < 1e-9);
    }
    assert!(d.events.is_empty());
}

#[test]
fn steady_circle_has_the_predicted_radius_and_friction() {
    let d = simulate("steady-circle", 2.0);
    let (lo, hi) = theta_range(&d);
    assert!(hi - lo < 1e-8, "{lo} {hi}");
    // Radius a Omega_z / p with p = -5 rad/s; nu = a |Omega_z p| / g.
    let (a, oz, p): (f64, f64, f64) = (0.03755, 13.240609818014546, -5.0);
    let radius: f64 = (a * oz / p).abs();
    let (xs, ys): (Vec<f64>, Vec<f64>) = d.samples.iter().map(|s| (s.state.x, s.state.y)).unzip();
    let cx = (xs.iter().cloned().fold(f64::INFINITY, f64::min)
        + xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max))
        / 2.0;
    let cy = (ys.iter().cloned().fold(f64::INFINITY, f64::min)
        + ys.iter().cloned().fold(f64::NEG_INFINITY, f64::max))
        / 2.0;
    for s in &d.samples {
        let r = (s.state.x - cx).hypot(s.state.y - cy);
        assert!((r - radius).abs() < 1e-6, "{r} vs {radius}");
        assert!((s.forces.nu - a * (oz * p).abs() / 9.81).abs() < 1e-8);
    }
}

#[test]
fn upright_rolling_is_stable_above_the_threshold_and_falls_below() {
    let (lo, _) = theta_range(&simulate("upright-stable", 3.0));
    assert!(
        lo > std::f64::consts::FRAC_PI_2 - 0.06,
        "stable disk tilted to {lo}"
    );
    let (lo, _) = theta_range(&simulate("upright-unstable", 3.0));
    assert!(lo < 1.0, "unstable disk only tilted to {lo}");
}

#[test]
fn the_rough_floor_never_lets_the_disk_slide() {
    let d = simulate("high-friction", 3.0);
    assert!(d.events.is_empty(), "{:?}", d.events.first());
    assert!(d.samples.iter().all(|s| s.forces.nu < 1.5));
}
