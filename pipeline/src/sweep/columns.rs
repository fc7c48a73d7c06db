//! The columns every sweep table has, whatever its axes: which summary keys become columns,
//! the error columns' prefix, the timing columns. Both the plan (which keys a sweep may keep
//! or draw) and the rows (what a table holds) read them.

use crate::analysis::summary::Summary;
use crate::record::RunData;

/// Prefix of the error columns (`err_transitions`).
pub const ERROR_PREFIX: &str = "err_";
/// Summary keys that have columns of their own in every table, so not repeated (the row's
/// own `stop_detail` says why a timed-out run stopped, which its summary cannot).
pub const FIXED_COLUMNS: &[&str] = &["stop_reason", "stop_detail", "wall_s", "cpu_s"];
/// Columns that measure time: they differ between two runs of the same point.
pub const TIMING_COLUMNS: &[&str] = &["wall_s", "cpu_s"];

/// The scalar entries of `summary`'s JSON form.
pub fn scalar_entries(summary: &Summary) -> serde_json::Map<String, serde_json::Value> {
    match serde_json::to_value(summary) {
        Ok(serde_json::Value::Object(map)) => map
            .into_iter()
            .filter(|(_, v)| !v.is_object() && !v.is_array())
            .collect(),
        _ => serde_json::Map::new(),
    }
}

/// The summary's scalar keys: those of the printed comparison in its order, then the rest
/// by name.
pub fn summary_keys() -> Vec<String> {
    let empty = Summary::of("", &RunData::default(), &equations::DiskParams::paper());
    let scalar = scalar_entries(&empty);
    let mut keys: Vec<String> = empty
        .comparison()
        .iter()
        .map(|r| r.key.to_string())
        .filter(|k| scalar.contains_key(k))
        .collect();
    let rest: Vec<String> = scalar
        .keys()
        .filter(|k| !keys.contains(k))
        .cloned()
        .collect();
    keys.extend(rest);
    keys
}
