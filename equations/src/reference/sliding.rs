//! The sliding disk, independent of the chart that carries the slip velocity.
//!
//! While sliding, the contact particle moves on the floor with velocity `u = v_C e_s` and the
//! floor pushes back with `N E_Z - μ_d N e_s`. The centre's horizontal velocity follows from
//! `u` and the rim velocity; its vertical velocity is a state tied to the contact by the
//! differentiated constraint. The slip velocity can be carried in polar form `(v_C, α)` (the
//! paper's) or in Cartesian form `(u_X, u_Y)`; a [`SlipChart`] says how, and everything else
//! is shared.

use super::affine::{Affine, AffineVec, DIM};
use super::body::{idx, solve_rows, Body};
use crate::{formulas, DiskParams, ParamError};
use model_runtime::{EvalError, Model, ModelInfo};
use nalgebra::Vector3;
use std::marker::PhantomData;

/// The slip velocity at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slip {
    /// Slip speed `v_C` (m/s).
    pub speed: f64,
    /// Direction of the friction force, `α` (rad): `e_s = -(cos α, sin α, 0)`.
    pub alpha: f64,
}

impl Slip {
    /// Unit slip direction `e_s = -(cos α, sin α, 0)`.
    pub fn direction(&self) -> Vector3<f64> {
        let (s, c) = self.alpha.sin_cos();
        Vector3::new(-c, -s, 0.0)
    }

    /// The slip velocity vector `v_C e_s`.
    pub fn velocity(&self) -> Vector3<f64> {
        self.direction() * self.speed
    }
}

/// The rate of the slip velocity, `d/dt (v_C e_s) = first · x[3] + second · x[4]`, where `x`
/// are the unknowns of the solve in the chart's slots 3 and 4.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlipRateColumns {
    /// Coefficient vector of unknown 3.
    pub first: Vector3<f64>,
    /// Coefficient vector of unknown 4.
    pub second: Vector3<f64>,
}

impl SlipRateColumns {
    fn affine(&self) -> AffineVec {
        AffineVec::along(self.first, Affine::derivative(idx::PAIR_1))
            + AffineVec::along(self.second, Affine::derivative(idx::PAIR_2))
    }
}

/// How a chart carries the slip velocity in states 3 and 4.
pub trait SlipChart {
    /// Model name, for errors.
    const NAME: &'static str;
    /// Derivative names, for errors.
    const DER_NAMES: [&'static str; DIM];
    /// Names, sizes and (zero) costs.
    fn info() -> &'static ModelInfo;
    /// The slip velocity at a state, or the pivot that makes the chart singular there.
    fn slip(y: &[f64; DIM]) -> Result<Slip, EvalError>;
    /// How the rate of the slip velocity vector depends on the solve's unknowns 3 and 4.
    fn slip_rate(slip: &Slip) -> SlipRateColumns;
    /// Maps the solve's unknowns to the state derivatives (in place).
    fn unknowns_to_derivatives(slip: &Slip, x: &mut [f64; DIM]) -> Result<(), EvalError>;
    /// Maps state derivatives back to the solve's unknowns (in place).
    fn derivatives_to_unknowns(slip: &Slip, x: &mut [f64; DIM]);
}

/// The sliding disk in chart `C`, assembled from the balance laws and solved numerically.
#[derive(Debug)]
pub struct SlidingReference<C> {
    params: DiskParams,
    chart: PhantomData<fn() -> C>,
}

impl<C> Clone for SlidingReference<C> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<C> Copy for SlidingReference<C> {}

/// Outputs common to both charts, by name.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlidingOutputs {
    /// Normal force (N).
    pub normal: f64,
    /// Friction force `T`: the contact force's component against the slip, `μ_d N` (N).
    pub friction: f64,
    /// Contact force, `E_X` component (N).
    pub r_x: f64,
    /// Contact force, `E_Y` component (N).
    pub r_y: f64,
    /// `T / N`.
    pub nu: f64,
    /// Centre velocity, `E_X` component (m/s).
    pub v_x: f64,
    /// Centre velocity, `E_Y` component (m/s).
    pub v_y: f64,
    /// Slip speed (m/s).
    pub slip_speed: f64,
    /// Friction direction `α` (rad).
    pub alpha: f64,
    /// Total energy (J).
    pub energy: f64,
    /// Power of the friction force, `R · u` (W).
    pub friction_power: f64,
    /// `Z - a sin θ` (m).
    pub z_residual: f64,
    /// `V_Z - a Ω_y cos θ` (m/s).
    pub vz_residual: f64,
}

