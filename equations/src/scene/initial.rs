//! The initial state: what the scene gives, completed from the contact constraints.
//!
//! A scene names only a consistent subset of the state; the height, the vertical velocity and
//! (for a start without slip) the horizontal velocity follow from the constraints
//! (docs/physics.md §3.4, the paper's Box 2), computed by `crate::modes` as the run's own
//! projections compute them. A value the scene does give must agree with its constraint, else
//! the first step would start off the constraint manifold and every drift indicator would be
//! meaningless; the issue says by how much it disagrees. The slip is given either as `v_C`,
//! `alpha` or through the centre's velocity `V_X`, `V_Y`, and comes out explicit in the
//! [`InitialState`].

use crate::issue::{Checks, Rule};
use crate::modes::layout::{OMEGA_X, OMEGA_Y, OMEGA_Z, PHI, PSI, THETA, V_X, V_Y, V_Z, X, Y, Z};
use crate::modes::{no_slip_velocity, Mode, PhysicalState, Slip, DIM};
use crate::params::DiskParams;
use crate::start::{InitialState, CONSTRAINT_TOL};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// `[initial]`: the state by the paper's names; omitted entries follow from the constraints
/// (`Z`, `V_Z`, and the horizontal velocity of a start without slip) or are 0.
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
pub struct InitialTable {
    /// Centre position X (m).
    pub X: Option<f64>,
    /// Centre position Y (m).
    pub Y: Option<f64>,
    /// Centre height (m); must equal `a sin(theta)`.
    pub Z: Option<f64>,
    /// Centre velocity X (m/s).
    pub V_X: Option<f64>,
    /// Centre velocity Y (m/s).
    pub V_Y: Option<f64>,
    /// Centre velocity Z (m/s); must equal `a Omega_y cos(theta)`.
    pub V_Z: Option<f64>,
    /// Precession angle (rad).
    pub psi: Option<f64>,
    /// Inclination (rad), required, in (0, π).
    pub theta: Option<f64>,
    /// Spin angle (rad).
    pub phi: Option<f64>,
    /// Angular velocity, `e_x` component (rad/s).
    pub Omega_x: Option<f64>,
    /// Angular velocity, `e_y` component (rad/s).
    pub Omega_y: Option<f64>,
    /// Angular velocity, `e_z` component (rad/s).
    pub Omega_z: Option<f64>,
    /// Slip speed of the contact particle (m/s), instead of `V_X`, `V_Y`.
    pub v_C: Option<f64>,
    /// Direction of the friction force (rad), with `v_C`.
    pub alpha: Option<f64>,
}

fn key(name: &str) -> String {
    format!("initial.{name}")
}

