//! The quantities a run can record, with their units, under the paper's names.
//!
//! One table drives the CSV header, the `[output] quantities` check and the value lookup, so
//! a quantity's name, unit and meaning cannot drift apart between those places.

use super::sample::Sample;
use crate::params::DiskParams;

/// A recordable quantity.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[allow(non_camel_case_types)]
pub enum Quantity {
    /// Centre position X.
    X,
    /// Centre position Y.
    Y,
    /// Centre height Z.
    Z,
    /// Centre velocity X.
    V_X,
    /// Centre velocity Y.
    V_Y,
    /// Centre velocity Z.
    V_Z,
    /// Precession angle ψ.
    Psi,
    /// Inclination θ.
    Theta,
    /// Spin angle φ.
    Phi,
    /// Angular velocity Ω_x.
    Omega_x,
    /// Angular velocity Ω_y.
    Omega_y,
    /// Angular velocity Ω_z.
    Omega_z,
    /// Slip speed v_C (0 while rolling).
    V_C,
    /// Friction direction α (sliding) or the direction of the required friction (rolling).
    Alpha,
    /// θ̇ (= Ω_y).
    ThetaDot,
    /// ψ̇ (= −Ω_x / sin θ).
    PsiDot,
    /// φ̇ (= Ω_z + Ω_x cot θ).
    PhiDot,
    /// Normal contact force N.
    N,
    /// Friction force magnitude T.
    T,
    /// Friction ratio ν = T/N.
    Nu,
    /// Reduced normal force N/(m g).
    NOverMg,
    /// Contact reaction, X component.
    R_X,
    /// Contact reaction, Y component.
    R_Y,
    /// Total mechanical energy.
    Energy,
    /// Contact-constraint residual Z − a sin θ.
    ResidualZ,
    /// Velocity-constraint residual V_Z − a Ω_y cos θ.
    ResidualV_Z,
}

impl Quantity {
    /// Every quantity, in CSV column order.
    pub const ALL: [Quantity; 26] = [
        Quantity::X,
        Quantity::Y,
        Quantity::Z,
        Quantity::V_X,
        Quantity::V_Y,
        Quantity::V_Z,
        Quantity::Psi,
        Quantity::Theta,
        Quantity::Phi,
        Quantity::Omega_x,
        Quantity::Omega_y,
        Quantity::Omega_z,
        Quantity::V_C,
        Quantity::Alpha,
        Quantity::ThetaDot,
        Quantity::PsiDot,
        Quantity::PhiDot,
        Quantity::N,
        Quantity::T,
        Quantity::Nu,
        Quantity::NOverMg,
        Quantity::R_X,
        Quantity::R_Y,
        Quantity::Energy,
        Quantity::ResidualZ,
        Quantity::ResidualV_Z,
    ];

