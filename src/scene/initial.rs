//! The initial state: what the scene gives, completed from the contact constraints.
//!
//! A scene names only a consistent subset of the state; the height, the vertical velocity and
//! (for a start without slip) the horizontal velocity follow from the constraints
//! (docs/physics.md §3.4, the paper's Box 2). A value the scene does give must agree with its
//! constraint, else the first step would start off the constraint manifold and every drift
//! indicator would be meaningless; the issue says by how much it disagrees.

use std::f64::consts::PI;

use super::issue::{Issue, Rule};
use super::schema::InitialTable;
use crate::sample::{DiskState, Slip};

/// Relative tolerance for a given value against its constraint: `|given − required| <=
/// CONSTRAINT_TOL · (1 + |required|)` in SI units.
pub const CONSTRAINT_TOL: f64 = 1e-9;

/// The completed initial condition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InitialCondition {
    /// The state in the rolling chart; `V_X`, `V_Y` include the slip.
    pub state: DiskState,
    /// The slip (`v_C = 0` for a start without slip).
    pub slip: Slip,
}

/// The horizontal centre velocity of a disk whose contact particle is at rest (Box 2).
pub fn no_slip_velocity(a: f64, psi: f64, theta: f64, omega_y: f64, omega_z: f64) -> [f64; 2] {
    let (sp, cp) = psi.sin_cos();
    let st = theta.sin();
    [
        a * (omega_y * cp * st + omega_z * sp),
        a * (omega_y * sp * st - omega_z * cp),
    ]
}

fn key(name: &str) -> String {
    format!("initial.{name}")
}

fn within(given: f64, required: f64) -> bool {
    (given - required).abs() <= CONSTRAINT_TOL * (1.0 + required.abs())
}

