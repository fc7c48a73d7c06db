//! A pendulum on a cart with friction: the accelerations of the cart and of the pendulum form a
//! coupled 2 x 2 block, checked against an LU solve of the mass matrix written by hand. A
//! variant keeps only the swing: with the friction fixed to zero the cart's position and velocity
//! drop out, and the variant must give the same swing for the states it keeps.

use crate::common::{assert_close, assert_jacobian_matches_differences, assert_same_derivatives};
use model_runtime::{Model as _, WithOutputs as _};
use nalgebra::{Matrix2, Vector2};
use proptest::prelude::*;

model_macros::model! {
    pub mod cart {
        params { M = 2.0, m = 0.5, l = 0.8, g = 9.81, c = 0.3 }
        states { x, v, phi, omega }
        let bob_vx = v + l * cos(phi) * omega;
        let bob_vy = l * sin(phi) * omega;
        equations {
            der(x) = v;
            der(phi) = omega;
            horizontal: der(M * v + m * bob_vx) = -c * v;
            swing: m * l^2 * der(omega) + m * l * cos(phi) * der(v) = -m * g * l * sin(phi);
        }
        outputs {
            energy = M / 2 * v^2 + m / 2 * (bob_vx^2 + bob_vy^2) - m * g * l * cos(phi);
            power = der(energy);
        }
        /// Only the swing, frictionless.
        variant swing_only { keep { omega } fix { c = 0 } }
        /// The cart's position, which needs everything.
        variant cart_only { keep { x } }
    }
}

/// The accelerations from the mass matrix, solved by nalgebra.
fn hand_rhs(p: &[f64; 5], y: &[f64; 4]) -> [f64; 4] {
    let [big_m, m, l, g, c] = *p;
    let [_, v, phi, omega] = *y;
    let (s, co) = phi.sin_cos();
    let mass = Matrix2::new(big_m + m, m * l * co, m * l * co, m * l * l);
    let force = Vector2::new(m * l * s * omega * omega - c * v, -m * g * l * s);
    let acc = mass
        .lu()
        .solve(&force)
        .expect("the mass matrix is positive definite");
    [v, acc[0], omega, acc[1]]
}

proptest! {
    #[test]
    fn derivatives_match_the_mass_matrix_solve(
        params in (0.1f64..5.0, 0.1f64..5.0, 0.1f64..2.0, 0.0f64..20.0, 0.0f64..2.0),
        y in (-5.0f64..5.0, -5.0f64..5.0, -6.3f64..6.3, -10.0f64..10.0),
        t in -10.0f64..10.0,
    ) {
        let p = [params.0, params.1, params.2, params.3, params.4];
        let y = [y.0, y.1, y.2, y.3];
        let model = cart::Model::new(p);
        let mut dy = [0.0; 4];
        model.rhs(t, &y, &mut dy).unwrap();
        assert_same_derivatives(&dy, &hand_rhs(&p, &y), &cart::STATE_NAMES);
        assert_jacobian_matches_differences(&model, t, &y);
        // Friction is the only loss: power = -c v^2.
        let mut out = [0.0; 2];
        model.outputs(t, &y, &dy, &mut out).unwrap();
        assert_close(out[cart::output::power], -p[4] * y[1] * y[1], 1e-10, "power");
    }

    #[test]
    fn the_swing_variant_agrees_with_the_full_model(
        params in (0.1f64..5.0, 0.1f64..5.0, 0.1f64..2.0, 0.0f64..20.0),
        y in (-5.0f64..5.0, -5.0f64..5.0, -6.3f64..6.3, -10.0f64..10.0),
    ) {
        let full = cart::Model::new([params.0, params.1, params.2, params.3, 0.0]);
        let reduced = cart::swing_only::Model::new([params.0, params.1, params.2, params.3]);
        let y = [y.0, y.1, y.2, y.3];
        let mut dy = [0.0; 4];
        full.rhs(0.0, &y, &mut dy).unwrap();
        let z = [y[cart::state::phi], y[cart::state::omega]];
        let mut dz = [0.0; 2];
        reduced.rhs(0.0, &z, &mut dz).unwrap();
        use cart::swing_only::state;
        assert_close(dz[state::phi], dy[cart::state::phi], 1e-12, "der(phi)");
        assert_close(dz[state::omega], dy[cart::state::omega], 1e-12, "der(omega)");
        assert_jacobian_matches_differences(&reduced, 0.0, &z);
    }
}

