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

mod affine;
mod body;
pub mod rolling;
pub mod sliding;
pub mod sliding_cartesian;
pub mod sliding_polar;

pub use rolling::RollingReference;
pub use sliding::{
    Slip, SlipAcceleration, SlipChart, SlipRateColumns, SlidingOutputs, SlidingReference,
};
pub use sliding_cartesian::{Cartesian, SlidingCartesianReference};
pub use sliding_polar::{Polar, SlidingPolarReference};

use model_runtime::{EvalError, OpCounts};

/// Number of states of every disk model.
pub const N_STATES: usize = affine::DIM;

/// Hand-written models have no emitted code to count.
const ZERO_OPS: OpCounts = OpCounts {
    add: 0,
    mul: 0,
    div: 0,
    sqrt: 0,
    trig: 0,
    transcendental: 0,
};

/// Rejects a non-finite output, naming it.
fn check_outputs(model: &'static str, names: &[&'static str], out: &[f64]) -> Result<(), EvalError> {
    match out.iter().zip(names).find(|(v, _)| !v.is_finite()) {
        Some((value, quantity)) => Err(EvalError::NonFinite {
            model,
            quantity,
            value: *value,
        }),
        None => Ok(()),
    }
}
