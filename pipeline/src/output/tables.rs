//! The trajectory's CSV rows and the events' table.
//!
//! Plain CSV with a header whose every column carries its unit, numbers printed so they
//! parse back to the same bits, so the files can be read by anything and compared exactly;
//! the events' table is also written as Parquet (`output::cells`).

use std::io::{self, Write};

use equations::{DiskParams, Number};

use super::cells::{Cell, Table};
use equations::record::Quantity;
use equations::record::{Sample, Stop};
use equations::TransitionRecord;

/// Formats a number so that it parses back to the same `f64`, compactly: plain notation for
/// moderate magnitudes, exponent notation otherwise (Rust prints the shortest round-trip
/// digits in both). [`Number`] is the same as a `Display`, which a writer formats in place,
/// without a `String` per number (a trajectory has millions of them).
pub fn number(v: f64) -> String {
    Number(v).to_string()
}

/// The header of `trajectory.csv` for `quantities`.
pub fn trajectory_header(quantities: &[Quantity]) -> String {
    let mut h = String::from("t_s,mode");
    for q in quantities {
        h.push(',');
        h.push_str(&q.column());
    }
    h
}

/// Writes one row of `trajectory.csv` (a run streams them as its samples arrive).
pub fn write_trajectory_row<W: Write>(
    w: &mut W,
    quantities: &[Quantity],
    s: &Sample,
    p: &DiskParams,
) -> io::Result<()> {
    write!(w, "{},{}", Number(s.t), s.mode)?;
    for q in quantities {
        write!(w, ",{}", Number(q.value(s, p)))?;
    }
    writeln!(w)
}

/// The header of `events.csv`.
pub const EVENTS_HEADER: &str = "t_s,from,to,trigger,value,value_meaning,slip_direction_rad";

/// The table `events.csv` (or `.parquet`): one row per mode decision, then, when the run's
/// stop is known, one row with it (`to` = `stop`, `trigger` = the reason, `value_meaning` =
/// its details).
pub fn events_table(events: &[TransitionRecord], stop: Option<&Stop>) -> Table {
    let mut table = Table::new(EVENTS_HEADER.split(','));
    for e in events {
        table.rows.push(vec![
            Cell::Float(e.t),
            Cell::text(e.from.name()),
            Cell::text(e.to.name()),
            Cell::text(e.trigger.kind().name()),
            Cell::Float(e.trigger.value()),
            Cell::text(e.trigger.kind().value_meaning()),
            Cell::float(e.slip_direction),
        ]);
    }
    if let Some(stop) = stop {
        table.rows.push(vec![
            Cell::Float(stop.t),
            Cell::text(stop.mode.name()),
            Cell::text("stop"),
            Cell::text(stop.kind.name()),
            Cell::Null,
            Cell::text(stop.detail.as_str()),
            Cell::Null,
        ]);
    }
    table
}

/// Splits one CSV line into its fields, undoing the quoting of the tables' writer (`quoted`).
pub fn split_fields(line: &str) -> Vec<String> {
    let mut fields = vec![String::new()];
    let mut in_quotes = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        let field = fields.last_mut().expect("never empty");
        match (c, in_quotes) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => in_quotes = !in_quotes,
            (',', false) => fields.push(String::new()),
            _ => field.push(c),
        }
    }
    fields
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::cells::quoted;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn numbers_round_trip(v in any::<f64>().prop_filter("finite", |v| v.is_finite())) {
            let text = number(v);
            prop_assert_eq!(text.parse::<f64>().unwrap().to_bits(), v.to_bits(), "{}", text);
        }
    }

    #[test]
    fn compact_forms() {
        assert_eq!(number(0.0), "0");
        assert_eq!(number(0.115), "0.115");
        assert_eq!(number(1e-10), "1e-10");
        assert_eq!(number(-2.5e20), "-2.5e20");
    }

    #[test]
    fn stop_detail_with_commas_is_quoted() {
        let stop = Stop::failed(1.0, equations::Mode::Rolling, "a, b".into());
        let text = events_table(&[], Some(&stop)).csv();
        assert_eq!(
            text.lines().nth(1).unwrap(),
            "1,rolling,stop,error,,\"a, b\","
        );
        assert_eq!(split_fields(text.lines().nth(1).unwrap())[5], "a, b");
        let tricky = "say \"x\", then y";
        assert_eq!(
            split_fields(&format!("1,{}", quoted(tricky))),
            ["1", tricky]
        );
    }
}
