//! A table of typed cells, written as CSV or as Parquet from the same rows.
//!
//! The events, the extrema and a sweep's table are built once as rows of [`Cell`]s; the CSV
//! writer prints them (numbers so that they parse back to the same bits, text quoted when it
//! needs it) and the Parquet writer (`output::parquet`) gives each column the type its cells
//! have (`output::files` chooses between them). So the two formats cannot drift apart: same
//! columns, same order, same values.

use equations::Number;
use std::io::{self, Write};

/// Quotes a CSV field when it needs it.
pub fn quoted(text: &str) -> String {
    if text.contains([',', '"', '\n']) {
        format!("\"{}\"", text.replace('"', "\"\"").replace('\n', " "))
    } else {
        text.to_string()
    }
}

/// One value of a table.
#[derive(Clone, Debug, PartialEq)]
pub enum Cell {
    /// No value (an empty CSV field, a Parquet null).
    Null,
    /// An integer (counts, steps).
    Int(i64),
    /// A number.
    Float(f64),
    /// A yes or no.
    Bool(bool),
    /// A word or a sentence.
    Text(String),
}

impl Cell {
    /// A text cell.
    pub fn text(s: impl Into<String>) -> Cell {
        Cell::Text(s.into())
    }

    /// A number, or no value.
    pub fn float(v: Option<f64>) -> Cell {
        v.map_or(Cell::Null, Cell::Float)
    }

    /// A JSON scalar as a cell (integers stay integers, floats keep their bits).
    pub fn from_json(v: Option<&serde_json::Value>) -> Cell {
        match v {
            None | Some(serde_json::Value::Null) => Cell::Null,
            Some(serde_json::Value::Number(n)) => match (n.as_i64(), n.as_f64()) {
                (Some(i), _) => Cell::Int(i),
                (_, Some(f)) => Cell::Float(f),
                _ => Cell::Text(n.to_string()),
            },
            Some(serde_json::Value::Bool(b)) => Cell::Bool(*b),
            Some(serde_json::Value::String(s)) => Cell::text(s.as_str()),
            Some(other) => Cell::Text(other.to_string()),
        }
    }

    /// A TOML value (a sweep's axis value) as a cell; a list is its TOML text.
    pub fn from_toml(v: &toml::Value) -> Cell {
        match v {
            toml::Value::Float(f) => Cell::Float(*f),
            toml::Value::Integer(i) => Cell::Int(*i),
            toml::Value::Boolean(b) => Cell::Bool(*b),
            toml::Value::String(s) => Cell::text(s.as_str()),
            other => Cell::Text(other.to_string()),
        }
    }

    /// The cell as a CSV field.
    pub fn csv(&self) -> String {
        match self {
            Cell::Null => String::new(),
            Cell::Int(i) => i.to_string(),
            Cell::Float(f) => Number(*f).to_string(),
            Cell::Bool(b) => b.to_string(),
            Cell::Text(s) => quoted(s),
        }
    }
}

/// A table: its column names and its rows (each as long as the header).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// The column names, units in the names (`t_s`).
    pub header: Vec<String>,
    /// The rows.
    pub rows: Vec<Vec<Cell>>,
}

impl Table {
    /// An empty table with these columns.
    pub fn new<S: Into<String>>(header: impl IntoIterator<Item = S>) -> Table {
        Table {
            header: header.into_iter().map(Into::into).collect(),
            rows: Vec::new(),
        }
    }

    /// Writes the table as CSV: the header, then one line per row.
    pub fn write_csv<W: Write>(&self, w: &mut W) -> io::Result<()> {
        writeln!(w, "{}", self.header.join(","))?;
        for row in &self.rows {
            let fields: Vec<String> = row.iter().map(Cell::csv).collect();
            writeln!(w, "{}", fields.join(","))?;
        }
        Ok(())
    }

    /// The table as CSV text.
    pub fn csv(&self) -> String {
        let mut out = Vec::new();
        self.write_csv(&mut out).expect("writing to memory");
        String::from_utf8(out).expect("the cells are text")
    }

    /// The cells of column `index`, top to bottom.
    pub fn column(&self, index: usize) -> impl Iterator<Item = &Cell> {
        self.rows.iter().map(move |r| &r[index])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_print_as_the_csv_writers_did() {
        let mut t = Table::new(["t_s", "what", "n", "ok", "x"]);
        t.rows.push(vec![
            Cell::Float(0.1),
            Cell::text("a, b"),
            Cell::Int(-3),
            Cell::Bool(true),
            Cell::Null,
        ]);
        assert_eq!(t.csv(), "t_s,what,n,ok,x\n0.1,\"a, b\",-3,true,\n");
        let json: serde_json::Value = serde_json::json!({"i": 7, "f": 7.0, "s": "x"});
        assert_eq!(Cell::from_json(json.get("i")), Cell::Int(7));
        assert_eq!(Cell::from_json(json.get("f")), Cell::Float(7.0));
        assert_eq!(Cell::from_json(json.get("nothing")), Cell::Null);
        let list = toml::Value::Array(vec![toml::Value::String("rolling".into())]);
        assert_eq!(Cell::from_toml(&list).csv(), "\"[\"\"rolling\"\"]\"");
    }
}
