//! The values of one axis: explicit, evenly or geometrically spaced, or seeded random.
//!
//! Random values come from SplitMix64 written out here, not from a crate whose algorithm may
//! change between versions: a seed must give the same sweep on every machine and in every
//! release, or resuming and merging shards made by different builds would mix points.

use super::spec::{AxisSpec, RandomSpec, Span};

/// Why an axis cannot make its values: the key in the sweep file and what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct AxisIssue {
    /// The key's path in the sweep file (`axis[0].linspace.num`).
    pub key: String,
    /// What is wrong.
    pub message: String,
}

/// An axis with its values made.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct AxisValues {
    /// The scene key.
    pub key: String,
    /// Its values, in order.
    pub values: Vec<toml::Value>,
}

impl AxisValues {
    /// The values as numbers, when they all are.
    pub fn numbers(&self) -> Option<Vec<f64>> {
        self.values.iter().map(as_number).collect()
    }
}

/// A TOML value as a number, when it is one.
pub fn as_number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(f) => Some(*f),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// Most values one axis may have.
pub const MAX_VALUES: u32 = 100_000;

/// Makes the values of axis number `index`.
pub fn values(index: usize, spec: &AxisSpec) -> Result<AxisValues, AxisIssue> {
    let at = |field: &str| format!("axis[{index}].{field}");
    let issue = |field: &str, message: String| AxisIssue {
        key: at(field),
        message,
    };
    let given: Vec<&str> = [
        ("values", spec.values.is_some()),
        ("linspace", spec.linspace.is_some()),
        ("logspace", spec.logspace.is_some()),
        ("random", spec.random.is_some()),
    ]
    .iter()
    .filter(|(_, g)| *g)
    .map(|(n, _)| *n)
    .collect();
    if given.len() != 1 {
        return Err(issue(
            "key",
            format!(
                "axis `{}` needs exactly one of `values`, `linspace`, `logspace`, `random`; it has {}",
                spec.key,
                if given.is_empty() {
                    "none".to_string()
                } else {
                    given.join(", ")
                }
            ),
        ));
    }
    let numbers = |v: Vec<f64>| v.into_iter().map(toml::Value::Float).collect();
    let values = if let Some(v) = &spec.values {
        if v.is_empty() {
            return Err(issue("values", "must not be empty".into()));
        }
        if let Some(bad) = v
            .iter()
            .find(|x| matches!(x, toml::Value::Table(_) | toml::Value::Datetime(_)))
        {
            return Err(issue(
                "values",
                format!("`{bad}` is not a number, a word, a boolean or a list"),
            ));
        }
        v.clone()
    } else if let Some(s) = &spec.linspace {
        check_span(s, false).map_err(|(f, m)| issue(&format!("linspace.{f}"), m))?;
        numbers(spaced(s, |a, b, f| a + (b - a) * f))
    } else if let Some(s) = &spec.logspace {
        check_span(s, true).map_err(|(f, m)| issue(&format!("logspace.{f}"), m))?;
        numbers(spaced(s, |a, b, f| a * (b / a).powf(f)))
    } else if let Some(r) = &spec.random {
        check_random(r).map_err(|(f, m)| issue(&format!("random.{f}"), m))?;
        numbers(random(r))
    } else {
        unreachable!("exactly one generator is given")
    };
    Ok(AxisValues {
        key: spec.key.clone(),
        values,
    })
}

