//! The mode graph held to its reference: the disk's mode graph run through the observer
//! contract (`simulate_graph`) against the hand-written hybrid system (`simulate`), on the
//! paper's scene, through one recording observer: decision for decision (time, modes,
//! trigger), the stop, the count, the samples, the extrema, the trailing steps and the
//! largest drift, to the tolerances [`T`] and [`REL`] justify — and at the main job's
//! settings to the bit.

use equations::{
    simulate, simulate_graph, DiskConfig, DiskObserver, DiskParams, DiskSample, Engine, Extremum,
    GeneratedModels, InitialState, Integrator, Mode, RunOutcome, SimError, Slip, SlipChart,
    SlipSign, Trailing, TransitionRecord, Watched, GRAPH_ENGINE,
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

/// How far the main path may stray from its reference where the two round differently. The
/// engines do the same arithmetic but for one guard: the graph's `slips` is compiled as
/// `sqrt(der(V_X)^2*m^2 + m^2*der(V_Y)^2) - m*mu_st*(der(V_Z) + g)`, the hand-written one is
/// `hypot`-free `sqrt((m V̇_X)² + (m V̇_Y)²) - mu_st (m (V̇_Z + g))` (or `T/mu_st - N` above
/// `mu_st = 1`): the same zero, rounded apart. Where the root search lands on the same bits
/// anyway (the main job's settings: [`the_paper_scene_from_a_bridge_runs_alike`]), the runs
/// are the same to the bit; elsewhere an event may move by an ulp, and the rattling amplifies
/// it. The decisions land within 3e-13 s of each other over the runs below (the tolerance
/// leaves a factor 30), and the states agree to 1e-6 of their scale, far inside the
/// integration's own error (rtol 1e-8) and far too tight to hide a real difference: a
/// decision taken differently moves a time by its whole segment, ms, not ps.
const T: f64 = 1e-11;
/// The relative tolerance of sampled states and forces (scale: the value, or 1).
const REL: f64 = 1e-6;
/// How far apart the same extremum may be located (s).
const EXTREMUM_T: f64 = 1e-6;

/// Whether `a` and `b` agree to `REL` (relative to the larger, or 1 below it).
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= REL * a.abs().max(b.abs()).max(1.0)
}

/// The two samples agree: time, mode, state, slip, force and energy.
fn same_sample(h: &DiskSample, g: &DiskSample) -> bool {
    let pairs = (h.state.y.iter().zip(&g.state.y)).chain([
        (&h.state.slip.speed, &g.state.slip.speed),
        (&h.force.r_x, &g.force.r_x),
        (&h.force.r_y, &g.force.r_y),
        (&h.force.normal, &g.force.normal),
        (&h.energy, &g.energy),
    ]);
    h.t == g.t && h.mode == g.mode && pairs.into_iter().all(|(a, b)| close(*a, *b))
}

