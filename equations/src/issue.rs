//! A broken rule of a scene or of a run's settings, named by the key it is about.
//!
//! One type for every check, whoever asks: a scene being loaded and [`crate::simulate`] being
//! called directly are held to the same rules and report them the same way. Validation
//! collects every issue before failing (one run of the command shows all the mistakes), and
//! each issue carries the numbers that explain it.

use std::fmt;

/// A number as scenes, messages and tables print it: plainly between 1e-4 and 1e15 (and 0),
/// in scientific notation otherwise; both parse back to the same `f64` (Rust prints the
/// shortest round-trip digits).
#[derive(Clone, Copy, Debug)]
pub struct Number(pub f64);

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        if v == 0.0 || (1e-4..1e15).contains(&v.abs()) {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}

fn number(v: f64) -> Number {
    Number(v)
}

/// One broken rule, about one key (`table.key`).
#[derive(Clone, Debug, PartialEq)]
pub struct Issue {
    /// The key, as `table.key`.
    pub key: String,
    /// The rule it breaks.
    pub rule: Rule,
}

impl Issue {
    /// The issue `rule` about `key`.
    pub fn new(key: impl Into<String>, rule: Rule) -> Self {
        Issue {
            key: key.into(),
            rule,
        }
    }
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
        /// The mode needed (its name, `rolling` or `sliding`).
        mode: &'static str,
        /// Why it is needed.
        because: String,
    },
    /// A setting that cannot go with another one.
    Incompatible {
        /// The value, as written.
        value: String,
        /// Why it cannot be used here.
        reason: &'static str,
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
    /// Finite values whose products overflow.
    Overflows {
        /// The product that overflows.
        what: &'static str,
    },
    /// A value completed from finite given ones is not finite: their products overflow.
    CompletesNonFinite {
        /// The completed value.
        value: f64,
    },
}

impl fmt::Display for Issue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "`{}`: ", self.key)?;
        match &self.rule {
            Rule::Missing => write!(f, "is required"),
            Rule::RequiredWith { other } => write!(f, "is required when `{other}` is given"),
            Rule::NotFinite { value } => write!(f, "must be a finite number, got {value}"),
            Rule::Overflows { what } => write!(
                f,
                "is too large: {what} overflows (is not a finite number)"
            ),
            Rule::CompletesNonFinite { value } => write!(
                f,
                "completes to {value} from the radius `disk.a` and the given angles and rates \
                 (their products overflow): give smaller values"
            ),
            Rule::NotPositive { value } => write!(f, "must be > 0, got {}", number(*value)),
            Rule::Negative { value } => write!(f, "must be >= 0, got {}", number(*value)),
            Rule::OutOfRange {
                value,
                min,
                max,
                open,
            } => {
                let (l, r) = if *open { ('(', ')') } else { ('[', ']') };
                write!(
                    f,
                    "must lie in {l}{}, {}{r}, got {}",
                    number(*min),
                    number(*max),
                    number(*value)
                )
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
            Rule::Incompatible { value, reason } => write!(f, "`{value}` {reason}"),
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
                "would record {} samples ({} s × {} per s), more than the sample limit {limit:.0e}: \
                 shorten `run.t_end` to at most {} s (`--t-end`), or lower `run.sample_rate` \
                 to at most {} per s (`--set run.sample_rate=...`)",
                if samples.is_finite() {
                    format!("{samples:.3e}")
                } else {
                    // The product overflowed.
                    format!("over {:.3e}", f64::MAX)
                },
                number(*t_end),
                number(*sample_rate),
                number(limit / sample_rate),
                number(limit / t_end),
            ),
        }
    }
}

/// Collects the issues of one validation; the helpers check one value each and report whether
/// it passed, so a later rule that needs the value usable can skip it.
#[derive(Debug, Default)]
pub(crate) struct Checks {
    /// Every issue found so far, in the order of the checks.
    pub issues: Vec<Issue>,
}

impl Checks {
    /// Records `rule` about `key`.
    pub fn push(&mut self, key: &str, rule: Rule) {
        self.issues.push(Issue::new(key, rule));
    }

    /// `value` must be finite.
    pub fn finite(&mut self, key: &str, value: f64) -> bool {
        let ok = value.is_finite();
        if !ok {
            self.push(key, Rule::NotFinite { value });
        }
        ok
    }

    /// `value` must be finite and > 0.
    pub fn positive(&mut self, key: &str, value: f64) -> bool {
        let ok = self.finite(key, value) && value > 0.0;
        if value.is_finite() && !ok {
            self.push(key, Rule::NotPositive { value });
        }
        ok
    }

    /// `value` must be finite and >= 0.
    pub fn non_negative(&mut self, key: &str, value: f64) -> bool {
        let ok = self.finite(key, value) && value >= 0.0;
        if value.is_finite() && !ok {
            self.push(key, Rule::Negative { value });
        }
        ok
    }

    /// `value` must be finite and lie in `[min, max]` (`(min, max)` when `open`).
    pub fn in_range(&mut self, key: &str, value: f64, min: f64, max: f64, open: bool) -> bool {
        let inside = if open {
            value > min && value < max
        } else {
            (min..=max).contains(&value)
        };
        let ok = self.finite(key, value) && inside;
        if value.is_finite() && !ok {
            self.push(
                key,
                Rule::OutOfRange {
                    value,
                    min,
                    max,
                    open,
                },
            );
        }
        ok
    }
}
