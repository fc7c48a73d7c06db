//! Bad input to the library's `simulate`, the layer under the CLI.
//!
//! The scene loader and the `eval` command are fuzzed at the CLI (`tests/suite/scenes.rs`,
//! `tests/suite/cli_eval.rs`: random keys, types, NaN, ±inf, 1e400, random text) and the models at
//! non-finite states (`singular.rs`); what had no test is the library entry point itself, which
//! other programs call without those front ends. Any setting or initial component set to NaN,
//! ±inf, zero, a negative or a huge number must give a typed error naming it by the scene's key
//! (the same rules a scene is held to), or a run whose every number is finite; never a panic
//! or a hang (the work is bounded by a short horizon and a step budget).

use crate::common::extreme::{dop853, models, Watch};
use equations::{simulate, SimError};
use equations::{DiskConfig, InitialState};
use equations::{DiskParams, STATE_NAMES};
use proptest::prelude::*;

fn bad_number() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-1.0),
        Just(1e300),
        Just(-1e300),
        Just(1e-300),
        -10.0..10.0f64,
    ]
}

/// The configuration fields that take a number, by the key their issues name.
const FIELDS: [&str; 6] = [
    "solver.rtol",
    "solver.atol",
    "run.t_end",
    "stick_threshold",
    "min_inclination",
    "run.sample_rate",
];

/// The keys of the issues of a rejected setup.
fn keys(e: &SimError) -> Vec<String> {
    match e {
        SimError::Invalid { issues } => issues.iter().map(|i| i.key.clone()).collect(),
        _ => vec![],
    }
}

fn with_field(mut c: DiskConfig, field: &str, v: f64) -> DiskConfig {
    match field {
        "solver.rtol" => c.rtol = v,
        "solver.atol" => c.atol = v,
        "run.t_end" => c.t_end = v,
        "stick_threshold" => c.stick_threshold = v,
        "min_inclination" => c.min_inclination = v,
        "run.sample_rate" => c.sample_rate = Some(v),
        _ => unreachable!(),
    }
    c
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn a_bad_setting_is_named_or_the_run_is_finite(
        field in prop::sample::select(&FIELDS[..]),
        value in bad_number(),
    ) {
        let p = DiskParams::paper();
        let base = DiskConfig { max_steps: 20_000, sample_rate: Some(100.0), ..dop853(1e-8, 0.05) };
        let config = with_field(base, field, value);
        let mut watch = Watch::streaming();
        match simulate(&models(p), &config, &InitialState::paper(&p), &mut watch).map_err(SimError::from) {
            Ok(_) => prop_assert!(watch.first_non_finite.is_none(), "{field} = {value}"),
            // A huge end time is named through the sample count it would need, a huge atol
            // through the stick threshold that must stay above it; nothing else is named.
            Err(e @ SimError::Invalid { .. }) => {
                let keys = keys(&e);
                prop_assert!(
                    !keys.is_empty() && keys.iter().all(|k| k == field
                        || (field == "run.t_end" && k == "run.sample_rate")
                        || (field == "solver.atol" && k == "stick_threshold")),
                    "{field} = {value}: {keys:?}"
                )
            }
            // Legal but unworkable values (rtol 1e-300, a stick threshold of 1e-300 m/s, a huge
            // end time) end with a typed integration failure: a collapse or the step budget; a
            // stick threshold of 1e300 m/s with a singular pivot (`|u|² = inf`) at the start.
            Err(SimError::Solve { .. } | SimError::Transition { .. }) => {}
            Err(e) => prop_assert!(false, "{field} = {value}: {e}"),
        }
    }

    #[test]
    fn a_bad_initial_component_is_named_or_the_run_is_finite(
        component in 0usize..12,
        value in bad_number(),
    ) {
        let p = DiskParams::paper();
        let mut initial = InitialState::paper(&p);
        initial.state.y[component] = value;
        let config = DiskConfig { max_steps: 20_000, ..dop853(1e-8, 0.01) };
        let mut watch = Watch::streaming();
        match simulate(&models(p), &config, &initial, &mut watch).map_err(SimError::from) {
            Ok(_) => prop_assert!(watch.first_non_finite.is_none(), "y[{component}] = {value}"),
            Err(e @ SimError::Invalid { .. }) => prop_assert_eq!(
                keys(&e),
                vec![format!("initial.{}", STATE_NAMES[component])]
            ),
            // Huge rates: a typed integration failure (collapse, budget) is a named stop too.
            Err(SimError::Solve { .. } | SimError::Transition { .. } | SimError::Onset { .. }) => {}
            Err(e) => prop_assert!(false, "y[{component}] = {value}: {e}"),
        }
    }
}

/// Every sample is delivered, so 1e300 Hz over 0.05 s would ask for 5e298 samples and never
/// end (it did, before the rate was bounded against the horizon).
#[test]
fn an_absurd_sample_rate_is_rejected_by_name() {
    let p = DiskParams::paper();
    let config = DiskConfig {
        sample_rate: Some(1e300),
        ..dop853(1e-8, 0.05)
    };
    let result = simulate(&models(p), &config, &InitialState::paper(&p), &mut ());
    let error = result.unwrap_err().error;
    assert_eq!(keys(&error), ["run.sample_rate"], "{error}");
    assert!(
        error.to_string().contains("more than the sample limit 1e9"),
        "{error}"
    );
}
