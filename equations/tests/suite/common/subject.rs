//! A model under test, whatever its origin: the reference or generated code. Tests are
//! written once against these helpers and run on every implementation.

use equations::reference::{rolling, sliding_cartesian, sliding_polar};
use equations::DiskParams;
use model_runtime::{EvalError, WithOutputs};

/// Derivatives and outputs at one state.
pub struct Eval<const M: usize> {
    pub dy: [f64; 12],
    pub out: [f64; M],
}

/// Evaluates `rhs` then `outputs`.
pub fn eval<T: WithOutputs<12, M>, const M: usize>(
    model: &T,
    y: &[f64; 12],
) -> Result<Eval<M>, EvalError> {
    let mut dy = [0.0; 12];
    model.rhs(0.0, y, &mut dy)?;
    let mut out = [0.0; M];
    model.outputs(0.0, y, &dy, &mut out)?;
    Ok(Eval { dy, out })
}

/// A family of models of one mode, built from the disk's parameters.
pub trait Family<const M: usize> {
    type Model: WithOutputs<12, M>;
    /// The implementation's name, for messages.
    const NAME: &'static str;
    fn build(p: &DiskParams) -> Self::Model;
}

/// The rolling outputs, in the reference's order (the generated models must match it).
pub const ROLLING_OUTPUTS: usize = rolling::N_OUTPUTS;
/// The polar sliding outputs.
pub const SLIDING_OUTPUTS: usize = sliding_polar::N_OUTPUTS;
/// The Cartesian sliding outputs.
pub const CARTESIAN_OUTPUTS: usize = sliding_cartesian::N_OUTPUTS;

pub struct RollingRef;
impl Family<ROLLING_OUTPUTS> for RollingRef {
    type Model = equations::reference::RollingReference;
    const NAME: &'static str = "rolling reference";
    fn build(p: &DiskParams) -> Self::Model {
        equations::reference::RollingReference::new(*p).unwrap()
    }
}

pub struct SlidingRef;
impl Family<SLIDING_OUTPUTS> for SlidingRef {
    type Model = equations::reference::SlidingPolarReference;
    const NAME: &'static str = "sliding polar reference";
    fn build(p: &DiskParams) -> Self::Model {
        equations::reference::SlidingPolarReference::new(*p).unwrap()
    }
}

pub struct CartesianRef;
impl Family<CARTESIAN_OUTPUTS> for CartesianRef {
    type Model = equations::reference::SlidingCartesianReference;
    const NAME: &'static str = "sliding cartesian reference";
    fn build(p: &DiskParams) -> Self::Model {
        equations::reference::SlidingCartesianReference::new(*p).unwrap()
    }
}

pub struct RollingGen;
impl Family<ROLLING_OUTPUTS> for RollingGen {
    type Model = equations::models::rolling::Model;
    const NAME: &'static str = "rolling (generated)";
    fn build(p: &DiskParams) -> Self::Model {
        equations::models::rolling::Model::new(p.to_array())
    }
}

pub struct SlidingGen;
impl Family<SLIDING_OUTPUTS> for SlidingGen {
    type Model = equations::models::sliding::Model;
    const NAME: &'static str = "sliding polar (generated)";
    fn build(p: &DiskParams) -> Self::Model {
        equations::models::sliding::Model::new(p.to_array())
    }
}

pub struct CartesianGen;
impl Family<CARTESIAN_OUTPUTS> for CartesianGen {
    type Model = equations::models::sliding_cartesian::Model;
    const NAME: &'static str = "sliding cartesian (generated)";
    fn build(p: &DiskParams) -> Self::Model {
        equations::models::sliding_cartesian::Model::new(p.to_array())
    }
}