#[test]
fn the_swing_variant_keeps_what_the_swing_needs() {
    use cart::swing_only;
    assert_eq!(swing_only::STATE_NAMES, ["phi", "omega"]);
    assert_eq!(swing_only::PARAM_NAMES, ["M", "m", "l", "g"]);
    assert_eq!(swing_only::OUTPUT_NAMES, [""; 0]);
    assert_eq!(swing_only::INFO.name, "cart::swing_only");
    // Fixing the friction removed its terms: the variant costs less than the full model.
    assert!(swing_only::INFO.rhs_ops.total() < cart::INFO.rhs_ops.total());
}

#[test]
fn keeping_the_position_keeps_everything_it_depends_on() {
    use cart::cart_only;
    assert_eq!(cart_only::STATE_NAMES, ["x", "v", "phi", "omega"]);
    assert_eq!(cart_only::PARAM_NAMES, cart::PARAM_NAMES);
    let y = [0.1, 0.2, 0.3, 0.4];
    let (mut a, mut b) = ([0.0; 4], [0.0; 4]);
    cart::Model::default().rhs(0.0, &y, &mut a).unwrap();
    cart_only::Model::default().rhs(0.0, &y, &mut b).unwrap();
    assert_same_derivatives(&a, &b, &cart::STATE_NAMES);
}

#[test]
fn named_forms_follow_the_index_constants() {
    // Distinct values, so a field wired to the wrong index cannot go unnoticed.
    let params = cart::Params {
        M: 1.0,
        m: 2.0,
        l: 3.0,
        g: 4.0,
        c: 5.0,
    };
    let array = params.to_array();
    for (name, index) in [
        ("M", cart::param::M),
        ("m", cart::param::m),
        ("l", cart::param::l),
        ("g", cart::param::g),
        ("c", cart::param::c),
    ] {
        assert_eq!(cart::PARAM_NAMES[index], name);
        assert_eq!(array[index], (index + 1) as f64);
    }
    assert_eq!(cart::Params::from_array(&array), params);
    assert_eq!(cart::Model::from(params).named_params(), params);
    // `Default` is the DSL's values, the same as the model's.
    assert_eq!(
        cart::Params::default().to_array(),
        cart::Model::default().params
    );
    let state = cart::State {
        x: 1.0,
        v: 2.0,
        phi: 3.0,
        omega: 4.0,
    };
    assert_eq!(state.to_array()[cart::state::phi], 3.0);
    assert_eq!(cart::State::from(state.to_array()), state);
}

#[test]
fn evaluate_returns_the_derivatives_and_the_outputs_of_the_separate_calls() {
    let model = cart::Model::from_params(cart::Params {
        c: 0.7,
        ..Default::default()
    });
    let y = [0.1, -0.4, 0.9, 1.3];
    let mut dy = [0.0; cart::N_STATES];
    model.rhs(0.5, &y, &mut dy).unwrap();
    let mut out = [0.0; cart::N_OUTPUTS];
    model.outputs(0.5, &y, &dy, &mut out).unwrap();
    let ev = model.evaluate(0.5, &y).unwrap();
    assert_eq!(ev.der, dy);
    assert_eq!(ev.outputs, out);
    // With friction the power is the friction's: -c v^2.
    assert_close(
        cart::Outputs::from(ev.outputs).power,
        -0.7 * 0.4 * 0.4,
        1e-12,
        "power with friction",
    );
}