/// The two runs agree: decision for decision, the stop, the count, every sample and every
/// extremum (within [`T`] and [`REL`]); returns the largest decision time difference.
fn assert_same(
    (reference, hand): &(RunOutcome, Everything),
    (main, graph): &(RunOutcome, Everything),
) -> f64 {
    assert!(
        hand.transitions.len() > 20,
        "{} decisions",
        hand.transitions.len()
    );
    let mut worst: f64 = 0.0;
    for (k, (h, g)) in hand.transitions.iter().zip(&graph.transitions).enumerate() {
        let same_kind = std::mem::discriminant(&h.trigger) == std::mem::discriminant(&g.trigger);
        assert!(
            h.from == g.from && h.to == g.to && same_kind,
            "decision {k}: {h:?}\nagainst {g:?}"
        );
        assert!((h.t - g.t).abs() <= T, "decision {k}: {h:?}\nagainst {g:?}");
        assert_eq!(
            h.slip_direction.is_some(),
            g.slip_direction.is_some(),
            "decision {k}"
        );
        worst = worst.max((h.t - g.t).abs());
    }
    assert_eq!(hand.transitions.len(), graph.transitions.len(), "decisions");
    assert_eq!(reference.transitions, main.transitions, "counted decisions");
    assert_eq!(reference.stop.name(), main.stop.name());
    assert!(
        same_sample(&reference.last, &main.last),
        "{:?}\nagainst {:?}",
        reference.last,
        main.last
    );
    for (name, h, g) in [
        ("sample", &hand.samples, &graph.samples),
        ("trailing sample", &hand.trailing, &graph.trailing),
    ] {
        assert_eq!(h.len(), g.len(), "{name}s");
        if let Some(k) = (0..h.len()).find(|&k| !same_sample(&h[k], &g[k])) {
            panic!("{name} {k}: {:?}\nagainst {:?}", h[k], g[k]);
        }
    }
    let unmatched = |of: &[Extremum], among: &[Extremum]| -> Vec<Extremum> {
        (of.iter())
            .filter(|h| {
                !among.iter().any(|g| {
                    g.quantity == h.quantity
                        && g.kind == h.kind
                        && (g.t - h.t).abs() <= EXTREMUM_T
                        && close(g.value, h.value)
                })
            })
            .copied()
            .collect()
    };
    let lost = unmatched(&hand.extrema, &graph.extrema);
    let extra = unmatched(&graph.extrema, &hand.extrema);
    // The one kind that may be found by one run and not the other: the slip speed's minimum
    // where sliding ends at the stick threshold δ, a touch whose bracket round-off decides.
    let at_threshold = |e: &Extremum| {
        e.quantity == Watched::SlipSpeed
            && (e.value - DiskConfig::default().stick_threshold).abs() <= 1e-15
    };
    for e in lost.iter().chain(&extra) {
        assert!(at_threshold(e), "extremum found by one engine only: {e:?}");
    }
    assert!(
        lost.len() + extra.len() <= 5,
        "{} extrema found by one engine only",
        lost.len() + extra.len()
    );
    // The largest drift is a maximum over steps whose states agree to round-off: to 1e-3.
    let (d_ref, d_main) = (reference.max_drift.max_abs(), main.max_drift.max_abs());
    assert!(
        (d_ref - d_main).abs() <= 1e-3 * d_ref.max(d_main),
        "{:?} against {:?}",
        reference.max_drift,
        main.max_drift
    );
    eprintln!(
        "{} decisions within {worst:.1e} s, {} samples, {} extrema; {} steps against {}",
        hand.transitions.len(),
        hand.samples.len(),
        hand.extrema.len(),
        reference.stats.steps,
        main.stats.steps
    );
    worst
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

/// The paper's scene at the main job's settings (DOP853, regularised time), 15 s: it starts
/// on a bridge (rolling would need more friction than static friction gives). Here the two
/// engines are the same run to the bit — every decision, step, sample, trailing sample and
/// extremum, the outcome — as the main job's files are the same to the byte whichever engine
/// writes them (only the work beside the steps differs: the hand-written system evaluates
/// the guards once more when a mode starts). The modes integrate the `still` variants'
/// right-hand sides to the bit (unit test in `hybrid::switching`), and the first step after
/// a bridge rounds as the hand-written one (`3 (v_C / |u̇|)`); a regrouping there is what
/// moved every decision after the first bridge by an ulp before.
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
    let ((reference, hand), (main, graph)) = (reference, main);
    assert_bitwise("decision", &hand.transitions, &graph.transitions);
    assert_bitwise("step", &hand.steps, &graph.steps);
    assert_bitwise("sample", &hand.samples, &graph.samples);
    assert_bitwise("trailing sample", &hand.trailing, &graph.trailing);
    assert_bitwise("extremum", &hand.extrema, &graph.extrema);
    let outcome = |o: &RunOutcome| {
        let s = &o.stats;
        let (stop, last, drift) = (&o.stop, &o.last, &o.max_drift);
        format!("{stop:?} {last:?} {drift:?}, {} decisions, {} steps, {} rejected", o.transitions, s.steps, s.rejected)
    };
    assert_eq!(outcome(&reference), outcome(&main));
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
    let paper = InitialState::paper(&params);
    let slip = Slip {
        speed: 0.05,
        direction: 1.0,
    };
    let initial = InitialState::sliding(&params, 0.0, paper.state.y, slip);
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