    /// The name used in scenes and in `eval` output (the paper's notation).
    pub fn name(self) -> &'static str {
        self.spec().0
    }

    /// The unit, spelt for a CSV column (`m_per_s`, `rad`, `ratio` for dimensionless).
    pub fn unit(self) -> &'static str {
        self.spec().1
    }

    /// The CSV column name: name and unit, e.g. `theta_rad`.
    pub fn column(self) -> String {
        format!("{}_{}", self.name(), self.unit())
    }

    /// Looks a quantity up by its name.
    pub fn from_name(name: &str) -> Option<Quantity> {
        Quantity::ALL.iter().copied().find(|q| q.name() == name)
    }

    fn spec(self) -> (&'static str, &'static str) {
        match self {
            Quantity::X => ("X", "m"),
            Quantity::Y => ("Y", "m"),
            Quantity::Z => ("Z", "m"),
            Quantity::V_X => ("V_X", "m_per_s"),
            Quantity::V_Y => ("V_Y", "m_per_s"),
            Quantity::V_Z => ("V_Z", "m_per_s"),
            Quantity::Psi => ("psi", "rad"),
            Quantity::Theta => ("theta", "rad"),
            Quantity::Phi => ("phi", "rad"),
            Quantity::Omega_x => ("Omega_x", "rad_per_s"),
            Quantity::Omega_y => ("Omega_y", "rad_per_s"),
            Quantity::Omega_z => ("Omega_z", "rad_per_s"),
            Quantity::V_C => ("v_C", "m_per_s"),
            Quantity::Alpha => ("alpha", "rad"),
            Quantity::ThetaDot => ("theta_dot", "rad_per_s"),
            Quantity::PsiDot => ("psi_dot", "rad_per_s"),
            Quantity::PhiDot => ("phi_dot", "rad_per_s"),
            Quantity::N => ("N", "N"),
            Quantity::T => ("T", "N"),
            Quantity::Nu => ("nu", "ratio"),
            Quantity::NOverMg => ("N_over_mg", "ratio"),
            Quantity::R_X => ("R_X", "N"),
            Quantity::R_Y => ("R_Y", "N"),
            Quantity::Energy => ("energy", "J"),
            Quantity::ResidualZ => ("residual_Z", "m"),
            Quantity::ResidualV_Z => ("residual_V_Z", "m_per_s"),
        }
    }

    /// The states (by their names in the rolling layout, `X` … `Omega_z`) whose values or
    /// derivatives the quantity is computed from. A run that does not integrate one of them
    /// (a pruned model leaves `X`, `Y`, `Z` and `phi` frozen) cannot report the quantity.
    ///
    /// The slip and the contact forces are listed by the velocities they come from; a sliding
    /// model carries the slip itself and computes the centre's velocity from it.
    pub fn reads(self) -> &'static [&'static str] {
        const SLIP: &[&str] = &[
            "V_X", "V_Y", "psi", "theta", "Omega_x", "Omega_y", "Omega_z",
        ];
        const FORCE: &[&str] = &["V_X", "V_Y", "V_Z", "psi", "theta"];
        match self {
            Quantity::X => &["X"],
            Quantity::Y => &["Y"],
            Quantity::Z => &["Z"],
            Quantity::V_X => &["V_X"],
            Quantity::V_Y => &["V_Y"],
            Quantity::V_Z => &["V_Z"],
            Quantity::Psi => &["psi"],
            Quantity::Theta => &["theta"],
            Quantity::Phi => &["phi"],
            Quantity::Omega_x => &["Omega_x"],
            Quantity::Omega_y | Quantity::ThetaDot => &["Omega_y"],
            Quantity::Omega_z => &["Omega_z"],
            Quantity::V_C | Quantity::Alpha => SLIP,
            Quantity::PsiDot => &["Omega_x", "theta"],
            Quantity::PhiDot => &["Omega_x", "Omega_z", "theta"],
            Quantity::N | Quantity::T | Quantity::Nu | Quantity::NOverMg => FORCE,
            Quantity::R_X | Quantity::R_Y => FORCE,
            Quantity::Energy => &["Z", "V_X", "V_Y", "V_Z", "Omega_x", "Omega_y", "Omega_z"],
            Quantity::ResidualZ => &["Z", "theta"],
            Quantity::ResidualV_Z => &["V_Z", "Omega_y", "theta"],
        }
    }

    /// The states among `frozen` (states a run does not integrate) that this quantity reads.
    pub fn reads_among(self, frozen: &[&str]) -> Vec<&'static str> {
        self.reads()
            .iter()
            .copied()
            .filter(|s| frozen.contains(s))
            .collect()
    }

    /// Whether a run that leaves the states `frozen` unintegrated computes this quantity.
    pub fn computed_without(self, frozen: &[&str]) -> bool {
        !self.reads().iter().any(|s| frozen.contains(s))
    }

    /// The quantity's value in a sample of a disk with parameters `p`.
    pub fn value(self, s: &Sample, p: &DiskParams) -> f64 {
        let st = &s.state;
        match self {
            Quantity::X => st.x,
            Quantity::Y => st.y,
            Quantity::Z => st.z,
            Quantity::V_X => st.v_x,
            Quantity::V_Y => st.v_y,
            Quantity::V_Z => st.v_z,
            Quantity::Psi => st.psi,
            Quantity::Theta => st.theta,
            Quantity::Phi => st.phi,
            Quantity::Omega_x => st.omega_x,
            Quantity::Omega_y => st.omega_y,
            Quantity::Omega_z => st.omega_z,
            Quantity::V_C => s.slip.speed,
            Quantity::Alpha => s.slip.direction,
            Quantity::ThetaDot => st.omega_y,
            Quantity::PsiDot => st.psi_dot(),
            Quantity::PhiDot => st.phi_dot(),
            Quantity::N => s.forces.normal,
            Quantity::T => s.forces.friction,
            Quantity::Nu => s.forces.nu,
            Quantity::NOverMg => s.forces.normal / p.weight(),
            Quantity::R_X => s.forces.r_x,
            Quantity::R_Y => s.forces.r_y,
            Quantity::Energy => s.energy,
            Quantity::ResidualZ => st.z - p.a * st.theta.sin(),
            Quantity::ResidualV_Z => st.v_z - p.a * st.omega_y * st.theta.cos(),
        }
    }
}

/// Replaces every value of `sample` that depends on a state in `frozen` (a state the models
/// did not integrate) by NaN, so a frozen value can never pass for a result. The rule lives
/// with the quantities, which know what each value reads.
pub fn forget_frozen(sample: &mut Sample, frozen: &[&str]) {
    for name in frozen {
        if let Some(v) = sample.state.get_mut(name) {
            *v = f64::NAN;
        }
    }
    if !Quantity::Energy.computed_without(frozen) {
        sample.energy = f64::NAN;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    #[test]
    fn names_and_columns_are_unique_and_round_trip() {
        let names: HashSet<_> = Quantity::ALL.iter().map(|q| q.name()).collect();
        let columns: HashSet<_> = Quantity::ALL.iter().map(|q| q.column()).collect();
        assert_eq!(names.len(), Quantity::ALL.len());
        assert_eq!(columns.len(), Quantity::ALL.len());
        for q in Quantity::ALL {
            assert_eq!(Quantity::from_name(q.name()), Some(q));
        }
        assert_eq!(Quantity::Theta.column(), "theta_rad");
        assert_eq!(Quantity::from_name("Theta"), None);
    }

    #[test]
    fn reads_name_states_of_the_rolling_layout() {
        let states = crate::models::rolling::STATE_NAMES;
        for q in Quantity::ALL {
            assert!(!q.reads().is_empty(), "{}", q.name());
            for s in q.reads() {
                assert!(states.contains(s), "{}: `{s}`", q.name());
            }
        }
    }

    #[test]
    fn a_frozen_position_takes_exactly_what_reads_it() {
        let frozen = ["X", "Y", "Z", "phi"];
        let lost: Vec<_> = Quantity::ALL
            .into_iter()
            .filter(|q| !q.computed_without(&frozen))
            .map(|q| q.name())
            .collect();
        assert_eq!(lost, ["X", "Y", "Z", "phi", "energy", "residual_Z"]);
    }
}