/// Completes the initial state for a disk of radius `a`, pushing every problem to `issues`.
/// Returns `None` when an issue prevents completing it.
pub fn complete(init: &InitialTable, a: f64, issues: &mut Vec<Issue>) -> Option<InitialCondition> {
    let before = issues.len();
    let named: [(&str, Option<f64>); 14] = [
        ("X", init.X),
        ("Y", init.Y),
        ("Z", init.Z),
        ("V_X", init.V_X),
        ("V_Y", init.V_Y),
        ("V_Z", init.V_Z),
        ("psi", init.psi),
        ("theta", init.theta),
        ("phi", init.phi),
        ("Omega_x", init.Omega_x),
        ("Omega_y", init.Omega_y),
        ("Omega_z", init.Omega_z),
        ("v_C", init.v_C),
        ("alpha", init.alpha),
    ];
    for (name, value) in named {
        if let Some(value) = value.filter(|v| !v.is_finite()) {
            issues.push(Issue {
                key: key(name),
                rule: Rule::NotFinite { value },
            });
        }
    }
    match init.theta {
        None => issues.push(Issue {
            key: key("theta"),
            rule: Rule::Missing,
        }),
        Some(value) if value.is_finite() && !(value > 0.0 && value < PI) => issues.push(Issue {
            key: key("theta"),
            rule: Rule::OutOfRange {
                value,
                min: 0.0,
                max: PI,
                open: true,
            },
        }),
        _ => {}
    }
    if let Some(v_c) = init.v_C.filter(|v| v.is_finite() && *v < 0.0) {
        issues.push(Issue {
            key: key("v_C"),
            rule: Rule::Negative { value: v_c },
        });
    }
    let gives_velocity = init.V_X.is_some() || init.V_Y.is_some();
    let gives_slip = init.v_C.is_some() || init.alpha.is_some();
    if gives_velocity && gives_slip {
        let (mine, other) = if init.V_X.is_some() {
            (
                "V_X",
                if init.v_C.is_some() {
                    "initial.v_C"
                } else {
                    "initial.alpha"
                },
            )
        } else {
            (
                "V_Y",
                if init.v_C.is_some() {
                    "initial.v_C"
                } else {
                    "initial.alpha"
                },
            )
        };
        issues.push(Issue {
            key: key(mine),
            rule: Rule::Conflicts { other },
        });
    }
    if init.v_C.is_some_and(|v| v > 0.0) && init.alpha.is_none() {
        issues.push(Issue {
            key: key("alpha"),
            rule: Rule::RequiredWith {
                other: "initial.v_C",
            },
        });
    }
    if issues.len() > before {
        return None;
    }

    let theta = init.theta?;
    let psi = init.psi.unwrap_or(0.0);
    let omega_x = init.Omega_x.unwrap_or(0.0);
    let omega_y = init.Omega_y.unwrap_or(0.0);
    let omega_z = init.Omega_z.unwrap_or(0.0);
    let z_required = a * theta.sin();
    let v_z_required = a * omega_y * theta.cos();
    let checks = [
        ("Z", init.Z, z_required, "Z = a sin(theta)", "m"),
        (
            "V_Z",
            init.V_Z,
            v_z_required,
            "V_Z = a Omega_y cos(theta)",
            "m/s",
        ),
    ];
    for (name, given, required, constraint, unit) in checks {
        if let Some(given) = given.filter(|g| !within(*g, required)) {
            issues.push(Issue {
                key: key(name),
                rule: Rule::ConstraintViolated {
                    constraint,
                    required,
                    given,
                    unit,
                },
            });
        }
    }
    if issues.len() > before {
        return None;
    }

    let no_slip = no_slip_velocity(a, psi, theta, omega_y, omega_z);
    let (velocity, slip) = if gives_velocity {
        let v = [
            init.V_X.unwrap_or(no_slip[0]),
            init.V_Y.unwrap_or(no_slip[1]),
        ];
        let u = [v[0] - no_slip[0], v[1] - no_slip[1]];
        let speed = u[0].hypot(u[1]);
        let scale = 1.0 + no_slip[0].hypot(no_slip[1]);
        if speed <= CONSTRAINT_TOL * scale {
            (no_slip, Slip::default())
        } else {
            let alpha = (-u[1]).atan2(-u[0]);
            (v, Slip { v_c: speed, alpha })
        }
    } else {
        let slip = Slip {
            v_c: init.v_C.unwrap_or(0.0),
            alpha: init.alpha.unwrap_or(0.0),
        };
        let (sa, ca) = slip.alpha.sin_cos();
        (
            [no_slip[0] - slip.v_c * ca, no_slip[1] - slip.v_c * sa],
            slip,
        )
    };
    let state = DiskState {
        x: init.X.unwrap_or(0.0),
        y: init.Y.unwrap_or(0.0),
        z: z_required,
        v_x: velocity[0],
        v_y: velocity[1],
        v_z: v_z_required,
        psi,
        theta,
        phi: init.phi.unwrap_or(0.0),
        omega_x,
        omega_y,
        omega_z,
    };
    Some(InitialCondition { state, slip })
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: f64 = 0.03755;

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

    #[test]
    fn completes_a_rolling_start_from_the_constraints() {
        let mut issues = vec![];
        let ic = complete(&table(0.5), A, &mut issues).unwrap();
        assert!(issues.is_empty());
        let s = ic.state;
        assert_eq!(s.z, A * 0.5f64.sin());
        assert_eq!(s.v_z, A * 0.3 * 0.5f64.cos());
        // The contact particle is at rest: V + Omega x a e_x = 0 (docs/physics.md §1).
        let (sp, cp) = s.psi.sin_cos();
        let vc_x = s.v_x - A * (s.omega_y * cp * s.theta.sin() + s.omega_z * sp);
        let vc_y = s.v_y - A * (s.omega_y * sp * s.theta.sin() - s.omega_z * cp);
        assert!(vc_x.abs() < 1e-15 && vc_y.abs() < 1e-15);
        assert_eq!(ic.slip.v_c, 0.0);
    }

    #[test]
    fn slip_from_velocity_and_back() {
        let mut issues = vec![];
        let mut t = table(0.7);
        t.v_C = Some(0.25);
        t.alpha = Some(2.0);
        let ic = complete(&t, A, &mut issues).unwrap();
        let mut t2 = table(0.7);
        t2.V_X = Some(ic.state.v_x);
        t2.V_Y = Some(ic.state.v_y);
        let ic2 = complete(&t2, A, &mut issues).unwrap();
        assert!(issues.is_empty());
        assert!((ic2.slip.v_c - 0.25).abs() < 1e-14);
        assert!((ic2.slip.alpha - 2.0).abs() < 1e-12);
    }

    #[test]
    fn violations_say_by_how_much() {
        let mut issues = vec![];
        let mut t = table(0.5);
        t.Z = Some(0.02);
        assert!(complete(&t, A, &mut issues).is_none());
        assert_eq!(issues[0].key, "initial.Z");
        let text = issues[0].to_string();
        assert!(text.contains("Z = a sin(theta)"), "{text}");
        assert!(
            text.contains(&format!("{:.3e}", 0.02 - A * 0.5f64.sin())),
            "{text}"
        );
    }

    #[test]
    fn every_problem_is_collected() {
        let mut issues = vec![];
        let t = InitialTable {
            theta: Some(4.0),
            Omega_x: Some(f64::NAN),
            v_C: Some(-1.0),
            V_X: Some(0.0),
            ..Default::default()
        };
        assert!(complete(&t, A, &mut issues).is_none());
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