type FieldIssue = (&'static str, String);

fn check_count(num: u32) -> Result<(), FieldIssue> {
    if num == 0 || num > MAX_VALUES {
        return Err(("num", format!("must lie in [1, {MAX_VALUES}], got {num}")));
    }
    Ok(())
}

fn check_bounds(
    lo: (&'static str, f64),
    hi: (&'static str, f64),
    log: bool,
) -> Result<(), FieldIssue> {
    for (name, v) in [lo, hi] {
        if !v.is_finite() {
            return Err((name, format!("must be a finite number, got {v}")));
        }
        if log && v <= 0.0 {
            return Err((name, format!("must be > 0 on a logarithmic scale, got {v}")));
        }
    }
    Ok(())
}

fn check_span(s: &Span, log: bool) -> Result<(), FieldIssue> {
    check_count(s.num)?;
    check_bounds(("from", s.from), ("to", s.to), log)
}

fn check_random(r: &RandomSpec) -> Result<(), FieldIssue> {
    check_count(r.num)?;
    check_bounds(("min", r.min), ("max", r.max), r.log)?;
    if r.max < r.min {
        return Err((
            "max",
            format!("must not be below `min` = {}, got {}", r.min, r.max),
        ));
    }
    Ok(())
}

/// `num` values from `from` to `to` (both exact) placed by `at(from, to, fraction)`, the
/// inner ones rounded to 15 significant digits so that they print as one would write them
/// (`1e-6`, not `1.0000000000000002e-6`).
fn spaced(s: &Span, at: fn(f64, f64, f64) -> f64) -> Vec<f64> {
    let n = s.num as usize;
    (0..n)
        .map(|i| match i {
            0 => s.from,
            i if i + 1 == n => s.to,
            i => round15(at(s.from, s.to, i as f64 / (n - 1) as f64)),
        })
        .collect()
}

/// `v` rounded to 15 significant digits.
fn round15(v: f64) -> f64 {
    format!("{v:.14e}").parse().unwrap_or(v)
}

/// SplitMix64 (Steele, Lea & Flood 2014): a tiny generator whose output is fixed by its seed.
#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator started at `seed`.
    pub fn new(seed: u64) -> Self {
        SplitMix64(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A uniform number in [0, 1) with 53 random bits.
    pub fn next_unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn random(r: &RandomSpec) -> Vec<f64> {
    let mut rng = SplitMix64::new(r.seed);
    (0..r.num)
        .map(|_| {
            let u = rng.next_unit();
            if r.log {
                (r.min.ln() + (r.max.ln() - r.min.ln()) * u)
                    .exp()
                    .clamp(r.min, r.max)
            } else {
                (r.min + (r.max - r.min) * u).clamp(r.min, r.max)
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(text: &str) -> AxisSpec {
        toml::from_str(&format!("key = \"friction.mu_d\"\n{text}")).unwrap()
    }

    fn floats(a: &AxisValues) -> Vec<f64> {
        a.numbers().unwrap()
    }

    #[test]
    fn spans_hit_their_ends_exactly() {
        let lin = values(0, &axis("linspace = { from = 0.1, to = 0.3, num = 3 }")).unwrap();
        assert_eq!(floats(&lin), [0.1, 0.2, 0.3]);
        let log = values(0, &axis("logspace = { from = 1e-3, to = 1e-9, num = 4 }")).unwrap();
        let v = floats(&log);
        assert_eq!(v, [1e-3, 1e-5, 1e-7, 1e-9]);
    }

    #[test]
    fn random_values_are_fixed_by_the_seed_and_in_range() {
        let a = values(
            0,
            &axis("random = { min = 0.1, max = 0.2, num = 50, seed = 7 }"),
        )
        .unwrap();
        let b = values(
            0,
            &axis("random = { min = 0.1, max = 0.2, num = 50, seed = 7 }"),
        )
        .unwrap();
        let c = values(
            0,
            &axis("random = { min = 0.1, max = 0.2, num = 50, seed = 8 }"),
        )
        .unwrap();
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert!(floats(&a).iter().all(|v| (0.1..=0.2).contains(v)));
        // SplitMix64's published first output for seed 0 (a fixed algorithm, not a crate's).
        assert_eq!(SplitMix64::new(0).next_u64(), 0xe220_a839_7b1d_cdaf);
    }

    #[test]
    fn bad_axes_name_the_field_and_value() {
        let cases = [
            (
                "linspace = { from = 0.1, to = 0.2, num = 0 }",
                "axis[0].linspace.num",
                "got 0",
            ),
            (
                "logspace = { from = 0.0, to = 1.0, num = 3 }",
                "axis[0].logspace.from",
                "got 0",
            ),
            (
                "random = { min = 0.3, max = 0.2, num = 3, seed = 1 }",
                "axis[0].random.max",
                "got 0.2",
            ),
            ("values = []", "axis[0].values", "empty"),
            ("", "axis[0].key", "none"),
            (
                "values = [1.0]\nlinspace = { from = 0.1, to = 0.2, num = 2 }",
                "axis[0].key",
                "values, linspace",
            ),
        ];
        for (text, key, word) in cases {
            let e = values(0, &axis(text)).unwrap_err();
            assert_eq!(e.key, key, "{text}");
            assert!(e.message.contains(word), "{text}: {}", e.message);
        }
    }
}
