//! The pair of models a hybrid run integrates, whoever wrote them.
//!
//! The mode logic must run unchanged on the hand-written reference and on the models the
//! equation compiler emits, so it sees the models only through [`Model<12>`]: everything it needs
//! beyond `rhs` — the contact force, the slip, the acceleration of the contact particle at zero
//! slip — is derived from `rhs` and the shared state layout ([`crate::modes::layout`]).
//!
//! Three sets exist: the hand-written reference, the generated models, and the generated
//! *pruned* variants ([`PrunedModels`]), which integrate only what the mode switching needs in
//! still air (8 of the 12 states; [`super::embedded`] explains how they run in the 12-state
//! driver and why the states they drop must never be reported).

use super::embedded::{Embedded, Embedding};
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

/// A generated model for a disk in moving air, or its variant with still air compiled in
/// (`still`: every state kept, `mu_a = 0` and `w_z = 0` fixed), chosen at run time by the
/// parameters.
///
/// A disk in still air integrates the variant, whose air terms vanished at compile time, so it
/// pays nothing for air it does not have ("model only what the scene requires"); it is also
/// what the mode graph integrates (`crate::hybrid::switching`, whose air is still), to the bit.
/// Dispatch is one `match` per evaluation, as for [`SlidingModel`].
#[derive(Clone, Copy, Debug)]
pub enum AirModel<M, S> {
    /// Any air: `mu_a` and `w_z` are parameters.
    Moving(M),
    /// Still air, compiled in.
    Still(S),
}

impl<M, S> AirModel<M, S> {
    /// The still variant built from `still`'s parameters (the disk's without the air's) where
    /// there are some, else the model with air.
    fn of(
        still: Option<[f64; STILL_PARAMS]>,
        moving: impl FnOnce() -> M,
        variant: impl FnOnce([f64; STILL_PARAMS]) -> S,
    ) -> Self {
        match still {
            Some(p) => AirModel::Still(variant(p)),
            None => AirModel::Moving(moving()),
        }
    }
}

/// `Model<DIM>` for an enum holding one of two models (`$a` or `$b`), dispatched by one
/// `match` per call: the sliding model in either chart, a model with or without air.
macro_rules! one_of_two_models {
    ($name:ident, $a:ident, $b:ident) => {
        impl<A: Model<DIM>, B: Model<DIM>> Model<DIM> for $name<A, B> {
            fn info(&self) -> &'static ModelInfo {
                match self {
                    $name::$a(m) => m.info(),
                    $name::$b(m) => m.info(),
                }
            }

            #[inline]
            fn rhs(&self, t: f64, y: &[f64; DIM], dy: &mut [f64; DIM]) -> Result<(), EvalError> {
                match self {
                    $name::$a(m) => m.rhs(t, y, dy),
                    $name::$b(m) => m.rhs(t, y, dy),
                }
            }

            fn jacobian(
                &self,
                t: f64,
                y: &[f64; DIM],
                jac: &mut [[f64; DIM]; DIM],
            ) -> Result<(), EvalError> {
                match self {
                    $name::$a(m) => m.jacobian(t, y, jac),
                    $name::$b(m) => m.jacobian(t, y, jac),
                }
            }
        }
    };
}

one_of_two_models!(SlidingModel, Cartesian, Polar);
one_of_two_models!(AirModel, Moving, Still);

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

/// The models the equation compiler generated from the paper's boxes (the default for runs):
/// in still air their `still` variants, else the models with the air as parameters
/// ([`AirModel`]).
pub type GeneratedModels = DiskModels<
    AirModel<rolling::Model, rolling::still::Model>,
    SlidingModel<
        AirModel<sliding_cartesian::Model, sliding_cartesian::still::Model>,
        AirModel<sliding::Model, sliding::still::Model>,
    >,
>;

impl GeneratedModels {
    /// The generated models for `params`, sliding in `chart`: the still-air variants when
    /// `mu_a` and `w_z` are zero.
    pub fn generated(params: DiskParams, chart: SlipChart) -> Result<Self, ParamError> {
        let params = params.validated()?;
        let values = params.to_array();
        let still = (params.mu_a == 0.0 && params.w_z == 0.0).then(|| still_params(&params));
        let sliding = match chart {
            SlipChart::Cartesian => SlidingModel::Cartesian(AirModel::of(
                still,
                || sliding_cartesian::Model::new(values),
                sliding_cartesian::still::Model::new,
            )),
            SlipChart::Polar => SlidingModel::Polar(AirModel::of(
                still,
                || sliding::Model::new(values),
                sliding::still::Model::new,
            )),
        };
        let rolling = AirModel::of(
            still,
            || rolling::Model::new(values),
            rolling::still::Model::new,
        );
        Ok(DiskModels {
            params,
            rolling,
            sliding,
            chart,
        })
    }
}

