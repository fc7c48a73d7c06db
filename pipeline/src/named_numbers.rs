//! Named numbers on the command line, read so that every rejection names the key.
//!
//! Every subcommand takes states and parameters the same way, as repeated `NAME=VALUE` items
//! (`--state theta=0.5 --set m=1`, [`parse_assignments`]). `eval` once took a JSON object
//! (`--state '{"theta": 0.5}'`); an item that is such an object is still read, item by item
//! under the same rules, so old scripts keep working ([`is_json_object`] lets the command
//! say the spelling is deprecated). Parsing straight into
//! `HashMap<String, f64>` would lose the key on a bad value (serde reports a column, not a
//! name), silently keep the last of two duplicate keys, and turn `1e400` into a bare range
//! error. Here each value is kept raw until its key is known, then parsed on its own.

use std::collections::BTreeMap;
use std::fmt;

use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde_json::value::RawValue;

/// Why an object of named numbers was rejected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NamedNumbersError {
    /// The text is not a JSON object (syntax error, or another JSON type).
    #[error("{what}: not a JSON object of numbers ({reason})")]
    NotAnObject {
        /// Which argument (e.g. `--state`).
        what: String,
        /// The parser's explanation.
        reason: String,
    },
    /// A key appears twice.
    #[error("{what}: key `{key}` appears twice")]
    Duplicate {
        /// Which argument.
        what: String,
        /// The repeated key.
        key: String,
    },
    /// A key is not one of the accepted names.
    #[error("{what}: unknown key `{key}` (expected one of: {expected})")]
    UnknownKey {
        /// Which argument.
        what: String,
        /// The offending key.
        key: String,
        /// The accepted names, comma separated.
        expected: String,
    },
    /// A value is not a JSON number.
    #[error("{what}: key `{key}` must be a number, got {found}")]
    NotANumber {
        /// Which argument.
        what: String,
        /// The key whose value is wrong.
        key: String,
        /// The value as written (shortened).
        found: String,
    },
    /// An item is neither `NAME=VALUE` nor a JSON object.
    #[error(transparent)]
    NotAnAssignment(#[from] NotAnAssignment),
    /// A value is a number too large for `f64`.
    #[error("{what}: key `{key}` = {found} is not a finite number")]
    NotFinite {
        /// Which argument.
        what: String,
        /// The key whose value is wrong.
        key: String,
        /// The value as written (shortened).
        found: String,
    },
}

/// An item that is neither `NAME=VALUE` nor a JSON object.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{what} `{text}`: expected NAME=VALUE")]
pub struct NotAnAssignment {
    /// Which argument.
    pub what: String,
    /// The item as given.
    pub text: String,
}

impl NamedNumbersError {
    /// The key this error is about, if it is about one.
    pub fn key(&self) -> Option<&str> {
        match self {
            NamedNumbersError::NotAnObject { .. } | NamedNumbersError::NotAnAssignment(_) => None,
            NamedNumbersError::Duplicate { key, .. }
            | NamedNumbersError::UnknownKey { key, .. }
            | NamedNumbersError::NotANumber { key, .. }
            | NamedNumbersError::NotFinite { key, .. } => Some(key),
        }
    }
}

/// Parses `text` as a JSON object whose keys are among `allowed` and whose values are finite
/// numbers. `what` names the argument in error messages.
pub fn parse_named_numbers(
    what: &str,
    text: &str,
    allowed: &[&str],
) -> Result<BTreeMap<String, f64>, NamedNumbersError> {
    let entries = parse_entries(what, text)?;
    let mut out = BTreeMap::new();
    for (key, raw) in entries {
        if out.contains_key(&key) {
            return Err(NamedNumbersError::Duplicate {
                what: what.to_string(),
                key,
            });
        }
        if !allowed.contains(&key.as_str()) {
            return Err(NamedNumbersError::UnknownKey {
                what: what.to_string(),
                key,
                expected: allowed.join(", "),
            });
        }
        let value = parse_number(what, &key, raw.get())?;
        out.insert(key, value);
    }
    Ok(out)
}

/// Whether a `--state`/`--set` item is written as a JSON object (the old spelling of `eval`).
pub fn is_json_object(item: &str) -> bool {
    item.trim_start().starts_with('{')
}

/// Parses repeated `NAME=VALUE` items (or JSON objects, the old spelling) whose names are
/// among `allowed` and whose values are finite numbers; a name given twice, in one item or
/// across items, is an error. `what` names the flag in error messages.
pub fn parse_assignments(
    what: &str,
    items: &[String],
    allowed: &[&str],
) -> Result<BTreeMap<String, f64>, NamedNumbersError> {
    let mut out = BTreeMap::new();
    for item in items {
        let entries: Vec<(String, f64)> = if is_json_object(item) {
            parse_named_numbers(what, item, allowed)?
                .into_iter()
                .collect()
        } else {
            let (key, raw) = item.split_once('=').ok_or_else(|| NotAnAssignment {
                what: what.to_string(),
                text: item.clone(),
            })?;
            let key = key.trim().to_string();
            if !allowed.contains(&key.as_str()) {
                return Err(NamedNumbersError::UnknownKey {
                    what: what.to_string(),
                    key,
                    expected: allowed.join(", "),
                });
            }
            let value = parse_plain_number(what, &key, raw)?;
            vec![(key, value)]
        };
        for (key, value) in entries {
            if out.insert(key.clone(), value).is_some() {
                return Err(NamedNumbersError::Duplicate {
                    what: what.to_string(),
                    key,
                });
            }
        }
    }
    Ok(out)
}

