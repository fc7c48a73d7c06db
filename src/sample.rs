//! One recorded instant of a run, in named fields.
//!
//! The simulation streams arrays in a model's index order; everything downstream (CSV,
//! figures, summary) reads names instead, so a change of chart or of model index order is
//! absorbed in one conversion and never reaches the figures.

use equations::Mode;

/// The disk's state in the rolling chart (the paper's rolling unknowns), SI units.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DiskState {
    /// Centre X (m).
    pub x: f64,
    /// Centre Y (m).
    pub y: f64,
    /// Centre height Z (m).
    pub z: f64,
    /// Centre velocity X (m/s).
    pub v_x: f64,
    /// Centre velocity Y (m/s).
    pub v_y: f64,
    /// Centre velocity Z (m/s).
    pub v_z: f64,
    /// Precession ψ (rad).
    pub psi: f64,
    /// Inclination θ (rad).
    pub theta: f64,
    /// Spin φ (rad).
    pub phi: f64,
    /// Ω_x (rad/s).
    pub omega_x: f64,
    /// Ω_y (rad/s).
    pub omega_y: f64,
    /// Ω_z (rad/s).
    pub omega_z: f64,
}

impl DiskState {
    /// The state as an array in the rolling models' index order
    /// (X, Y, Z, V_X, V_Y, V_Z, psi, theta, phi, Omega_x, Omega_y, Omega_z).
    pub fn to_array(self) -> [f64; 12] {
        [
            self.x,
            self.y,
            self.z,
            self.v_x,
            self.v_y,
            self.v_z,
            self.psi,
            self.theta,
            self.phi,
            self.omega_x,
            self.omega_y,
            self.omega_z,
        ]
    }

    /// The inverse of [`DiskState::to_array`].
    pub fn from_array(y: &[f64; 12]) -> Self {
        DiskState {
            x: y[0],
            y: y[1],
            z: y[2],
            v_x: y[3],
            v_y: y[4],
            v_z: y[5],
            psi: y[6],
            theta: y[7],
            phi: y[8],
            omega_x: y[9],
            omega_y: y[10],
            omega_z: y[11],
        }
    }

    /// The state named `name` (rolling-layout names, `X` … `Omega_z`).
    pub fn get_mut(&mut self, name: &str) -> Option<&mut f64> {
        Some(match name {
            "X" => &mut self.x,
            "Y" => &mut self.y,
            "Z" => &mut self.z,
            "V_X" => &mut self.v_x,
            "V_Y" => &mut self.v_y,
            "V_Z" => &mut self.v_z,
            "psi" => &mut self.psi,
            "theta" => &mut self.theta,
            "phi" => &mut self.phi,
            "Omega_x" => &mut self.omega_x,
            "Omega_y" => &mut self.omega_y,
            "Omega_z" => &mut self.omega_z,
            _ => return None,
        })
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

/// The slip of the contact particle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Slip {
    /// Slip speed (m/s), 0 while rolling.
    pub v_c: f64,
    /// Friction direction (rad): in sliding the paper's α, in rolling the direction of the
    /// friction force rolling needs.
    pub alpha: f64,
}

/// Contact forces.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContactForces {
    /// Normal force N (N).
    pub normal: f64,
    /// Friction magnitude T (N).
    pub friction: f64,
    /// ν = T / N.
    pub nu: f64,
    /// Reaction X component (N).
    pub r_x: f64,
    /// Reaction Y component (N).
    pub r_y: f64,
}

/// One instant of a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Time (s).
    pub t: f64,
    /// The mode in force.
    pub mode: Mode,
    /// The state in the rolling chart.
    pub state: DiskState,
    /// The slip.
    pub slip: Slip,
    /// Contact forces.
    pub forces: ContactForces,
    /// Total mechanical energy (J).
    pub energy: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn array_round_trip_keeps_every_name_in_place() {
        let y: [f64; 12] = std::array::from_fn(|i| i as f64 + 0.5);
        let s = DiskState::from_array(&y);
        assert_eq!(s.theta, 7.5);
        assert_eq!(s.omega_z, 11.5);
        assert_eq!(s.to_array(), y);
        let mut named = s;
        for (i, name) in equations::models::rolling::STATE_NAMES.iter().enumerate() {
            assert_eq!(*named.get_mut(name).unwrap(), y[i], "{name}");
        }
        assert!(named.get_mut("v_C").is_none());
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
}