/// Number of parameters of the still-air variants: the disk's less the air's two.
const STILL_PARAMS: usize = rolling::still::N_PARAMS;

/// A still-air variant's parameters: the disk's without `mu_a` and `w_z`, which come last
/// (test `still_variants_take_the_disks_parameters_without_the_air`).
fn still_params(params: &DiskParams) -> [f64; STILL_PARAMS] {
    let values = params.to_array();
    std::array::from_fn(|i| values[i])
}

/// A pruned variant of a generated model, run in the 12-state layout.
pub type Pruned<M> = Embedded<M, PRUNED_STATES>;

/// Number of states the pruned variants integrate (the same for all three).
pub const PRUNED_STATES: usize = rolling::pruned::N_STATES;

/// The pruned variants of the generated models: still air compiled in, `X`, `Y`, `Z` and `φ`
/// frozen ([`PrunedModels::frozen_states`]).
pub type PrunedModels = DiskModels<
    Pruned<rolling::pruned::Model>,
    SlidingModel<Pruned<sliding_cartesian::pruned::Model>, Pruned<sliding::pruned::Model>>,
>;

/// Why the pruned models cannot run a disk.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PruneError {
    /// The parameters are invalid.
    #[error("invalid parameters: {0}")]
    Params(#[from] ParamError),
    /// The pruned variants fix the air to still (`mu_a = 0`, `w_z = 0`) at compile time.
    #[error("the pruned models assume still air, but parameter `{name}` = {value} (must be 0)")]
    AirNotStill {
        /// The parameter (`mu_a` or `w_z`).
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// A variant has a parameter the disk does not.
    #[error("model `{model}` has a parameter `{name}` that the disk's parameters lack")]
    UnknownParam {
        /// The variant.
        model: String,
        /// The parameter.
        name: String,
    },
}

/// A variant's parameter array, taken from `params` by the variant's parameter names.
fn variant_params<const P: usize>(
    info: &'static ModelInfo,
    params: &DiskParams,
) -> Result<[f64; P], PruneError> {
    let values = params.to_array();
    let mut out = [0.0; P];
    for (slot, name) in out.iter_mut().zip(info.param_names.iter()) {
        let i = (DiskParams::NAMES.iter().position(|&n| n == name)).ok_or_else(|| {
            PruneError::UnknownParam {
                model: info.name.to_string(),
                name: name.to_string(),
            }
        })?;
        *slot = values[i];
    }
    Ok(out)
}

impl PrunedModels {
    /// The pruned variants for `params`, sliding in `chart`; the air must be still.
    pub fn pruned(params: DiskParams, chart: SlipChart) -> Result<Self, PruneError> {
        let params = params.validated()?;
        for (name, value) in [("mu_a", params.mu_a), ("w_z", params.w_z)] {
            if value != 0.0 {
                return Err(PruneError::AirNotStill { name, value });
            }
        }
        let sliding = match chart {
            SlipChart::Cartesian => {
                SlidingModel::Cartesian(Embedded::new(sliding_cartesian::pruned::Model::new(
                    variant_params(&sliding_cartesian::pruned::INFO, &params)?,
                )))
            }
            SlipChart::Polar => SlidingModel::Polar(Embedded::new(sliding::pruned::Model::new(
                variant_params(&sliding::pruned::INFO, &params)?,
            ))),
        };
        let rolling = Embedded::new(rolling::pruned::Model::new(variant_params(
            &rolling::pruned::INFO,
            &params,
        )?));
        Ok(DiskModels {
            params,
            rolling,
            sliding,
            chart,
        })
    }

    /// The states of the rolling layout that either mode leaves frozen, by name (`X`, `Y`, `Z`,
    /// `phi`): their values in a run's samples, and everything computed from them (the energy,
    /// the height residual `Z − a sin θ`), are not results. A slip kept by the sliding variant
    /// counts as keeping `V_X` and `V_Y`, which follow from it.
    pub fn frozen_states(&self) -> Vec<&'static str> {
        let sliding: Embedding<PRUNED_STATES> = match &self.sliding {
            SlidingModel::Cartesian(m) => m.embedding(),
            SlidingModel::Polar(m) => m.embedding(),
        };
        let rolling = self.rolling.embedding();
        (0..DIM)
            .filter(|&i| !(rolling.keeps(i) && sliding.keeps(i)))
            .map(|i| rolling::STATE_NAMES[i])
            .collect()
    }
}

