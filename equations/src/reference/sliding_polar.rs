//! The sliding disk in the paper's polar slip chart `(v_C, α)`.
//!
//! The solve uses `w = v_C α̇` as its unknown instead of `α̇`, so the linear system stays
//! regular at `v_C = 0`; only the final `α̇ = w / v_C` is singular there, and reports it.

use super::affine::DIM;
use super::reference_info;
use super::sliding::{SlidingReference, Slip, SlipChart, SlipRateColumns};
use model_runtime::{EvalError, ModelInfo, WithOutputs};

/// State indices of the polar sliding model (the DSL's spelling).
#[allow(non_upper_case_globals)]
pub mod state {
    /// Centre position, `E_X` component (m).
    pub const X: usize = 0;
    /// Centre position, `E_Y` component (m).
    pub const Y: usize = 1;
    /// Centre height (m).
    pub const Z: usize = 2;
    /// Slip speed of the contact particle (m/s).
    pub const v_C: usize = 3;
    /// Direction of the friction force (rad): slip is along `-(cos α, sin α)`.
    pub const alpha: usize = 4;
    /// Centre velocity, vertical (m/s).
    pub const V_Z: usize = 5;
    /// Precession angle (rad).
    pub const psi: usize = 6;
    /// Inclination of the disk plane to the floor (rad).
    pub const theta: usize = 7;
    /// Spin angle (rad).
    pub const phi: usize = 8;
    /// Angular velocity along `e_x` (rad/s).
    pub const Omega_x: usize = 9;
    /// Angular velocity along `e_y` (rad/s).
    pub const Omega_y: usize = 10;
    /// Angular velocity along the normal `e_z` (rad/s).
    pub const Omega_z: usize = 11;
}

/// Output indices of the polar sliding model.
#[allow(non_upper_case_globals)]
pub mod output {
    /// Normal contact force (N).
    pub const N: usize = 0;
    /// Friction force `μ_d N` (N).
    pub const T: usize = 1;
    /// Contact force, `E_X` component (N).
    pub const R_X: usize = 2;
    /// Contact force, `E_Y` component (N).
    pub const R_Y: usize = 3;
    /// `T/N` (equals `μ_d`).
    pub const nu: usize = 4;
    /// Centre velocity, `E_X` component (m/s).
    pub const V_X: usize = 5;
    /// Centre velocity, `E_Y` component (m/s).
    pub const V_Y: usize = 6;
    /// Total energy (J).
    pub const energy: usize = 7;
    /// Friction power `-T v_C` (W).
    pub const friction_power: usize = 8;
    /// `Z - a sin θ` (m).
    pub const z_residual: usize = 9;
    /// `V_Z - a Ω_y cos θ` (m/s).
    pub const vz_residual: usize = 10;
}

/// Number of outputs of the polar sliding model.
pub const N_OUTPUTS: usize = 11;

/// State names in index order.
pub const STATE_NAMES: [&str; DIM] = [
    "X", "Y", "Z", "v_C", "alpha", "V_Z", "psi", "theta", "phi", "Omega_x", "Omega_y", "Omega_z",
];

/// Output names in index order.
pub const OUTPUT_NAMES: [&str; N_OUTPUTS] = [
    "N",
    "T",
    "R_X",
    "R_Y",
    "nu",
    "V_X",
    "V_Y",
    "energy",
    "friction_power",
    "z_residual",
    "vz_residual",
];

static INFO: ModelInfo = reference_info(
    Polar::NAME,
    &STATE_NAMES,
    &OUTPUT_NAMES,
    &["sin(theta)", "beta0", "v_C", "M(y)"],
);

/// The polar chart `(v_C, α)` of the slip velocity.
#[derive(Clone, Copy, Debug)]
pub enum Polar {}

impl SlipChart for Polar {
    const NAME: &'static str = "sliding_reference";
    const DER_NAMES: [&'static str; DIM] = [
        "der(X)",
        "der(Y)",
        "der(Z)",
        "der(v_C)",
        "der(alpha)",
        "der(V_Z)",
        "der(psi)",
        "der(theta)",
        "der(phi)",
        "der(Omega_x)",
        "der(Omega_y)",
        "der(Omega_z)",
    ];

    fn info() -> &'static ModelInfo {
        &INFO
    }

    fn slip(y: &[f64; DIM]) -> Result<Slip, EvalError> {
        Ok(Slip {
            speed: y[state::v_C],
            alpha: y[state::alpha],
        })
    }

    /// `d/dt (v_C e_s) = v̇_C e_s + w e_s⊥` with `w = v_C α̇` in the `alpha` slot.
    fn slip_rate(slip: &Slip) -> SlipRateColumns {
        let e_s = slip.direction();
        SlipRateColumns {
            first: e_s,
            second: nalgebra::Vector3::new(-e_s.y, e_s.x, 0.0),
        }
    }

    fn unknowns_to_derivatives(slip: &Slip, x: &mut [f64; DIM]) -> Result<(), EvalError> {
        if slip.speed == 0.0 || !slip.speed.is_finite() {
            return Err(EvalError::SingularPivot {
                model: Self::NAME.into(),
                pivot: "v_C".into(),
                value: slip.speed,
            });
        }
        x[state::alpha] /= slip.speed;
        if !x[state::alpha].is_finite() {
            return Err(EvalError::NonFinite {
                model: Self::NAME.into(),
                quantity: "der(alpha)".into(),
                value: x[state::alpha],
            });
        }
        Ok(())
    }

    fn derivatives_to_unknowns(slip: &Slip, x: &mut [f64; DIM]) {
        x[state::alpha] *= slip.speed;
    }
}

/// The sliding disk in the paper's polar chart.
pub type SlidingPolarReference = SlidingReference<Polar>;

impl WithOutputs<DIM, N_OUTPUTS> for SlidingPolarReference {
    fn outputs(
        &self,
        _t: f64,
        y: &[f64; DIM],
        dy: &[f64; DIM],
        out: &mut [f64; N_OUTPUTS],
    ) -> Result<(), EvalError> {
        let o = self.named_outputs(y, dy)?;
        *out = [
            o.normal,
            o.friction,
            o.r_x,
            o.r_y,
            o.nu,
            o.v_x,
            o.v_y,
            o.energy,
            o.friction_power,
            o.z_residual,
            o.vz_residual,
        ];
        super::check_outputs(Polar::NAME, &OUTPUT_NAMES, out)
    }
}
