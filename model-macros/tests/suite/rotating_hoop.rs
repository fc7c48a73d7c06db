//! A bead sliding without friction on a hoop that spins about its vertical diameter at a
//! prescribed, time-varying rate. The kinematics are written through the bead's height,
//! `der(-r cos(theta)) = r sin(theta) omega`, so the solve divides by `sin(theta)`: a pivot that
//! vanishes at the bottom of the hoop and must be reported, not turned into a NaN.

use crate::common::{
    assert_close, assert_jacobian_matches_differences, assert_same_derivatives, assert_singular,
};
use model_runtime::{EvalError, Model as _, WithOutputs as _};
use proptest::prelude::*;

model_macros::model! {
    /// A bead on a spinning hoop.
    pub mod rotating_hoop {
        params { m = 0.1, r = 0.5, g = 9.81, w0 = 3.0, w1 = 0.0 }
        states { theta, omega }
        let spin = w0 + w1 * sin(t);
        equations {
            height: der(-r * cos(theta)) = r * sin(theta) * omega;
            swing: m * r^2 * der(omega) = m * r^2 * spin^2 * sin(theta) * cos(theta) - m * g * r * sin(theta);
        }
        outputs {
            jacobi = m * r^2 / 2 * (omega^2 - spin^2 * sin(theta)^2) - m * g * r * cos(theta);
            jacobi_rate = m * r^2 * omega * der(omega) - m * r^2 * spin^2 * sin(theta) * cos(theta) * der(theta)
                + m * g * r * sin(theta) * der(theta);
        }
    }
}

use rotating_hoop::Model;

fn hand_rhs(p: &[f64; 5], t: f64, y: &[f64; 2]) -> [f64; 2] {
    let [_, r, g, w0, w1] = *p;
    let spin = w0 + w1 * t.sin();
    let (s, c) = y[0].sin_cos();
    [y[1], spin * spin * s * c - g / r * s]
}

proptest! {
    #[test]
    fn derivatives_match_the_hand_solution(
        params in (0.01f64..2.0, 0.1f64..2.0, 0.0f64..20.0, -5.0f64..5.0, -2.0f64..2.0),
        theta in 0.05f64..3.09,
        side in prop::bool::ANY,
        omega in -10.0f64..10.0,
        t in -10.0f64..10.0,
    ) {
        let p = [params.0, params.1, params.2, params.3, params.4];
        let y = [if side { theta } else { -theta }, omega];
        let model = Model::new(p);
        let mut dy = [0.0; 2];
        model.rhs(t, &y, &mut dy).unwrap();
        assert_same_derivatives(&dy, &hand_rhs(&p, t, &y), &rotating_hoop::STATE_NAMES);
        assert_jacobian_matches_differences(&model, t, &y);
        let mut out = [0.0; 2];
        model.outputs(t, &y, &dy, &mut out).unwrap();
        // With a steady spin the Jacobi integral is conserved along the flow.
        if p[4] == 0.0 {
            assert_close(out[rotating_hoop::output::jacobi_rate], 0.0, 1e-12, "jacobi rate");
        }
    }
}

#[test]
fn a_steady_spin_conserves_the_jacobi_integral() {
    let model = Model::default();
    let y = [1.1, -0.4];
    let mut dy = [0.0; 2];
    model.rhs(0.3, &y, &mut dy).unwrap();
    let mut out = [0.0; 2];
    model.outputs(0.3, &y, &dy, &mut out).unwrap();
    assert_close(
        out[rotating_hoop::output::jacobi_rate],
        0.0,
        1e-12,
        "jacobi rate",
    );
}

#[test]
fn the_bottom_of_the_hoop_is_a_singular_pivot_named_by_its_text() {
    let model = Model::default();
    let error = assert_singular(&model, 0.0, &[0.0, 1.0]);
    let EvalError::SingularPivot { pivot, .. } = error else {
        unreachable!("checked by assert_singular")
    };
    assert!(pivot.contains("sin(theta)"), "{pivot}");
}

#[test]
fn a_massless_bead_is_a_singular_pivot_too() {
    let model = Model::new([0.0, 0.5, 9.81, 3.0, 0.0]);
    let error = assert_singular(&model, 0.0, &[1.0, 1.0]);
    let EvalError::SingularPivot { pivot, .. } = error else {
        unreachable!("checked by assert_singular")
    };
    assert!(pivot.contains('m'), "{pivot}");
}
