//! The expansion is clean under strict lints, including for the smallest models: no parameters,
//! no outputs, no variants, no doc comments.
#![deny(missing_docs, warnings, unused)]

use model_runtime::{Model as _, WithOutputs as _};

model_macros::model! {
    pub mod decay {
        states { x }
        equations { der(x) = -x; }
    }
}

model_macros::model! {
    /// A documented model with everything.
    pub(crate) mod full {
        params {
            /// The spring's stiffness.
            k = 2.0,
            c,
        }
        states {
            /// The position.
            x,
            v,
        }
        let spring = k * x;
        equations {
            der(x) = v;
            der(v) = -spring - c * v + sin(t);
        }
        outputs {
            /// The mechanical energy.
            energy = v^2 / 2 + k * x^2 / 2;
        }
        variant undamped { keep { v } fix { c = 0 } }
    }
}

fn main() {
    let mut dy = [0.0];
    decay::Model::default().rhs(0.0, &[2.0], &mut dy).unwrap();
    assert_eq!(dy, [-2.0]);
    assert_eq!(decay::N_PARAMS + decay::N_OUTPUTS, 0);
    let mut out = [0.0; 0];
    decay::Model::new([])
        .outputs(0.0, &[2.0], &dy, &mut out)
        .unwrap();

    let model = full::Model::new([2.0, 0.5]);
    let mut dy = [0.0; 2];
    model.rhs(0.0, &[1.0, 1.0], &mut dy).unwrap();
    assert_eq!(dy, [1.0, -2.5]);
    let mut jac = [[0.0; 2]; 2];
    model.jacobian(0.0, &[1.0, 1.0], &mut jac).unwrap();
    assert_eq!(jac, [[0.0, 1.0], [-2.0, -0.5]]);
    assert_eq!(full::undamped::PARAM_NAMES, ["k"]);
}
