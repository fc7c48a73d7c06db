//! The non-smooth functions expand to code that is clean under strict lints, and a NaN input
//! is refused rather than hidden by `max`.
#![deny(missing_docs, warnings, unused)]

use model_runtime::Model as _;

model_macros::model! {
    /// A block pressed against a wall by a saturated force, with Coulomb friction.
    pub mod block {
        params { m = 1.0, mu = 0.5, k = 100.0, F = 3.0, Fmax = 2.0 }
        states { x, v }
        equations {
            der(x) = v;
            m * der(v) = min(F, Fmax) - max(0, k * x) - mu * if(x >= 0, k * x, 0) * sign(v);
        }
    }
}

fn main() {
    let model = block::Model::default();
    let mut dy = [0.0; 2];
    model.rhs(0.0, &[0.01, 0.5], &mut dy).unwrap();
    assert!((dy[1] - (2.0 - 1.0 - 0.5)).abs() < 1e-12, "{dy:?}");
    assert!(model.rhs(0.0, &[f64::NAN, 0.5], &mut dy).is_err());
}
