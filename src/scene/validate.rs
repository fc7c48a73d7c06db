//! The rules between a scene's values, checked all at once.
//!
//! Serde already guarantees the shape (known keys, right types); what remains are the rules
//! of the physics and of the numerics. Every rule is checked even after one fails, so the user
//! sees all the problems of a scene in one go.

use std::collections::HashSet;

use equations::params::DiskParams;

use super::initial::{self, InitialCondition};
use super::issue::{Issue, Rule};
use super::schema::{ModeName, SceneFile};
use crate::quantity::Quantity;

/// Smallest relative tolerance accepted: below it the error target is below round-off.
pub const RTOL_MIN: f64 = 1e-14;
/// Largest relative tolerance accepted.
pub const RTOL_MAX: f64 = 1.0;
/// Largest absolute tolerance accepted (SI units).
pub const ATOL_MAX: f64 = 1.0;
/// Most samples a run may record (they are kept for the figures).
pub const MAX_SAMPLES: f64 = 5e6;

/// A scene whose every rule holds, with its derived values.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The scene's name (file stem).
    pub name: String,
    /// The tables as written, after command-line overrides.
    pub file: SceneFile,
    /// The disk's parameters.
    pub params: DiskParams,
    /// The completed initial condition.
    pub initial: InitialCondition,
    /// The quantities written to `trajectory.csv`, in the scene's order.
    pub quantities: Vec<Quantity>,
}

fn finite(issues: &mut Vec<Issue>, key: &str, value: f64) -> bool {
    if value.is_finite() {
        true
    } else {
        issues.push(Issue {
            key: key.to_string(),
            rule: Rule::NotFinite { value },
        });
        false
    }
}

fn positive(issues: &mut Vec<Issue>, key: &str, value: f64) {
    if finite(issues, key, value) && value <= 0.0 {
        issues.push(Issue {
            key: key.to_string(),
            rule: Rule::NotPositive { value },
        });
    }
}

fn non_negative(issues: &mut Vec<Issue>, key: &str, value: f64) {
    if finite(issues, key, value) && value < 0.0 {
        issues.push(Issue {
            key: key.to_string(),
            rule: Rule::Negative { value },
        });
    }
}

fn in_range(issues: &mut Vec<Issue>, key: &str, value: f64, min: f64, max: f64) {
    if finite(issues, key, value) && !(min..=max).contains(&value) {
        issues.push(Issue {
            key: key.to_string(),
            rule: Rule::OutOfRange {
                value,
                min,
                max,
                open: false,
            },
        });
    }
}

/// Checks every rule of `file`; on success returns the scene, else every issue found.
pub fn validate(name: &str, file: SceneFile) -> Result<Scene, Vec<Issue>> {
    let mut issues = Vec::new();
    let f = &file;
    positive(&mut issues, "disk.m", f.disk.m);
    positive(&mut issues, "disk.a", f.disk.a);
    positive(&mut issues, "disk.g", f.disk.g);
    non_negative(&mut issues, "friction.mu_d", f.friction.mu_d);
    non_negative(&mut issues, "friction.mu_st", f.friction.mu_st);
    if f.friction.mu_d.is_finite() && f.friction.mu_st < f.friction.mu_d {
        issues.push(Issue {
            key: "friction.mu_st".into(),
            rule: Rule::BelowOther {
                value: f.friction.mu_st,
                other: "friction.mu_d",
                other_value: f.friction.mu_d,
            },
        });
    }
    non_negative(&mut issues, "air.mu_a", f.air.mu_a);
    finite(&mut issues, "air.w_z", f.air.w_z);
    in_range(
        &mut issues,
        "solver.rtol",
        f.solver.rtol,
        RTOL_MIN,
        RTOL_MAX,
    );
    positive(&mut issues, "solver.atol", f.solver.atol);
    if f.solver.atol > ATOL_MAX && f.solver.atol.is_finite() {
        issues.push(Issue {
            key: "solver.atol".into(),
            rule: Rule::OutOfRange {
                value: f.solver.atol,
                min: 0.0,
                max: ATOL_MAX,
                open: false,
            },
        });
    }
    positive(&mut issues, "run.t_end", f.run.t_end);
    positive(&mut issues, "run.sample_rate", f.run.sample_rate);
    let samples = f.run.t_end * f.run.sample_rate;
    if samples.is_finite() && samples > MAX_SAMPLES {
        // Blame the key that left its usual value: a raised rate, else the duration.
        let key = if f.run.sample_rate > super::schema::default_sample_rate() {
            "run.sample_rate"
        } else {
            "run.t_end"
        };
        issues.push(Issue {
            key: key.into(),
            rule: Rule::TooManySamples {
                samples,
                limit: MAX_SAMPLES,
                t_end: f.run.t_end,
                sample_rate: f.run.sample_rate,
            },
        });
    }
    check_modes(&mut issues, &f.modes.allowed);
    let quantities = check_quantities(&mut issues, &f.output.quantities);

    let a_usable = f.disk.a.is_finite() && f.disk.a > 0.0;
    let initial = if a_usable {
        initial::complete(&f.initial, f.disk.a, &mut issues)
    } else {
        None
    };
    if let Some(ic) = &initial {
        if ic.slip.v_c > 0.0 && !f.modes.allowed.contains(&ModeName::Sliding) {
            issues.push(Issue {
                key: "initial.v_C".into(),
                rule: Rule::ModeNotAllowed {
                    mode: "sliding",
                    because: format!("the contact particle slips at {:e} m/s", ic.slip.v_c),
                },
            });
        }
    }
    match initial {
        Some(initial) if issues.is_empty() => Ok(Scene {
            name: name.to_string(),
            params: DiskParams {
                m: f.disk.m,
                a: f.disk.a,
                g: f.disk.g,
                mu_d: f.friction.mu_d,
                mu_st: f.friction.mu_st,
                mu_a: f.air.mu_a,
                w_z: f.air.w_z,
            },
            initial,
            quantities,
            file,
        }),
        _ => Err(issues),
    }
}

fn check_modes(issues: &mut Vec<Issue>, allowed: &[ModeName]) {
    if allowed.is_empty() {
        issues.push(Issue {
            key: "modes.allowed".into(),
            rule: Rule::Empty,
        });
    }
    let mut seen = HashSet::new();
    for mode in allowed {
        if !seen.insert(*mode) {
            issues.push(Issue {
                key: "modes.allowed".into(),
                rule: Rule::Duplicate {
                    name: mode.to_string(),
                },
            });
        }
    }
}

fn check_quantities(issues: &mut Vec<Issue>, names: &[String]) -> Vec<Quantity> {
    if names.is_empty() {
        issues.push(Issue {
            key: "output.quantities".into(),
            rule: Rule::Empty,
        });
    }
    let mut out = Vec::new();
    for name in names {
        match Quantity::from_name(name) {
            None => issues.push(Issue {
                key: "output.quantities".into(),
                rule: Rule::Unknown {
                    name: name.clone(),
                    expected: Quantity::ALL.map(|q| q.name()).join(", "),
                },
            }),
            Some(q) if out.contains(&q) => issues.push(Issue {
                key: "output.quantities".into(),
                rule: Rule::Duplicate { name: name.clone() },
            }),
            Some(q) => out.push(q),
        }
    }
    out
}
