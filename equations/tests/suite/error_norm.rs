//! The disk's vector error norm: its groups name the right states in every mode, chart and
//! model set, and a run with it makes the same decisions as the per-component norm.

use equations::DiskParams;
use equations::{
    simulate, DiskModels, DiskRecorder, Embedded, GeneratedModels, PrunedModels, ReferenceModels,
    RunOutcome, SlidingModel, Variant,
};
use equations::{DiskConfig, ErrorNorm, InitialState, Integrator, LimitingComponent};
use equations::{SlipChart, DIM};
use model_runtime::Model;

use crate::common::assert_same_decisions;

const OMEGA: [&str; 3] = ["Omega_x", "Omega_y", "Omega_z"];

/// The state names of a 12-state model, by layout index.
fn full<M: Model<DIM>>(m: &M) -> Vec<&'static str> {
    m.info().state_names.iter().collect()
}

/// The layout seen through a pruned model: its own state names at their slots, and
/// "(frozen)" where the layout state is not integrated.
fn embedded<M: Variant<K>, const K: usize>(m: &Embedded<M, K>) -> Vec<&'static str> {
    let mut names = vec!["(frozen)"; DIM];
    for (k, &slot) in m.embedding().slots().iter().enumerate() {
        names[slot] = m.info().state_names.get(k).expect("a kept state");
    }
    names
}

fn sliding<C, P>(
    m: &SlidingModel<C, P>,
    cartesian: impl Fn(&C) -> Vec<&'static str>,
    polar: impl Fn(&P) -> Vec<&'static str>,
) -> Vec<&'static str> {
    match m {
        SlidingModel::Cartesian(c) => cartesian(c),
        SlidingModel::Polar(p) => polar(p),
    }
}

/// The names of the states in each group of a run's norm, for a model whose layout states
/// are named `names`.
fn grouped(norm: ErrorNorm, chart: SlipChart, names: &[&'static str]) -> Vec<Vec<&'static str>> {
    let config = DiskConfig {
        error_norm: norm,
        ..DiskConfig::paper()
    };
    let tol = config.tolerance(chart).unwrap();
    tol.groups()
        .iter()
        .map(|g| g.range().map(|i| names[i]).collect())
        .collect()
}

#[test]
fn the_groups_name_the_same_vectors_in_every_mode_chart_and_model_set() {
    let params = DiskParams::paper();
    for chart in [SlipChart::Cartesian, SlipChart::Polar] {
        let generated = GeneratedModels::generated(params, chart).unwrap();
        let reference = ReferenceModels::reference(params, chart).unwrap();
        let pruned = PrunedModels::pruned(params, chart).unwrap();
        let sets: [(&str, Vec<&str>, Vec<&str>); 3] = [
            (
                "generated",
                full(&generated.rolling),
                sliding(&generated.sliding, full, full),
            ),
            (
                "reference",
                full(&reference.rolling),
                sliding(&reference.sliding, full, full),
            ),
            (
                "pruned",
                embedded(&pruned.rolling),
                sliding(&pruned.sliding, embedded, embedded),
            ),
        ];
        let (rolling_groups, sliding_groups): (Vec<Vec<&str>>, Vec<Vec<&str>>) = match chart {
            SlipChart::Cartesian => (
                vec![vec!["V_X", "V_Y"], OMEGA.to_vec()],
                vec![vec!["u_X", "u_Y"], OMEGA.to_vec()],
            ),
            SlipChart::Polar => (vec![OMEGA.to_vec()], vec![OMEGA.to_vec()]),
        };
        for (set, rolling, sliding) in &sets {
            let at = format!("{set} models, {chart:?} chart");
            assert_eq!(
                grouped(ErrorNorm::Vectors, chart, rolling),
                rolling_groups,
                "rolling, {at}"
            );
            assert_eq!(
                grouped(ErrorNorm::Vectors, chart, sliding),
                sliding_groups,
                "sliding, {at}"
            );
            for names in [rolling, sliding] {
                assert!(grouped(ErrorNorm::Components, chart, names).is_empty());
            }
        }
    }
}

fn run(norm: ErrorNorm, t_end: f64) -> (RunOutcome, DiskRecorder) {
    let params = DiskParams::paper();
    let models: GeneratedModels = DiskModels::generated(params, SlipChart::Cartesian).unwrap();
    let config = DiskConfig {
        integrator: Integrator::Dop853,
        rtol: 1e-10,
        atol: 1e-12,
        t_end,
        error_norm: norm,
        limiting_component: LimitingComponent::Tracked,
        ..DiskConfig::paper()
    };
    let mut record = DiskRecorder::default();
    let out = simulate(&models, &config, &InitialState::paper(&params), &mut record).unwrap();
    (out, record)
}

/// The norm changes the steps, not the motion: the same decisions at the same times (to the
/// integration accuracy), and every accepted step counted once by its limiting component.
#[test]
fn the_vector_norm_makes_the_same_decisions() {
    let (a, ra) = run(ErrorNorm::Components, 0.5);
    let (b, rb) = run(ErrorNorm::Vectors, 0.5);
    assert!(ra.transitions.len() >= 3, "{}", ra.transitions.len());
    assert_same_decisions(&ra.transitions, &rb.transitions, 1e-8);
    assert_eq!(a.stop, b.stop);
    for out in [&a, &b] {
        assert_eq!(out.stats.limiting.total(), out.stats.steps);
    }
    assert_ne!(a.stats.steps, b.stats.steps, "the grouping had no effect");
}
