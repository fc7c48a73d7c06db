//! The semantics oracle for compiled models: a fixed, seeded set of the random models of
//! `model-interpreted`'s oracle, compiled by `model!` (`oracle_models.rs`, written by that
//! generator), run by the switched driver and compared with the same reference driver, which
//! reads the models' numbers, not their text.

#[allow(dead_code)] // The generator's text side is the interpreted tests' concern.
#[path = "../../../model-runtime/interpreted/tests/suite/oracle/generate.rs"]
mod generate;
#[path = "../../../model-runtime/interpreted/tests/suite/oracle/reference.rs"]
mod reference;

use crate::oracle_models;
use generate::Model;
use model_runtime::Fired;
use reference::RefEnd;

#[test]
fn compiled_random_models_agree_with_the_reference_driver() {
    let t_end = 2.0;
    let mut compared = 0;
    for seed in oracle_models::SEEDS {
        let model = Model::random(seed);
        let (events, end) = reference::run(&model, t_end);
        let run = oracle_models::run(seed, t_end);
        let ran: Vec<_> = (run.events.iter())
            .filter(|e| matches!(e.fired, Fired::Reset | Fired::Stopped))
            .collect();
        for (k, want) in events.iter().enumerate() {
            let got = ran.get(k).unwrap_or_else(|| panic!("seed {seed}: event {k} missing"));
            assert_eq!(got.event, want.name, "seed {seed}: event {k}");
            assert!((got.t - want.t).abs() < 1e-7, "seed {seed}: event {k}: {} vs {}", got.t, want.t);
            for i in 0..2 {
                assert!((got.y[i] - want.y[i]).abs() < 1e-6, "seed {seed}: event {k}");
            }
            compared += 1;
        }
        match end {
            RefEnd::EndTime(y) => {
                assert_eq!((ran.len(), run.stopped_by.as_deref()), (events.len(), None), "seed {seed}");
                assert!((run.y[0] - y[0]).abs() < 1e-6 && (run.y[1] - y[1]).abs() < 1e-6, "seed {seed}");
            }
            RefEnd::Stop(name) => assert_eq!(run.stopped_by, Some(name), "seed {seed}"),
            RefEnd::Chatter | RefEnd::Unresolved(_) => {}
        }
    }
    assert!(compared > 5, "{compared} events compared");
}
