//! The summary's heights, periods and amplitudes come from extrema located on the dense
//! output, so they do not depend on the sampling rate: the main job at 1 kHz and at 20 kHz
//! gives the same values (to 1e-6 relative; in fact to the last bit, since the steps do not
//! depend on the samples). `extrema.csv` lists them.

use std::sync::atomic::AtomicBool;

use crate::quiet_run::{run_quietly, Quiet};
use eulerdisk::{load_scene, Override};

/// The paper's scene at `rate` samples per second, without trajectory or figures.
fn main_job_at(rate: f64) -> (tempfile::TempDir, eulerdisk::RunReport) {
    let overrides = [Override::new("run", "sample_rate", rate)];
    let scene = load_scene("tangent-toy", &overrides).unwrap();
    run_quietly(
        &scene,
        &overrides,
        Quiet::default(),
        &AtomicBool::new(false),
    )
}

#[test]
fn located_numbers_do_not_depend_on_the_sampling_rate() {
    let (_a, coarse) = main_job_at(1000.0);
    let (dir, fine) = main_job_at(20_000.0);
    let (c, f) = (&coarse.summary, &fine.summary);
    assert_eq!(c.t_end, 100.0);
    for (key, a, b) in [
        ("n_over_mg_max", c.n_over_mg_max, f.n_over_mg_max),
        (
            "n_over_mg_max_last_s",
            c.n_over_mg_max_last_s,
            f.n_over_mg_max_last_s,
        ),
        ("n_over_mg_min", c.n_over_mg_min, f.n_over_mg_min),
        (
            "theta_max_after_50s",
            c.theta_max_after_50s,
            f.theta_max_after_50s,
        ),
        (
            "theta_period_first_s",
            c.theta_period_first_s,
            f.theta_period_first_s,
        ),
        (
            "theta_period_last_s",
            c.theta_period_last_s,
            f.theta_period_last_s,
        ),
        (
            "slip_speed_max_after_50s",
            c.slip_speed_max_after_50s,
            f.slip_speed_max_after_50s,
        ),
    ] {
        let (a, b) = (a.unwrap(), b.unwrap());
        assert!(
            (a - b).abs() <= 1e-6 * b.abs(),
            "{key}: {a} at 1 kHz, {b} at 20 kHz"
        );
    }
    // The located peaks are at least as high as any sample (the 20 kHz samples of the last
    // second miss most of each peak's top).
    let text = std::fs::read_to_string(dir.path().join("extrema.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("t_s,quantity,kind,value"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert!(rows
        .iter()
        .all(|r| r.len() == 4 && (r[2] == "max" || r[2] == "min")));
    let peak = rows
        .iter()
        .filter(|r| r[1] == "N_over_mg" && r[2] == "max")
        .map(|r| r[3].parse::<f64>().unwrap())
        .fold(f64::MIN, f64::max);
    assert_eq!(peak, f.n_over_mg_max.unwrap());
    let times: Vec<f64> = rows.iter().map(|r| r[0].parse().unwrap()).collect();
    assert!(times.windows(2).all(|w| w[0] <= w[1]), "time order");
    // θ turns ~150 times a second at the end: every one of them is listed.
    let last_second_minima = rows
        .iter()
        .filter(|r| r[1] == "theta_rad" && r[2] == "min")
        .filter(|r| r[0].parse::<f64>().unwrap() >= 99.0)
        .count();
    assert!(
        (23..=25).contains(&last_second_minima),
        "{last_second_minima}"
    );
}

#[test]
fn a_disk_that_rolls_throughout_has_one_rolling_phase() {
    // Steady rolling on a circle never slides: one phase, all of the last second rolling.
    let scene = load_scene("steady-circle", &[]).unwrap();
    let (_dir, report) = run_quietly(&scene, &[], Quiet::default(), &AtomicBool::new(false));
    let s = report.summary;
    assert_eq!(s.transitions, 0);
    assert_eq!(s.rolling_phases_per_s_last, Some(1.0));
    assert_eq!(s.rolling_phases_long_per_s_last, Some(1.0));
    assert_eq!(s.rolling_fraction_last, Some(1.0));
}

/// The curves of θ and N/mg in the window figures (Fig. 1, 8 and 10) pass through the located
/// extrema, at a coarse and at a fine sampling rate: each located extremum in a window is a
/// point of its curve, and each peak of the curve is a located maximum (the samples alone, at
/// 20 kHz, fall short of the force peaks by a factor up to ten).
#[test]
fn the_figures_curves_reach_the_located_extrema() {
    use equations::{ExtremumKind, Watched};
    use eulerdisk::{paper_charts, simulate_scene, Backend};
    for rate in [50.0, 2000.0] {
        let overrides = [
            Override::new("run", "sample_rate", rate),
            Override::new("run", "t_end", 2.5),
        ];
        let scene = load_scene("tangent-toy", &overrides).unwrap();
        let run = simulate_scene(&scene, Backend::Generated, &AtomicBool::new(false)).unwrap();
        let data = &run.data;
        let mg = scene.params.weight();
        let charts = paper_charts(data, &scene.params, true);
        for (stem, label, q, scale) in [
            ("fig01a_theta", "θ", Watched::Theta, 1.0),
            ("fig01b_theta", "θ", Watched::Theta, 1.0),
            ("fig08a_normal_force", "N/mg", Watched::NormalForce, mg),
            ("fig08b_normal_force", "N/mg", Watched::NormalForce, mg),
            (
                "fig10_normal_force_last_second",
                "N/mg",
                Watched::NormalForce,
                mg,
            ),
        ] {
            let chart = charts.iter().find(|c| c.stem == stem).unwrap();
            let curve = &chart
                .lines
                .iter()
                .find(|l| l.label.starts_with(label))
                .unwrap_or_else(|| panic!("{stem}: no line {label}"))
                .points;
            let (t0, t1) = (curve[0].0, curve[curve.len() - 1].0);
            let located: Vec<(f64, f64)> = data
                .extrema
                .iter()
                .filter(|e| e.quantity == q && e.t >= t0 && e.t <= t1)
                .map(|e| (e.t, e.value / scale))
                .collect();
            assert!(located.len() > 3, "{stem} at {rate}/s: {located:?}");
            for e in &located {
                assert!(
                    curve.contains(e),
                    "{stem} at {rate}/s: {e:?} not on the curve"
                );
            }
            // Every peak of the curve (a point above the one before it and not below the one
            // after) is a located maximum.
            let maxima: Vec<(f64, f64)> = data
                .extrema
                .iter()
                .filter(|e| e.quantity == q && e.kind == ExtremumKind::Max)
                .map(|e| (e.t, e.value / scale))
                .collect();
            let peaks: Vec<&(f64, f64)> = curve
                .windows(3)
                .filter(|w| w[1].1 > w[0].1 && w[1].1 >= w[2].1)
                .map(|w| &w[1])
                .collect();
            assert!(!peaks.is_empty(), "{stem} at {rate}/s");
            for peak in peaks {
                assert!(
                    maxima.contains(peak),
                    "{stem} at {rate}/s: the curve peaks at {peak:?}, no located maximum"
                );
            }
        }
    }
}
