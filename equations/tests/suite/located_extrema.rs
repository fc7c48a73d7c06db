//! Extrema located on the dense output (module `equations::hybrid::extrema`) at the paper's
//! tolerance (rtol 1e-8, atol 1e-10) against a run a hundred times tighter (1e-10, 1e-12): in
//! the first and the last simulated second of the paper's scene, the same θ turning points and
//! force peaks, at the same times and heights to what the tolerance gives (docs/physics.md §13).
//!
//! Measured: in the first second the times agree to 1.7e-9 s and the values to 1.2e-8
//! (relative; N's peaks the largest), i.e. the tolerance's 1e-8; after 100 s and 7483 mode
//! decisions the accumulated phase error is 2.4e-5 s and the values agree to 9.2e-6. The bounds
//! below are those, rounded up to the next power of ten (first second) or to 1e-4 / 5e-5.

use equations::{
    simulate, DiskConfig, DiskObserver, DiskParams, Extremum, ExtremumKind, GeneratedModels,
    InitialState, SlipChart, Watched,
};

#[derive(Default)]
struct Extrema(Vec<Extremum>);

impl DiskObserver for Extrema {
    fn wants_sample(&self, _t: f64) -> bool {
        false
    }
    fn wants_extrema(&self) -> bool {
        true
    }
    fn on_extremum(&mut self, e: &Extremum) {
        self.0.push(*e);
    }
}

fn located(rtol: f64, atol: f64) -> Vec<Extremum> {
    let p = DiskParams::paper();
    let models = GeneratedModels::generated(p, SlipChart::Cartesian).unwrap();
    let config = DiskConfig {
        rtol,
        atol,
        t_end: 100.0,
        sample_rate: None,
        ..DiskConfig::default()
    };
    let mut seen = Extrema::default();
    simulate(&models, &config, &InitialState::paper(&p), &mut seen).unwrap();
    seen.0
}

/// θ's turning points of `kind` in `[t0, t1]` that are not ripples (θ moves at least 1e-3 rad
/// between consecutive turning points of the two kinds), in time order.
fn turns(list: &[Extremum], kind: ExtremumKind, t0: f64, t1: f64) -> Vec<(f64, f64)> {
    let mut theta: Vec<&Extremum> = list
        .iter()
        .filter(|e| e.quantity == Watched::Theta && e.t >= t0 && e.t <= t1)
        .collect();
    theta.sort_by(|a, b| a.t.total_cmp(&b.t));
    theta
        .iter()
        .enumerate()
        .filter(|(i, e)| {
            let near = |j: Option<&&Extremum>| j.is_none_or(|n| (n.value - e.value).abs() > 1e-3);
            e.kind == kind
                && near(theta.get(i + 1))
                && near(i.checked_sub(1).and_then(|j| theta.get(j)))
        })
        .map(|(_, e)| (e.t, e.value))
        .collect()
}

/// The largest N between consecutive maxima of θ (the force peak at each minimum of θ).
fn peaks(list: &[Extremum], t0: f64, t1: f64) -> Vec<(f64, f64)> {
    let bounds = turns(list, ExtremumKind::Max, t0, t1);
    bounds
        .windows(2)
        .filter_map(|w| {
            list.iter()
                .filter(|e| e.quantity == Watched::NormalForce && e.kind == ExtremumKind::Max)
                .filter(|e| e.t > w[0].0 && e.t < w[1].0)
                .max_by(|a, b| a.value.total_cmp(&b.value))
                .map(|e| (e.t, e.value))
        })
        .collect()
}

/// Largest differences (time, relative value) between paired lists.
fn differences(a: &[(f64, f64)], b: &[(f64, f64)]) -> (f64, f64) {
    assert_eq!(a.len(), b.len(), "{a:?}\n{b:?}");
    a.iter().zip(b).fold((0.0f64, 0.0f64), |(dt, dv), (x, y)| {
        (
            dt.max((x.0 - y.0).abs()),
            dv.max((x.1 - y.1).abs() / y.1.abs()),
        )
    })
}

#[test]
fn located_extrema_agree_between_rtol_1e8_and_1e10() {
    let paper = located(1e-8, 1e-10);
    let tight = located(1e-10, 1e-12);
    // (window, largest time difference (s), largest relative value difference)
    for (t0, t1, dt_max, dv_max) in [(0.0, 1.0, 1e-8, 1e-7), (99.0, 100.0, 1e-4, 5e-5)] {
        let min = differences(
            &turns(&paper, ExtremumKind::Min, t0, t1),
            &turns(&tight, ExtremumKind::Min, t0, t1),
        );
        let max = differences(
            &turns(&paper, ExtremumKind::Max, t0, t1),
            &turns(&tight, ExtremumKind::Max, t0, t1),
        );
        let force = differences(&peaks(&paper, t0, t1), &peaks(&tight, t0, t1));
        for (what, (dt, dv)) in [("θ minima", min), ("θ maxima", max), ("N peaks", force)] {
            assert!(
                dt <= dt_max && dv <= dv_max,
                "[{t0}, {t1}] s, {what}: times differ by {dt:e} s, values by {dv:e}"
            );
        }
    }
}
