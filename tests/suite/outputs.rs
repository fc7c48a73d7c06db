//! Summary and figures on a synthetic run whose answers are known: θ oscillates with a set
//! period, the disk slides while θ falls and rolls while it rises.

use equations::record::StopKind;
use equations::DiskParams;
use std::sync::atomic::AtomicBool;

use eulerdisk::{paper_charts, write_paper_figures, Summary, SyntheticRun, FIGURE_STEMS};

fn synthetic(period: f64, t_end: f64) -> (DiskParams, eulerdisk::RunData) {
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
    let mut s = Summary::of("synthetic", &data, &p);
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
    assert_eq!(s.stop_reason.map(StopKind::name), Some("end_time"));
    // The paper's column is shown only beside the paper's scene.
    let table = s.table();
    assert!(table.contains("theta_period_first_s"), "{table}");
    assert!(
        !table.contains("paper") && !table.contains("0.14"),
        "{table}"
    );
    assert!(s.comparison().iter().all(|r| r.paper.is_none()));
    s.compared_with_paper = true;
    let table = s.table();
    assert!(table.contains("paper") && table.contains("0.14"), "{table}");
    for (key, paper) in [
        ("transitions", "over 6000"),
        ("stop_reason", "contact kept"),
        ("t_end", "100"),
    ] {
        let row = s.comparison().into_iter().find(|r| r.key == key).unwrap();
        assert!(row.paper.unwrap_or("").contains(paper), "{key}: {row:?}");
    }
}

#[test]
fn an_abandoned_run_says_why_and_reports_no_made_up_counters() {
    let (p, mut data) = synthetic(0.1, 3.0);
    data.work.steps = None;
    data.work.rhs_evals = None;
    data.constraint_drift_max = None;
    let stop = data.stop.as_mut().unwrap();
    stop.kind = StopKind::Error;
    stop.detail = "step size 1e-20 s below the spacing of t at t = 2.5 s".into();
    let s = Summary::of("synthetic", &data, &p);
    assert_eq!(s.stop_reason.map(StopKind::name), Some("error"));
    assert!(s.stop_detail.contains("step size"), "{}", s.stop_detail);
    assert_eq!(
        (s.steps, s.rhs_evals, s.constraint_drift_max),
        (None, None, None)
    );
    for key in ["steps", "rhs_evals", "constraint_drift_max"] {
        let why = &s.not_computed[key];
        assert!(
            why.contains("abandoned") && why.contains("error"),
            "{key}: {why}"
        );
    }
    let json = serde_json::to_value(&s).unwrap();
    assert!(json["steps"].is_null());
    assert!(json["stop_detail"].as_str().unwrap().contains("step size"));
    assert!(
        s.table().contains("null (the simulation was abandoned"),
        "{}",
        s.table()
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
    let charts = paper_charts(&data, &p, true);
    let stems: Vec<&str> = charts.iter().map(|c| c.stem.as_str()).collect();
    assert_eq!(
        stems, FIGURE_STEMS,
        "the stems a run owns are the ones it draws"
    );
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
    let stop = AtomicBool::new(false);
    let figures = write_paper_figures(&data, &p, true, dir.path(), &stop).unwrap();
    assert_eq!(figures.drawn, FIGURE_STEMS);
    assert!(figures.not_drawn.is_empty());
    for stem in figures.drawn {
        for ext in ["png", "svg"] {
            let meta = std::fs::metadata(dir.path().join(format!("{stem}.{ext}"))).unwrap();
            assert!(meta.len() > 1000, "{stem}.{ext}");
        }
    }
}

/// A stop set before the figures are drawn draws none, and says so figure by figure.
#[test]
fn an_interrupt_before_the_figures_draws_none() {
    let (p, data) = synthetic(0.1, 2.0);
    let dir = tempfile::tempdir().unwrap();
    let figures = write_paper_figures(&data, &p, true, dir.path(), &AtomicBool::new(true)).unwrap();
    assert!(figures.drawn.is_empty());
    assert_eq!(figures.not_drawn, FIGURE_STEMS);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// A run where nothing moves but time: θ constant, no nutation, no slip (as spinning in place).
fn steady(t_end: f64) -> (DiskParams, eulerdisk::RunData) {
    let (p, mut data) = synthetic(0.1, t_end);
    for s in data
        .samples
        .iter_mut()
        .chain(data.first_second.iter_mut())
        .chain(data.last_second.iter_mut())
    {
        s.state.theta = 0.4;
        s.state.omega_y = 0.0;
        s.slip.speed = 0.0;
    }
    (p, data)
}

fn find<'a>(charts: &'a [eulerdisk::Chart], stem: &str) -> &'a eulerdisk::Chart {
    charts.iter().find(|c| c.stem == stem).unwrap()
}

