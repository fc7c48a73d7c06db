//! `eulerdisk eval` as a user runs it: valid states print every derivative and output under
//! the paper's names, numbers that parse back to the same bits, and every bad input is a
//! non-zero exit with a message naming the key. States and parameters are `NAME=VALUE` items,
//! as in `model eval`; the old JSON objects are still read, with a note.

use std::process::{Command, Output};

use equations::Mode;
use eulerdisk::{evaluate, parse_named_numbers, parse_params, parse_state, Backend};
use proptest::prelude::*;
use serde_json::Value;

fn eval(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .arg("eval")
        .args(args)
        .output()
        .unwrap()
}

fn ok_json(args: &[&str]) -> Value {
    let out = eval(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn rejected(args: &[&str], key: &str) -> String {
    let out = eval(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(out.stdout.is_empty(), "printed despite the error");
    assert!(err.contains(&format!("`{key}`")), "{key} not named: {err}");
    assert!(!err.contains("panicked"), "{err}");
    err
}

const PAPER_STATE: [&str; 3] = ["theta=0.5707963267948966", "Omega_x=1", "Z=0.020409"];

/// `args` followed by `--state ITEM` for every item of `state`.
fn with_state<'a>(args: &[&'a str], state: &[&'a str]) -> Vec<&'a str> {
    let mut all = args.to_vec();
    for item in state {
        all.extend(["--state", item]);
    }
    all
}

fn owned(items: &[&str]) -> Vec<String> {
    items.iter().map(|s| s.to_string()).collect()
}

#[test]
fn rolling_prints_every_name() {
    let v = ok_json(&with_state(&["--mode", "rolling"], &PAPER_STATE));
    assert_eq!(v["mode"], "rolling");
    let names = [
        "X", "Y", "Z", "V_X", "V_Y", "V_Z", "psi", "theta", "phi", "Omega_x", "Omega_y", "Omega_z",
    ]
    .map(|n| format!("der({n})"));
    let d = v["derivatives"].as_object().unwrap();
    let mut sorted = names.clone();
    sorted.sort_unstable();
    assert_eq!(
        d.keys().collect::<Vec<_>>(),
        sorted.iter().collect::<Vec<_>>()
    );
    // Printed in the model's order.
    let out = eval(&with_state(&["--mode", "rolling"], &PAPER_STATE));
    let text = String::from_utf8(out.stdout).unwrap();
    let at = |k: &str| text.find(&format!("\"{k}\":")).unwrap();
    assert!(names.windows(2).all(|w| at(&w[0]) < at(&w[1])), "{text}");
    for key in ["N", "T", "nu", "energy"] {
        assert!(v["outputs"][key].as_f64().unwrap().is_finite(), "{key}");
    }
    // docs/physics.md §11: rolling would need nu = 0.8355, N/mg = 0.4345 at the paper's start.
    let nu = v["outputs"]["nu"].as_f64().unwrap();
    assert!((nu - 0.8355).abs() < 5e-4, "{nu}");
    let n = v["outputs"]["N"].as_f64().unwrap() / (0.4387 * 9.81);
    assert!((n - 0.4345).abs() < 5e-4, "{n}");
    assert_eq!(
        d["der(theta)"].as_f64(),
        Some(0.0),
        "der(theta) = Omega_y = 0"
    );
}

#[test]
fn sliding_uses_slip_speed_and_direction() {
    let v = ok_json(&with_state(
        &["--mode", "sliding"],
        &["theta=0.57", "Omega_x=1", "v_C=0.01", "alpha=3.14159"],
    ));
    let d = v["derivatives"].as_object().unwrap();
    assert!(d.contains_key("der(v_C)") && d.contains_key("der(alpha)"));
    assert!(!d.contains_key("der(V_X)"));
    let nu = v["outputs"]["nu"].as_f64().unwrap();
    assert!((nu - 0.115).abs() < 1e-12, "{nu}");
}

#[test]
fn printed_numbers_round_trip_to_the_same_bits() {
    let p = parse_params("--set", &[]).unwrap();
    for (mode, state) in [
        (Mode::Rolling, &PAPER_STATE[..]),
        (
            Mode::Sliding,
            &["theta=1.1", "Omega_z=30", "v_C=0.3", "alpha=1"][..],
        ),
    ] {
        for (backend, flag) in [
            (Backend::Generated, None),
            (Backend::Reference, Some("--reference")),
        ] {
            let mut args = with_state(&["--mode", mode.name()], state);
            args.extend(flag);
            let printed = ok_json(&args);
            let y = parse_state(mode, &owned(state)).unwrap();
            let direct = evaluate(backend, mode, &p, &y).unwrap();
            for (name, value) in direct.derivatives.0.iter().chain(&direct.outputs.0) {
                let section = if direct.derivatives.0.iter().any(|(n, _)| n == name) {
                    "derivatives"
                } else {
                    "outputs"
                };
                let got = printed[section][name.as_str()].as_f64().unwrap();
                assert_eq!(got.to_bits(), value.to_bits(), "{mode} {backend:?} {name}");
            }
        }
    }
}

#[test]
fn reference_and_generated_agree() {
    let g = ok_json(&with_state(&["--mode", "rolling"], &PAPER_STATE));
    let r = ok_json(&with_state(
        &["--mode", "rolling", "--reference"],
        &PAPER_STATE,
    ));
    for (k, v) in g["derivatives"].as_object().unwrap() {
        let (a, b) = (v.as_f64().unwrap(), r["derivatives"][k].as_f64().unwrap());
        assert!((a - b).abs() <= 1e-9 * (1.0 + b.abs()), "{k}: {a} vs {b}");
    }
}

#[test]
fn the_old_json_spelling_gives_the_same_answer_with_a_note() {
    let new = eval(&with_state(
        &["--mode", "rolling", "--set", "mu_d=0.1"],
        &PAPER_STATE,
    ));
    let old = eval(&[
        "--mode",
        "rolling",
        "--params",
        r#"{"mu_d": 0.1}"#,
        "--state",
        r#"{"theta": 0.5707963267948966, "Omega_x": 1, "Z": 0.020409}"#,
    ]);
    assert!(new.status.success() && old.status.success());
    assert_eq!(new.stdout, old.stdout);
    let note = String::from_utf8_lossy(&old.stderr);
    assert!(note.contains("`--params` is deprecated"), "{note}");
    assert!(
        note.contains("`--state` as a JSON object is deprecated"),
        "{note}"
    );
    assert!(new.stderr.is_empty());
}

#[test]
fn model_eval_of_a_disk_model_is_eval() {
    let via_model = Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .args(with_state(&["model", "eval", "rolling"], &PAPER_STATE))
        .output()
        .unwrap();
    let via_eval = eval(&with_state(&["--mode", "rolling"], &PAPER_STATE));
    assert!(via_model.status.success(), "{via_model:?}");
    assert_eq!(via_model.stdout, via_eval.stdout);
    // The Cartesian slip chart has no `--mode`: only `model eval` reaches it.
    let cartesian = Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .args(["model", "eval", "sliding-cartesian", "--state", "theta=1"])
        .args(["--state", "u_X=0.01", "--set", "mu_d=0.1"])
        .output()
        .unwrap();
    assert!(cartesian.status.success(), "{cartesian:?}");
    let v: Value = serde_json::from_slice(&cartesian.stdout).unwrap();
    let nu = v["outputs"]["nu"].as_f64().unwrap();
    assert!((nu - 0.1).abs() < 1e-12, "sliding at mu_d: {nu}");
}

#[test]
fn every_error_class_names_its_key() {
    rejected(&["--mode", "rolling", "--state", "tehta=1"], "tehta");
    rejected(&["--mode", "rolling", "--state", "theta=x"], "theta");
    rejected(&["--mode", "rolling", "--state", "theta=1e999"], "theta");
    rejected(
        &[
            "--mode", "rolling", "--state", "theta=1", "--state", "theta=2",
        ],
        "theta",
    );
    rejected(&["--mode", "rolling", "--set", "m=-1"], "m");
    rejected(&["--mode", "rolling", "--set", "mass=1"], "mass");
    rejected(
        &["--mode", "rolling", "--state", r#"{"tehta": 1}"#],
        "tehta",
    );
    rejected(
        &["--mode", "rolling", "--state", r#"{"theta": "1"}"#],
        "theta",
    );
    rejected(
        &["--mode", "rolling", "--state", r#"{"theta": 1e999}"#],
        "theta",
    );
    rejected(
        &[
            "--mode",
            "rolling",
            "--state",
            r#"{"theta": 1, "theta": 2}"#,
        ],
        "theta",
    );
    rejected(
        &["--mode", "rolling", "--state", r#"{"theta": 0}"#],
        "theta",
    );
    rejected(
        &["--mode", "rolling", "--reference", "--state", "{}"],
        "theta",
    );
    rejected(&["--mode", "sliding", "--state", r#"{"theta": 1}"#], "v_C");
    rejected(&["--mode", "sliding", "--state", r#"{"V_X": 1}"#], "V_X");
    rejected(&["--mode", "rolling", "--params", r#"{"m": -1}"#], "m");
    rejected(
        &["--mode", "rolling", "--params", r#"{"mu_st": 0.01}"#],
        "mu_d",
    );
    rejected(&["--mode", "rolling", "--params", r#"{"mass": 1}"#], "mass");
    let out = eval(&["--mode", "rolling", "--state", "{theta: 1}"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--state"));
}

fn json_value() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<f64>()
            .prop_filter("finite", |v| v.is_finite())
            .prop_map(|v| format!("{v:e}")),
        Just("1e400".to_string()),
        Just("-1e400".to_string()),
        Just("null".to_string()),
        Just("true".to_string()),
        Just("\"NaN\"".to_string()),
        Just("[1.0]".to_string()),
        Just("{\"x\": 1}".to_string()),
        any::<i64>().prop_map(|v| v.to_string()),
    ]
}

const KEYS: &[&str] = &[
    "X", "Z", "V_X", "theta", "Omega_x", "Omega_z", "v_C", "alpha", "psi", "nope", "", "θ",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    /// Random objects: either every value is a finite number under a known name, or the
    /// rejection names an offending key.
    #[test]
    fn state_parsing_names_every_rejection(
        entries in prop::collection::vec((prop::sample::select(KEYS), json_value()), 0..5),
        mode in prop::sample::select(&[Mode::Rolling, Mode::Sliding][..]),
    ) {
        let body: Vec<String> = entries.iter().map(|(k, v)| format!("\"{k}\": {v}")).collect();
        let text = format!("{{{}}}", body.join(", "));
        match parse_state(mode, std::slice::from_ref(&text)) {
            Ok(y) => prop_assert!(y.iter().all(|v| v.is_finite())),
            Err(e) => {
                let key = e.key().expect("a rejection of an object names a key");
                prop_assert!(entries.iter().any(|(k, _)| *k == key), "{key} {text}");
                prop_assert!(e.to_string().contains(key));
            }
        }
    }

    /// Whatever the state, evaluation returns finite numbers or an error; never a panic.
    #[test]
    fn evaluation_never_panics_or_prints_nan(
        values in prop::collection::vec(
            prop_oneof![-1e3..1e3f64, Just(0.0), Just(1e300), Just(-1e300), Just(std::f64::consts::PI)],
            12,
        ),
        sliding in any::<bool>(),
        reference in any::<bool>(),
    ) {
        let mode = if sliding { Mode::Sliding } else { Mode::Rolling };
        let backend = if reference { Backend::Reference } else { Backend::Generated };
        let y: [f64; 12] = std::array::from_fn(|i| values[i]);
        let p = parse_params("--set", &[]).unwrap();
        if let Ok(e) = evaluate(backend, mode, &p, &y) {
            for (_, v) in e.derivatives.0.iter().chain(&e.outputs.0) {
                prop_assert!(v.is_finite());
            }
        }
    }

    #[test]
    fn any_text_is_parsed_or_rejected(text in ".{0,60}") {
        let _ = parse_named_numbers("--state", &text, &["theta"]);
    }
}

/// A full standard output (the device that is always full stands for a full disk) makes the
/// answer unprintable: a failure said on standard error, exit 1, not a panic (exit 101). A
/// closed pipe fails the same way (`EPIPE` instead of `ENOSPC`) but cannot be tested without a
/// race: a concurrently forked process may hold the pipe's read end open for a moment.
#[cfg(target_os = "linux")]
#[test]
fn a_full_standard_output_is_a_failure_not_a_panic() {
    for args in [
        &["eval", "--mode", "rolling", "--state", PAPER_STATE[0]][..],
        &["scenes"][..],
    ] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
            .args(args)
            .stdout(full)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains("cannot write to standard output"), "{err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}
