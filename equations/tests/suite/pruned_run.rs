//! The pruned variants run by the hybrid driver against the full generated models.
//!
//! In still air they are the same equations with the air term compiled out and `X`, `Y`, `Z`,
//! `φ` left out, so a run must make the same decisions at the same times, and give the same θ
//! and N, to the accuracy of the integration; and the states they drop must stay frozen.

use equations::DiskParams;
use equations::{layout, SlipChart};
use equations::{
    simulate, DiskModels, DiskRecorder, DiskSample, GeneratedModels, PruneError, PrunedModels,
    RunOutcome, TransitionRecord,
};
use equations::{DiskConfig, InitialState, Integrator};
use model_runtime::Model;

/// The paper's scene to `t_end` at tight tolerances (DOP853, `rtol = 1e-10`, `atol = 1e-12`).
fn tight(t_end: f64) -> DiskConfig {
    DiskConfig {
        integrator: Integrator::Dop853,
        rtol: 1e-10,
        atol: 1e-12,
        t_end,
        sample_rate: Some(200.0),
        ..DiskConfig::paper()
    }
}

fn run<R: Model<12>, S: Model<12>>(
    models: &DiskModels<R, S>,
    config: &DiskConfig,
) -> (RunOutcome, DiskRecorder) {
    let mut record = DiskRecorder::default();
    let params = models.params;
    let out = simulate(models, config, &InitialState::paper(&params), &mut record).unwrap();
    (out, record)
}

fn assert_same_decisions(full: &[TransitionRecord], pruned: &[TransitionRecord], tol: f64) {
    assert_eq!(full.len(), pruned.len(), "number of transitions");
    let mut worst = 0.0f64;
    for (k, (f, p)) in full.iter().zip(pruned).enumerate() {
        worst = worst.max((f.t - p.t).abs());
        assert_eq!(
            (f.from, f.to),
            (p.from, p.to),
            "transition {k} at t = {}",
            f.t
        );
        assert!(
            (f.t - p.t).abs() <= tol,
            "transition {k}: full at {} s, pruned at {} s",
            f.t,
            p.t
        );
    }
    eprintln!("{} transitions, times agree to {worst:.1e} s", full.len());
}

fn assert_same_samples(full: &[DiskSample], pruned: &[DiskSample]) {
    assert_eq!(full.len(), pruned.len(), "number of samples");
    let (mut theta_err, mut n_err) = (0.0f64, 0.0f64);
    for (f, p) in full.iter().zip(pruned) {
        assert_eq!(f.t, p.t);
        assert_eq!(f.mode, p.mode, "mode at t = {}", f.t);
        theta_err = theta_err.max((f.state.y[layout::THETA] - p.state.y[layout::THETA]).abs());
        n_err = n_err.max((f.force.normal - p.force.normal).abs() / f.force.normal.abs());
    }
    // The two runs take different steps (the frozen states add nothing to the error norm), so
    // they differ by their integration errors, a few hundred times rtol where θ is smallest
    // and N peaks at a few hundred mg; a different equation would differ in the first digits.
    assert!(theta_err < 1e-9, "theta differs by {theta_err:e} rad");
    assert!(n_err < 1e-6, "N differs by {n_err:e} (relative)");
    eprintln!("largest differences: theta {theta_err:.1e} rad, N {n_err:.1e} (relative)");
}

#[test]
fn pruned_and_full_models_agree_on_the_papers_scene() {
    let params = DiskParams::paper();
    assert_eq!((params.mu_a, params.w_z), (0.0, 0.0));
    let config = tight(5.0);
    for chart in [SlipChart::Cartesian, SlipChart::Polar] {
        let full = GeneratedModels::generated(params, chart).unwrap();
        let pruned = PrunedModels::pruned(params, chart).unwrap();
        let (out_f, rec_f) = run(&full, &config);
        let (out_p, rec_p) = run(&pruned, &config);
        assert_eq!(out_f.stop, out_p.stop, "{chart:?}");
        assert!(
            rec_f.transitions.len() > 20,
            "{chart:?}: too few transitions to compare"
        );
        assert_same_decisions(&rec_f.transitions, &rec_p.transitions, 1e-9);
        assert_same_samples(&rec_f.samples, &rec_p.samples);
        assert_eq!(out_f.transitions, out_p.transitions);
    }
}

#[test]
fn dropped_states_stay_frozen_and_are_named() {
    let params = DiskParams::paper();
    let pruned = PrunedModels::pruned(params, SlipChart::Cartesian).unwrap();
    assert_eq!(pruned.frozen_states(), ["X", "Y", "Z", "phi"]);
    let polar = PrunedModels::pruned(params, SlipChart::Polar).unwrap();
    assert_eq!(polar.frozen_states(), ["X", "Y", "Z", "phi"]);

    let (_, record) = run(&pruned, &tight(0.5));
    let start = InitialState::paper(&params).state.y;
    let full = GeneratedModels::generated(params, SlipChart::Cartesian).unwrap();
    let (_, moving) = run(&full, &tight(0.5));
    for (p, f) in record.samples.iter().zip(&moving.samples).skip(1) {
        for i in [layout::X, layout::Y, layout::PHI] {
            assert_eq!(p.state.y[i], start[i], "state {i} moved at t = {}", p.t);
        }
        // The full model does move them: the check above can fail.
        assert!(f.state.y[layout::PHI] != start[layout::PHI] || f.t < 1e-3);
    }
}

#[test]
fn moving_air_is_refused_by_name() {
    for (name, params) in [
        (
            "mu_a",
            DiskParams {
                mu_a: 0.1,
                ..DiskParams::paper()
            },
        ),
        (
            "w_z",
            DiskParams {
                w_z: -0.5,
                ..DiskParams::paper()
            },
        ),
    ] {
        let err = PrunedModels::pruned(params, SlipChart::Cartesian).unwrap_err();
        assert!(
            matches!(err, PruneError::AirNotStill { name: n, .. } if n == name),
            "{err:?}"
        );
        assert!(err.to_string().contains(&format!("`{name}`")), "{err}");
    }
    let bad = DiskParams {
        m: -1.0,
        ..DiskParams::paper()
    };
    assert!(matches!(
        PrunedModels::pruned(bad, SlipChart::Polar),
        Err(PruneError::Params(_))
    ));
}
