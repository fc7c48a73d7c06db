//! The paper's numbers (its column in the summary, the reference values in Fig. 10's legend,
//! the sound's printed and plotted rates) appear for the paper's scene only: another disk has
//! other numbers, and quoting the paper's beside them would read as a comparison.

use std::sync::atomic::AtomicBool;

use crate::quiet_run::{run_quietly, Quiet};
use eulerdisk::{load_scene, sound_scene, Backend, Override, SoundOptions, DEFAULT_SCENE};

/// The paper's scene shortened to `t_end`, with `μ_st` changed when `mu_st` is given.
fn scene_overrides(t_end: f64, mu_st: Option<f64>) -> Vec<Override> {
    let mut o = vec![Override::new("run", "t_end", t_end)];
    o.extend(mu_st.map(|mu| Override::new("friction", "mu_st", mu)));
    o
}

/// Whether a text quotes the paper's numbers ("paper 149 s⁻¹, recorded sound 154 s⁻¹").
fn quotes_the_paper(text: &str) -> bool {
    text.contains("paper") || text.contains("recorded")
}

#[test]
fn the_run_quotes_the_paper_only_for_the_papers_scene() {
    for (mu_st, expected) in [(None, true), (Some(0.3), false)] {
        let overrides = scene_overrides(2.0, mu_st);
        let scene = load_scene(DEFAULT_SCENE, &overrides).unwrap();
        let how = Quiet {
            figures: true,
            ..Quiet::default()
        };
        let (dir, report) = run_quietly(&scene, &overrides, how, &AtomicBool::new(false));
        let s = &report.summary;
        assert_eq!(s.compared_with_paper, expected, "μ_st {mu_st:?}");
        assert_eq!(
            s.table().contains("paper"),
            expected,
            "μ_st {mu_st:?}:\n{}",
            s.table()
        );
        // Fig. 10's legend: the located rate, and the paper's only for its scene.
        let fig10 =
            std::fs::read_to_string(dir.path().join("fig10_normal_force_last_second.svg")).unwrap();
        assert!(fig10.contains("2π/T = "), "Fig. 10 legend");
        assert_eq!(
            quotes_the_paper(&fig10),
            expected,
            "Fig. 10, μ_st {mu_st:?}"
        );
    }
}

#[test]
fn the_sound_quotes_the_paper_only_for_the_papers_scene() {
    for (mu_st, expected) in [(None, true), (Some(0.3), false)] {
        let scene = load_scene(DEFAULT_SCENE, &scene_overrides(1.5, mu_st)).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let report = sound_scene(
            &scene,
            Backend::Generated,
            &SoundOptions::default(),
            dir.path(),
        )
        .unwrap();
        let s = &report.summary;
        assert_eq!(s.paper.is_some(), expected, "μ_st {mu_st:?}");
        let table = s.table();
        assert_eq!(table.contains("paper"), expected, "{table}");
        let json = std::fs::read_to_string(dir.path().join("sound_summary.json")).unwrap();
        let parsed: serde_json::Value = serde_json::from_str(&json).unwrap();
        assert_eq!(parsed["paper"].is_null(), !expected, "{json}");
        assert!(dir.path().join("sound_peak_rate.png").is_file());
    }
}
