//! Summary and figures on a synthetic run whose answers are known: θ oscillates with a set
//! period, the disk slides while θ falls and rolls while it rises.

use equations::params::DiskParams;
use eulerdisk::analysis::summary::Summary;
use eulerdisk::analysis::synthetic::SyntheticRun;
use eulerdisk::figures::paper::{paper_charts, write_paper_figures};

fn synthetic(period: f64, t_end: f64) -> (DiskParams, eulerdisk::record::RunData) {
    let p = DiskParams::paper();
    let data = SyntheticRun {
        period,
        t_end,
        rate: 1000.0,
    }
    .data(&p);
    (p, data)
}

#[test]
fn summary_reads_the_known_answers() {
    let period = 0.125;
    let (p, data) = synthetic(period, 60.0);
    let s = Summary::of("synthetic", &data, &p);
    for got in [
        s.theta_period_first_s.unwrap(),
        s.theta_period_last_s.unwrap(),
    ] {
        assert!((got - period).abs() < 1e-9 * period, "{got}");
    }
    let omega = 2.0 * std::f64::consts::PI / period;
    assert!((s.theta_omega_last.unwrap() - omega).abs() < 1e-7);
    assert!((s.nu_sliding.unwrap() - p.mu_d).abs() < 1e-12);
    // One rolling phase per oscillation: 8 per second.
    assert_eq!(s.rolling_phases_per_s_last, Some(8.0));
    // θ = 0.4 + 0.2 e^(-0.05 t) cos(ωt): after 50 s the largest θ is 0.4 + 0.2 e^(-2.5).
    let theta_max = s.theta_max_after_50s.unwrap();
    assert!(
        (theta_max - (0.4 + 0.2 * (-2.5f64).exp())).abs() < 1e-4,
        "{theta_max}"
    );
    assert!(s.slip_speed_max_after_50s.unwrap() > 0.0);
    assert_eq!(s.transitions, data.events.len());
    assert_eq!(s.energy_drift_rel, Some(0.0));
    assert_eq!(s.stop_reason, "end_time");
    let table = s.table();
    assert!(
        table.contains("theta_period_first_s") && table.contains("0.14"),
        "{table}"
    );
}

#[test]
fn short_runs_have_no_settled_values() {
    let (p, data) = synthetic(0.1, 3.0);
    let s = Summary::of("synthetic", &data, &p);
    assert_eq!(s.theta_max_after_50s, None);
    assert_eq!(s.slip_speed_max_after_50s, None);
    let json = serde_json::to_value(&s).unwrap();
    assert!(json["theta_max_after_50s"].is_null());
}

#[test]
fn every_paper_figure_is_drawn() {
    let (p, data) = synthetic(0.1, 5.0);
    let charts = paper_charts(&data, &p);
    assert_eq!(charts.len(), 15);
    for c in &charts {
        assert!(c.title.starts_with("Fig. "), "{}", c.title);
        assert!(
            c.x_label.contains('(') && c.y_label.contains('('),
            "units on {}",
            c.stem
        );
        assert!(c.lines.iter().all(|l| !l.points.is_empty()), "{}", c.stem);
    }
    let dir = tempfile::tempdir().unwrap();
    let stems = write_paper_figures(&data, &p, dir.path()).unwrap();
    assert_eq!(stems.len(), 15);
    for stem in stems {
        for ext in ["png", "svg"] {
            let meta = std::fs::metadata(dir.path().join(format!("{stem}.{ext}"))).unwrap();
            assert!(meta.len() > 1000, "{stem}.{ext}");
        }
    }
}
