//! A pendulum in Cartesian coordinates: the rod's tension is eliminated by writing the torque
//! balance and the twice-differentiated length constraint, which couple `der(u)` and `der(v)`
//! through a mass matrix whose determinant, `-(x^2 + y^2)`, vanishes at the pivot point.

use crate::common::{
    assert_close, assert_jacobian_matches_differences, assert_same_derivatives, assert_singular,
};
use model_runtime::{EvalError, Model as _, WithOutputs as _};
use proptest::prelude::*;

model_macros::model! {
    /// A point mass on a rigid rod, in Cartesian coordinates.
    pub mod cartesian_pendulum {
        params { m = 1.5, l = 0.7, g = 9.81 }
        states { x, y, u, v }
        equations {
            der(x) = u;
            der(y) = v;
            torque: m * (x * der(v) - y * der(u)) = -m * g * x;
            length: der(x * u + y * v) = 0;
        }
        outputs {
            energy = m / 2 * (u^2 + v^2) + m * g * y;
            tension = -(m * (x * der(u) + y * der(v)) + m * g * y) / l;
        }
    }
}

use cartesian_pendulum::{output, state, Model};

/// The same equations solved by hand (Cramer's rule on the 2 x 2 block).
fn hand_rhs(p: &[f64; 3], y: &[f64; 4]) -> [f64; 4] {
    let g = p[2];
    let [x, y, u, v] = *y;
    let r2 = x * x + y * y;
    let speed2 = u * u + v * v;
    [
        u,
        v,
        (g * x * y - x * speed2) / r2,
        -(y * speed2 + g * x * x) / r2,
    ]
}

fn hand_tension(p: &[f64; 3], y: &[f64; 4]) -> f64 {
    let [m, l, g] = *p;
    (m * (y[2] * y[2] + y[3] * y[3]) - m * g * y[1]) / l
}

#[test]
fn index_constants_and_info_follow_the_declaration() {
    assert_eq!(cartesian_pendulum::STATE_NAMES, ["x", "y", "u", "v"]);
    assert_eq!((state::x, state::v, output::tension), (0, 3, 1));
    assert_eq!(
        cartesian_pendulum::PARAM_DEFAULTS,
        [Some(1.5), Some(0.7), Some(9.81)]
    );
    let info = &cartesian_pendulum::INFO;
    assert_eq!(info.name, "cartesian_pendulum");
    assert!(!info.pivots.is_empty());
    assert!(info.rhs_ops.total() > 0 && info.jacobian_ops.total() > 0);
}

proptest! {
    #[test]
    fn derivatives_match_the_hand_solution(
        params in (0.1f64..5.0, 0.1f64..3.0, 0.0f64..20.0),
        angle in -3.1f64..3.1,
        radius in 0.2f64..3.0,
        velocity in (-5.0f64..5.0, -5.0f64..5.0),
        t in -10.0f64..10.0,
    ) {
        let p = [params.0, params.1, params.2];
        let y = [radius * angle.sin(), -radius * angle.cos(), velocity.0, velocity.1];
        let model = Model::new(p);
        let mut dy = [0.0; 4];
        model.rhs(t, &y, &mut dy).unwrap();
        assert_same_derivatives(&dy, &hand_rhs(&p, &y), &cartesian_pendulum::STATE_NAMES);
        let mut out = [0.0; 2];
        model.outputs(t, &y, &dy, &mut out).unwrap();
        assert_close(out[output::tension], hand_tension(&p, &y), 1e-12, "tension");
        let energy = p[0] / 2.0 * (y[2] * y[2] + y[3] * y[3]) + p[0] * p[2] * y[1];
        assert_close(out[output::energy], energy, 1e-12, "energy");
        assert_jacobian_matches_differences(&model, t, &y);
    }
}

#[test]
fn the_pivot_point_is_a_singular_pivot_not_a_nan() {
    let model = Model::default();
    assert_singular(&model, 0.0, &[0.0, 0.0, 1.0, -2.0]);
}

#[test]
fn a_non_finite_state_is_reported() {
    let model = Model::default();
    let mut dy = [0.0; 4];
    let error = model
        .rhs(0.0, &[0.3, -0.2, f64::INFINITY, 0.0], &mut dy)
        .unwrap_err();
    assert!(
        matches!(
            error,
            EvalError::NonFinite { .. } | EvalError::SingularPivot { .. }
        ),
        "{error}"
    );
}
