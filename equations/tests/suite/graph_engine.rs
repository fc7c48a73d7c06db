//! The mode graph held to its reference: the disk's mode graph run through the observer
//! contract (`simulate_graph`, the main job's default engine) against the hand-written hybrid
//! system (`simulate`), through one recording observer, from three starts of the paper's
//! scene: the same run to the bit, decision for decision and step for step ([`assert_same`]
//! says why nothing less).

use equations::{
    simulate, simulate_graph, DiskConfig, DiskObserver, DiskParams, DiskSample, Engine, Extremum,
    GeneratedModels, InitialState, Integrator, Mode, RunOutcome, SimError, Slip, SlipChart,
    SlipSign, Trailing, TransitionRecord, GRAPH_ENGINE,
};

/// Everything a run hands its observer.
#[derive(Debug, Default, PartialEq)]
struct Everything {
    samples: Vec<DiskSample>,
    steps: Vec<DiskSample>,
    transitions: Vec<TransitionRecord>,
    extrema: Vec<Extremum>,
    /// The kept last steps, sampled on the run's grid.
    trailing: Vec<DiskSample>,
}

impl DiskObserver for Everything {
    fn on_sample(&mut self, sample: &DiskSample) {
        self.samples.push(*sample);
    }
    fn wants_steps(&self) -> bool {
        true
    }
    fn on_step(&mut self, sample: &DiskSample) {
        self.steps.push(*sample);
    }
    fn on_transition(&mut self, record: &TransitionRecord) {
        self.transitions.push(*record);
    }
    fn wants_extrema(&self) -> bool {
        true
    }
    fn on_extremum(&mut self, extremum: &Extremum) {
        self.extrema.push(*extremum);
    }
    fn keeps_trailing(&self) -> Option<f64> {
        Some(0.05)
    }
    fn on_trailing(&mut self, trailing: &Trailing<'_>) {
        if let Some((from, _)) = trailing.span() {
            let grid: Vec<f64> = trailing.grid(from).collect();
            let kept = grid.into_iter().filter_map(|t| trailing.sample(t)?.ok());
            self.trailing.extend(kept);
        }
    }
}

/// Both engines from `initial` under `config`, each through its own recorder.
fn both(
    params: DiskParams,
    config: &DiskConfig,
    initial: &InitialState,
) -> ((RunOutcome, Everything), (RunOutcome, Everything)) {
    let models = GeneratedModels::generated(params, SlipChart::Cartesian).unwrap();
    let mut hand = Everything::default();
    let reference = simulate(&models, config, initial, &mut hand).unwrap();
    let mut graph = Everything::default();
    let main = simulate_graph(&models, config, initial, &mut graph).unwrap();
    ((reference, hand), (main, graph))
}

/// `a` and `b` to the bit, element by element: `Debug` prints each `f64` as the shortest text
/// that reads back to its bits, so two records print alike exactly when every number in them
/// is the same `f64` (`0.0` and `-0.0` apart). Names the first element that differs.
fn assert_bitwise<T: std::fmt::Debug>(what: &str, a: &[T], b: &[T]) {
    let text = |x: &T| format!("{x:?}");
    if let Some(k) = (0..a.len().min(b.len())).find(|&k| text(&a[k]) != text(&b[k])) {
        panic!("{what} {k}: {:?}\nagainst {:?}", a[k], b[k]);
    }
    assert_eq!(a.len(), b.len(), "{what}s");
}

/// The two runs are the same run, to the bit: every decision (time, modes, trigger, slip and
/// rolling directions, drift), every step and sample, the trailing steps, every extremum, the
/// stop, the last state, the count, the largest drift, the steps taken and rejected.
///
/// Why nothing less: the engines do the same arithmetic. The modes integrate the `still`
/// variants' right-hand sides (one source of rows, the air compiled out alike: unit test
/// `hybrid::switching::tests::the_modes_right_hand_sides_are_the_still_variants_to_the_bit`);
/// the guards, clocks and first steps round as the hand-written ones (the first step after a
/// bridge `max(3 v_C, 0)/hypot(u̇)`, the still-air friction margin as the graph's `slips`
/// compiles); the decisions are the hand-written maps'. So a difference of one ulp is a
/// difference in what the graph says, and it shows: before these were aligned, the first
/// step's grouping alone moved every decision after the first bridge by ~1e-13 s. Only the
/// work beside the steps may differ (the hand-written system evaluates the guards once more
/// when a mode starts). Above `mu_st = 1` the hand-written margin is scaled (`T/mu_st - N`)
/// and so is the graph's (`a_high_grip_runs_alike`).
fn assert_same(
    (reference, hand): &(RunOutcome, Everything),
    (main, graph): &(RunOutcome, Everything),
) {
    assert!(
        hand.transitions.len() > 20,
        "{} decisions",
        hand.transitions.len()
    );
    assert_bitwise("decision", &hand.transitions, &graph.transitions);
    assert_bitwise("step", &hand.steps, &graph.steps);
    assert_bitwise("sample", &hand.samples, &graph.samples);
    assert_bitwise("trailing sample", &hand.trailing, &graph.trailing);
    assert_bitwise("extremum", &hand.extrema, &graph.extrema);
    let outcome = |o: &RunOutcome| {
        let (stop, last, drift, stats) = (&o.stop, &o.last, &o.max_drift, &o.stats);
        let (steps, rejected) = (stats.steps, stats.rejected);
        format!(
            "{stop:?} {last:?} {drift:?} {} {steps} {rejected}",
            o.transitions
        )
    };
    assert_eq!(outcome(reference), outcome(main));
    eprintln!(
        "to the bit: {} decisions, {} steps, {} samples, {} extrema",
        hand.transitions.len(),
        hand.steps.len(),
        hand.samples.len(),
        hand.extrema.len()
    );
}

