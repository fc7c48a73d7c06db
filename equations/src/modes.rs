//! The disk's two contact modes and the maps between their state vectors.
//!
//! Rolling and sliding integrate different 12-vectors: rolling carries the centre's horizontal
//! velocity `(V_X, V_Y)`, sliding carries the slip of the contact particle instead, either in the
//! paper's polar form `(v_C, α)` or in the Cartesian form `u = v_C e_s` (docs/physics.md §6).
//! Everything that has to compare or report states across modes (guards, transition maps,
//! constraint projection, samples) goes through one *physical* view — the rolling variables plus
//! the slip — so that each conversion is written once. The contact force is recovered from the
//! state derivative the integrator already holds (the secondary outputs of Box 1 and Box 3), so a
//! guard costs no extra model evaluation.

use crate::formulas::{self, BodyRates};
use crate::params::DiskParams;
use nalgebra::Vector3;

/// Number of states of every disk model.
pub const DIM: usize = 12;

/// Indices shared by every disk model's state vector.
///
/// Indices 3 and 4 differ between the layouts: `(V_X, V_Y)` in rolling, `(v_C, alpha)` in the
/// polar sliding chart, `(u_X, u_Y)` in the Cartesian sliding chart.
pub mod layout {
    /// Centre of mass, X (m).
    pub const X: usize = 0;
    /// Centre of mass, Y (m).
    pub const Y: usize = 1;
    /// Centre of mass height Z (m).
    pub const Z: usize = 2;
    /// Rolling: centre velocity V_X (m/s).
    pub const V_X: usize = 3;
    /// Rolling: centre velocity V_Y (m/s).
    pub const V_Y: usize = 4;
    /// Polar sliding chart: slip speed v_C (m/s).
    pub const V_C: usize = 3;
    /// Polar sliding chart: friction direction alpha (rad).
    pub const ALPHA: usize = 4;
    /// Cartesian sliding chart: slip velocity u_X (m/s).
    pub const U_X: usize = 3;
    /// Cartesian sliding chart: slip velocity u_Y (m/s).
    pub const U_Y: usize = 4;
    /// Vertical centre velocity V_Z (m/s).
    pub const V_Z: usize = 5;
    /// Precession angle psi (rad).
    pub const PSI: usize = 6;
    /// Inclination theta (rad).
    pub const THETA: usize = 7;
    /// Spin angle phi (rad).
    pub const PHI: usize = 8;
    /// Angular velocity Omega_x (rad/s).
    pub const OMEGA_X: usize = 9;
    /// Angular velocity Omega_y (rad/s).
    pub const OMEGA_Y: usize = 10;
    /// Angular velocity Omega_z (rad/s).
    pub const OMEGA_Z: usize = 11;
}

use layout::*;

/// The contact mode of the disk; spelled `rolling` or `sliding` in scenes and output files.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Deserialize, serde::Serialize,
)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    /// No slip at the contact: `v_C = 0`, friction below `mu_st N`.
    Rolling,
    /// The contact particle slips: friction `mu_d N` opposes the slip.
    Sliding,
}

impl Mode {
    /// Lower-case name, as written in output files.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Rolling => "rolling",
            Mode::Sliding => "sliding",
        }
    }
}

impl std::fmt::Display for Mode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The coordinates in which the sliding model carries the slip.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlipChart {
    /// `u = v_C e_s = (u_X, u_Y)`: smooth wherever `u ≠ 0`, including near misses of the origin.
    Cartesian,
    /// The paper's `(v_C, α)`: `α̇ = w / v_C` is singular at every onset of sliding.
    Polar,
}

/// The slip of the contact particle, in the paper's polar terms.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Slip {
    /// Slip speed `v_C` (m/s); negative only under [`crate::SlipSign::Paper`].
    pub speed: f64,
    /// Direction `α` of the friction force (rad): the slip points along `-(cos α, sin α)`.
    pub direction: f64,
}

impl Slip {
    /// The slip velocity vector `u = v_C e_s = -v_C (cos α, sin α)`.
    pub fn vector(&self) -> [f64; 2] {
        let (s, c) = self.direction.sin_cos();
        [-self.speed * c, -self.speed * s]
    }

    /// The slip of a Cartesian slip vector `u` (direction `atan2(-u_Y, -u_X)`).
    pub fn from_vector(u: [f64; 2]) -> Slip {
        Slip {
            speed: u[0].hypot(u[1]),
            direction: (-u[1]).atan2(-u[0]),
        }
    }
}

/// The slip speed of a sliding state vector of `chart`: the speed of
/// [`PhysicalState::from_sliding`]'s slip, the same bits, without the slip's direction (an
/// `atan2`) or the no-slip velocity (two `sin_cos`) that the rest of the physical state needs.
pub fn slip_speed(chart: SlipChart, y: &[f64; DIM]) -> f64 {
    match chart {
        SlipChart::Cartesian => y[U_X].hypot(y[U_Y]),
        SlipChart::Polar => y[V_C],
    }
}

