//! The quantities a scene asks for decide the models that run: the pruned 8-state models
//! when nothing written needs a state they drop, the full ones otherwise; and a pruned run
//! reports no value of a frozen state.

use std::fs;
use std::sync::atomic::AtomicBool;

use crate::quiet_run::{run_quietly, Quiet};
use equations::record::Quantity;
use eulerdisk::{choose, load_scene, Backend, Override, RunModel, RunReport, Scene};

const PRUNED: &str = "tangent-toy-pruned";

fn load(name: &str, sets: &[&str]) -> Scene {
    let overrides: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    load_scene(name, &overrides).unwrap()
}

fn short_run(scene: &Scene, figures: bool) -> (tempfile::TempDir, RunReport) {
    let how = Quiet {
        figures,
        trajectory: true,
        ..Quiet::default()
    };
    run_quietly(scene, &[], how, &AtomicBool::new(false))
}

#[test]
fn the_quantities_decide_the_models() {
    let pruned = load(PRUNED, &[]);
    let c = choose(&pruned, Backend::Generated, true);
    assert_eq!(c.model, RunModel::Pruned, "{}", c.reason);
    assert_eq!(c.frozen, ["X", "Y", "Z", "phi"]);
    assert_eq!(c.model.label(), "pruned (8 states)");

    // The default scene asks for the energy, which needs Z.
    let full = load("tangent-toy", &[]);
    let c = choose(&full, Backend::Generated, true);
    assert_eq!(c.model, RunModel::Full);
    assert!(c.reason.contains("energy"), "{}", c.reason);

    for q in ["X", "Y", "Z", "phi", "energy", "residual_Z"] {
        let s = load(
            PRUNED,
            &[&format!("output.quantities=[\"theta\", \"{q}\"]")],
        );
        let c = choose(&s, Backend::Generated, true);
        assert_eq!(c.model, RunModel::Full, "{q}");
        assert!(c.reason.contains("output.quantities"), "{}", c.reason);
        assert!(c.reason.contains(q), "{q}: {}", c.reason);
    }

    let windy = load(PRUNED, &["air.mu_a=0.01"]);
    let c = choose(&windy, Backend::Generated, true);
    assert_eq!(c.model, RunModel::Full);
    assert!(c.reason.contains("air.mu_a"), "{}", c.reason);
    let blowing = load(PRUNED, &["air.w_z=0.1"]);
    assert!(choose(&blowing, Backend::Generated, true)
        .reason
        .contains("air.w_z"));

    let c = choose(&pruned, Backend::Reference, true);
    assert_eq!(c.model, RunModel::Reference);
}

#[test]
fn every_quantity_without_a_dropped_state_runs_pruned() {
    for q in Quantity::ALL {
        let s = load(PRUNED, &[&format!("output.quantities=[\"{}\"]", q.name())]);
        let c = choose(&s, Backend::Generated, true);
        let needs_dropped = q.reads().iter().any(|s| ["X", "Y", "Z", "phi"].contains(s));
        assert_eq!(c.model == RunModel::Full, needs_dropped, "{}", q.name());
    }
}

#[test]
fn a_pruned_run_reports_no_frozen_value_and_says_which_model_ran() {
    let scene = load(PRUNED, &["run.t_end=1.2"]);
    let (dir, report) = short_run(&scene, false);
    let s = &report.summary;
    assert_eq!(s.model, "pruned (8 states)");
    assert_eq!(s.energy_drift_rel, None);
    assert_eq!(s.constraint_drift_max, None);
    assert!(s.not_computed["energy_drift_rel"].contains('Z'));
    assert!(s.table().contains("energy_drift_rel"));
    assert!(s.table().contains("null (pruned models: Z not integrated)"));

    let json: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(dir.path().join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(json["model"], "pruned (8 states)");
    assert!(json["energy_drift_rel"].is_null());
    assert!(json["constraint_drift_max"].is_null());
    assert!(json["not_computed"]["energy_drift_rel"].is_string());

    let text = fs::read_to_string(dir.path().join("trajectory.csv")).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let mut expected = vec!["t_s", "mode"];
    let columns: Vec<String> = scene.quantities.iter().map(|q| q.column()).collect();
    expected.extend(columns.iter().map(String::as_str));
    assert_eq!(header, expected);
    for frozen in [
        Quantity::X,
        Quantity::Y,
        Quantity::Z,
        Quantity::Phi,
        Quantity::Energy,
    ] {
        assert!(!header.contains(&frozen.column().as_str()));
    }
    for line in text.lines().skip(1) {
        for v in line.split(',').skip(2) {
            assert!(v.parse::<f64>().unwrap().is_finite(), "{line}");
        }
    }
}

#[test]
fn pruned_and_full_runs_of_the_paper_scene_agree() {
    let pruned = load(PRUNED, &["run.t_end=1.5"]);
    // The same scene asking for X as well runs the full models.
    let full = load(
        PRUNED,
        &[
            "run.t_end=1.5",
            "output.quantities=[\"theta\", \"N\", \"X\", \"energy\"]",
        ],
    );
    let (_a, p) = short_run(&pruned, false);
    let (_b, f) = short_run(&full, false);
    assert_eq!(f.summary.model, "full (12 states)");
    assert!(f.summary.energy_drift_rel.is_some());
    assert!(f.summary.not_computed.is_empty());
    let (p, f) = (&p.summary, &f.summary);
    assert_eq!(p.transitions, f.transitions);
    assert_eq!(p.start_mode, f.start_mode);
    let close = |a: Option<f64>, b: Option<f64>, rel: f64| {
        let (a, b) = (a.unwrap(), b.unwrap());
        assert!((a - b).abs() <= rel * b.abs(), "{a} {b}");
    };
    close(p.theta_period_first_s, f.theta_period_first_s, 1e-6);
    close(p.n_over_mg_max, f.n_over_mg_max, 1e-4);
    close(p.n_over_mg_min, f.n_over_mg_min, 1e-6);
    close(p.nu_max, f.nu_max, 1e-6);
}
