//! An independent oracle for the semantics of switched models: random models
//! ([`generate`]) solved by the interpreter and by a reference driver written only for this
//! ([`reference`]), compared on their event sequences (names, times to 1e-7 s, states) and on
//! how and where they end. A bounded set runs with the suite; the campaign
//! (`cargo test -p model-interpreted --test suite oracle_campaign -- --ignored`, with
//! `ORACLE_MODELS=N` models from `ORACLE_SEED`) prints its tally. The compiled leg
//! ([`compiled`]): the first [`COMPILED`] models, written as `model!` invocations into a
//! source file that a test keeps equal to the generator's output, run by `run_switched` and
//! held to the interpreter's events.

mod compiled;
mod generate;
mod reference;

use crate::compile;
use generate::Model;
use model_interpreted::{solve, EventKind, SolveFailure, SolveRequest, Stop};
use model_runtime::Fired;
use reference::{RefEnd, Ties, RESOLVED};

/// The span of every run.
const T_END: f64 = 2.0;

/// What comparing one model gave.
#[derive(Clone, Debug, PartialEq)]
enum Verdict {
    /// Every event and the end agree.
    Agree,
    /// The events agree up to where the reference cannot judge (the reason).
    AgreeUntil(&'static str),
    /// A disagreement, described.
    Disagree(String),
}

/// The interpreter's run of `model` against the reference's.
fn compare(model: &Model) -> Verdict {
    compare_with(model, Ties::Unresolved)
}

/// As [`compare`], with the reference's surface ties taken as `ties` says.
fn compare_with(model: &Model, ties: Ties) -> Verdict {
    let text = model.text();
    let file = compile("rnd.dsl", &text);
    let mut request = SolveRequest::new(T_END);
    (request.rtol, request.atol) = (1e-11, 1e-13);
    let solved = solve(file.model(None).unwrap(), &request);
    let (events, end) = reference::run_with(model, T_END, ties);
    let ran = match &solved {
        Ok(s) => (s.events.iter())
            .filter(|e| e.kind == EventKind::Crossing)
            .map(|e| (e.name.clone(), e.row[0], [e.row[1], e.row[2]]))
            .collect::<Vec<_>>(),
        Err(SolveFailure::Run(_)) => Vec::new(),
        Err(other) => return Verdict::Disagree(format!("fails: {other}")),
    };
    let failed = |what: String| {
        let mut what = format!("{what}\n{text}");
        if std::env::var_os("ORACLE_VERBOSE").is_some() {
            what += &format!("reference ({end:?}):\n");
            for e in &events {
                what += &format!("  {} {:.17} {:?}\n", e.name, e.t, e.y);
            }
            what += &format!("interpreter ({:?}):\n", solved.as_ref().map(|s| &s.stop));
            for (name, t, y) in &ran {
                what += &format!("  {name} {t:.17} {y:?}\n");
            }
        }
        Verdict::Disagree(what)
    };
    for (k, want) in events.iter().enumerate() {
        let Some((name, t, y)) = ran.get(k) else {
            if solved.is_err() && matches!(end, RefEnd::Unresolved(_)) {
                // A failure (which keeps no events) where the reference cannot judge either.
                return Verdict::AgreeUntil("a failure beyond what the reference judges");
            }
            if solved.is_err() {
                // A failure before: allowed only for a chatter the reference sees too.
                if end == RefEnd::Chatter {
                    return Verdict::Agree;
                }
                return failed(format!("failed before event {k} {want:?}: {solved:?}"));
            }
            return failed(format!("event {k} missing: {want:?}"));
        };
        let close = (t - want.t).abs() < 1e-7
            && (y[0] - want.y[0]).abs() < 1e-6
            && (y[1] - want.y[1]).abs() < 1e-6;
        if *name != want.name || !close {
            return failed(format!(
                "event {k}: {name} at {t} {y:?}, reference {} at {} {:?}",
                want.name, want.t, want.y
            ));
        }
    }
    let extra = ran.get(events.len());
    match (&end, &solved) {
        (RefEnd::Unresolved(why), _) => Verdict::AgreeUntil(why),
        (RefEnd::Chatter, Err(SolveFailure::Run(_))) => Verdict::Agree,
        (RefEnd::EndTime(y), Ok(s)) if s.stop == Stop::EndTime && extra.is_none() => {
            let last = s.last_row().unwrap();
            if (last[1] - y[0]).abs() < 1e-6 && (last[2] - y[1]).abs() < 1e-6 {
                Verdict::Agree
            } else {
                failed(format!("end state {:?} vs {y:?}", &last[1..3]))
            }
        }
        (RefEnd::Stop(name), Ok(s)) if extra.is_none() => match &s.stop {
            Stop::Event {
                name: got,
                kind: EventKind::Crossing,
            } if got == name => Verdict::Agree,
            other => failed(format!("stop {other:?}, reference {name}")),
        },
        (_, Ok(s)) => {
            // An accumulation the interpreter declared after the last compared event: the
            // reference stops comparing once events come closer than it resolves.
            let close =
                extra.is_some_and(|e| events.last().is_some_and(|last| e.1 - last.t < RESOLVED));
            if close {
                Verdict::AgreeUntil("events closer than the fixed step resolves")
            } else {
                failed(format!(
                    "end {:?} (next {extra:?}), reference {end:?}",
                    s.stop
                ))
            }
        }
        (_, Err(e)) => failed(format!("failed: {e}; reference {end:?}")),
    }
}

/// The tally of a set of models.
#[derive(Debug, Default)]
struct Tally {
    agree: usize,
    agree_until: std::collections::BTreeMap<&'static str, usize>,
    disagree: Vec<(u64, String)>,
    events: usize,
}

fn campaign(seeds: impl Iterator<Item = u64>) -> Tally {
    let mut tally = Tally::default();
    let trace = std::env::var_os("ORACLE_TRACE").is_some();
    for seed in seeds {
        if trace {
            eprintln!("seed {seed}");
        }
        let model = Model::random(seed);
        tally.events += reference::run(&model, T_END).0.len();
        match compare(&model) {
            Verdict::Agree => tally.agree += 1,
            Verdict::AgreeUntil(why) => *tally.agree_until.entry(why).or_default() += 1,
            Verdict::Disagree(what) => tally.disagree.push((seed, what)),
        }
    }
    tally
}

#[test]
fn random_models_agree_with_the_reference_driver() {
    let tally = campaign(0..120);
    assert!(tally.disagree.is_empty(), "{:#?}", tally.disagree);
    // The comparison is not vacuous: most models are compared to their end.
    assert!(tally.agree > 60, "{tally:?}");
    assert!(tally.events > 200, "{tally:?}");
}

/// The campaign's disagreements, each fixed and kept: a guard left a few ulps to one side of
/// its surface by an event located there, when a mode is entered at that instant, read as
/// holding (an immediate switch back, a chatter the reference does not see: 1000152) or as
/// not departing (an `==` guard leaving through its surface unseen, a chatter missed:
/// 1000020, 1000237, 1000365).
#[test]
fn the_campaigns_disagreements_are_fixed() {
    for seed in [1_000_020, 1_000_152, 1_000_237, 1_000_365] {
        // The campaign calls these surface ties (beyond what it judges); taken as the
        // reference computes them, exactly on the surface, the interpreter agrees.
        let model = Model::random(seed);
        assert_eq!(
            compare_with(&model, Ties::AsComputed),
            Verdict::Agree,
            "seed {seed}"
        );
    }
}

/// The campaign's later disagreements, each a tie below what the reference resolves, now
/// judged as such (the events before it compared): a guard within rounding of its surface on
/// entry, a departure that turns within the fixed step, a thin excursion before a crossing
/// (1002877). None may turn into a disagreement again.
#[test]
fn the_campaigns_ties_are_judged_not_compared() {
    let seeds = [
        1_002_877, 1_003_448, 1_003_558, 1_003_767, 1_003_807, 1_004_241, 1_004_367, 1_004_445,
        1_004_497, 1_006_404, 1_006_638, 1_006_716, 1_007_081, 1_007_308, 1_007_559, 1_007_671,
        1_007_778, 1_008_402,
    ];
    for seed in seeds {
        let verdict = compare(&Model::random(seed));
        assert!(
            !matches!(verdict, Verdict::Disagree(_)),
            "seed {seed}: {verdict:?}"
        );
    }
}

#[test]
#[ignore = "the campaign: minutes; run by hand"]
fn oracle_campaign() {
    let var = |name: &str, default: u64| {
        std::env::var(name)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let (count, seed) = (var("ORACLE_MODELS", 10_000), var("ORACLE_SEED", 1_000_000));
    let tally = campaign(seed..seed + count);
    println!(
        "{count} models from seed {seed}: {} agree to the end, {:?} agree until the reference \
         stops judging, {} disagree; {} reference events",
        tally.agree,
        tally.agree_until,
        tally.disagree.len(),
        tally.events
    );
    for (seed, what) in tally.disagree.iter().take(20) {
        println!("seed {seed}: {what}");
    }
    assert!(tally.disagree.is_empty());
}

/// How many of the generator's models (seeds `0..COMPILED`) the compiled leg holds.
const COMPILED: u64 = 40;

/// The compiled leg's source: each model as a `model!` invocation, and the function that runs
/// one by its seed.
fn compiled_source() -> String {
    let mut s = String::from(
        "//! The oracle's compiled leg, written by the generator (`ORACLE_BLESS=1 cargo test -p \
         model-interpreted\n//! --test suite compiled_leg_is_the_generators` writes it again): \
         the first models of\n//! `generate`, compiled by `model!`, and their runs by seed.\n\n\
         use model_macros::model;\nuse model_runtime::{\n    run_switched, Const, Dop853, \
         HybridOptions, SwitchedFailure, SwitchedRun, Tolerance,\n};\n",
    );
    for seed in 0..COMPILED {
        let text = Model::random(seed).text_named(&format!("rnd_{seed}"));
        s += &format!("\nmodel! {{\n{text}}}\n");
    }
    s += "\n/// The compiled run of the model of `seed` to `t_end` at rtol 1e-11, atol 1e-13 (`None`: \
          not compiled).\npub fn run(\n    seed: u64,\n    t_end: f64,\n) -> \
          Option<Result<SwitchedRun<Const<2>>, SwitchedFailure<Const<2>>>> {\n    \
          macro_rules! go {\n        ($m:ident) => {\n            Some(run_switched(\n                \
          $m::Model::default(),\n                Dop853::new(),\n                \
          Tolerance::scalar(1e-11, 1e-13),\n                HybridOptions::default(),\n                \
          (0.0, $m::INITIAL),\n                t_end,\n            ))\n        };\n    }\n    \
          match seed {\n";
    for seed in 0..COMPILED {
        s += &format!("        {seed} => go!(rnd_{seed}),\n");
    }
    s + "        _ => None,\n    }\n}\n"
}

#[test]
fn compiled_leg_is_the_generators() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/suite/oracle/compiled.rs"
    );
    let want = compiled_source();
    if std::env::var_os("ORACLE_BLESS").is_some() {
        std::fs::write(path, &want).unwrap();
    }
    let have = std::fs::read_to_string(path).unwrap();
    assert!(
        have == want,
        "{path} is not the generator's output: ORACLE_BLESS=1 writes it again"
    );
}