/// A number as Rust reads it (`.5`, `1e-3`, `-2`); NaN and infinities are not finite.
fn parse_plain_number(what: &str, key: &str, raw: &str) -> Result<f64, NamedNumbersError> {
    let raw = raw.trim();
    match raw.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(NamedNumbersError::NotFinite {
            what: what.to_string(),
            key: key.to_string(),
            found: shorten(raw),
        }),
        Err(_) => Err(NamedNumbersError::NotANumber {
            what: what.to_string(),
            key: key.to_string(),
            found: shorten(raw),
        }),
    }
}

fn shorten(text: &str) -> String {
    const MAX: usize = 40;
    if text.chars().count() <= MAX {
        text.to_string()
    } else {
        let head: String = text.chars().take(MAX).collect();
        format!("{head}...")
    }
}

fn parse_number(what: &str, key: &str, raw: &str) -> Result<f64, NamedNumbersError> {
    let raw = raw.trim();
    let is_number = raw.starts_with('-') || raw.starts_with(|c: char| c.is_ascii_digit());
    if !is_number {
        return Err(NamedNumbersError::NotANumber {
            what: what.to_string(),
            key: key.to_string(),
            found: shorten(raw),
        });
    }
    // JSON number syntax was checked by the raw parse; Rust's parser is exact (round-trips).
    match raw.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(NamedNumbersError::NotFinite {
            what: what.to_string(),
            key: key.to_string(),
            found: shorten(raw),
        }),
    }
}

type Entries = Vec<(String, Box<RawValue>)>;

fn parse_entries(what: &str, text: &str) -> Result<Entries, NamedNumbersError> {
    struct EntriesVisitor;
    impl<'de> Visitor<'de> for EntriesVisitor {
        type Value = Entries;
        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            f.write_str("a JSON object")
        }
        fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Entries, A::Error> {
            let mut entries = Vec::new();
            while let Some(key) = map.next_key::<String>()? {
                let value: Box<RawValue> = map.next_value()?;
                entries.push((key, value));
            }
            Ok(entries)
        }
    }
    struct EntriesSeed;
    impl<'de> de::DeserializeSeed<'de> for EntriesSeed {
        type Value = Entries;
        fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Entries, D::Error> {
            d.deserialize_map(EntriesVisitor)
        }
    }
    let mut de = serde_json::Deserializer::from_str(text);
    let result = de::DeserializeSeed::deserialize(EntriesSeed, &mut de).and_then(|v| {
        de.end()?;
        Ok(v)
    });
    result.map_err(|e| NamedNumbersError::NotAnObject {
        what: what.to_string(),
        reason: e.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const NAMES: &[&str] = &["theta", "Omega_x"];

    fn parse(text: &str) -> Result<BTreeMap<String, f64>, NamedNumbersError> {
        parse_named_numbers("--state", text, NAMES)
    }

    #[test]
    fn accepts_numbers_and_empty_object() {
        let m = parse(r#"{"theta": 0.5, "Omega_x": -1e-3}"#).unwrap();
        assert_eq!(m["theta"], 0.5);
        assert_eq!(m["Omega_x"], -1e-3);
        assert!(parse("{}").unwrap().is_empty());
    }

    #[test]
    fn parses_exactly() {
        let text = r#"{"theta": 0.57079632679489656}"#;
        assert_eq!(
            parse(text).unwrap()["theta"],
            std::f64::consts::FRAC_PI_2 - 1.0
        );
    }

    #[test]
    fn rejections_name_the_key() {
        let cases = [
            (r#"{"theta": "0.5"}"#, "theta"),
            (r#"{"theta": null}"#, "theta"),
            (r#"{"theta": [1]}"#, "theta"),
            (r#"{"theta": true}"#, "theta"),
            (r#"{"theta": 1e400}"#, "theta"),
            (r#"{"Omega_x": -1e400}"#, "Omega_x"),
            (r#"{"thet": 1}"#, "thet"),
            (r#"{"theta": 1, "theta": 2}"#, "theta"),
        ];
        for (text, key) in cases {
            let err = parse(text).unwrap_err();
            assert_eq!(err.key(), Some(key), "{text}: {err}");
            assert!(err.to_string().contains(key), "{err}");
        }
    }

    fn assign(items: &[&str]) -> Result<BTreeMap<String, f64>, NamedNumbersError> {
        let items: Vec<String> = items.iter().map(|s| s.to_string()).collect();
        parse_assignments("--state", &items, NAMES)
    }

    #[test]
    fn assignments_and_the_old_json_spelling_agree() {
        let new = assign(&["theta=0.57079632679489656", "Omega_x = -1e-3"]).unwrap();
        let old = assign(&[r#"{"theta": 0.57079632679489656, "Omega_x": -1e-3}"#]).unwrap();
        assert_eq!(new, old);
        assert_eq!(new["theta"], std::f64::consts::FRAC_PI_2 - 1.0);
        assert!(assign(&[]).unwrap().is_empty());
    }

    #[test]
    fn assignment_rejections_name_the_key() {
        let cases = [
            (&["theta=x"][..], Some("theta")),
            (&["theta=1e400"][..], Some("theta")),
            (&["theta=nan"][..], Some("theta")),
            (&["thet=1"][..], Some("thet")),
            (&["theta=1", r#"{"theta": 2}"#][..], Some("theta")),
            (&["theta"][..], None),
        ];
        for (items, key) in cases {
            let err = assign(items).unwrap_err();
            assert_eq!(err.key(), key, "{items:?}: {err}");
            assert!(err.to_string().contains("--state"), "{err}");
        }
    }

    #[test]
    fn non_objects_are_rejected() {
        for text in ["[]", "1", "", "{", r#"{"theta": NaN}"#, r#"{"theta": 1} x"#] {
            assert!(
                matches!(parse(text), Err(NamedNumbersError::NotAnObject { .. })),
                "{text}"
            );
        }
    }
}
