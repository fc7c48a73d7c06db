//! A mass on a moving belt, with every non-smooth function of the DSL: Coulomb friction on the
//! relative velocity (`sign`), a wall on the left that only pushes (`max`), a ramped drive force
//! that saturates (`min`), quadratic drag (`abs`), and a load picked up past `xs` (`if`, in the
//! mass: a pivot with a jump). The compiled `rhs` and `jacobian` are compared with the
//! compiler's interpreter and with the equations solved by hand at random states on both sides
//! of each kink, and the Jacobian with finite differences away from them.

use crate::common::{assert_close, assert_jacobian_matches_differences};
use model_runtime::{EvalError, Model as _, WithOutputs as _};
use proptest::prelude::*;

/// Emits the model and keeps its text, so the interpreter reads exactly what the macro compiled.
macro_rules! model_and_text {
    ($($body:tt)*) => {
        model_macros::model! { $($body)* }
        /// The model as text, for the interpreter.
        const TEXT: &str = stringify!($($body)*);
    };
}

model_and_text! {
    mod belt {
        params {
            m = 1.5, ma = 0.5, k = 4, mu = 0.3, g = 9.81, vb = 0.4,
            d = -0.8, kc = 60, xs = -0.5, F = 2, Fmax = 1.2, c = 0.2
        }
        states { x, v }
        equations {
            der(x) = v;
            if(x > xs, m + ma, m) * der(v) = -k*x - mu*m*g*sign(v - vb) + max(0, kc*(d - x))
                + min(F*t, Fmax) - c*abs(v)*v;
        }
        outputs {
            friction = -mu*m*g*sign(v - vb);
            speeding_up = sign(der(v) * v);
        }
    }
}

const PARAMS: [f64; 12] = [
    1.5, 0.5, 4.0, 0.3, 9.81, 0.4, -0.8, 60.0, -0.5, 2.0, 1.2, 0.2,
];

/// The model as the compiler's interpreter runs it.
fn interpreted() -> model_algebra::CompiledModel {
    let models = model_dsl::Source::new("belt.dsl", TEXT).compile();
    models.unwrap_or_else(|e| panic!("{e}")).remove(0).compiled
}

/// The acceleration solved by hand.
fn hand_acceleration(t: f64, [x, v]: [f64; 2]) -> f64 {
    let [m, ma, k, mu, g, vb, d, kc, xs, f, fmax, c] = PARAMS;
    let mass = if x > xs { m + ma } else { m };
    let friction = -mu * m * g * (v - vb).signum();
    let wall = (kc * (d - x)).max(0.0);
    (-k * x + friction + wall + (f * t).min(fmax) - c * v.abs() * v) / mass
}

/// `∂der(v)/∂x` and `∂der(v)/∂v` by hand: the wall's stiffness where it touches, the drag's
/// `2c|v|`; the jumps of the mass and of the friction have no derivative.
fn hand_gradient([x, v]: [f64; 2]) -> [f64; 2] {
    let [m, ma, k, _, _, _, d, kc, xs, _, _, c] = PARAMS;
    let mass = if x > xs { m + ma } else { m };
    let wall = if x < d { -kc } else { 0.0 };
    [(-k + wall) / mass, -2.0 * c * v.abs() / mass]
}

/// Random states and times, on either side of every kink (`x = d`, `x = xs`, `v = vb`,
/// `F t = Fmax`).
fn state() -> impl Strategy<Value = (f64, [f64; 2])> {
    (0.0..1.2, [-1.5..1.0, -1.0..1.5]).prop_map(|(t, y)| (t, y))
}