#[test]
fn figures_with_nothing_to_show_say_why() {
    let (p, data) = steady(2.0);
    let charts = paper_charts(&data, &p, true);
    for (stem, why) in [
        ("fig02_theta_envelope", "completes no oscillation"),
        ("fig04_theta_dot_over_psi_dot", "no nutation"),
        ("fig07_slip_speed_envelope", "completes no oscillation"),
    ] {
        let c = find(&charts, stem);
        assert!(c.is_empty(), "{stem} should be empty");
        assert!(c.empty_note.contains(why), "{stem}: {}", c.empty_note);
    }
    // θ itself is there to draw, so its figure is not empty; a run of a constant has a line.
    assert!(!find(&charts, "fig01a_theta").is_empty());
    // Empty figures are drawn (with their note), not skipped.
    let dir = tempfile::tempdir().unwrap();
    assert_eq!(
        write_paper_figures(&data, &p, true, dir.path(), &AtomicBool::new(false))
            .unwrap()
            .drawn
            .len(),
        15
    );

    // A run shorter than a second has nothing after its first second.
    let (p, short) = synthetic(0.1, 0.5);
    let charts = paper_charts(&short, &p, true);
    for stem in [
        "fig04_theta_dot_over_psi_dot",
        "fig09_normal_force_vs_theta",
    ] {
        let c = find(&charts, stem);
        assert!(c.is_empty(), "{stem}");
        assert!(
            c.empty_note.contains("before its first second"),
            "{}",
            c.empty_note
        );
    }
}

#[test]
fn time_axes_span_the_time_each_figure_covers() {
    let (p, data) = synthetic(0.1, 2.0);
    let charts = paper_charts(&data, &p, true);
    // Per-oscillation envelopes have points only inside the run; the axis spans all of it.
    let fig7 = find(&charts, "fig07_slip_speed_envelope");
    let first = fig7.lines[0].points.first().unwrap().0;
    assert!(first > 0.0, "{first}");
    assert_eq!(fig7.x_axis(), 0.0..2.0);
    assert_eq!(find(&charts, "fig02_theta_envelope").x_axis(), 0.0..2.0);
    assert_eq!(
        find(&charts, "fig04_theta_dot_over_psi_dot").x_axis(),
        1.0..2.0
    );
    // The windows span their samples.
    assert_eq!(find(&charts, "fig01a_theta").x_axis(), 0.0..1.0);
    assert_eq!(find(&charts, "fig01b_theta").x_axis(), 1.0..2.0);
    // Fig. 9's x axis is θ (here within a decade: linear), inside the data's θ range.
    let fig9 = find(&charts, "fig09_normal_force_vs_theta");
    let x = fig9.x_axis();
    assert!(x.start > 0.1 && x.end < 1.0, "{x:?}");
}

#[test]
fn titles_write_time_ranges_one_way_and_fig8_draws_theta_under_the_force() {
    let (p, data) = synthetic(0.1, 3.0);
    for c in paper_charts(&data, &p, true) {
        if let Some(open) = c.title.find('[') {
            let range = &c.title[open..];
            let close = range.find("] s").unwrap_or_else(|| panic!("{}", c.title));
            let inner = &range[1..close];
            let (a, b) = inner
                .split_once(", ")
                .unwrap_or_else(|| panic!("{}", c.title));
            for v in [a, b] {
                let parsed: f64 = v.parse().unwrap_or_else(|_| panic!("{}", c.title));
                // At most four decimals, no trailing zeros: the one format (its rounding is
                // tested next to it, in the figures' axes).
                if let Some((_, decimals)) = v.split_once('.') {
                    assert!(
                        (1..=4).contains(&decimals.len()) && !decimals.ends_with('0'),
                        "{}",
                        c.title
                    );
                }
                assert!(parsed.is_finite() && v != "-0", "{}", c.title);
            }
        }
        if c.stem.starts_with("fig08") {
            assert_eq!(c.lines[0].label, "θ", "θ first, under N/mg");
            assert_eq!(c.lines[1].label, "N/mg");
        }
    }
}