/// The compiled leg: each model compiled by `model!` and run by `run_switched` meets the same
/// events as the interpreter (names; times to 1e-9 s, states to 1e-8: the same runtime, the
/// same steps, another evaluation of the same expressions) and ends alike; the interpreter
/// is held to the reference by the tests above, on the same models.
#[test]
fn compiled_models_meet_the_interpreters_events() {
    let mut compared = 0;
    for seed in 0..COMPILED {
        let model = Model::random(seed);
        let file = compile("rnd.dsl", &model.text());
        let mut request = SolveRequest::new(T_END);
        (request.rtol, request.atol) = (1e-11, 1e-13);
        let interpreted = solve(file.model(None).unwrap(), &request);
        let compiled = compiled::run(seed, T_END).unwrap();
        let (ran, failed) = match &interpreted {
            Ok(s) => (s.events.clone(), false),
            Err(SolveFailure::Run(f)) => (
                f.partial
                    .as_ref()
                    .map(|p| p.events.clone())
                    .unwrap_or_default(),
                true,
            ),
            Err(other) => panic!("seed {seed}: {other}"),
        };
        let crossings: Vec<_> = ran
            .iter()
            .filter(|e| e.kind == EventKind::Crossing)
            .collect();
        let (events, ended) = match &compiled {
            Ok(run) => (&run.events, true),
            Err(f) => (&f.events, false),
        };
        assert_eq!(
            ended, !failed,
            "seed {seed}: {interpreted:?} vs {compiled:?}"
        );
        let fired: Vec<_> = events
            .iter()
            .filter(|e| !matches!(e.fired, Fired::Accumulated | Fired::AccumulatedStop))
            .collect();
        assert_eq!(
            fired.len(),
            crossings.len(),
            "seed {seed}: {fired:?} vs {crossings:?}"
        );
        for (c, i) in fired.iter().zip(&crossings) {
            let close = (c.t - i.row[0]).abs() < 1e-9
                && (c.y[0] - i.row[1]).abs() < 1e-8
                && (c.y[1] - i.row[2]).abs() < 1e-8;
            assert!(c.event == i.name && close, "seed {seed}: {c:?} vs {i:?}");
            compared += 1;
        }
    }
    assert!(compared > 100, "{compared} events compared");
}
