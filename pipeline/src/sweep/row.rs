//! One row per run, and the table `sweep.csv` made of them.
//!
//! A row holds the point's axis values, how the run ended, every scalar key of its summary
//! (as JSON values, so floats keep their bits) and its timing. The table is always rebuilt
//! from the rows in point order, so the table of a sweep does not depend on the order runs
//! finished in, on how many workers ran them, or on how many shards: sharded and merged, it is
//! the same table row for row (the timing columns aside).

use equations::record::StopKind;
use serde::{Deserialize, Serialize};

use super::axes::as_number;
use super::columns::{ERROR_PREFIX, TIMING_COLUMNS};
use super::expand::{axis_number, Definition, PointId};
use crate::output::cells::{Cell, Table};

/// How a run ended, for the sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// The simulation ended by itself (end time, contact lost, ...).
    Completed,
    /// The simulation failed (singular pivot, step-size collapse, forbidden mode, a panic),
    /// or its outputs could not be written.
    Failed,
    /// Stopped after the sweep's `timeout_s`.
    Timeout,
}

impl Status {
    /// The word in `sweep.csv`.
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Completed => "completed",
            Status::Failed => "failed",
            Status::Timeout => "timeout",
        }
    }
}

/// Why one run of a sweep ended: the run's own stop, or what the sweep saw of it. Written
/// as one word (`end_time`, `contact_lost`, `error`, `timeout`, ...).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum PointStop {
    /// The run's stop.
    Run(StopKind),
    /// The sweep's word for a run that ended outside the simulation.
    Sweep(SweepStop),
}

/// How a sweep's run ended outside the simulation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SweepStop {
    /// Stopped after the sweep's `timeout_s`.
    Timeout,
    /// The run's outputs could not be written.
    OutputError,
    /// The run panicked.
    Panic,
}

impl PointStop {
    /// The word in `sweep.csv` (the serde name).
    pub fn name(self) -> &'static str {
        match self {
            PointStop::Run(kind) => kind.name(),
            PointStop::Sweep(SweepStop::Timeout) => "timeout",
            PointStop::Sweep(SweepStop::OutputError) => "output_error",
            PointStop::Sweep(SweepStop::Panic) => "panic",
        }
    }
}

impl std::fmt::Display for PointStop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The result of one run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// The point (its index in the sweep).
    pub point: usize,
    /// The point's axis values (checked against the definition when rows are read back).
    pub values: Vec<toml::Value>,
    /// How it ended.
    pub status: Status,
    /// The stop reason (`end_time`, `contact_lost`, `error`, `timeout`, ...).
    pub stop_reason: PointStop,
    /// Details of the stop (the error's message), may be empty.
    pub stop_detail: String,
    /// Every scalar key of the run's summary (empty when the run produced none).
    pub summary: serde_json::Map<String, serde_json::Value>,
    /// Wall time of the whole run, outputs included (s).
    pub wall_s: f64,
    /// CPU time of the process during the run (s); only with one worker, where it is the
    /// run's own.
    pub cpu_s: Option<f64>,
}

impl Row {
    /// The run's name (`r000042`).
    pub fn id(&self) -> String {
        PointId(self.point).name()
    }

    /// The row without its timing, for comparing two runs of the same point.
    pub fn untimed(&self) -> Row {
        let mut r = self.clone();
        r.wall_s = 0.0;
        r.cpu_s = None;
        for k in TIMING_COLUMNS {
            r.summary.remove(*k);
        }
        r
    }
}

/// The reference row of the error columns: the completed row with the smallest value of the
/// `against` axis, the first such point on a tie.
pub fn reference<'r>(d: &Definition, rows: impl IntoIterator<Item = &'r Row>) -> Option<&'r Row> {
    let against = &d.file.error.as_ref()?.against;
    rows.into_iter()
        .filter(|r| r.status == Status::Completed)
        .filter_map(|r| axis_number(d, against, &r.values).map(|v| (v, r)))
        .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.point.cmp(&b.1.point)))
        .map(|(_, r)| r)
}

/// `|v - v_ref| / |v_ref|` (or `|v - v_ref|` when `v_ref` is 0) of summary key `key`.
pub fn relative_error(row: &Row, reference: &Row, key: &str) -> Option<f64> {
    let get = |r: &Row| r.summary.get(key).and_then(serde_json::Value::as_f64);
    let (v, v_ref) = (get(row)?, get(reference)?);
    let diff = (v - v_ref).abs();
    Some(if v_ref == 0.0 {
        diff
    } else {
        diff / v_ref.abs()
    })
}

/// The value of column `key` (a summary key, a timing or an error column) in `row`.
pub fn value(row: &Row, reference: Option<&Row>, key: &str) -> Option<f64> {
    match key {
        "wall_s" => return Some(row.wall_s),
        "cpu_s" => return row.cpu_s,
        _ => {}
    }
    match key.strip_prefix(ERROR_PREFIX) {
        Some(k) if !row.summary.contains_key(key) => relative_error(row, reference?, k),
        _ => row.summary.get(key).and_then(serde_json::Value::as_f64),
    }
}

/// The header of `sweep.csv`.
pub fn header(d: &Definition) -> Vec<String> {
    let mut h = vec!["run".to_string()];
    h.extend(d.axes.iter().map(|a| a.key.clone()));
    h.extend(["status", "stop_reason"].map(String::from));
    h.extend(d.columns.iter().cloned());
    if let Some(e) = &d.file.error {
        h.extend(e.keys.iter().map(|k| format!("{ERROR_PREFIX}{k}")));
    }
    h.extend(["stop_detail", "wall_s", "cpu_s"].map(String::from));
    h
}

/// The sweep's table (`sweep.csv` or `sweep.parquet`): the header, then one row per run in
/// point order.
pub fn table(d: &Definition, rows: &[Row]) -> Table {
    let mut rows: Vec<&Row> = rows.iter().collect();
    rows.sort_by_key(|r| r.point);
    let reference = reference(d, rows.iter().copied());
    let mut table = Table::new(header(d));
    for r in rows {
        let mut f = vec![Cell::Text(r.id())];
        f.extend(r.values.iter().map(Cell::from_toml));
        f.push(Cell::text(r.status.as_str()));
        f.push(Cell::text(r.stop_reason.name()));
        f.extend(d.columns.iter().map(|k| Cell::from_json(r.summary.get(k))));
        if let Some(e) = &d.file.error {
            f.extend(
                e.keys
                    .iter()
                    .map(|k| Cell::float(reference.and_then(|re| relative_error(r, re, k)))),
            );
        }
        f.push(Cell::text(r.stop_detail.as_str()));
        f.push(Cell::Float(r.wall_s));
        f.push(Cell::float(r.cpu_s));
        table.rows.push(f);
    }
    table
}

/// Whether an axis value of a row is the one of the definition's point (a row read back
/// from disk must belong to this sweep).
pub fn belongs(d: &Definition, row: &Row) -> bool {
    d.points.get(row.point).is_some_and(|p| {
        p.len() == row.values.len()
            && p.iter()
                .zip(&row.values)
                .all(|(a, b)| match (as_number(a), as_number(b)) {
                    (Some(x), Some(y)) => x.to_bits() == y.to_bits(),
                    _ => a == b,
                })
    })
}
