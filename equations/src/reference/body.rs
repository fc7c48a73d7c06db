//! The rigid disk and its contact point, shared by every mode and chart.
//!
//! Rolling and sliding differ only in how the centre's velocity and the contact force are
//! tied to the states; the Euler-angle kinematics, the angular-momentum balance, the motion
//! of the contact particle relative to the centre and the air loads are the same physics and
//! live here once. Everything is built from the frame `e_x, e_y, e_z` and vector products
//! (frame components where the disk is concerned, spatial ones for the floor), never from
//! the row forms of the models.

use super::affine::{Affine, AffineVec, DIM};
use crate::DiskParams;
use model_runtime::{EvalError, Name, Names};
use nalgebra::{Matrix3, Rotation3, SMatrix, SVector, Vector3};

/// Indices shared by every chart: the position, the vertical velocity, the Euler angles and the
/// body components of the angular velocity.
pub(crate) mod idx {
    pub const X: usize = 0;
    pub const Y: usize = 1;
    pub const Z: usize = 2;
    /// First slot of the chart-specific velocity pair (`V_X`, `v_C` or `u_X`).
    pub const PAIR_1: usize = 3;
    /// Second slot of the pair (`V_Y`, `alpha` or `u_Y`).
    pub const PAIR_2: usize = 4;
    pub const V_Z: usize = 5;
    pub const PSI: usize = 6;
    pub const THETA: usize = 7;
    pub const PHI: usize = 8;
    pub const OMEGA_X: usize = 9;
    pub const OMEGA_Y: usize = 10;
    pub const OMEGA_Z: usize = 11;
}

/// The disk at one state: its frame and its angular velocity.
///
/// Vectors tied to the disk are handled in frame components, where `e_x, e_y, e_z` are the
/// exact unit vectors and their orthogonality holds without rounding; the spatial axes are
/// the rows of the frame matrix. Near a flat disk (`sin θ → 0`) a rounded `e_z · e_x` would
/// otherwise leak the spin rate into the precession row.
pub(crate) struct Body {
    pub p: DiskParams,
    /// Columns `e_x, e_y, e_z` in spatial components: maps frame to spatial components.
    pub to_space: Matrix3<f64>,
    /// The transpose: maps spatial to frame components.
    pub to_frame: Matrix3<f64>,
    /// Disk angular velocity `(Ω_x, Ω_y, Ω_z)`, frame components.
    pub spin: Vector3<f64>,
}

impl Body {
    /// The frame of the 3–2–3 Euler angles: rotate by `psi` about `E_Z`, then by `theta`
    /// about the new `y` axis; `e_x` is the image of `E_X`, `e_z` of `E_Z`.
    pub fn new(p: DiskParams, y: &[f64; DIM]) -> Self {
        let (st, ct) = y[idx::THETA].sin_cos();
        // In the frame turned by psi about E_Z, the nutation by theta about its y axis maps
        // x and z to (cos θ, 0, -sin θ) and (sin θ, 0, cos θ). Composing the two keeps every
        // component a product (no cancellation near θ = 0 or π/2).
        let precession = Rotation3::from_axis_angle(&Vector3::z_axis(), y[idx::PSI]);
        let nutation = Matrix3::new(ct, 0.0, st, 0.0, 1.0, 0.0, -st, 0.0, ct);
        let to_space = precession.matrix() * nutation;
        Body {
            p,
            to_space,
            to_frame: to_space.transpose(),
            spin: Vector3::new(y[idx::OMEGA_X], y[idx::OMEGA_Y], y[idx::OMEGA_Z]),
        }
    }

    /// A spatial axis `E_k` in frame components (exact: a row of the frame matrix).
    pub fn axis(&self, k: usize) -> Vector3<f64> {
        self.to_frame.column(k).into_owned()
    }

    /// Checks the input and the pivot every chart shares: a non-finite state is refused by
    /// name (it would otherwise ride along silently, e.g. `X` feeds nothing back), and the
    /// Euler-angle chart is singular at `sin θ = 0`.
    pub fn check_chart(
        &self,
        model: &'static str,
        state_names: &Names,
        y: &[f64; DIM],
    ) -> Result<(), EvalError> {
        if let Some(k) = y.iter().position(|v| !v.is_finite()) {
            return Err(EvalError::NonFinite {
                model: model.into(),
                quantity: state_names.name(k).unwrap_or(Name::Borrowed("a state")),
                value: y[k],
            });
        }
        let s = y[idx::THETA].sin();
        if s == 0.0 || !s.is_finite() {
            return Err(EvalError::SingularPivot {
                model: model.into(),
                pivot: "sin(theta)".into(),
                value: s,
            });
        }
        Ok(())
    }

