//! Reference model of the rolling disk.
//!
//! Rolling means the contact particle is at rest: `V + Ω × a e_x = 0`, imposed (as in the
//! paper) in differential form. The contact force is whatever linear momentum requires,
//! `R = m V̇ + m g E_Z - F_a`, and enters the angular-momentum balance through its moment.
//! The solve carries `V̇` in frame components (rotated to `V̇_X, V̇_Y, V̇_Z` afterwards), so
//! the spin rate, which only sees `V̇ · e_y`, does not inherit the size of `V̇_X, V̇_Y`.

use super::affine::{Affine, AffineVec, DIM};
use super::body::{idx, solve_rows, Body};
use super::reference_info;
use crate::{DiskParams, ParamError};
use model_runtime::{EvalError, Model, ModelInfo, WithOutputs};
use nalgebra::Vector3;

/// State indices of the rolling model (the DSL's spelling).
#[allow(non_upper_case_globals)]
pub mod state {
    /// Centre position, `E_X` component (m).
    pub const X: usize = 0;
    /// Centre position, `E_Y` component (m).
    pub const Y: usize = 1;
    /// Centre height (m).
    pub const Z: usize = 2;
    /// Centre velocity, `E_X` component (m/s).
    pub const V_X: usize = 3;
    /// Centre velocity, `E_Y` component (m/s).
    pub const V_Y: usize = 4;
    /// Centre velocity, vertical (m/s).
    pub const V_Z: usize = 5;
    /// Precession angle (rad).
    pub const psi: usize = 6;
    /// Inclination of the disk plane to the floor (rad), `π/2` upright.
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

/// Output indices of the rolling model.
#[allow(non_upper_case_globals)]
pub mod output {
    /// Contact force, `E_X` component (N).
    pub const R_X: usize = 0;
    /// Contact force, `E_Y` component (N).
    pub const R_Y: usize = 1;
    /// Normal contact force (N).
    pub const N: usize = 2;
    /// Magnitude of the horizontal contact force needed for rolling (N).
    pub const T: usize = 3;
    /// Friction ratio `T/N` rolling needs.
    pub const nu: usize = 4;
    /// Direction of the needed friction force, `atan2(R_Y, R_X)` (rad).
    pub const alpha_r: usize = 5;
    /// Total energy (J).
    pub const energy: usize = 6;
    /// `Z - a sin θ` (m).
    pub const z_residual: usize = 7;
    /// `V_Z - a Ω_y cos θ` (m/s).
    pub const vz_residual: usize = 8;
    /// `V_X - a (Ω_y cos ψ sin θ + Ω_z sin ψ)` (m/s).
    pub const vx_residual: usize = 9;
    /// `V_Y - a (Ω_y sin ψ sin θ - Ω_z cos ψ)` (m/s).
    pub const vy_residual: usize = 10;
}

/// Number of rolling outputs.
pub const N_OUTPUTS: usize = 11;

/// State names in index order.
pub const STATE_NAMES: [&str; DIM] = [
    "X", "Y", "Z", "V_X", "V_Y", "V_Z", "psi", "theta", "phi", "Omega_x", "Omega_y", "Omega_z",
];

/// Output names in index order.
pub const OUTPUT_NAMES: [&str; N_OUTPUTS] = [
    "R_X",
    "R_Y",
    "N",
    "T",
    "nu",
    "alpha_r",
    "energy",
    "z_residual",
    "vz_residual",
    "vx_residual",
    "vy_residual",
];

const DER_NAMES: [&str; DIM] = [
    "der(X)",
    "der(Y)",
    "der(Z)",
    "der(V_X)",
    "der(V_Y)",
    "der(V_Z)",
    "der(psi)",
    "der(theta)",
    "der(phi)",
    "der(Omega_x)",
    "der(Omega_y)",
    "der(Omega_z)",
];

const NAME: &str = "rolling_reference";

static INFO: ModelInfo = reference_info(NAME, &STATE_NAMES, &OUTPUT_NAMES, &["sin(theta)", "M(y)"]);

/// The rolling disk, assembled from the balance laws and solved numerically at each call.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RollingReference {
    params: DiskParams,
}

/// The implicit system at one state, with the contact force still affine in `ẏ`.
struct Assembled {
    body: Body,
    rows: [Affine; DIM],
    velocity: Vector3<f64>,
}

