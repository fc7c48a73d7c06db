//! One recorded instant of a run, in named fields.
//!
//! The state is named in the rolling layout ([`crate::layout`], names [`crate::STATE_NAMES`]):
//! the one place the index order meets the names, so a change of model index order is absorbed
//! here and never reaches a table or a figure.

use crate::hybrid::DiskSample;
use crate::modes::layout::{OMEGA_X, OMEGA_Y, OMEGA_Z, PHI, PSI, THETA, V_X, V_Y, V_Z, X, Y, Z};
use crate::modes::{Mode, Slip, DIM};
use crate::params::DiskParams;
use crate::start::STATE_NAMES;

/// The disk's state in the rolling chart (the paper's rolling unknowns), SI units. Written
/// by the state names ([`STATE_NAMES`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct DiskState {
    /// Centre X (m).
    #[serde(rename = "X")]
    pub x: f64,
    /// Centre Y (m).
    #[serde(rename = "Y")]
    pub y: f64,
    /// Centre height Z (m).
    #[serde(rename = "Z")]
    pub z: f64,
    /// Centre velocity X (m/s).
    #[serde(rename = "V_X")]
    pub v_x: f64,
    /// Centre velocity Y (m/s).
    #[serde(rename = "V_Y")]
    pub v_y: f64,
    /// Centre velocity Z (m/s).
    #[serde(rename = "V_Z")]
    pub v_z: f64,
    /// Precession ψ (rad).
    pub psi: f64,
    /// Inclination θ (rad).
    pub theta: f64,
    /// Spin φ (rad).
    pub phi: f64,
    /// Ω_x (rad/s).
    #[serde(rename = "Omega_x")]
    pub omega_x: f64,
    /// Ω_y (rad/s).
    #[serde(rename = "Omega_y")]
    pub omega_y: f64,
    /// Ω_z (rad/s).
    #[serde(rename = "Omega_z")]
    pub omega_z: f64,
}

impl DiskState {
    /// The component at index `i` of the rolling layout; `None` past the last.
    pub fn component_mut(&mut self, i: usize) -> Option<&mut f64> {
        Some(match i {
            X => &mut self.x,
            Y => &mut self.y,
            Z => &mut self.z,
            V_X => &mut self.v_x,
            V_Y => &mut self.v_y,
            V_Z => &mut self.v_z,
            PSI => &mut self.psi,
            THETA => &mut self.theta,
            PHI => &mut self.phi,
            OMEGA_X => &mut self.omega_x,
            OMEGA_Y => &mut self.omega_y,
            OMEGA_Z => &mut self.omega_z,
            _ => return None,
        })
    }

    /// The state as an array in the rolling layout's order.
    pub fn to_array(mut self) -> [f64; DIM] {
        std::array::from_fn(|i| self.component_mut(i).map_or(f64::NAN, |v| *v))
    }

    /// The inverse of [`DiskState::to_array`].
    pub fn from_array(y: &[f64; DIM]) -> Self {
        let mut s = DiskState::default();
        for (i, v) in y.iter().enumerate() {
            if let Some(slot) = s.component_mut(i) {
                *slot = *v;
            }
        }
        s
    }

    /// The state named `name` (the rolling layout's names, [`STATE_NAMES`]).
    pub fn get_mut(&mut self, name: &str) -> Option<&mut f64> {
        let i = STATE_NAMES.iter().position(|n| *n == name)?;
        self.component_mut(i)
    }

    /// Precession rate ψ̇ = −Ω_x / sin θ (kinematics, both modes).
    pub fn psi_dot(&self) -> f64 {
        -self.omega_x / self.theta.sin()
    }

    /// Spin rate φ̇ = Ω_z + Ω_x cot θ (kinematics, both modes).
    pub fn phi_dot(&self) -> f64 {
        self.omega_z + self.omega_x * self.theta.cos() / self.theta.sin()
    }
}

/// Contact forces of a sample, with the friction's magnitude and ratio.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct ContactForces {
    /// Normal force N (N).
    pub normal: f64,
    /// Friction magnitude T (N).
    pub friction: f64,
    /// ν = T / N (see [`FrictionLaw::nu`]).
    pub nu: f64,
    /// Reaction X component (N).
    pub r_x: f64,
    /// Reaction Y component (N).
    pub r_y: f64,
}

/// One instant of a run.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Sample {
    /// Time (s).
    pub t: f64,
    /// The mode in force.
    pub mode: Mode,
    /// The state in the rolling chart.
    pub state: DiskState,
    /// The slip of the contact particle: its speed (0 while rolling) and the friction
    /// direction (in sliding the paper's α, in rolling the direction of the friction force
    /// rolling needs).
    pub slip: Slip,
    /// Contact forces.
    pub forces: ContactForces,
    /// Total mechanical energy (J).
    pub energy: f64,
}

