//! The format of the table files: CSV or Parquet, one choice for a run's trajectory, events
//! and extrema and for a sweep's table (`[output] format` in a scene, `-f/--format` on the
//! command line).
//!
//! CSV is read by anything and compared by eye; Parquet is columnar, typed and compressed,
//! read directly by pandas, Polars, Arrow, DuckDB, Julia and R, and far smaller for a finely
//! sampled run. The tables have the same columns, named with the same units, in both.

use serde::{Deserialize, Serialize};

/// Why a front end without a Parquet writer refuses the format, as the refusal says it
/// (`output::parquet`).
pub const PARQUET_UNAVAILABLE: &str =
    "cannot be written here: this front end installs no Parquet writer (the command line does); use \"csv\"";

/// How the table files are written.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TableFormat {
    /// Comma-separated text, numbers that parse back to the same bits.
    #[default]
    Csv,
    /// Apache Parquet: typed columns, Snappy-compressed.
    Parquet,
}

impl TableFormat {
    /// Both formats.
    pub const ALL: [TableFormat; 2] = [TableFormat::Csv, TableFormat::Parquet];

    /// The name as scenes and flags write it, which is also the files' extension.
    pub fn name(self) -> &'static str {
        match self {
            TableFormat::Csv => "csv",
            TableFormat::Parquet => "parquet",
        }
    }

    /// The file name of table `stem` in this format (`events` -> `events.parquet`).
    pub fn file(self, stem: &str) -> String {
        format!("{stem}.{}", self.name())
    }
}

impl std::fmt::Display for TableFormat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_extensions() {
        assert_eq!(TableFormat::Csv.file("events"), "events.csv");
        assert_eq!(TableFormat::Parquet.file("sweep"), "sweep.parquet");
        assert_eq!(TableFormat::default(), TableFormat::Csv);
    }
}