/// The angular velocity components of a state vector (every layout).
fn body_rates(y: &[f64; DIM]) -> BodyRates {
    BodyRates {
        omega_x: y[OMEGA_X],
        omega_y: y[OMEGA_Y],
        omega_z: y[OMEGA_Z],
    }
}

/// The horizontal velocity of the centre when the contact particle is at rest (Box 2):
/// `a (Ω_y cos ψ sin θ + Ω_z sin ψ, Ω_y sin ψ sin θ − Ω_z cos ψ)`.
pub fn no_slip_velocity(p: &DiskParams, y: &[f64; DIM]) -> [f64; 2] {
    let v = formulas::rolling_consistent(p, y[PSI], y[THETA], &body_rates(y)).velocity;
    [v.x, v.y]
}

/// A disk state in the rolling variables `(X, Y, Z, V_X, V_Y, V_Z, ψ, θ, φ, Ω_x, Ω_y, Ω_z)`
/// together with its slip: the common view of every mode's state vector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhysicalState {
    /// The state in rolling variables (the centre's velocity includes the slip).
    pub y: [f64; DIM],
    /// The slip; zero speed in rolling.
    pub slip: Slip,
}

impl PhysicalState {
    /// Reads a rolling state vector; `friction_direction` is reported as the slip direction.
    pub fn from_rolling(y: &[f64; DIM], friction_direction: f64) -> Self {
        PhysicalState {
            y: *y,
            slip: Slip {
                speed: 0.0,
                direction: friction_direction,
            },
        }
    }

    /// Reads a sliding state vector of the given chart (the centre's velocity from S1/S2).
    pub fn from_sliding(chart: SlipChart, p: &DiskParams, y: &[f64; DIM]) -> Self {
        let slip = match chart {
            SlipChart::Cartesian => Slip::from_vector([y[U_X], y[U_Y]]),
            SlipChart::Polar => Slip {
                speed: slip_speed(chart, y),
                direction: y[ALPHA],
            },
        };
        let roll = no_slip_velocity(p, y);
        let u = slip.vector();
        let mut phys = *y;
        phys[V_X] = roll[0] + u[0];
        phys[V_Y] = roll[1] + u[1];
        PhysicalState { y: phys, slip }
    }

    /// The slip velocity `V_hor − V_no-slip` computed from the centre's velocity.
    pub fn velocity_slip(&self, p: &DiskParams) -> [f64; 2] {
        let roll = no_slip_velocity(p, &self.y);
        [self.y[V_X] - roll[0], self.y[V_Y] - roll[1]]
    }

    /// The state vector of the rolling model.
    pub fn rolling_vector(&self) -> [f64; DIM] {
        self.y
    }

    /// The state vector of a sliding chart with the given slip (the centre's velocity in `self`
    /// is not used: S1/S2 determine it from the slip).
    pub fn sliding_vector(&self, chart: SlipChart, slip: Slip) -> [f64; DIM] {
        let mut y = self.y;
        match chart {
            SlipChart::Cartesian => {
                let u = slip.vector();
                y[U_X] = u[0];
                y[U_Y] = u[1];
            }
            SlipChart::Polar => {
                y[V_C] = slip.speed;
                y[ALPHA] = slip.direction;
            }
        }
        y
    }

    /// The centre's velocity `(V_X, V_Y, V_Z)`.
    pub fn centre_velocity(&self) -> Vector3<f64> {
        Vector3::new(self.y[V_X], self.y[V_Y], self.y[V_Z])
    }

    /// Total mechanical energy (docs/physics.md §8).
    pub fn energy(&self, p: &DiskParams) -> f64 {
        formulas::total_energy(p, &self.centre_velocity(), &body_rates(&self.y), self.y[Z])
    }

    /// Normal velocity of the centre `v_z = V · e_z` (the air-drag argument).
    pub fn normal_velocity(&self) -> f64 {
        formulas::normal_velocity(self.y[PSI], self.y[THETA], &self.centre_velocity())
    }

    /// The drift of the constraints imposed only in differential form.
    pub fn residuals(&self, p: &DiskParams, mode: Mode) -> ConstraintResiduals {
        let (a, y) = (p.a, &self.y);
        let (st, ct) = y[THETA].sin_cos();
        let no_slip = match mode {
            Mode::Rolling => {
                let s = self.velocity_slip(p);
                s[0].hypot(s[1])
            }
            Mode::Sliding => 0.0,
        };
        ConstraintResiduals {
            height: y[Z] - a * st,
            vertical_speed: y[V_Z] - a * y[OMEGA_Y] * ct,
            no_slip,
        }
    }

