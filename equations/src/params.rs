//! The disk's physical parameters in one validated value.
//!
//! Every model of the disk (the reference, the generated models, the closed-form formulas)
//! takes the same seven numbers; keeping them in one type with one validation means a bad
//! parameter is rejected once, by name, before it can turn into a NaN deep inside a solve.

use std::f64::consts::PI;

use crate::issue::{Checks, Issue, Rule};

/// Parameters of a thin homogeneous disk on a rough plane (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiskParams {
    /// Mass (kg).
    pub m: f64,
    /// Radius (m).
    pub a: f64,
    /// Gravitational acceleration (m/s²).
    pub g: f64,
    /// Dynamic (sliding) friction coefficient.
    pub mu_d: f64,
    /// Static friction coefficient: rolling holds while `T/N < mu_st`.
    pub mu_st: f64,
    /// Air-drag coefficient of the paper's eq. (11) (N·s/m³), zero for no air.
    pub mu_a: f64,
    /// Uniform normal air velocity (m/s), zero for still air.
    pub w_z: f64,
}

/// Why a set of disk parameters was rejected.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum ParamError {
    /// A parameter that must be finite and strictly positive is not.
    #[error("parameter `{name}` must be finite and > 0, got {value}")]
    NotPositive {
        /// The parameter's name.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// A parameter that must be finite is not.
    #[error("parameter `{name}` must be finite, got {value}")]
    NotFinite {
        /// The parameter's name.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// A parameter that must be finite and non-negative is not.
    #[error("parameter `{name}` must be finite and >= 0, got {value}")]
    Negative {
        /// The parameter's name.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// Finite parameters whose products (`m a²`, `m g a`) overflow.
    #[error("parameter `{name}` = {value} makes the disk's inertia m a^2 or weight moment m g a overflow")]
    Overflow {
        /// The parameter's name.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// Dynamic friction exceeds static friction.
    #[error("dynamic friction mu_d = {mu_d} exceeds static friction mu_st = {mu_st}")]
    DynamicAboveStatic {
        /// The dynamic coefficient.
        mu_d: f64,
        /// The static coefficient.
        mu_st: f64,
    },
}

impl DiskParams {
    /// Parameter names in the order used by every model's parameter array.
    pub const NAMES: [&'static str; 7] = ["m", "a", "g", "mu_d", "mu_st", "mu_a", "w_z"];

    /// The paper's disk and scene (Saje & Zupan; `g` assumed, `mu_a = 0`, still air).
    pub fn paper() -> Self {
        DiskParams {
            m: 0.4387,
            a: 0.03755,
            g: 9.81,
            mu_d: 0.115,
            mu_st: 0.2,
            mu_a: 0.0,
            w_z: 0.0,
        }
    }

    /// The scene keys of the parameters, in [`DiskParams::NAMES`] order.
    pub const KEYS: [&'static str; 7] = [
        "disk.m",
        "disk.a",
        "disk.g",
        "friction.mu_d",
        "friction.mu_st",
        "air.mu_a",
        "air.w_z",
    ];

    /// Every rule the parameters break, each with its scene key ([`DiskParams::KEYS`]): `m`,
    /// `a`, `g` finite and > 0, with `m a²` and `m g a` finite; `mu_d`, `mu_st`, `mu_a` finite
    /// and >= 0; `mu_st >= mu_d`;
    /// `w_z` finite. The one set of rules for parameters, whether a scene or a program gives
    /// them.
    pub fn issues(&self) -> Vec<Issue> {
        let mut c = Checks::default();
        let [m, a, g, mu_d, mu_st, mu_a, w_z] = Self::KEYS;
        let sizes_ok = c.positive(m, self.m) & c.positive(a, self.a) & c.positive(g, self.g);
        let (inertia, weight_moment) = (self.m * self.a * self.a, self.m * self.g * self.a);
        if sizes_ok && !(inertia.is_finite() && weight_moment.is_finite()) {
            // Every model multiplies by them: a radius of 1e308 m passed every other rule and
            // started the disk with an infinite velocity. The largest factor is blamed.
            let key = [(m, self.m), (a, self.a), (g, self.g)]
                .into_iter()
                .fold(
                    (a, 0.0),
                    |best, (k, v)| if v > best.1 { (k, v) } else { best },
                )
                .0;
            c.push(
                key,
                Rule::Overflows {
                    what: "the inertia `disk.m` × `disk.a`^2 or the weight moment \
                           `disk.m` × `disk.g` × `disk.a`",
                },
            );
        }
        let mu_d_ok = c.non_negative(mu_d, self.mu_d);
        if c.non_negative(mu_st, self.mu_st) && mu_d_ok && self.mu_st < self.mu_d {
            c.push(
                mu_st,
                Rule::BelowOther {
                    value: self.mu_st,
                    other: mu_d,
                    other_value: self.mu_d,
                },
            );
        }
        c.non_negative(mu_a, self.mu_a);
        c.finite(w_z, self.w_z);
        c.issues
    }

    /// The first of [`DiskParams::issues`], named by the parameter.
    pub fn validate(&self) -> Result<(), ParamError> {
        let Some(issue) = self.issues().into_iter().next() else {
            return Ok(());
        };
        let index = Self::KEYS.iter().position(|k| *k == issue.key).unwrap_or(0);
        let name = Self::NAMES[index];
        Err(match issue.rule {
            Rule::NotFinite { value } => ParamError::NotFinite { name, value },
            Rule::NotPositive { value } => ParamError::NotPositive { name, value },
            Rule::Overflows { .. } => ParamError::Overflow {
                name,
                value: self.to_array()[index],
            },
            Rule::BelowOther { .. } => ParamError::DynamicAboveStatic {
                mu_d: self.mu_d,
                mu_st: self.mu_st,
            },
            // Negative is the only rule left.
            _ => ParamError::Negative {
                name,
                value: self.to_array()[index],
            },
        })
    }

    /// Validates and returns the parameters, so construction and checking read as one step.
    pub fn validated(self) -> Result<Self, ParamError> {
        self.validate().map(|()| self)
    }

    /// The parameters as an array in [`DiskParams::NAMES`] order (the generated models' order).
    pub fn to_array(&self) -> [f64; 7] {
        [
            self.m, self.a, self.g, self.mu_d, self.mu_st, self.mu_a, self.w_z,
        ]
    }

    /// The disk's weight `m g` (N): the scale of the normal force (`N/mg`).
    pub fn weight(&self) -> f64 {
        self.m * self.g
    }

    /// Moment of inertia about any diameter (`e_x`, `e_y`): `m a² / 4`.
    #[allow(non_snake_case)]
    pub fn A(&self) -> f64 {
        0.25 * self.m * self.a * self.a
    }

    /// Moment of inertia about the disk normal `e_z`: `m a² / 2`.
    #[allow(non_snake_case)]
    pub fn C(&self) -> f64 {
        0.5 * self.m * self.a * self.a
    }

    /// Air-force coefficient of one face, `mu_a π a²`.
    #[allow(non_snake_case)]
    pub fn k_F(&self) -> f64 {
        self.mu_a * PI * self.a * self.a
    }

    /// Air-moment coefficient of one face, `mu_a π a⁴ / 4`.
    #[allow(non_snake_case)]
    pub fn k_M(&self) -> f64 {
        0.25 * self.mu_a * PI * self.a.powi(4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_values_are_valid_and_match_the_table() {
        let p = DiskParams::paper();
        assert_eq!(p.validate(), Ok(()));
        // docs/physics.md §11 prints A and C to seven digits.
        assert!((p.A() - 1.546420e-4).abs() < 5e-11);
        assert!((p.C() - 3.092840e-4).abs() < 5e-11);
        assert_eq!(p.k_F(), 0.0);
        assert_eq!(p.k_M(), 0.0);
    }

    #[test]
    fn each_bad_parameter_is_named() {
        let p = DiskParams::paper();
        let cases = [
            (DiskParams { m: 0.0, ..p }, "m"),
            (DiskParams { a: -1.0, ..p }, "a"),
            (DiskParams { a: f64::NAN, ..p }, "a"),
            (
                DiskParams {
                    g: f64::INFINITY,
                    ..p
                },
                "g",
            ),
            (DiskParams { w_z: f64::NAN, ..p }, "w_z"),
            (DiskParams { mu_d: -0.1, ..p }, "mu_d"),
            (DiskParams { mu_a: -1e-3, ..p }, "mu_a"),
        ];
        for (bad, name) in cases {
            let err = bad.validate().unwrap_err();
            assert!(err.to_string().contains(&format!("`{name}`")), "{err}");
        }
        let err = DiskParams { mu_d: 0.3, ..p }.validate().unwrap_err();
        assert_eq!(
            err,
            ParamError::DynamicAboveStatic {
                mu_d: 0.3,
                mu_st: 0.2
            }
        );
    }

    #[test]
    fn air_coefficients_follow_one_face() {
        let p = DiskParams {
            mu_a: 2.0,
            ..DiskParams::paper()
        };
        assert!((p.k_F() - 2.0 * PI * p.a * p.a).abs() < 1e-15);
        assert!((p.k_M() / p.k_F() - p.a * p.a / 4.0).abs() < 1e-15);
    }
}
