//! `sign`, `min`, `max` and `if` through the whole compiler: hand-computed derivatives on both
//! sides of each kink, Jacobians against differences away from them, pivots with a `sign` or
//! `if` factor, the printed solution, and the nonlinear uses located at their tokens.

use crate::common::model;
use model_algebra::{compile, CompileOptions, CompiledModel, EvalFailure};
use model_dsl::Source;

/// A mass on a belt moving at `vb`: Coulomb friction on the relative velocity, a stop that
/// only pushes (at `x > d`), a drive force saturated at `Fmax`, and a damper that acts only
/// while the mass moves away from the origin.
const BELT: &str = "
mod belt {
    params { m = 2, k = 3, mu = 0.4, g = 9.81, vb = 0.5, d = 1, kc = 50, F = 7, Fmax = 5, c = 0.3 }
    states { x, v }
    equations {
        der(x) = v;
        m*der(v) = -k*x - mu*m*g*sign(v - vb) - max(0, kc*(x - d)) + min(F, Fmax)
            - if(x*v > 0, c*v, 0);
    }
    outputs { direction = sign(der(v)); }
}
";

const PARAMS: [f64; 10] = [2.0, 3.0, 0.4, 9.81, 0.5, 1.0, 50.0, 7.0, 5.0, 0.3];

fn belt() -> CompiledModel {
    compile(&model(BELT), &CompileOptions::default()).expect("compiles")
}

/// `der(v)` computed by hand.
fn hand_acceleration(x: f64, v: f64) -> f64 {
    let [m, k, mu, g, vb, d, kc, f, fmax, c] = PARAMS;
    let friction = -mu * m * g * (v - vb).signum();
    let stop = -(kc * (x - d)).max(0.0);
    let damper = if x * v > 0.0 { -c * v } else { 0.0 };
    (-k * x + friction + stop + f.min(fmax) + damper) / m
}

/// `∂der(v)/∂x` and `∂der(v)/∂v` by hand.
fn hand_gradient(x: f64, v: f64) -> [f64; 2] {
    let [m, k, _, _, _, d, kc, _, _, c] = PARAMS;
    let stop = if x > d { -kc } else { 0.0 };
    let damper = if x * v > 0.0 { -c } else { 0.0 };
    [(-k + stop) / m, damper / m]
}

/// States on both sides of each kink: `v` around `vb`, `x` around `d`, `x*v` around 0.
const STATES: [[f64; 2]; 8] = [
    [0.5, 0.2],
    [0.5, 0.8],
    [1.3, 0.2],
    [1.3, 0.8],
    [-0.4, 0.3],
    [-0.4, -0.3],
    [0.7, -1.1],
    [1.2, -0.2],
];

#[test]
fn derivatives_equal_hand_values_on_both_sides_of_each_kink() {
    let model = belt();
    for y in STATES {
        let der = model.derivatives(0.0, &y, &PARAMS).unwrap();
        assert_eq!(der[0], y[1]);
        let hand = hand_acceleration(y[0], y[1]);
        assert!(
            (der[1] - hand).abs() <= 1e-14 * (1.0 + hand.abs()),
            "{y:?}: {der:?} vs {hand}"
        );
        let out = model.outputs_at(0.0, &y, &der, &PARAMS).unwrap();
        assert_eq!(out[0], hand.signum());
    }
}

#[test]
fn jacobian_follows_the_selected_branch_and_matches_differences() {
    let model = belt();
    for y in STATES {
        let jac = model
            .jacobian
            .eval(&model_algebra::Inputs {
                t: 0.0,
                states: &y,
                params: &PARAMS,
                ders: &[],
            })
            .unwrap()
            .jacobian(2);
        assert_eq!(jac[0], [0.0, 1.0]);
        let hand = hand_gradient(y[0], y[1]);
        for j in 0..2 {
            assert!(
                (jac[1][j] - hand[j]).abs() < 1e-14,
                "{y:?}: {jac:?} vs {hand:?}"
            );
        }
        // Every state is at least 0.1 from a kink: steps of 1e-6 stay on one side.
        let fd = model.finite_difference_jacobian(&y, &PARAMS, 1e-6).unwrap();
        for (row, fd_row) in jac.iter().zip(&fd) {
            for (a, b) in row.iter().zip(fd_row) {
                assert!((a - b).abs() < 1e-6, "{y:?}: {jac:?} vs {fd:?}");
            }
        }
    }
}