/// Whether `(t, y)` is at least `margin` from every kink.
fn away_from_kinks(t: f64, [x, v]: [f64; 2], margin: f64) -> bool {
    let [_, _, _, _, _, vb, d, _, xs, f, fmax, _] = PARAMS;
    [x - d, x - xs, v - vb, f * t - fmax]
        .iter()
        .all(|gap| gap.abs() > margin)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn rhs_equals_the_interpreter_and_the_hand_solution((t, y) in state()) {
        let model = belt::Model::default();
        let mut dy = [0.0; 2];
        model.rhs(t, &y, &mut dy).unwrap();
        let interpreted = interpreted().derivatives(t, &y, &PARAMS).unwrap();
        prop_assert_eq!(dy.to_vec(), interpreted);
        prop_assert_eq!(dy[0], y[1]);
        assert_close(dy[1], hand_acceleration(t, y), 1e-14, "der(v)");
        let mut out = [0.0; 2];
        model.outputs(t, &y, &dy, &mut out).unwrap();
        prop_assert_eq!(out[1], (dy[1] * y[1]).signum());
    }

    #[test]
    fn jacobian_equals_the_interpreter_and_the_hand_gradient((t, y) in state()) {
        let model = belt::Model::default();
        let mut jac = [[0.0; 2]; 2];
        model.jacobian(t, &y, &mut jac).unwrap();
        let inputs = model_algebra::Inputs { t, states: &y, params: &PARAMS, ders: &[] };
        let interpreted = interpreted().jacobian.eval(&inputs).unwrap().jacobian(2);
        prop_assert_eq!(jac.iter().map(|r| r.to_vec()).collect::<Vec<_>>(), interpreted);
        prop_assert_eq!(jac[0], [0.0, 1.0]);
        let hand = hand_gradient(y);
        for j in 0..2 {
            assert_close(jac[1][j], hand[j], 1e-14, &format!("jacobian entry [1][{j}]"));
        }
    }

    #[test]
    fn jacobian_matches_differences_away_from_kinks((t, y) in state()) {
        prop_assume!(away_from_kinks(t, y, 1e-3));
        assert_jacobian_matches_differences(&belt::Model::default(), t, &y);
    }
}

#[test]
fn the_mass_with_a_jump_is_a_checked_pivot() {
    assert_eq!(belt::INFO.pivots, ["if(x > xs, m + ma, m)"]);
    // Without the belt's own mass the pivot is zero left of `xs`, and fine right of it.
    let massless = belt::Model::from_params(belt::Params {
        m: 0.0,
        ..Default::default()
    });
    let mut dy = [0.0; 2];
    match massless.rhs(0.0, &[-1.0, 0.0], &mut dy) {
        Err(EvalError::SingularPivot { pivot, value, .. }) => {
            assert_eq!((&*pivot, value), ("if(x > xs, m + ma, m)", 0.0));
        }
        other => panic!("{other:?}"),
    }
    massless.rhs(0.0, &[0.0, 0.0], &mut dy).unwrap();
}

#[test]
fn a_nan_state_is_refused_not_hidden_by_a_branch() {
    let model = belt::Model::default();
    let mut dy = [0.0; 2];
    for y in [[0.2, f64::NAN], [f64::NAN, 0.2]] {
        assert!(model.rhs(0.5, &y, &mut dy).is_err(), "{y:?}: {dy:?}");
    }
    // An output reading the friction alone is refused too.
    let mut out = [0.0; 2];
    let error = model.outputs(0.0, &[0.0, f64::NAN], &[0.0, 0.0], &mut out);
    assert!(
        matches!(error, Err(EvalError::NonFinite { .. })),
        "{error:?}"
    );
}

#[test]
fn comparisons_count_as_additions() {
    // `rhs`: the sums and differences (7) and one comparison each for `sign`, `max`, `min` and
    // the mass's `if` (4); the products of the five forces (8); one division by the pivot.
    let ops = belt::INFO.rhs_ops;
    assert_eq!((ops.add, ops.mul, ops.div), (11, 8, 1), "{ops:?}");
    assert_eq!((ops.sqrt, ops.trig, ops.transcendental), (0, 0, 0));
    let ops = belt::INFO.jacobian_ops;
    assert_eq!((ops.add, ops.mul, ops.div), (9, 5, 1), "{ops:?}");
}