    /// Angular velocity of the frame, `ψ̇ E_Z + θ̇ e_y` (the frame does not spin with `φ`),
    /// frame components.
    pub fn frame_rate(&self) -> AffineVec {
        AffineVec::along(self.axis(2), Affine::derivative(idx::PSI))
            + AffineVec::along(Vector3::y(), Affine::derivative(idx::THETA))
    }

    /// Euler-angle kinematics: the disk spins relative to the frame at `φ̇` about `e_z`, so
    /// `ω + φ̇ e_z = Ω`, frame components.
    pub fn kinematic_rows(&self, frame_rate: &AffineVec) -> [Affine; 3] {
        let mismatch = *frame_rate + AffineVec::along(Vector3::z(), Affine::derivative(idx::PHI))
            - AffineVec::constant(self.spin);
        [
            mismatch.component(0),
            mismatch.component(1),
            mismatch.component(2),
        ]
    }

    /// Centre-to-contact vector `a e_x`, frame components.
    fn contact_arm(&self) -> Vector3<f64> {
        Vector3::x() * self.p.a
    }

    /// Velocity of the contact particle relative to the centre, `Ω × a e_x`, spatial.
    pub fn rim_velocity(&self) -> Vector3<f64> {
        self.to_space * self.spin.cross(&self.contact_arm())
    }

    /// Acceleration of the contact particle relative to the centre, frame components: the
    /// frame components of `Ω × a e_x` change at `Ω̇ × a e_x`, and the frame turns at `ω`.
    pub fn rim_acceleration(&self, frame_rate: &AffineVec) -> AffineVec {
        let arm = self.contact_arm();
        let spin_rate = AffineVec::along(Vector3::x(), Affine::derivative(idx::OMEGA_X))
            + AffineVec::along(Vector3::y(), Affine::derivative(idx::OMEGA_Y))
            + AffineVec::along(Vector3::z(), Affine::derivative(idx::OMEGA_Z));
        let rim = self.spin.cross(&arm);
        -1.0 * spin_rate.crossed_by(&arm) - frame_rate.crossed_by(&rim)
    }

    /// Air force on one face for spatial centre velocity `v`: `-k_F (v·e_z - w_z) e_z`, spatial.
    pub fn air_force(&self, v: &Vector3<f64>) -> Vector3<f64> {
        let e_z = self.to_space.column(2).into_owned();
        -self.p.k_F() * ((self.to_frame * v).z - self.p.w_z) * e_z
    }

    /// Angular-momentum balance about the centre, `dH/dt = a e_x × R + M_a`, frame
    /// components, for the contact force `reaction` in frame components.
    ///
    /// `H = (A Ω_x, A Ω_y, C Ω_z)` in the frame, so `dH/dt = (A Ω̇_x, A Ω̇_y, C Ω̇_z) + ω × H`.
    /// The frame turns at `ω = Ω - φ̇ e_z`, hence `ω × H = Ω × H - φ̇ e_z × H`, and for the
    /// axisymmetric disk `Ω × H = (C - A) Ω_z Ω × e_z` has no `e_z` part: the gyroscopic terms
    /// of the spin row vanish identically instead of cancelling in rounding. The air moment of
    /// one face is `-k_M (Ω_x e_x + Ω_y e_y)`.
    pub fn euler_rows(&self, reaction: &AffineVec) -> [Affine; 3] {
        let (a_in, c_in) = (self.p.A(), self.p.C());
        let w = &self.spin;
        let h = Vector3::new(a_in * w.x, a_in * w.y, c_in * w.z);
        let gyroscopic = (c_in - a_in) * w.z * w.cross(&Vector3::z());
        let h_rate = AffineVec::along(Vector3::x(), a_in * Affine::derivative(idx::OMEGA_X))
            + AffineVec::along(Vector3::y(), a_in * Affine::derivative(idx::OMEGA_Y))
            + AffineVec::along(Vector3::z(), c_in * Affine::derivative(idx::OMEGA_Z))
            + AffineVec::constant(gyroscopic)
            - AffineVec::along(Vector3::z().cross(&h), Affine::derivative(idx::PHI));
        let air_moment = -self.p.k_M() * Vector3::new(w.x, w.y, 0.0);
        let moment = reaction.crossed_by(&self.contact_arm()) + AffineVec::constant(air_moment);
        let balance = h_rate - moment;
        [
            balance.component(0),
            balance.component(1),
            balance.component(2),
        ]
    }

    /// Kinetic plus potential energy for spatial centre velocity `v` and height `z`.
    pub fn energy(&self, v: &Vector3<f64>, z: f64) -> f64 {
        let w = &self.spin;
        0.5 * self.p.m * v.norm_squared()
            + 0.5 * self.p.A() * (w.x * w.x + w.y * w.y)
            + 0.5 * self.p.C() * w.z * w.z
            + self.p.m * self.p.g * z
    }

