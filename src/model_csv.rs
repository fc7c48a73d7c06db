//! `model solve`'s tables: a solution of the library written as CSV, numbers in Rust's
//! shortest round-trip form, so that a reader gets back the exact values.

use model_interpreted::Solution;
use std::io::Write;

/// The trajectory: the header `t`, the states, the outputs, then one line per row.
pub fn write_csv(solution: &Solution, mut out: impl Write) -> std::io::Result<()> {
    writeln!(out, "{}", solution.columns.join(","))?;
    for row in &solution.rows {
        write_row(&mut out, None, row)?;
    }
    Ok(())
}

/// The events: `event`, `t`, the states and the outputs; an accumulation is labelled
/// `NAME accumulates`.
pub fn write_events_csv(solution: &Solution, mut out: impl Write) -> std::io::Result<()> {
    writeln!(out, "event,{}", solution.columns.join(","))?;
    for event in &solution.events {
        write_row(&mut out, Some(&event.label()), &event.row)?;
    }
    Ok(())
}

/// One CSV line: the label (if any), then the numbers in Rust's shortest round-trip form.
fn write_row(out: &mut impl Write, label: Option<&str>, row: &[f64]) -> std::io::Result<()> {
    let numbers = row.iter().map(f64::to_string);
    let cells: Vec<String> = label
        .map(str::to_string)
        .into_iter()
        .chain(numbers)
        .collect();
    writeln!(out, "{}", cells.join(","))
}