#[test]
fn a_nan_input_is_not_hidden_by_min_max_or_if() {
    let model = belt();
    for y in [[f64::NAN, 0.3], [0.3, f64::NAN]] {
        let der = model.derivatives(0.0, &y, &PARAMS).unwrap();
        assert!(der[1].is_nan(), "{y:?}: {der:?}");
    }
}

#[test]
fn the_solution_prints_the_functions_as_written() {
    let explanation = belt().explanation;
    let markdown = explanation.markdown;
    for text in [
        "sign(v - vb)",
        "max(0, ",
        "min(F, Fmax)",
        "if(",
        "sign(der(v))",
    ] {
        assert!(markdown.contains(text), "`{text}` not in\n{markdown}");
    }
    let latex = explanation.latex;
    let sign = r"\operatorname{sign}\left(v - \mathrm{vb}\right)";
    let min = r"\min\left(F, \mathrm{Fmax}\right)";
    for text in [sign, min, r"\max\left(0, ", r"\begin{cases}"] {
        assert!(latex.contains(text), "`{text}` not in\n{latex}");
    }
}

#[test]
fn pivots_with_a_sign_or_if_factor_are_checked() {
    let text = "mod m { states { x, v } equations {
        sign(x)*der(x) = 1;
        if(v > 0, 2, 0)*der(v) = -x;
    } }";
    let model = compile(&model(text), &CompileOptions::default()).unwrap();
    assert_eq!(model.pivots, ["sign(x)", "if(v > 0, 2, 0)"]);
    let der = model.derivatives(0.0, &[-0.5, 1.0], &[]).unwrap();
    assert_eq!(der, [-1.0, 0.25]);
    for (y, pivot) in [([0.0, 1.0], "sign(x)"), ([0.5, -1.0], "if(v > 0, 2, 0)")] {
        match model.derivatives(0.0, &y, &[]) {
            Err(EvalFailure::SingularPivot { text, value }) => {
                assert_eq!((text.as_str(), value), (pivot, 0.0), "{y:?}");
            }
            other => panic!("{y:?}: {other:?}"),
        }
    }
}

#[test]
fn derivatives_inside_the_functions_are_located_at_their_tokens() {
    let rows = [
        (
            "if(der(x) > 0, 1, 2) + der(x) = 0",
            "der(x) > 0",
            "a condition on a derivative",
        ),
        ("sign(der(x)) = 1", "sign(der(x))", "`sign` of a derivative"),
        (
            "max(der(x), 0) = x",
            "max(der(x), 0)",
            "`max` of a derivative",
        ),
    ];
    for (equation, token, message) in rows {
        let text = format!("mod m {{ states {{ x }} equations {{ {equation}; }} }}");
        let found = Source::new("m.dsl", text.as_str()).compile().unwrap_err().0;
        assert_eq!(found.len(), 1, "{found:#?}");
        let at = text.find(token).unwrap();
        let place = (found[0].line, found[0].column, found[0].width);
        assert_eq!(place, (1, at + 1, token.len()), "{found:#?}");
        assert!(found[0].message.contains(message), "{}", found[0].message);
    }
}

#[test]
fn der_of_a_kink_is_linear_piecewise() {
    // der(x + max(x, 0)) = 1: the coefficient of der(x) is 2 right of the kink and 1 left of it.
    let text = "mod m { states { x } equations { der(x + max(x, 0)) = 1; } }";
    let model = compile(&model(text), &CompileOptions::default()).unwrap();
    assert_eq!(model.pivots, ["1 + if(0 > x, 0, 1)"]);
    for (x, der) in [(1.0, 0.5), (-1.0, 1.0), (0.0, 0.5)] {
        assert_eq!(model.derivatives(0.0, &[x], &[]).unwrap(), [der], "x = {x}");
    }
}
