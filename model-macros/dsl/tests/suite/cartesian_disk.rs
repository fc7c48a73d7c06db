//! The sliding disk in the Cartesian slip chart (`v_C` and `alpha` as lets of `u`), checked
//! against the polar chart through the change of variables `u = -v_C (cos alpha, sin alpha)`.
//! The two charts reach their code by different identities (the Cartesian one through
//! `sin(atan2)`, the polar one by expanding `sin(alpha - psi)`), so agreement checks both.

use crate::common::{charted, model, sliding};
use model_algebra::CompiledModel;
use model_algebra::{compile, CompileOptions};
use model_algebra::{EvalFailure, Inputs};

use crate::sliding_disk::{state, PARAMS};

/// The sliding disk in its Cartesian chart, as the `equations` crate compiles it.
pub fn cartesian() -> model_algebra::ModelSpec {
    charted(&sliding(), "sliding_cartesian")
}
fn rhs(m: &CompiledModel, y: &[f64], p: &[f64]) -> Result<Vec<f64>, EvalFailure> {
    let inputs = Inputs {
        t: 0.0,
        states: y,
        params: p,
        ders: &[],
    };
    Ok(m.rhs.eval(&inputs)?.ders(y.len()))
}

fn close(got: f64, want: f64, what: &str) {
    assert!(
        (got - want).abs() <= 1e-12 * (1.0 + want.abs()),
        "{what}: {got} vs {want}"
    );
}

#[test]
fn the_cartesian_chart_agrees_with_the_polar_one() {
    let polar = compile(&model(&sliding()), &CompileOptions::default()).expect("polar compiles");
    let spec = cartesian();
    let cart = compile(&spec, &CompileOptions::default()).expect("cartesian compiles");
    // No atan2 is left, and the only calls are the sine and cosine of theta and psi.
    assert_eq!(cart.rhs.ops().trig, 2, "{}", cart.rhs);
    assert_eq!(cart.rhs.to_string().matches("sin_cos").count(), 2);
    for (v_c, alpha) in [(0.3, 2.5), (1e-3, -0.4), (2.0, 3.1)] {
        let mut y = state();
        y[3] = v_c;
        y[4] = alpha;
        let dp = rhs(&polar, &y, &PARAMS).unwrap();
        let mut yc = y;
        yc[3] = -v_c * alpha.cos();
        yc[4] = -v_c * alpha.sin();
        let dc = rhs(&cart, &yc, &PARAMS).unwrap();
        let (dv, da) = (dp[3], dp[4]);
        close(
            dc[3],
            -dv * alpha.cos() + v_c * alpha.sin() * da,
            "der(u_X)",
        );
        close(
            dc[4],
            -dv * alpha.sin() - v_c * alpha.cos() * da,
            "der(u_Y)",
        );
        for k in (0..12).filter(|&k| k != 3 && k != 4) {
            close(dc[k], dp[k], &format!("der {}", spec.states[k].name));
        }
        crate::end_to_end::assert_jacobian_matches(&cart, &yc, &PARAMS);
    }
}

#[test]
fn zero_slip_is_a_named_pivot() {
    let cart = compile(&cartesian(), &CompileOptions::default()).unwrap();
    let mut y = state();
    y[3] = 0.0;
    y[4] = 0.0;
    assert_eq!(
        rhs(&cart, &y, &PARAMS),
        Err(EvalFailure::SingularPivot {
            text: "u_X^2 + u_Y^2".into(),
            value: 0.0
        })
    );
    // The reduced variant refuses it too.
    let v = &cart.variants[0];
    assert_eq!(v.states[..2], ["u_X", "u_Y"]);
    let mut reduced: Vec<f64> = [3, 4, 5, 6, 7, 9, 10, 11].iter().map(|&i| y[i]).collect();
    assert!(matches!(
        rhs(v, &reduced, &PARAMS[..5]),
        Err(EvalFailure::SingularPivot { text, .. }) if text == "u_X^2 + u_Y^2"
    ));
    reduced[0] = 1e-9;
    assert!(rhs(v, &reduced, &PARAMS[..5]).is_ok());
}
