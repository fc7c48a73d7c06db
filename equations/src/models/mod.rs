//! The paper's models in the equation DSL, compiled to explicit Rust at build time.
//!
//! The rows of each box are a `.dsl` file that reads like its box in the paper (row labels
//! R1–R12 in `box1_rolling.dsl`, S1–S12 in `box3_sliding.dsl`), included by the models here and
//! by the modes of the disk's mode graph (`crate::hybrid::switching`), so the disk is said
//! once; docs/physics.md §12 lists where the printed boxes were damaged and what was restored. The emitted modules implement
//! `model_runtime::Model<12>` and `WithOutputs`, with the same state and output order as the
//! hand-written reference in `crate::reference`, which the tests hold them to.
//!
//! ```
//! use equations::models::sliding;
//! use model_runtime::{Model, WithOutputs};
//!
//! // Paper's parameters by default; a sliding state with slip speed 0.1 m/s.
//! let model = sliding::Model::default();
//! let mut y = [0.0; sliding::N_STATES];
//! y[sliding::state::theta] = 0.5;
//! y[sliding::state::Z] = 0.03755 * 0.5f64.sin();
//! y[sliding::state::v_C] = 0.1;
//! y[sliding::state::Omega_z] = 30.0;
//! let mut dy = [0.0; sliding::N_STATES];
//! model.rhs(0.0, &y, &mut dy)?;
//! let mut out = [0.0; sliding::N_OUTPUTS];
//! model.outputs(0.0, &y, &dy, &mut out)?;
//! // Friction saturates while sliding: T = mu_d N.
//! assert!((out[sliding::output::nu] - 0.115).abs() < 1e-15);
//! // A flat disk is refused by name, never a NaN.
//! y[sliding::state::theta] = 0.0;
//! assert!(model.rhs(0.0, &y, &mut dy).is_err());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod box1_rolling;
mod box3_sliding;

pub use box1_rolling::rolling;
pub use box3_sliding::{sliding, sliding_cartesian};
