//! The disk's mode graph said in the DSL (`equations::disk`) against the hand-written system:
//! on the paper's scene at the default settings the same decisions, as many and at the same
//! times; the guards, clocks and first steps the DSL compiled equal the hand-written ones bit
//! for bit where the runs meet; and what the switched disk cannot run is refused by key.

use equations::{
    disk, simulate, simulate_switched, DiskConfig, DiskParams, DiskRecorder, GeneratedModels,
    InitialState, Integrator, SimError, SlipChart, SlipSign, Trigger,
};

/// Both runs of the paper's scene to `t_end` under `config`: the hand-written decisions'
/// times (the initial decision, which neither counts, left out) and the switched run's.
fn both(config: &DiskConfig) -> (Vec<f64>, u64, Vec<f64>) {
    let params = DiskParams::paper();
    let models = GeneratedModels::generated(params, SlipChart::Cartesian).unwrap();
    let initial = InitialState::paper(&params);
    let mut record = DiskRecorder::default();
    let out = simulate(&models, config, &initial, &mut record).unwrap();
    let hand: Vec<f64> = (record.transitions.iter())
        .filter(|r| !matches!(r.trigger, Trigger::InitialFriction { .. }))
        .map(|r| r.t)
        .collect();
    let switched = simulate_switched(&params, config, &initial).unwrap();
    assert_eq!(switched.stopped_by, None, "the switched run ends at t_end");
    assert_eq!(switched.t, config.t_end);
    (hand, out.transitions, switched.decisions())
}

/// The paper's 100 s scene at the default settings (DOP853, regularised time, rtol 1e-8,
/// atol 1e-10): the hand-written run's 7483 decisions, and the first 28 within 1e-9 s.
#[test]
fn the_paper_scene_decides_alike() {
    let config = DiskConfig {
        t_end: 100.0,
        sample_rate: None,
        ..DiskConfig::default()
    };
    let (hand, counted, switched) = both(&config);
    assert_eq!(counted, 7483, "the hand-written run's count changed");
    assert_eq!(hand.len() as u64, counted);
    assert_eq!(switched.len(), hand.len(), "decisions of the switched disk");
    let worst = (hand.iter().zip(&switched).take(28))
        .map(|(h, s)| (h - s).abs())
        .fold(0.0f64, f64::max);
    assert!(
        worst <= 1e-9,
        "first 28 decisions differ by up to {worst:e} s"
    );
    // Over the whole run they stay together to the tolerance's accuracy.
    let late = (hand.iter().zip(&switched))
        .map(|(h, s)| (h - s).abs())
        .fold(0.0f64, f64::max);
    eprintln!("first 28 within {worst:.1e} s, all 7483 within {late:.1e} s");
    assert!(late <= 1e-6, "decisions drift apart by {late:e} s");
}

/// The paper's own settings (DP5 in physical time), 10 s: the same decisions.
#[test]
fn the_papers_settings_decide_alike() {
    let config = DiskConfig {
        t_end: 10.0,
        sample_rate: None,
        ..DiskConfig::paper()
    };
    let (hand, _, switched) = both(&config);
    assert!(hand.len() > 100, "{} decisions in 10 s", hand.len());
    assert_eq!(switched.len(), hand.len());
    for (k, (h, s)) in hand.iter().zip(&switched).enumerate().take(28) {
        assert!((h - s).abs() <= 1e-9, "decision {k}: {h} against {s}");
    }
}

/// Every event of the switched run is one of its graph's and goes where the graph allows:
/// an onset leads to a bridge (or sliding at once), a stick through the bridge to the zero,
/// and the two bridges end in sliding and in a decision.
#[test]
fn the_events_follow_the_graph() {
    let params = DiskParams::paper();
    let config = DiskConfig {
        t_end: 2.0,
        ..DiskConfig::default()
    };
    let run = simulate_switched(&params, &config, &InitialState::paper(&params)).unwrap();
    assert!(run.events.len() > 50);
    for e in &run.events {
        let next = e.next.as_deref().unwrap();
        let allowed: &[&str] = match (e.mode.as_str(), e.event.as_str()) {
            ("rolling", "slips") => &["starting", "sliding"],
            ("sliding", "sticks") => &["stopping", "rolling", "starting", "sliding"],
            ("starting", "slides") => &["sliding"],
            ("stopping", "halts") => &["rolling", "starting", "sliding"],
            other => panic!("unexpected event {other:?} at t = {}", e.t),
        };
        assert!(allowed.contains(&next), "{e:?}");
    }
    assert_eq!(
        disk::MODE_NAMES,
        ["rolling", "sliding", "starting", "stopping"]
    );
    // The DSL prints the graph for a reader: every mode and event, the Rust maps named.
    for word in [
        "slips",
        "sticks",
        "slides",
        "halts",
        "by slip_onset",
        "by stick_or_slide",
    ] {
        assert!(disk::SWITCHING_MARKDOWN.contains(word), "{word}");
    }
}

/// What the switched disk cannot run is refused by key, before any step.
#[test]
fn air_and_other_settings_are_refused_by_key() {
    let still = DiskParams::paper();
    let initial = InitialState::paper(&still);
    let windy = DiskParams {
        mu_a: 1e-3,
        ..still
    };
    let config = DiskConfig {
        t_end: 0.1,
        ..DiskConfig::default()
    };
    let keys = |result: Result<_, equations::SimFailure>| match result.map(|_| ()) {
        Err(failure) => match failure.error {
            SimError::Invalid { issues } => issues.into_iter().map(|i| i.key).collect(),
            other => panic!("{other}"),
        },
        Ok(()) => Vec::<String>::new(),
    };
    assert_eq!(
        keys(simulate_switched(&windy, &config, &initial)),
        ["air.mu_a"]
    );
    let polar = DiskConfig {
        slip_sign: SlipSign::Paper,
        ..config
    };
    assert_eq!(
        keys(simulate_switched(&still, &polar, &initial)),
        ["run.slip_sign"]
    );
    let rodas = DiskConfig {
        integrator: Integrator::Rodas4,
        ..config
    };
    assert_eq!(
        keys(simulate_switched(&still, &rodas, &initial)),
        ["solver.integrator"]
    );
}
