//! `eulerdisk model show|eval|solve` as a user runs them on a DSL file: the example heavy top
//! shown, evaluated (against a hand derivation) and solved (its energy kept); a file with a
//! mistake gives `file:line:col: message`, the line and a caret, and exit code 2.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

const HEAVY_TOP: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/model-macros/examples/heavy_top.dsl"
);

fn model(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .arg("model")
        .args(args)
        .output()
        .unwrap()
}

fn ok(args: &[&str]) -> String {
    let out = model(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {stderr}");
    String::from_utf8(out.stdout).unwrap()
}

/// A DSL file in a fresh temporary directory.
fn file(text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("model.dsl");
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

fn arg(path: &Path) -> &str {
    path.to_str().unwrap()
}

#[test]
fn show_prints_the_solved_equations_of_a_file() {
    let text = ok(&["show", HEAVY_TOP]);
    assert!(
        text.starts_with("# `heavy_top`: the solved equations"),
        "{text}"
    );
    for state in ["phi", "theta", "psi", "w_phi", "w_theta", "w_psi"] {
        assert!(
            text.contains(&format!("der({state}) = ")),
            "der({state}):\n{text}"
        );
    }
    // The momenta's block divides by sin(theta): a pivot, named.
    assert!(text.contains("sin(theta)"), "{text}");
    let latex = ok(&["show", HEAVY_TOP, "--format", "latex"]);
    assert!(latex.starts_with("\\begin{align*}"), "{latex}");
    assert!(latex.contains("\\dot{\\theta} &= w_{\\theta}"), "{latex}");
    // A disk model by name still works.
    assert!(ok(&["show", "rolling"]).contains("## At the paper's start"));
}

#[test]
fn a_chart_is_shown_after_its_model_and_evaluated_by_name() {
    let (_dir, path) = file(
        "mod oscillator {
            params { w = 2 }
            states { x, v }
            equations { der(x) = v; der(v) = -w^2 * x; }
            outputs { energy = (v^2 + w^2 * x^2) / 2; }
            chart polar {
                states { r, phi } replace { x, v }
                let x = r * cos(phi);
                let v = -w * r * sin(phi);
            }
        }",
    );
    let text = ok(&["show", arg(&path)]);
    let (at_model, at_chart) = (
        text.find("# `oscillator`").unwrap(),
        text.find("# `polar`").unwrap(),
    );
    assert!(at_model < at_chart, "{text}");
    let out = ok(&[
        "eval",
        arg(&path),
        "--chart",
        "polar",
        "--state",
        "r=1.5",
        "--state",
        "phi=0.3",
    ]);
    let v: Value = serde_json::from_str(&out).unwrap();
    assert!(
        v["derivatives"]["der(r)"].as_f64().unwrap().abs() < 1e-14,
        "{out}"
    );
    assert!(
        (v["derivatives"]["der(phi)"].as_f64().unwrap() - 2.0).abs() < 1e-14,
        "{out}"
    );
    assert!(
        (v["outputs"]["energy"].as_f64().unwrap() - 4.5).abs() < 1e-14,
        "{out}"
    );
    let wrong = model(&["eval", arg(&path), "--chart", "cartesian"]);
    assert_eq!(wrong.status.code(), Some(2));
    let err = String::from_utf8_lossy(&wrong.stderr);
    assert!(
        err.contains(
            "`cartesian` is not a chart of the model; the file defines `oscillator`, `polar`"
        ),
        "{err}"
    );
}

#[test]
fn eval_prints_derivatives_and_outputs_by_name() {
    let (theta, w_phi, w_psi): (f64, f64, f64) = (0.4, 2.0, 150.0);
    let out = ok(&[
        "eval",
        HEAVY_TOP,
        "--state",
        &format!("theta={theta}"),
        "--state",
        &format!("w_phi={w_phi}"),
        "--state",
        &format!("w_psi={w_psi}"),
        "--set",
        "m=1",
    ]);
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["model"], "heavy_top");
    // Printed in the model's order.
    let at = |k: &str| out.find(&format!("\"{k}\":")).unwrap();
    assert!(at("der(phi)") < at("der(theta)") && at("der(theta)") < at("der(w_psi)"));
    assert!(at("energy") < at("momentum_phi"));
    // The nutation equation by hand (w_theta = 0), with m = 1 from --set.
    let (g, l, i1, i3) = (9.81, 0.04, 0.0012, 0.0009);
    let omega3 = w_psi + w_phi * theta.cos();
    let want = (i1 * w_phi * w_phi * theta.sin() * theta.cos() - i3 * omega3 * w_phi * theta.sin()
        + g * l * theta.sin())
        / i1;
    let got = v["derivatives"]["der(w_theta)"].as_f64().unwrap();
    assert!((got - want).abs() <= 1e-12 * want.abs(), "{got} vs {want}");
    let energy =
        i1 / 2.0 * (w_phi * theta.sin()).powi(2) + i3 / 2.0 * omega3 * omega3 + g * l * theta.cos();
    let got = v["outputs"]["energy"].as_f64().unwrap();
    assert!((got - energy).abs() <= 1e-12 * energy, "{got} vs {energy}");
}