/// Slip speed at which the sliding model is probed to read the contact acceleration "at zero
/// slip". The accelerations contain no `1/v_C` (docs/physics.md §4.2): the speed enters only
/// through the air drag, `k_F v_C`, so at `1e-30` m/s the probe differs from the limit `v_C → 0` by
/// far less than round-off, while `v_C²` (a pivot of the Cartesian chart) stays a normal number.
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modes::layout::{OMEGA_X, OMEGA_Y, OMEGA_Z, PSI, THETA, V_X, V_Y, V_Z, Z};

    #[test]
    fn still_variants_take_the_disks_parameters_without_the_air() {
        for info in [
            &rolling::still::INFO,
            &sliding::still::INFO,
            &sliding_cartesian::still::INFO,
        ] {
            let names: [&str; STILL_PARAMS] = std::array::from_fn(|i| DiskParams::NAMES[i]);
            assert_eq!(info.param_names, names, "{}", info.name);
        }
    }

    /// A state with every term of the boxes alive: `V_X, V_Y` rolling, the slip in those slots
    /// sliding (`(u_X, u_Y)`, or `(v_C, alpha)` in the polar chart).
    fn state(k: usize) -> [f64; DIM] {
        let mut y = [0.0; DIM];
        let theta = 0.2 + 0.13 * k as f64;
        y[THETA] = theta;
        y[Z] = 0.03755 * theta.sin();
        y[PSI] = 0.7 * k as f64;
        y[V_X] = 0.01 * (k as f64 - 2.0) + 0.005;
        y[V_Y] = -0.02 + 0.005 * k as f64;
        y[V_Z] = 0.001 * k as f64;
        y[OMEGA_X] = 0.3;
        y[OMEGA_Y] = -0.2 * k as f64;
        y[OMEGA_Z] = 5.0 + 11.0 * k as f64;
        y
    }

    /// `a` and `b` agree to round-off, row by row.
    fn agree(what: &str, a: &dyn Model<DIM>, b: &dyn Model<DIM>, y: &[f64; DIM]) {
        let (mut da, mut db) = ([0.0; DIM], [0.0; DIM]);
        a.rhs(0.0, y, &mut da).unwrap();
        b.rhs(0.0, y, &mut db).unwrap();
        for i in 0..DIM {
            let scale = da[i].abs().max(db[i].abs()).max(1e-300);
            assert!(
                (da[i] - db[i]).abs() <= 1e-13 * scale,
                "{what} row {i}: {} vs {}",
                da[i],
                db[i]
            );
        }
    }

    /// In still air the generated models are the `still` variants, which give the full models'
    /// derivatives at `mu_a = w_z = 0` (to round-off: the simplifier may order the sums
    /// differently once the air's terms are gone); with air, the full models.
    #[test]
    fn still_air_runs_the_still_variants_and_they_agree_with_the_full_models() {
        let params = DiskParams::paper();
        let values = params.to_array();
        for chart in [SlipChart::Cartesian, SlipChart::Polar] {
            let models = GeneratedModels::generated(params, chart).unwrap();
            assert!(models.rolling.info().name.ends_with("::still"));
            assert!(models.sliding.info().name.ends_with("::still"));
            let full_sliding: SlidingModel<sliding_cartesian::Model, sliding::Model> = match chart {
                SlipChart::Cartesian => {
                    SlidingModel::Cartesian(sliding_cartesian::Model::new(values))
                }
                SlipChart::Polar => SlidingModel::Polar(sliding::Model::new(values)),
            };
            for k in 0..8 {
                let y = state(k);
                agree("rolling", &models.rolling, &rolling::Model::new(values), &y);
                agree("sliding", &models.sliding, &full_sliding, &y);
            }
        }
        let air = DiskParams {
            mu_a: 1e-3,
            ..params
        };
        let models = GeneratedModels::generated(air, SlipChart::Cartesian).unwrap();
        assert!(!models.rolling.info().name.ends_with("::still"));
        assert!(!models.sliding.info().name.ends_with("::still"));
    }
}
