//! A broken rule of a scene, named by the key it is about.
//!
//! Validation collects every issue of a scene before failing (one run of the command shows
//! all the mistakes), and each issue carries the numbers that explain it.

use std::fmt;

use crate::output::tables::number;

/// One broken rule, about one key (`table.key`).
#[derive(Clone, Debug, PartialEq)]
pub struct Issue {
    /// The key, as `table.key`.
    pub key: String,
    /// The rule it breaks.
    pub rule: Rule,
}

/// The rules a scene value can break.
#[derive(Clone, Debug, PartialEq)]
pub enum Rule {
    /// The key is required here.
    Missing,
    /// The key is required because another key is given.
    RequiredWith {
        /// The other key.
        other: &'static str,
    },
    /// NaN or infinite.
    NotFinite {
        /// The value.
        value: f64,
    },
    /// Must be > 0.
    NotPositive {
        /// The value.
        value: f64,
    },
    /// Must be >= 0.
    Negative {
        /// The value.
        value: f64,
    },
    /// Must lie in an interval.
    OutOfRange {
        /// The value.
        value: f64,
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
        /// Whether the bounds themselves are excluded.
        open: bool,
    },
    /// Must not be below another key's value.
    BelowOther {
        /// The value.
        value: f64,
        /// The other key.
        other: &'static str,
        /// The other key's value.
        other_value: f64,
    },
    /// An initial value violates a constraint of the disk.
    ConstraintViolated {
        /// The constraint, e.g. `Z = a sin(theta)`.
        constraint: &'static str,
        /// The value the constraint requires.
        required: f64,
        /// The value given.
        given: f64,
        /// The unit of both.
        unit: &'static str,
    },
    /// Two keys that cannot be given together.
    Conflicts {
        /// The other key.
        other: &'static str,
    },
    /// A name that is not a known one.
    Unknown {
        /// The name.
        name: String,
        /// The accepted names, comma separated.
        expected: String,
    },
    /// A list entry given twice.
    Duplicate {
        /// The entry.
        name: String,
    },
    /// A list that must not be empty.
    Empty,
    /// The initial state needs a mode the scene does not allow.
    ModeNotAllowed {
        /// The mode needed.
        mode: &'static str,
        /// Why it is needed.
        because: String,
    },
    /// The run would record more samples than is sensible.
    TooManySamples {
        /// The number of samples requested.
        samples: f64,
        /// The limit.
        limit: f64,
        /// `run.t_end` (s).
        t_end: f64,
        /// `run.sample_rate` (1/s).
        sample_rate: f64,
    },
}

impl fmt::Display for Issue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "`{}`: ", self.key)?;
        match &self.rule {
            Rule::Missing => write!(f, "is required"),
            Rule::RequiredWith { other } => write!(f, "is required when `{other}` is given"),
            Rule::NotFinite { value } => write!(f, "must be a finite number, got {value}"),
            Rule::NotPositive { value } => write!(f, "must be > 0, got {}", number(*value)),
            Rule::Negative { value } => write!(f, "must be >= 0, got {}", number(*value)),
            Rule::OutOfRange {
                value,
                min,
                max,
                open,
            } => {
                let (l, r) = if *open { ('(', ')') } else { ('[', ']') };
                write!(f, "must lie in {l}{min:e}, {max:e}{r}, got {value:e}")
            }
            Rule::BelowOther {
                value,
                other,
                other_value,
            } => write!(
                f,
                "must not be below `{other}` = {}, got {}",
                number(*other_value),
                number(*value)
            ),
            Rule::ConstraintViolated {
                constraint,
                required,
                given,
                unit,
            } => write!(
                f,
                "violates the constraint {constraint} by {:.3e} {unit} (given {given}, required {required}); omit it to have it computed",
                given - required
            ),
            Rule::Conflicts { other } => {
                write!(f, "cannot be given together with `{other}`")
            }
            Rule::Unknown { name, expected } => {
                write!(f, "unknown name `{name}` (expected one of: {expected})")
            }
            Rule::Duplicate { name } => write!(f, "`{name}` is listed twice"),
            Rule::Empty => write!(f, "must not be empty"),
            Rule::ModeNotAllowed { mode, because } => write!(
                f,
                "the initial state needs mode `{mode}` ({because}), which `modes.allowed` does not list"
            ),
            Rule::TooManySamples {
                samples,
                limit,
                t_end,
                sample_rate,
            } => write!(
                f,
                "would record {samples:.3e} samples ({} s × {} per s), more than {limit:.0e}: \
                 shorten `run.t_end` to at most {} s (`--t-end`), or lower `run.sample_rate` \
                 to at most {} per s (`--set run.sample_rate=...`)",
                number(*t_end),
                number(*sample_rate),
                number(limit / sample_rate),
                number(limit / t_end),
            ),
        }
    }
}