#[test]
fn bad_assignments_and_singular_states_are_named() {
    for (args, needle) in [
        (
            vec!["--state", "thetta=1"],
            "--state `thetta=1`: the model has no `thetta`; the names are `phi`, `theta`",
        ),
        (vec!["--set", "m"], "--set `m`: expected NAME=VALUE"),
        (
            vec!["--set", "m=heavy"],
            "--set `m=heavy`: `heavy` is not a finite number",
        ),
        (
            vec!["--state", "phi=1", "--state", "phi=2"],
            "`phi` is given twice",
        ),
        // theta = 0: the momenta's block divides by sin(theta).
        (vec![], "the pivot `I1*sin(theta)^2` is 0 at this state"),
    ] {
        let mut all = vec!["eval", HEAVY_TOP];
        all.extend(args.iter().copied());
        let out = model(&all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(out.stdout.is_empty());
    }
}

#[test]
fn a_mistake_in_the_file_is_located_with_a_caret() {
    let (_dir, path) = file("mod m {\n    states { x }\n    equations { der(x) = -k * x; }\n}\n");
    for (command, extra) in [
        ("show", vec![]),
        ("eval", vec![]),
        ("solve", vec!["--t-end", "1"]),
    ] {
        let mut args = vec![command, arg(&path)];
        args.extend(extra);
        let out = model(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{command:?}: {err}");
        let expected = format!("{}:3:27: unknown name `k`", path.display());
        assert!(err.contains(&expected), "{command:?}: {err}");
        assert!(
            err.contains("3 |     equations { der(x) = -k * x; }\n  |                           ^"),
            "{err}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }
    let (_dir, path) = file("mod m { states { x } equations { der(x) = (x; } }");
    let out = model(&["show", arg(&path)]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains(":1:"));
    let out = model(&["show", "no-such-model"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("neither a model of the disk"));
}

#[test]
fn solve_writes_a_trajectory_that_keeps_the_energy() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("top.csv");
    let out = model(&[
        "solve",
        HEAVY_TOP,
        "--state",
        "theta=0.5",
        "--state",
        "w_psi=150",
        "--t-end",
        "1",
        "--dt",
        "0.01",
        "--rtol",
        "1e-10",
        "--atol",
        "1e-12",
        "--out",
        arg(&csv),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t,phi,theta,psi,w_phi,w_theta,w_psi,energy,momentum_phi,momentum_psi"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 101);
    assert_eq!(rows.last().unwrap()[0], 1.0);
    let energy: Vec<f64> = rows.iter().map(|r| r[7]).collect();
    let drift = energy
        .iter()
        .map(|e| (e - energy[0]).abs())
        .fold(0.0, f64::max);
    assert!(drift < 1e-8 * energy[0].abs(), "energy drift {drift:e}");
    // The top nods: theta moves.
    let theta = rows.iter().map(|r| r[2]);
    let (lo, hi) = theta.fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
    assert!(hi - lo > 1e-4, "{lo} {hi}");
    // A singular start stops with the pivot named, exit 1.
    let out = model(&["solve", HEAVY_TOP, "--t-end", "1"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("sin(theta)"));
}