    /// Puts the state back onto the contact constraints: `Z = a sin θ`, `V_Z = a Ω_y cos θ`,
    /// and in rolling the no-slip velocity. Only the redundant coordinates move.
    pub fn project(&mut self, p: &DiskParams, mode: Mode) {
        let a = p.a;
        let (st, ct) = self.y[THETA].sin_cos();
        self.y[Z] = a * st;
        self.y[V_Z] = a * self.y[OMEGA_Y] * ct;
        if mode == Mode::Rolling {
            let roll = no_slip_velocity(p, &self.y);
            self.y[V_X] = roll[0];
            self.y[V_Y] = roll[1];
        }
    }
}

/// How far a state is from the contact constraints.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ConstraintResiduals {
    /// `Z − a sin θ` (m).
    pub height: f64,
    /// `V_Z − a Ω_y cos θ` (m/s).
    pub vertical_speed: f64,
    /// Rolling only: `|V_hor − V_no-slip|` (m/s); zero in sliding, where the slip is a state.
    pub no_slip: f64,
}

impl ConstraintResiduals {
    /// The larger of the absolute residuals, each in its own unit (m or m/s).
    pub fn max_abs(&self) -> f64 {
        self.height
            .abs()
            .max(self.vertical_speed.abs())
            .max(self.no_slip)
    }
}

/// The contact reaction `R = (R_X, R_Y, N)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactForce {
    /// Horizontal component along E_X (N).
    pub r_x: f64,
    /// Horizontal component along E_Y (N).
    pub r_y: f64,
    /// Normal force N (N).
    pub normal: f64,
}

/// `k_F (v_z − w_z)`: the air force along the disk normal (zero without air, skipping the trig).
fn air_drag(p: &DiskParams, state: &PhysicalState) -> f64 {
    let k_f = p.k_F();
    if k_f == 0.0 {
        0.0
    } else {
        k_f * (state.normal_velocity() - p.w_z)
    }
}

/// The normal force without the air's share: `m (V̇_Z + g)`.
fn vertical_balance(p: &DiskParams, dy: &[f64; DIM]) -> f64 {
    p.m * (dy[V_Z] + p.g)
}

impl ContactForce {
    /// The secondary outputs of Box 1 (rolling) from the state and its derivative `dy`.
    pub fn rolling(p: &DiskParams, state: &PhysicalState, dy: &[f64; DIM]) -> Self {
        let air = air_drag(p, state);
        // The air's share along the normal e_z, on the fixed axes. In still air no angle is
        // needed, which matters: the guards evaluate this millions of times per run.
        let [air_x, air_y, air_z] = if air == 0.0 {
            [0.0; 3]
        } else {
            let (sp, cp) = state.y[PSI].sin_cos();
            let (st, ct) = state.y[THETA].sin_cos();
            [air * st * cp, air * st * sp, air * ct]
        };
        ContactForce {
            r_x: p.m * dy[V_X] + air_x,
            r_y: p.m * dy[V_Y] + air_y,
            normal: vertical_balance(p, dy) + air_z,
        }
    }

    /// The normal force of Box 3 (sliding) from a state vector of `chart`; the physical state
    /// (an `atan2` and the no-slip velocity) is read only when air drag needs it.
    pub fn sliding_normal(
        p: &DiskParams,
        chart: SlipChart,
        y: &[f64; DIM],
        dy: &[f64; DIM],
    ) -> f64 {
        if p.k_F() == 0.0 {
            vertical_balance(p, dy)
        } else {
            Self::sliding(p, &PhysicalState::from_sliding(chart, p, y), dy).normal
        }
    }

    /// The secondary outputs of Box 3 (sliding): `N` from `V̇_Z`, friction `mu_d N` along α.
    pub fn sliding(p: &DiskParams, state: &PhysicalState, dy: &[f64; DIM]) -> Self {
        let air = air_drag(p, state);
        let normal = vertical_balance(p, dy) + air * state.y[THETA].cos();
        let (sa, ca) = state.slip.direction.sin_cos();
        let t = p.mu_d * normal;
        ContactForce {
            r_x: t * ca,
            r_y: t * sa,
            normal,
        }
    }

    /// Friction magnitude `T = |(R_X, R_Y)|`.
    pub fn friction(&self) -> f64 {
        // Not `hypot`: forces are far from overflow, and guards call this millions of times.
        (self.r_x * self.r_x + self.r_y * self.r_y).sqrt()
    }

    /// Friction ratio `nu = T / N`.
    pub fn ratio(&self) -> f64 {
        self.friction() / self.normal
    }

    /// Direction of the friction force `atan2(R_Y, R_X)`.
    pub fn direction(&self) -> f64 {
        self.r_y.atan2(self.r_x)
    }