impl InitialTable {
    /// The given values by name and state index (`None` for the slip, which is no state).
    fn named(&self) -> [(&'static str, Option<usize>, Option<f64>); 14] {
        [
            ("X", Some(X), self.X),
            ("Y", Some(Y), self.Y),
            ("Z", Some(Z), self.Z),
            ("V_X", Some(V_X), self.V_X),
            ("V_Y", Some(V_Y), self.V_Y),
            ("V_Z", Some(V_Z), self.V_Z),
            ("psi", Some(PSI), self.psi),
            ("theta", Some(THETA), self.theta),
            ("phi", Some(PHI), self.phi),
            ("Omega_x", Some(OMEGA_X), self.Omega_x),
            ("Omega_y", Some(OMEGA_Y), self.Omega_y),
            ("Omega_z", Some(OMEGA_Z), self.Omega_z),
            ("v_C", None, self.v_C),
            ("alpha", None, self.alpha),
        ]
    }

    /// Completes the initial state of a disk with parameters `p` (only its radius is read),
    /// pushing every problem to `c`; `None` when an issue prevents completing it.
    pub(crate) fn complete(&self, p: &DiskParams, c: &mut Checks) -> Option<InitialState> {
        let before = c.issues.len();
        for (name, _, value) in self.named() {
            if let Some(value) = value {
                c.finite(&key(name), value);
            }
        }
        match self.theta {
            None => c.push(&key("theta"), Rule::Missing),
            Some(value) if value.is_finite() => {
                c.in_range(&key("theta"), value, 0.0, PI, true);
            }
            _ => {}
        }
        if let Some(v_c) = self.v_C.filter(|v| v.is_finite() && *v < 0.0) {
            c.push(&key("v_C"), Rule::Negative { value: v_c });
        }
        let gives_velocity = self.V_X.is_some() || self.V_Y.is_some();
        let gives_slip = self.v_C.is_some() || self.alpha.is_some();
        if gives_velocity && gives_slip {
            let mine = if self.V_X.is_some() { "V_X" } else { "V_Y" };
            let other = if self.v_C.is_some() {
                "initial.v_C"
            } else {
                "initial.alpha"
            };
            c.push(&key(mine), Rule::Conflicts { other });
        }
        if self.v_C.is_some_and(|v| v > 0.0) && self.alpha.is_none() {
            c.push(
                &key("alpha"),
                Rule::RequiredWith {
                    other: "initial.v_C",
                },
            );
        }
        if c.issues.len() > before {
            return None;
        }

        let mut y = [0.0; DIM];
        for (_, index, value) in self.named() {
            if let (Some(i), Some(v)) = (index, value) {
                y[i] = v;
            }
        }
        // What the contact constraints require, as the run's projection computes it.
        let mut state = PhysicalState::from_rolling(&y, 0.0);
        state.project(p, Mode::Sliding);
        let checks = [
            ("Z", self.Z, state.y[Z], "Z = a sin(theta)", "m"),
            (
                "V_Z",
                self.V_Z,
                state.y[V_Z],
                "V_Z = a Omega_y cos(theta)",
                "m/s",
            ),
        ];
        for (name, given, required, constraint, unit) in checks {
            if let Some(given) =
                given.filter(|g| (g - required).abs() > CONSTRAINT_TOL * (1.0 + required.abs()))
            {
                c.push(
                    &key(name),
                    Rule::ConstraintViolated {
                        constraint,
                        required,
                        given,
                        unit,
                    },
                );
            }
        }
        if c.issues.len() > before {
            return None;
        }

        let start = self.finish(p, state);
        // Finite values can still complete to infinite ones (a radius of 1e308 times a rate).
        let completed = self.named().map(|(name, index, _)| {
            let value = match (index, name) {
                (Some(i), _) => start.state.y[i],
                (None, "v_C") => start.state.slip.speed,
                (None, _) => start.state.slip.direction,
            };
            (name, value)
        });
        for (name, value) in completed {
            if !value.is_finite() {
                c.push(&key(name), Rule::CompletesNonFinite { value });
            }
        }
        (c.issues.len() == before).then_some(start)
    }

    /// The completed start from `state`, which holds the given values and satisfies the
    /// height and vertical-velocity constraints.
    fn finish(&self, p: &DiskParams, mut state: PhysicalState) -> InitialState {
        if self.V_X.is_some() || self.V_Y.is_some() {
            let no_slip = no_slip_velocity(p, &state.y);
            state.y[V_X] = self.V_X.unwrap_or(no_slip[0]);
            state.y[V_Y] = self.V_Y.unwrap_or(no_slip[1]);
            return InitialState::from_velocity(p, 0.0, state.y);
        }
        match self.v_C.filter(|v| *v > 0.0) {
            Some(speed) => {
                let slip = Slip {
                    speed,
                    direction: self.alpha.unwrap_or(0.0),
                };
                InitialState::sliding(p, 0.0, state.y, slip)
            }
            None => {
                state.project(p, Mode::Rolling);
                InitialState::rolling(0.0, state.y)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::issue::Issue;

    fn params() -> DiskParams {
        DiskParams::paper()
    }

    fn table(theta: f64) -> InitialTable {
        InitialTable {
            theta: Some(theta),
            Omega_x: Some(1.0),
            Omega_y: Some(0.3),
            Omega_z: Some(-2.0),
            psi: Some(0.4),
            ..Default::default()
        }
    }

    fn complete(t: &InitialTable) -> Result<InitialState, Vec<Issue>> {
        let mut c = Checks::default();
        let start = t.complete(&params(), &mut c);
        match start {
            Some(s) if c.issues.is_empty() => Ok(s),
            _ => Err(c.issues),
        }
    }

    #[test]
    fn completes_a_rolling_start_from_the_constraints() {
        let p = params();
        let start = complete(&table(0.5)).unwrap();
        assert_eq!(start.mode, Mode::Rolling);
        let y = start.state.y;
        assert_eq!(y[Z], p.a * 0.5f64.sin());
        assert_eq!(y[V_Z], p.a * 0.3 * 0.5f64.cos());
        // The contact particle is at rest: V + Omega x a e_x = 0 (docs/physics.md §1),
        // written out by hand rather than through `modes`.
        let (sp, cp) = y[PSI].sin_cos();
        let st = y[THETA].sin();
        let vc_x = y[V_X] - p.a * (y[OMEGA_Y] * cp * st + y[OMEGA_Z] * sp);
        let vc_y = y[V_Y] - p.a * (y[OMEGA_Y] * sp * st - y[OMEGA_Z] * cp);
        assert!(vc_x.abs() < 1e-15 && vc_y.abs() < 1e-15);
        assert_eq!(start.state.slip.speed, 0.0);
        assert_eq!(start.state.residuals(&p, Mode::Rolling).max_abs(), 0.0);
    }

    /// Every given value is finite and every rule holds, but `a × Ω` overflows: the completed
    /// velocity is named, and no state comes out.
    #[test]
    fn a_start_that_completes_to_infinity_is_refused_naming_the_value() {
        let p = DiskParams {
            a: f64::MAX,
            ..params()
        };
        let spinning = InitialTable {
            Omega_z: Some(-20.0),
            ..table(0.5)
        };
        let mut c = Checks::default();
        assert!(spinning.complete(&p, &mut c).is_none());
        let keys: Vec<&str> = c.issues.iter().map(|i| i.key.as_str()).collect();
        assert!(keys.contains(&"initial.V_X"), "{keys:?}");
        let text = c.issues[0].to_string();
        assert!(
            text.contains("`disk.a`") && text.contains("overflow"),
            "{text}"
        );
    }

    #[test]
    fn slip_given_either_way_gives_the_same_start() {
        let p = params();
        let mut by_slip = table(0.7);
        by_slip.v_C = Some(0.25);
        by_slip.alpha = Some(2.0);
        let a = complete(&by_slip).unwrap();
        assert_eq!(a.mode, Mode::Sliding);
        assert_eq!(a.state.slip.speed, 0.25);
        assert_eq!(a.state.slip.direction, 2.0);
        // The velocity carries the slip: V − V_no-slip = u = −v_C (cos α, sin α).
        let u = a.state.velocity_slip(&p);
        assert!((u[0] + 0.25 * 2.0f64.cos()).abs() < 1e-15);
        assert!((u[1] + 0.25 * 2.0f64.sin()).abs() < 1e-15);
        let mut by_velocity = table(0.7);
        by_velocity.V_X = Some(a.state.y[V_X]);
        by_velocity.V_Y = Some(a.state.y[V_Y]);
        let b = complete(&by_velocity).unwrap();
        assert_eq!(b.mode, Mode::Sliding);
        assert!((b.state.slip.speed - 0.25).abs() < 1e-14);
        assert!((b.state.slip.direction - 2.0).abs() < 1e-12);
        for i in 0..DIM {
            assert!((a.state.y[i] - b.state.y[i]).abs() < 1e-15, "component {i}");
        }
    }

    #[test]
    fn a_velocity_without_slip_is_a_rolling_start() {
        let rolling = complete(&table(0.6)).unwrap();
        let mut t = table(0.6);
        t.V_X = Some(rolling.state.y[V_X]);
        t.V_Y = Some(rolling.state.y[V_Y] + 1e-13);
        let start = complete(&t).unwrap();
        assert_eq!(start.mode, Mode::Rolling);
        assert_eq!(start.state.y, rolling.state.y);
    }

    #[test]
    fn violations_say_by_how_much() {
        let p = params();
        let mut t = table(0.5);
        t.Z = Some(0.02);
        let issues = complete(&t).unwrap_err();
        assert_eq!(issues[0].key, "initial.Z");
        let text = issues[0].to_string();
        assert!(text.contains("Z = a sin(theta)"), "{text}");
        assert!(
            text.contains(&format!("{:.3e}", 0.02 - p.a * 0.5f64.sin())),
            "{text}"
        );
    }

    #[test]
    fn every_problem_is_collected() {
        let t = InitialTable {
            theta: Some(4.0),
            Omega_x: Some(f64::NAN),
            v_C: Some(-1.0),
            V_X: Some(0.0),
            ..Default::default()
        };
        let issues = complete(&t).unwrap_err();
        let keys: Vec<_> = issues.iter().map(|i| i.key.as_str()).collect();
        assert_eq!(
            keys,
            [
                "initial.Omega_x",
                "initial.theta",
                "initial.v_C",
                "initial.V_X"
            ]
        );
    }
}