/// Acceleration of the contact particle along and across the slip direction: regular even at
/// `v_C = 0`, where the polar chart is singular (docs/physics.md §4.2, lines 6–7).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlipAcceleration {
    /// Along `e_s`: `v̇_C` (m/s²).
    pub along: f64,
    /// Along `e_s⊥ = (sin α, -cos α, 0)`: `w = v_C α̇` (m/s²).
    pub across: f64,
}

struct Assembled {
    body: Body,
    slip: Slip,
    rows: [Affine; DIM],
    normal: Affine,
    velocity: Vector3<f64>,
}

impl<C: SlipChart> SlidingReference<C> {
    /// A sliding reference for validated parameters.
    pub fn new(params: DiskParams) -> Result<Self, ParamError> {
        Ok(SlidingReference {
            params: params.validated()?,
            chart: PhantomData,
        })
    }

    /// The parameters.
    pub fn params(&self) -> &DiskParams {
        &self.params
    }

    fn assemble_at(&self, y: &[f64; DIM], slip: Slip) -> Result<Assembled, EvalError> {
        let body = Body::new(self.params, y);
        body.check_chart(C::NAME, &C::info().state_names, y)?;
        let p = &self.params;
        let beta0 = formulas::beta0(p, y[idx::THETA], slip.alpha - y[idx::PSI]);
        let beta0_scale = p.A() + p.m * p.a * p.a * (1.0 + p.mu_d);
        if beta0.is_nan() || beta0.abs() <= 16.0 * f64::EPSILON * beta0_scale {
            return Err(EvalError::SingularPivot {
                model: C::NAME.into(),
                pivot: "beta0".into(),
                value: beta0,
            });
        }
        let rim = body.rim_velocity();
        let u = slip.velocity();
        let velocity = Vector3::new(u.x - rim.x, u.y - rim.y, y[idx::V_Z]);
        let frame_rate = body.frame_rate();
        let rim_accel = body
            .rim_acceleration(&frame_rate)
            .transformed(&body.to_space);
        // Horizontal centre acceleration: slip rate minus the rim's acceleration.
        let horizontal = C::slip_rate(&slip).affine() - rim_accel;
        let accel = AffineVec::along(Vector3::x(), horizontal.component(0))
            + AffineVec::along(Vector3::y(), horizontal.component(1))
            + AffineVec::along(Vector3::z(), Affine::derivative(idx::V_Z));
        let air = body.air_force(&velocity);
        let normal = p.m * accel.component(2) + Affine::constant(p.m * p.g - air.z);
        let reaction = AffineVec::along(-p.mu_d * slip.direction(), normal)
            + AffineVec::along(Vector3::z(), normal);
        // Horizontal linear momentum: m V̇ = R + F_a (the vertical part defines N above).
        let momentum = p.m * accel - reaction - AffineVec::constant(air);
        // The contact particle stays on the floor: its vertical acceleration vanishes.
        let stays_down = Affine::derivative(idx::V_Z) + rim_accel.component(2);
        let position = |i: usize, v: f64| Affine::derivative(i) - Affine::constant(v);
        let [k1, k2, k3] = body.kinematic_rows(&frame_rate);
        let [e1, e2, e3] = body.euler_rows(&reaction.transformed(&body.to_frame));
        let rows = [
            position(idx::X, velocity.x),
            position(idx::Y, velocity.y),
            position(idx::Z, velocity.z),
            momentum.component(0),
            momentum.component(1),
            stays_down,
            e1,
            e2,
            e3,
            k1,
            k2,
            k3,
        ];
        Ok(Assembled {
            body,
            slip,
            rows,
            normal,
            velocity,
        })
    }

    fn assemble(&self, y: &[f64; DIM]) -> Result<Assembled, EvalError> {
        self.assemble_at(y, C::slip(y)?)
    }

