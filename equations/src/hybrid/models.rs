//! The pair of models a hybrid run integrates, whoever wrote them.
//!
//! The mode logic must run unchanged on the hand-written reference and on the models the
//! equation compiler emits, so it sees the models only through [`Model<12>`]: everything it needs
//! beyond `rhs` — the contact force, the slip, the acceleration of the contact particle at zero
//! slip — is derived from `rhs` and the shared state layout ([`crate::modes::layout`]).

use super::onset::SlipAcceleration;
use crate::models::{rolling, sliding, sliding_cartesian};
use crate::modes::{PhysicalState, Slip, SlipChart, DIM};
use crate::params::DiskParams;
use crate::reference::{RollingReference, SlidingCartesianReference, SlidingPolarReference};
use crate::ParamError;
use model_runtime::{EvalError, Model, ModelInfo};

/// A sliding model in either chart, chosen at run time.
///
/// Dispatch is one `match` per evaluation, negligible beside the model itself, and it keeps the
/// chart a run-time option without a second copy of the driver.
#[derive(Clone, Copy, Debug)]
pub enum SlidingModel<C, P> {
    /// The Cartesian chart `(u_X, u_Y)`.
    Cartesian(C),
    /// The polar chart `(v_C, α)`.
    Polar(P),
}

impl<C, P> SlidingModel<C, P> {
    /// Which chart the model carries the slip in.
    pub fn chart(&self) -> SlipChart {
        match self {
            SlidingModel::Cartesian(_) => SlipChart::Cartesian,
            SlidingModel::Polar(_) => SlipChart::Polar,
        }
    }
}

impl<C: Model<DIM>, P: Model<DIM>> Model<DIM> for SlidingModel<C, P> {
    fn info(&self) -> &'static ModelInfo {
        match self {
            SlidingModel::Cartesian(m) => m.info(),
            SlidingModel::Polar(m) => m.info(),
        }
    }

    #[inline]
    fn rhs(&self, t: f64, y: &[f64; DIM], dy: &mut [f64; DIM]) -> Result<(), EvalError> {
        match self {
            SlidingModel::Cartesian(m) => m.rhs(t, y, dy),
            SlidingModel::Polar(m) => m.rhs(t, y, dy),
        }
    }

    fn jacobian(
        &self,
        t: f64,
        y: &[f64; DIM],
        jac: &mut [[f64; DIM]; DIM],
    ) -> Result<(), EvalError> {
        match self {
            SlidingModel::Cartesian(m) => m.jacobian(t, y, jac),
            SlidingModel::Polar(m) => m.jacobian(t, y, jac),
        }
    }
}

/// The disk's parameters, its rolling model and its sliding model.
#[derive(Clone, Copy, Debug)]
pub struct DiskModels<R, S> {
    /// Parameters shared by both models (the models must have been built from the same).
    pub params: DiskParams,
    /// The rolling model, state `(X, Y, Z, V_X, V_Y, V_Z, ψ, θ, φ, Ω_x, Ω_y, Ω_z)`.
    pub rolling: R,
    /// The sliding model in one of the two charts.
    pub sliding: S,
    /// The chart of `sliding`.
    pub chart: SlipChart,
}

/// The hand-written reference models.
pub type ReferenceModels =
    DiskModels<RollingReference, SlidingModel<SlidingCartesianReference, SlidingPolarReference>>;

impl ReferenceModels {
    /// The reference models for `params`, sliding in `chart`.
    pub fn reference(params: DiskParams, chart: SlipChart) -> Result<Self, ParamError> {
        let sliding = match chart {
            SlipChart::Cartesian => {
                SlidingModel::Cartesian(SlidingCartesianReference::new(params)?)
            }
            SlipChart::Polar => SlidingModel::Polar(SlidingPolarReference::new(params)?),
        };
        Ok(DiskModels {
            params: params.validated()?,
            rolling: RollingReference::new(params)?,
            sliding,
            chart,
        })
    }
}

/// The models the equation compiler generated from the paper's boxes (the default for runs).
pub type GeneratedModels =
    DiskModels<rolling::Model, SlidingModel<sliding_cartesian::Model, sliding::Model>>;

impl GeneratedModels {
    /// The generated models for `params`, sliding in `chart`.
    pub fn generated(params: DiskParams, chart: SlipChart) -> Result<Self, ParamError> {
        let params = params.validated()?;
        let values = params.to_array();
        let sliding = match chart {
            SlipChart::Cartesian => SlidingModel::Cartesian(sliding_cartesian::Model::new(values)),
            SlipChart::Polar => SlidingModel::Polar(sliding::Model::new(values)),
        };
        Ok(DiskModels {
            params,
            rolling: rolling::Model::new(values),
            sliding,
            chart,
        })
    }
}

/// Slip speed at which the sliding model is probed to read the contact acceleration "at zero
/// slip". The accelerations contain no `1/v_C` (EQUATIONS.md §4): the speed enters only through
/// the air drag, `k_F v_C`, so at `1e-30` m/s the probe differs from the limit `v_C → 0` by far
/// less than round-off, while `v_C²` (a pivot of the Cartesian chart) stays a normal number.
pub const PROBE_SLIP_SPEED: f64 = 1e-30;

impl<R: Model<DIM>, S: Model<DIM>> DiskModels<R, S> {
    /// The sliding state vector for a physical state and a slip.
    pub fn sliding_vector(&self, state: &PhysicalState, slip: Slip) -> [f64; DIM] {
        state.sliding_vector(self.chart, slip)
    }

    /// Reads a sliding state vector.
    pub fn sliding_state(&self, y: &[f64; DIM]) -> PhysicalState {
        PhysicalState::from_sliding(self.chart, &self.params, y)
    }

    /// Splits a sliding derivative into the slip's acceleration along and across `e_s`, at a
    /// state whose slip is `slip` (`w = v_C α̇`).
    pub fn slip_acceleration_of(&self, slip: Slip, dy: &[f64; DIM]) -> SlipAcceleration {
        use crate::modes::layout::{ALPHA, U_X, U_Y, V_C};
        match self.chart {
            SlipChart::Cartesian => {
                let (s, c) = slip.direction.sin_cos();
                // e_s = -(cos α, sin α), e_s⊥ = (sin α, -cos α).
                SlipAcceleration {
                    along: -(dy[U_X] * c + dy[U_Y] * s),
                    across: dy[U_X] * s - dy[U_Y] * c,
                }
            }
            SlipChart::Polar => SlipAcceleration {
                along: dy[V_C],
                across: dy[ALPHA] * slip.speed,
            },
        }
    }

    /// The contact particle's acceleration at zero slip with friction direction `alpha`, and
    /// the full sliding derivative there (probed at [`PROBE_SLIP_SPEED`]).
    pub fn probe_onset(
        &self,
        t: f64,
        state: &PhysicalState,
        alpha: f64,
    ) -> Result<(SlipAcceleration, [f64; DIM]), EvalError> {
        let slip = Slip {
            speed: PROBE_SLIP_SPEED,
            direction: alpha,
        };
        let y = self.sliding_vector(state, slip);
        let mut dy = [0.0; DIM];
        self.sliding.rhs(t, &y, &mut dy)?;
        Ok((self.slip_acceleration_of(slip, &dy), dy))
    }
}
