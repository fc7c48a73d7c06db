//! `model solve`'s tables: a solution of the library as the trajectory and the events, in
//! CSV (numbers in Rust's shortest round-trip form, so that a reader gets back the exact
//! values) or Parquet, the same columns in both.
//!
//! The trajectory is `t`, for a switched model the `mode` in force, the states, the discrete
//! values in force and the outputs. The events are `event`, `phase`, then the same columns:
//! one row per event with the state just before it (`phase` = `before`), and for an event that reset the state or changed the mode
//! a second row with the state the run went on from (`after`, its `mode` the new one); an
//! event that changed nothing (a smooth model's crossing, a record) has one row, `at`; an
//! accumulation has one row, `at` its extrapolated point, with the state its rule sets. A
//! last row `stop` says how the run ended (`phase` = the reason, as the terminal says it):
//! at the event that stopped it (at the event's one time), else at the trajectory's last
//! point, so a run that failed or was interrupted says so in its files.

use crate::output::cells::{Cell, Table};
use model_interpreted::{EventKind, Solution, Stop};

/// The trajectory's columns: `t`, `mode` for a switched model, then the library's.
fn header(solution: &Solution) -> Vec<String> {
    let mut header = vec![solution.columns[0].clone()];
    if !solution.modes.is_empty() {
        header.push("mode".to_string());
    }
    header.extend(solution.columns[1..].iter().cloned());
    header
}

/// One row as cells: `t`, the mode (if the model has modes), the rest.
fn cells(row: &[f64], mode: Option<&str>) -> Vec<Cell> {
    let mut cells = vec![Cell::Float(row[0])];
    cells.extend(mode.map(Cell::text));
    cells.extend(row[1..].iter().map(|&v| Cell::Float(v)));
    cells
}

/// The trajectory table.
pub fn trajectory(solution: &Solution) -> Table {
    let mut table = Table::new(header(solution));
    let mut row = Vec::new();
    for k in 0..solution.len() {
        solution.trajectory.row_into(k, &mut row);
        table.rows.push(cells(&row, solution.row_mode(k)));
    }
    table
}

/// The events table: `event`, `phase`, then the trajectory's columns; the `stop` row's
/// phase says how the run ended, a failure with `failure` (its message as the terminal
/// says it).
pub fn events(solution: &Solution, failure: Option<&str>) -> Table {
    let mut header = vec!["event".to_string(), "phase".to_string()];
    header.extend(self::header(solution));
    let mut table = Table::new(header);
    let mut push = |event: &str, phase: &str, mode: Option<&str>, row: &[f64]| {
        let mut line = vec![Cell::text(event), Cell::text(phase)];
        line.extend(cells(row, mode));
        table.rows.push(line);
    };
    for event in &solution.events {
        let label = event.label();
        let mode = event.mode.as_deref();
        match (&event.after, event.kind) {
            (Some(after), EventKind::Crossing) => {
                push(&label, "before", mode, &event.row);
                push(&label, "after", event.mode_after.as_deref(), after);
            }
            _ => push(&label, "at", mode, &event.row),
        }
    }
    // A run stopped by an event ends at that event, at its one time; any other at its last
    // row.
    let stopped_by = match &solution.stop {
        Stop::Event { .. } => solution.events.last(),
        _ => None,
    };
    let stop = match failure {
        Some(message) => format!("{}: {message}", solution.stop),
        None => solution.stop.to_string(),
    };
    match (stopped_by, solution.last_row()) {
        (Some(event), _) => push("stop", &stop, event.mode.as_deref(), &event.row),
        (None, Some(last)) => push("stop", &stop, solution.row_mode(solution.len() - 1), &last),
        (None, None) => {}
    }
    table
}