    /// Constraint residuals shared by both modes: contact height and its rate.
    pub fn contact_residuals(&self, y: &[f64; DIM]) -> ContactResiduals {
        let a = self.p.a;
        let theta = y[idx::THETA];
        ContactResiduals {
            height: y[idx::Z] - a * theta.sin(),
            vertical_speed: y[idx::V_Z] - a * y[idx::OMEGA_Y] * theta.cos(),
        }
    }
}

/// How far a state is from the contact manifold (both vanish on it).
pub(crate) struct ContactResiduals {
    /// `Z - a sin θ`.
    pub height: f64,
    /// `V_Z - a Ω_y cos θ`.
    pub vertical_speed: f64,
}

/// Refinement steps after the LU solve.
const REFINEMENT_STEPS: usize = 3;

/// Solves the rows `lin·ẏ + cst = 0` by LU with partial pivoting, after scaling each row to
/// unit maximum coefficient (the rows mix forces, moments and velocities).
pub(crate) fn solve_rows(
    model: &'static str,
    der_names: &[&'static str; DIM],
    rows: &[Affine; DIM],
) -> Result<[f64; DIM], EvalError> {
    let mut m = SMatrix::<f64, DIM, DIM>::zeros();
    let mut f = SVector::<f64, DIM>::zeros();
    for (i, row) in rows.iter().enumerate() {
        let scale = row.lin.amax();
        if scale == 0.0 || !scale.is_finite() {
            return Err(EvalError::SingularPivot {
                model: model.into(),
                pivot: "M(y)".into(),
                value: scale,
            });
        }
        m.set_row(i, &(row.lin.transpose() / scale));
        f[i] = -row.cst / scale;
    }
    let lu = m.lu();
    let mut x = lu.solve(&f).ok_or(EvalError::SingularPivot {
        model: model.into(),
        pivot: "M(y)".into(),
        value: 0.0,
    })?;
    // Iterative refinement makes the small components accurate relative to themselves, not
    // only to the largest one (componentwise backward stability, Skeel 1980).
    for _ in 0..REFINEMENT_STEPS {
        match lu.solve(&(f - m * x)) {
            Some(dx) => x += dx,
            None => break,
        }
    }
    let mut dy = [0.0; DIM];
    for (j, (out, v)) in dy.iter_mut().zip(x.iter()).enumerate() {
        if !v.is_finite() {
            return Err(EvalError::NonFinite {
                model: model.into(),
                quantity: der_names[j].into(),
                value: *v,
            });
        }
        *out = *v;
    }
    Ok(dy)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The frame of docs/physics.md §1, written out component by component.
    fn printed_frame(psi: f64, theta: f64) -> [Vector3<f64>; 3] {
        let (sp, cp) = psi.sin_cos();
        let (st, ct) = theta.sin_cos();
        [
            Vector3::new(cp * ct, sp * ct, -st),
            Vector3::new(-sp, cp, 0.0),
            Vector3::new(cp * st, sp * st, ct),
        ]
    }

    #[test]
    fn frame_is_the_printed_one_and_orthonormal() {
        for (psi, theta) in [
            (0.3, 0.7),
            (-2.0, 1e-9),
            (5.0, std::f64::consts::FRAC_PI_2 - 1e-7),
            (40.0, 2.5),
        ] {
            let mut y = [0.0; DIM];
            y[idx::PSI] = psi;
            y[idx::THETA] = theta;
            let body = Body::new(DiskParams::paper(), &y);
            let printed = printed_frame(psi, theta);
            for (k, e) in printed.iter().enumerate() {
                let ours = body.to_space.column(k);
                assert!((ours - e).norm() < 1e-15, "e_{k} at ψ={psi}, θ={theta}");
            }
            let gram = body.to_frame * body.to_space;
            assert!((gram - Matrix3::identity()).norm() < 1e-15);
            // e_y = e_z × e_x, and the spatial axes are rows of the frame matrix.
            let (e_x, e_z) = (body.to_space.column(0), body.to_space.column(2));
            assert!((e_z.cross(&e_x) - body.to_space.column(1)).norm() < 1e-15);
            assert_eq!(body.axis(2), body.to_frame * Vector3::z());
        }
    }

    #[test]
    fn rim_velocity_is_the_printed_one() {
        // docs/physics.md §1: Ω × a e_x = -a (Ω_y e_z - Ω_z e_y).
        let mut y = [0.0; DIM];
        y[idx::PSI] = 0.8;
        y[idx::THETA] = 0.4;
        y[idx::OMEGA_X] = 1.5;
        y[idx::OMEGA_Y] = -2.0;
        y[idx::OMEGA_Z] = 30.0;
        let p = DiskParams::paper();
        let body = Body::new(p, &y);
        let [_, e_y, e_z] = printed_frame(0.8, 0.4);
        let printed = -p.a * (-2.0 * e_z - 30.0 * e_y);
        assert!((body.rim_velocity() - printed).norm() < 1e-15);
    }
}