/// The paper's scene at the main job's settings (DOP853, regularised time), 15 s: it starts
/// on a bridge (rolling would need more friction than static friction gives). The main job's
/// files are the same to the byte whichever engine writes them because of this.
#[test]
fn the_paper_scene_from_a_bridge_runs_alike() {
    let params = DiskParams::paper();
    let config = DiskConfig {
        t_end: 15.0,
        sample_rate: Some(200.0),
        ..DiskConfig::default()
    };
    let initial = InitialState::paper(&params);
    let (reference, main) = both(params, &config, &initial);
    assert_eq!(main.1.transitions[0].from, Mode::Rolling);
    assert_eq!(main.1.transitions[0].to, Mode::Sliding);
    assert_same(&reference, &main);
}

/// The paper's start with a slip well above the stick threshold (0.05 m/s).
fn sliding_start(params: &DiskParams) -> InitialState {
    let paper = InitialState::paper(params);
    let slip = Slip {
        speed: 0.05,
        direction: 1.0,
    };
    InitialState::sliding(params, 0.0, paper.state.y, slip)
}

/// The paper's scene with the paper's settings (DP5, physical time), from a sliding start
/// (a slip well above the stick threshold), 10 s.
#[test]
fn a_sliding_start_runs_alike() {
    let params = DiskParams::paper();
    let config = DiskConfig {
        t_end: 10.0,
        sample_rate: Some(200.0),
        ..DiskConfig::paper()
    };
    let initial = sliding_start(&params);
    let (reference, main) = both(params, &config, &initial);
    assert_same(&reference, &main);
}

/// A rolling start (static friction high enough to hold the paper's start) that later
/// slides, 10 s.
#[test]
fn a_rolling_start_runs_alike() {
    let params = DiskParams {
        mu_st: 0.9,
        ..DiskParams::paper()
    };
    let config = DiskConfig {
        t_end: 10.0,
        sample_rate: Some(200.0),
        ..DiskConfig::default()
    };
    let initial = InitialState::paper(&params);
    let (reference, main) = both(params, &config, &initial);
    assert!(
        main.1.transitions.iter().all(|r| r.t > 0.0),
        "no decision at the start"
    );
    assert_same(&reference, &main);
}

/// A grip above 1 (`mu_st = 1.5`, where the friction margin is divided by `mu_st`), from a
/// sliding start: the slip stops and the disk rolls, 2 s.
#[test]
fn a_high_grip_runs_alike() {
    let params = DiskParams {
        mu_st: 1.5,
        ..DiskParams::paper()
    };
    let config = DiskConfig {
        t_end: 2.0,
        sample_rate: Some(200.0),
        ..DiskConfig::default()
    };
    let initial = sliding_start(&params);
    let (reference, main) = both(params, &config, &initial);
    assert_same(&reference, &main);
}

/// Which engine a run gets: the graph where it models the run, the hand-written system
/// (named as such) elsewhere; the graph refuses the rest by key.
#[test]
fn the_engine_is_chosen_by_what_the_graph_models() {
    let still = DiskParams::paper();
    let config = DiskConfig::default();
    assert_eq!(Engine::for_run(&still, &config), Engine::ModeGraph);
    assert_eq!(Engine::ModeGraph.name(), GRAPH_ENGINE);
    let windy = DiskParams { w_z: 0.1, ..still };
    assert_eq!(Engine::for_run(&windy, &config), Engine::HandWritten);
    let others = [
        DiskConfig {
            slip_sign: SlipSign::Paper,
            ..config
        },
        DiskConfig {
            integrator: Integrator::Rodas4,
            ..config
        },
        DiskConfig {
            project_each_step: true,
            ..config
        },
    ];
    for other in others {
        assert_eq!(
            Engine::for_run(&still, &other),
            Engine::HandWritten,
            "{other:?}"
        );
        let models = GeneratedModels::generated(still, other.chart()).unwrap();
        let initial = InitialState::paper(&still);
        let failure = simulate_graph(&models, &other, &initial, &mut ()).unwrap_err();
        assert!(
            matches!(failure.error, SimError::Invalid { .. }),
            "{failure}"
        );
    }
}