    /// The contact particle's acceleration along and across the slip direction `alpha`, with
    /// the slip speed taken as `slip_speed` (zero allowed): what sliding onset needs to pick a
    /// consistent friction direction (docs/physics.md §7.1). The chart's slip states in `y` are
    /// ignored.
    pub fn slip_acceleration(
        &self,
        y: &[f64; DIM],
        slip: Slip,
    ) -> Result<SlipAcceleration, EvalError> {
        let sys = self.assemble_at(y, slip)?;
        let dy = solve_rows(C::NAME, &C::DER_NAMES, &sys.rows)?;
        let rate = C::slip_rate(&slip).affine().eval(&dy);
        let e_s = slip.direction();
        let e_perp = Vector3::new(-e_s.y, e_s.x, 0.0);
        Ok(SlipAcceleration {
            along: rate.dot(&e_s),
            across: rate.dot(&e_perp),
        })
    }

    /// All sliding outputs by name, at `(y, dy)` with `dy` the state derivatives.
    pub fn named_outputs(
        &self,
        y: &[f64; DIM],
        dy: &[f64; DIM],
    ) -> Result<SlidingOutputs, EvalError> {
        let sys = self.assemble(y)?;
        let mut x = *dy;
        C::derivatives_to_unknowns(&sys.slip, &mut x);
        // Coulomb's law defines the friction from N: T = μ_d N against the slip, so T and R
        // are built from the one evaluated N (signed, so T = μ_d N also where N < 0).
        let normal = sys.normal.eval(&x);
        let friction = self.params.mu_d * normal;
        let r = -friction * sys.slip.direction() + normal * Vector3::z();
        let residuals = sys.body.contact_residuals(y);
        let friction_power = r.x * sys.slip.velocity().x + r.y * sys.slip.velocity().y;
        Ok(SlidingOutputs {
            normal: r.z,
            friction,
            r_x: r.x,
            r_y: r.y,
            nu: friction / r.z,
            v_x: sys.velocity.x,
            v_y: sys.velocity.y,
            slip_speed: sys.slip.speed,
            alpha: sys.slip.alpha,
            energy: sys.body.energy(&sys.velocity, y[idx::Z]),
            friction_power,
            z_residual: residuals.height,
            vz_residual: residuals.vertical_speed,
        })
    }
}

impl<C: SlipChart> Model<DIM> for SlidingReference<C> {
    fn info(&self) -> &'static ModelInfo {
        C::info()
    }

    fn rhs(&self, _t: f64, y: &[f64; DIM], dy: &mut [f64; DIM]) -> Result<(), EvalError> {
        let sys = self.assemble(y)?;
        let mut x = solve_rows(C::NAME, &C::DER_NAMES, &sys.rows)?;
        C::unknowns_to_derivatives(&sys.slip, &mut x)?;
        *dy = x;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::{Cartesian, Polar};

    fn state(v_c: f64, alpha: f64) -> [f64; DIM] {
        let p = DiskParams::paper();
        let theta: f64 = 0.5;
        [
            0.0,
            0.0,
            p.a * theta.sin(),
            v_c,
            alpha,
            0.01,
            0.3,
            theta,
            0.0,
            2.0,
            -1.0,
            25.0,
        ]
    }

    #[test]
    fn slip_acceleration_is_what_the_polar_rhs_implies() {
        let model = SlidingReference::<Polar>::new(DiskParams::paper()).unwrap();
        let y = state(0.2, 1.1);
        let mut dy = [0.0; DIM];
        model.rhs(0.0, &y, &mut dy).unwrap();
        let acc = model
            .slip_acceleration(
                &y,
                Slip {
                    speed: 0.2,
                    alpha: 1.1,
                },
            )
            .unwrap();
        assert!((acc.along - dy[idx::PAIR_1]).abs() < 1e-13 * acc.along.abs().max(1.0));
        let w = 0.2 * dy[idx::PAIR_2];
        assert!((acc.across - w).abs() < 1e-13 * w.abs().max(1.0));
    }

    #[test]
    fn slip_acceleration_is_continuous_at_zero_slip() {
        let model = SlidingReference::<Cartesian>::new(DiskParams::paper()).unwrap();
        let y = state(0.0, 0.0);
        let at = |speed| {
            model
                .slip_acceleration(&y, Slip { speed, alpha: 2.0 })
                .unwrap()
        };
        let (zero, tiny) = (at(0.0), at(1e-9));
        assert!((zero.along - tiny.along).abs() < 1e-6 * zero.along.abs().max(1.0));
        assert!((zero.across - tiny.across).abs() < 1e-6 * zero.along.abs().max(1.0));
    }
}