impl RollingReference {
    /// A rolling reference for validated parameters.
    pub fn new(params: DiskParams) -> Result<Self, ParamError> {
        Ok(RollingReference {
            params: params.validated()?,
        })
    }

    /// The parameters.
    pub fn params(&self) -> &DiskParams {
        &self.params
    }

    fn assemble(&self, y: &[f64; DIM]) -> Result<Assembled, EvalError> {
        let body = Body::new(self.params, y);
        body.check_chart(NAME, &INFO.state_names, y)?;
        let p = &self.params;
        let velocity = Vector3::new(y[state::V_X], y[state::V_Y], y[state::V_Z]);
        // The solve's unknowns 3–5 are the frame components of V̇ (rotated back to V̇_X, V̇_Y,
        // V̇_Z afterwards): near a flat disk V̇_X and V̇_Y are huge and nearly cancel in
        // V̇ · e_y, which sets Ω̇_z, while V̇ · e_y itself is moderate.
        let accel = AffineVec::along(Vector3::x(), Affine::derivative(state::V_X))
            + AffineVec::along(Vector3::y(), Affine::derivative(state::V_Y))
            + AffineVec::along(Vector3::z(), Affine::derivative(state::V_Z));
        let frame_rate = body.frame_rate();
        // Linear momentum gives the contact force: m V̇ = -m g E_Z + R + F_a (frame components).
        let loads = p.m * p.g * body.axis(2) - body.to_frame * body.air_force(&velocity);
        let reaction = p.m * accel + AffineVec::constant(loads);
        // No slip, differentiated: the contact particle's acceleration vanishes.
        let no_slip = accel + body.rim_acceleration(&frame_rate);
        let position = |i: usize, v: f64| Affine::derivative(i) - Affine::constant(v);
        let [k1, k2, k3] = body.kinematic_rows(&frame_rate);
        let [e1, e2, e3] = body.euler_rows(&reaction);
        let rows = [
            position(idx::X, velocity.x),
            position(idx::Y, velocity.y),
            position(idx::Z, velocity.z),
            no_slip.component(0),
            no_slip.component(1),
            no_slip.component(2),
            e1,
            e2,
            e3,
            k1,
            k2,
            k3,
        ];
        Ok(Assembled {
            body,
            rows,
            velocity,
        })
    }
}

impl Model<DIM> for RollingReference {
    fn info(&self) -> &'static ModelInfo {
        &INFO
    }

    fn rhs(&self, _t: f64, y: &[f64; DIM], dy: &mut [f64; DIM]) -> Result<(), EvalError> {
        let sys = self.assemble(y)?;
        let mut x = solve_rows(NAME, &DER_NAMES, &sys.rows)?;
        let frame_accel = Vector3::new(x[state::V_X], x[state::V_Y], x[state::V_Z]);
        let accel = sys.body.to_space * frame_accel;
        x[state::V_X] = accel.x;
        x[state::V_Y] = accel.y;
        x[state::V_Z] = accel.z;
        *dy = x;
        Ok(())
    }
}

impl WithOutputs<DIM, N_OUTPUTS> for RollingReference {
    fn outputs(
        &self,
        _t: f64,
        y: &[f64; DIM],
        dy: &[f64; DIM],
        out: &mut [f64; N_OUTPUTS],
    ) -> Result<(), EvalError> {
        let sys = self.assemble(y)?;
        // R = m V̇ + m g E_Z - F_a, spatial.
        let accel = Vector3::new(dy[state::V_X], dy[state::V_Y], dy[state::V_Z]);
        let p = &self.params;
        let r = p.m * accel + p.m * p.g * Vector3::z() - sys.body.air_force(&sys.velocity);
        let tangential = (r.x * r.x + r.y * r.y).sqrt();
        let residuals = sys.body.contact_residuals(y);
        // The no-slip velocity of the centre: minus the rim velocity.
        let slip = sys.velocity + sys.body.rim_velocity();
        out[output::N] = r.z;
        out[output::T] = tangential;
        out[output::R_X] = r.x;
        out[output::R_Y] = r.y;
        out[output::nu] = tangential / r.z;
        out[output::alpha_r] = r.y.atan2(r.x);
        out[output::energy] = sys.body.energy(&sys.velocity, y[state::Z]);
        out[output::z_residual] = residuals.height;
        out[output::vz_residual] = residuals.vertical_speed;
        out[output::vx_residual] = slip.x;
        out[output::vy_residual] = slip.y;
        super::check_outputs(NAME, &OUTPUT_NAMES, out)
    }
}
