//! The sliding disk in the Cartesian slip chart `u = v_C e_s = (u_X, u_Y)` (docs/physics.md §6).
//!
//! The same physics as the polar chart, but the slip rate is simply `(u̇_X, u̇_Y)`: nothing
//! turns infinitely fast when the slip vector passes near the origin. Only the friction
//! direction `u / |u|` is undefined at `u = 0`.

use super::affine::DIM;
use super::reference_info;
use super::sliding::{SlidingReference, Slip, SlipChart, SlipRateColumns};
use model_runtime::{EvalError, ModelInfo, WithOutputs};
use nalgebra::Vector3;

/// State indices of the Cartesian sliding model (the DSL's spelling).
#[allow(non_upper_case_globals)]
pub mod state {
    /// Centre position, `E_X` component (m).
    pub const X: usize = 0;
    /// Centre position, `E_Y` component (m).
    pub const Y: usize = 1;
    /// Centre height (m).
    pub const Z: usize = 2;
    /// Slip velocity of the contact particle, `E_X` component (m/s).
    pub const u_X: usize = 3;
    /// Slip velocity of the contact particle, `E_Y` component (m/s).
    pub const u_Y: usize = 4;
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

/// Output indices of the Cartesian sliding model.
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
    /// Slip speed `v_C = |u|` (m/s).
    pub const slip_speed: usize = 7;
    /// Friction direction `alpha = atan2(-u_Y, -u_X)` (rad).
    pub const slip_direction: usize = 8;
    /// Total energy (J).
    pub const energy: usize = 9;
    /// Friction power `-T v_C` (W).
    pub const friction_power: usize = 10;
    /// `Z - a sin θ` (m).
    pub const z_residual: usize = 11;
    /// `V_Z - a Ω_y cos θ` (m/s).
    pub const vz_residual: usize = 12;
}

/// Number of outputs of the Cartesian sliding model.
pub const N_OUTPUTS: usize = 13;

/// State names in index order.
pub const STATE_NAMES: [&str; DIM] = [
    "X", "Y", "Z", "u_X", "u_Y", "V_Z", "psi", "theta", "phi", "Omega_x", "Omega_y", "Omega_z",
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
    "slip_speed",
    "slip_direction",
    "energy",
    "friction_power",
    "z_residual",
    "vz_residual",
];

static INFO: ModelInfo = reference_info(
    Cartesian::NAME,
    &STATE_NAMES,
    &OUTPUT_NAMES,
    &["sin(theta)", "beta0", "v_C", "M(y)"],
);

/// The Cartesian chart `(u_X, u_Y)` of the slip velocity.
#[derive(Clone, Copy, Debug)]
pub enum Cartesian {}

impl SlipChart for Cartesian {
    const NAME: &'static str = "sliding_cartesian_reference";
    const DER_NAMES: [&'static str; DIM] = [
        "der(X)",
        "der(Y)",
        "der(Z)",
        "der(u_X)",
        "der(u_Y)",
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
        let (ux, uy) = (y[state::u_X], y[state::u_Y]);
        let speed = ux.hypot(uy);
        if speed == 0.0 || !speed.is_finite() {
            return Err(EvalError::SingularPivot {
                model: Self::NAME.into(),
                pivot: "v_C".into(),
                value: speed,
            });
        }
        Ok(Slip {
            speed,
            alpha: (-uy).atan2(-ux),
        })
    }

    fn slip_rate(_slip: &Slip) -> SlipRateColumns {
        SlipRateColumns {
            first: Vector3::x(),
            second: Vector3::y(),
        }
    }

    fn unknowns_to_derivatives(_slip: &Slip, _x: &mut [f64; DIM]) -> Result<(), EvalError> {
        Ok(())
    }

    fn derivatives_to_unknowns(_slip: &Slip, _x: &mut [f64; DIM]) {}
}

/// The sliding disk in the Cartesian slip chart.
pub type SlidingCartesianReference = SlidingReference<Cartesian>;

impl WithOutputs<DIM, N_OUTPUTS> for SlidingCartesianReference {
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
            o.slip_speed,
            o.alpha,
            o.energy,
            o.friction_power,
            o.z_residual,
            o.vz_residual,
        ];
        super::check_outputs(Cartesian::NAME, &OUTPUT_NAMES, out)
    }
}