impl Sample {
    /// The named record of the simulation's sample `s` of a disk whose friction follows
    /// `law`.
    pub fn of(s: &DiskSample, law: FrictionLaw) -> Sample {
        let f = &s.force;
        let friction = f.r_x.hypot(f.r_y);
        Sample {
            t: s.t,
            mode: s.mode,
            state: DiskState::from_array(&s.state.y),
            slip: s.state.slip,
            forces: ContactForces {
                normal: f.normal,
                friction,
                nu: law.nu(s.mode, friction, f.normal),
                r_x: f.r_x,
                r_y: f.r_y,
            },
            energy: s.energy,
        }
    }
}

/// The friction law's coefficients: they give ν where `T/N` of the computed forces does not.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrictionLaw {
    /// Dynamic friction `μ_d`.
    pub mu_d: f64,
    /// Static friction `μ_st`.
    pub mu_st: f64,
}

impl FrictionLaw {
    /// The coefficients of the disk `p`.
    pub fn of(p: &DiskParams) -> Self {
        FrictionLaw {
            mu_d: p.mu_d,
            mu_st: p.mu_st,
        }
    }

    /// The friction ratio ν in `mode` of a contact force with friction `t` and normal force
    /// `n`. Sliding: `μ_d` (`T = μ_d N` holds by construction; `T/N` of the computed forces
    /// would be `0/0`, or `−μ_d` from round-off, at the located instant the contact is lost).
    /// Rolling: `T/N` while the contact is compressed, `N > 0`; at the located loss of contact
    /// `N` is zero to round-off and `T/N` was `0/0` (NaN) or round-off's sign and size
    /// (−9.8e15 seen): there ν is the bound `μ_st` it stayed below while rolling, the one value
    /// the rolling law gives the ratio where the contact carries no force.
    pub fn nu(self, mode: Mode, t: f64, n: f64) -> f64 {
        match mode {
            Mode::Sliding => self.mu_d,
            Mode::Rolling if n > 0.0 && (t / n).is_finite() => t / n,
            Mode::Rolling => self.mu_st,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_state_is_written_by_the_state_names() {
        let y: [f64; 12] = std::array::from_fn(|i| i as f64 + 0.5);
        let written = toml::Value::try_from(DiskState::from_array(&y)).unwrap();
        let table = written.as_table().unwrap();
        assert_eq!(table.len(), STATE_NAMES.len());
        for (i, name) in STATE_NAMES.iter().enumerate() {
            assert_eq!(table[*name].as_float(), Some(y[i]), "{name}");
        }
    }

    #[test]
    fn array_round_trip_keeps_every_name_in_place() {
        let y: [f64; 12] = std::array::from_fn(|i| i as f64 + 0.5);
        let s = DiskState::from_array(&y);
        assert_eq!(s.theta, 7.5);
        assert_eq!(s.omega_z, 11.5);
        assert_eq!(s.to_array(), y);
        let mut named = s;
        for (i, name) in crate::models::rolling::STATE_NAMES.iter().enumerate() {
            assert_eq!(*named.get_mut(name).unwrap(), y[i], "{name}");
        }
        assert!(named.get_mut("v_C").is_none());
        assert!(named.component_mut(DIM).is_none());
    }

    #[test]
    fn kinematic_rates() {
        let s = DiskState {
            theta: std::f64::consts::FRAC_PI_4,
            omega_x: -2.0,
            omega_z: 1.0,
            ..Default::default()
        };
        assert!((s.psi_dot() - 2.0 * 2f64.sqrt()).abs() < 1e-12);
        assert!((s.phi_dot() - (1.0 - 2.0)).abs() < 1e-12);
    }

    #[test]
    fn nu_is_the_friction_laws_where_the_forces_give_none() {
        let law = FrictionLaw {
            mu_d: 0.115,
            mu_st: 0.2,
        };
        assert_eq!(law.nu(Mode::Rolling, 0.3, 2.0), 0.15);
        // The located loss of contact: 0/0, finite/round-off, a negative round-off N.
        for (t, n) in [(0.0, 0.0), (30.4, -3.1e-15), (1.0, 0.0), (0.0, -0.0)] {
            assert_eq!(law.nu(Mode::Rolling, t, n), 0.2, "{t}/{n}");
        }
        for (t, n) in [(0.0, 0.0), (0.23, 2.0), (-1.8e-16, -7.8e-16)] {
            assert_eq!(law.nu(Mode::Sliding, t, n), 0.115, "{t}/{n}");
        }
    }
}