    /// Whether static friction can hold the contact: `N > 0` and `T < mu_st N` (docs/physics.md
    /// §7.2).
    pub fn admits_rolling(&self, mu_st: f64) -> bool {
        self.normal > 0.0 && self.friction() < mu_st * self.normal
    }

    /// How far rolling is from needing more friction than `mu_st N`: `T − mu_st N`, divided by
    /// `mu_st` when that is above 1. The guard of the friction limit: it changes sign where
    /// `T = mu_st N`, and it stays finite for every finite force and coefficient. Unscaled,
    /// `mu_st = 1.8e308` made `mu_st N` overflow at the first newton of normal force and the
    /// run failed on a guard of `-inf`; the scaling by a constant keeps the zero and the sign,
    /// and leaves every coefficient up to 1 (every real contact) exactly as it was.
    pub fn friction_margin(&self, mu_st: f64) -> f64 {
        if mu_st > 1.0 {
            self.friction() / mu_st - self.normal
        } else {
            self.friction() - mu_st * self.normal
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_state() -> [f64; DIM] {
        [
            0.1, -0.2, 0.02, 0.3, -0.4, 0.05, 0.7, 0.6, 1.1, 2.0, -3.0, 5.0,
        ]
    }

    #[test]
    fn the_slip_speed_alone_is_the_physical_states() {
        let p = DiskParams::paper();
        let base = PhysicalState::from_rolling(&sample_state(), 0.0);
        for chart in [SlipChart::Cartesian, SlipChart::Polar] {
            for (speed, direction) in [(0.25, 2.0), (3e-9, -0.4), (1e-300, 3.1), (0.0, 0.0)] {
                let y = base.sliding_vector(chart, Slip { speed, direction });
                let full = PhysicalState::from_sliding(chart, &p, &y).slip.speed;
                assert_eq!(slip_speed(chart, &y).to_bits(), full.to_bits(), "{chart:?}");
                assert!(
                    (full - speed).abs() <= 1e-15 * speed,
                    "{chart:?}: {full} for {speed}"
                );
            }
        }
    }

    #[test]
    fn charts_round_trip_through_the_physical_state() {
        let p = DiskParams::paper();
        let slip = Slip {
            speed: 0.25,
            direction: 2.0,
        };
        let base = PhysicalState::from_rolling(&sample_state(), 0.0);
        for chart in [SlipChart::Cartesian, SlipChart::Polar] {
            let y = base.sliding_vector(chart, slip);
            let back = PhysicalState::from_sliding(chart, &p, &y);
            assert!((back.slip.speed - 0.25).abs() < 1e-15);
            assert!((back.slip.direction - 2.0).abs() < 1e-15);
            let u = back.velocity_slip(&p);
            let expected = slip.vector();
            assert!((u[0] - expected[0]).abs() < 1e-15 && (u[1] - expected[1]).abs() < 1e-15);
            let again = back.sliding_vector(chart, back.slip);
            for i in 0..DIM {
                assert!((again[i] - y[i]).abs() < 1e-15, "component {i}");
            }
        }
    }

    #[test]
    fn projection_zeroes_the_residuals() {
        let p = DiskParams::paper();
        let mut s = PhysicalState::from_rolling(&sample_state(), 0.0);
        assert!(s.residuals(&p, Mode::Rolling).max_abs() > 1e-3);
        s.project(&p, Mode::Rolling);
        let r = s.residuals(&p, Mode::Rolling);
        assert!(r.max_abs() < 1e-16, "{r:?}");
    }

    #[test]
    fn admissibility_is_strict_and_needs_compression() {
        let f = ContactForce {
            r_x: 0.3,
            r_y: 0.4,
            normal: 2.5,
        };
        assert!((f.ratio() - 0.2).abs() < 1e-15);
        assert!(!f.admits_rolling(0.2 - 1e-12) && f.admits_rolling(0.2 + 1e-12));
        let lifted = ContactForce { normal: -1.0, ..f };
        assert!(!lifted.admits_rolling(10.0));
    }

    #[test]
    fn the_friction_margin_is_finite_and_changes_sign_where_rolling_stops_holding() {
        let f = ContactForce {
            r_x: 3e3,
            r_y: 4e3,
            normal: 2.5,
        };
        // T = 5e3 N: rolling holds for mu_st above 2000.
        for mu_st in [0.0, 0.2, 1.0, 1999.0, 2001.0, 1e10, f64::MAX] {
            let margin = f.friction_margin(mu_st);
            assert!(margin.is_finite(), "{mu_st}: {margin}");
            assert_eq!(margin < 0.0, f.admits_rolling(mu_st), "{mu_st}");
        }
        // Up to 1 it is the plain T - mu_st N, bit for bit.
        assert_eq!(f.friction_margin(0.2), f.friction() - 0.2 * f.normal);
        let heavy = ContactForce { normal: 1e300, ..f };
        assert!(heavy.friction_margin(f64::MAX).is_finite());
    }
}
