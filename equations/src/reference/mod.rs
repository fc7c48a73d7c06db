//! An independent, hand-written reference for both modes of the disk.
//!
//! The generated models come from the paper's row forms through a symbolic compiler; to check
//! them we need the same physics reached by another road. Here each balance law is evaluated
//! as a vector equation (frame vectors, `dH/dt = M`, `m V̇ = F`, contact kinematics) whose
//! entries carry their exact linear dependence on the state derivatives; the resulting
//! 12×12 system `M(y)·ẏ = f(y)` is solved by LU at every call. Nothing here is transcribed
//! from the row tables, so an error in either road shows up as a disagreement.
//!
//! Each model implements [`model_runtime::Model`] and [`model_runtime::WithOutputs`], so the
//! runtime can integrate the reference exactly as it integrates generated code.
//!
//! Vectors tied to the disk are kept in frame components, where the frame's orthogonality is
//! exact, and the solve ends with one step of iterative refinement; the tests find every
//! derivative within a small multiple of ε times the size of the terms of its row, even with
//! the disk within 1e-12 rad of flat or upright.
//!
//! ```
//! use equations::reference::{rolling, RollingReference};
//! use equations::DiskParams;
//! use model_runtime::{Model, WithOutputs};
//!
//! // The paper's scene at t = 0: tilted by θ0 = π/2 - 1, turning at Ω_x = 1 rad/s.
//! let p = DiskParams::paper();
//! let theta0 = std::f64::consts::FRAC_PI_2 - 1.0;
//! let mut y = [0.0; 12];
//! y[rolling::state::Z] = p.a * theta0.sin();
//! y[rolling::state::theta] = theta0;
//! y[rolling::state::Omega_x] = 1.0;
//!
//! let model = RollingReference::new(p)?;
//! let mut dy = [0.0; 12];
//! model.rhs(0.0, &y, &mut dy)?;
//! let mut out = [0.0; rolling::N_OUTPUTS];
//! model.outputs(0.0, &y, &dy, &mut out)?;
//! // Rolling would need T/N = 0.8355, far above mu_st = 0.2: the disk slides from the start.
//! assert!((out[rolling::output::nu] - 0.8355).abs() < 1e-4);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod affine;
mod body;
pub mod rolling;
pub mod sliding;
pub mod sliding_cartesian;
pub mod sliding_polar;

pub use rolling::RollingReference;
pub use sliding::{
    SlidingOutputs, SlidingReference, Slip, SlipAcceleration, SlipChart, SlipRateColumns,
};
pub use sliding_cartesian::{Cartesian, SlidingCartesianReference};
pub use sliding_polar::{Polar, SlidingPolarReference};

use crate::DiskParams;
use model_runtime::{EvalError, ModelInfo, Name, Names, OpCounts};

/// Number of states of every disk model.
pub const N_STATES: usize = affine::DIM;

/// A reference model's info: the disk's parameters, no emitted code to count, the pivots it
/// checks, and one numeric block (the whole system, solved by LU at each call).
const fn reference_info(
    name: &'static str,
    states: &'static [&'static str],
    outputs: &'static [&'static str],
    pivots: &'static [&'static str],
) -> ModelInfo {
    ModelInfo {
        name: Name::Borrowed(name),
        state_names: Names::Static(states),
        param_names: Names::Static(&DiskParams::NAMES),
        output_names: Names::Static(outputs),
        rhs_ops: OpCounts::NONE,
        jacobian_ops: OpCounts::NONE,
        outputs_ops: OpCounts::NONE,
        pivots: Names::Static(pivots),
        numeric_blocks: Names::Static(&["all derivatives (12×12 LU)"]),
    }
}

/// Rejects a non-finite output, naming it.
fn check_outputs(
    model: &'static str,
    names: &[&'static str],
    out: &[f64],
) -> Result<(), EvalError> {
    match out.iter().zip(names).find(|(v, _)| !v.is_finite()) {
        Some((value, &quantity)) => Err(EvalError::NonFinite {
            model: model.into(),
            quantity: quantity.into(),
            value: *value,
        }),
        None => Ok(()),
    }
}
