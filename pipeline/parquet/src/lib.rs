//! Parquet files, written with the Apache Arrow crates, and read back: the writer the
//! `eulerdisk` command line installs into the library ([`install`]; the library's
//! `output::parquet` says why it is a crate of its own).
//!
//! A table of cells ([`Table`]) becomes one Parquet file whose columns have the type their
//! cells have: integers `Int64`, numbers `Float64` (integers among numbers are widened), yes/no
//! `Boolean`, anything else `Utf8`; an empty cell is a null, and a column without any value is
//! a `Float64` of nulls. A trajectory is streamed instead ([`ParquetFile`]): batches of
//! columns as the run produces them, so memory stays bounded by one row group. Pages are
//! Snappy-compressed (fast, and the only codec built in, to keep the build small). Like every
//! output, a file is written under a temporary name and appears only when complete.

use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use arrow_array::{
    Array, ArrayRef, BooleanArray, Float64Array, Int64Array, RecordBatch, RecordBatchReader,
    StringArray,
};
use arrow_schema::{DataType, Field, Schema, SchemaRef};
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use parquet::arrow::ArrowWriter;
use parquet::basic::Compression;
use parquet::file::properties::WriterProperties;

use equations::Number;
use eulerdisk::{AtomicFile, Cell, ParquetWriter, Table, WriteError};

/// Rows per row group: a reader can skip or read groups apart, and a streamed trajectory
/// holds at most one group in memory.
pub const ROW_GROUP_ROWS: usize = 128 * 1024;

/// A Parquet file being written batch by batch; it appears under its name on
/// [`ParquetFile::commit`] and, dropped before, leaves nothing.
pub struct ParquetFile {
    writer: ArrowWriter<AtomicFile>,
    schema: SchemaRef,
    path: PathBuf,
}

impl std::fmt::Debug for ParquetFile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ParquetFile")
            .field("path", &self.path)
            .field("schema", &self.schema)
            .finish_non_exhaustive()
    }
}

impl ParquetFile {
    /// Starts writing `path` with these columns.
    pub fn create(path: &Path, fields: Vec<Field>) -> Result<ParquetFile, WriteError> {
        let schema = Arc::new(Schema::new(fields));
        let file = AtomicFile::create(path)?;
        let props = WriterProperties::builder()
            .set_compression(Compression::SNAPPY)
            .set_max_row_group_row_count(Some(ROW_GROUP_ROWS))
            .build();
        let writer =
            ArrowWriter::try_new(file, schema.clone(), Some(props)).map_err(|e| error(path, e))?;
        Ok(ParquetFile {
            writer,
            schema,
            path: path.to_path_buf(),
        })
    }

    /// Appends one batch: one array per column, in the schema's order, all equally long.
    pub fn write(&mut self, columns: Vec<ArrayRef>) -> Result<(), WriteError> {
        let batch =
            RecordBatch::try_new(self.schema.clone(), columns).map_err(|e| error(&self.path, e))?;
        self.writer.write(&batch).map_err(|e| error(&self.path, e))
    }

    /// Writes the footer, flushes the file and gives it its name.
    pub fn commit(self) -> Result<(), WriteError> {
        let path = self.path;
        self.writer
            .into_inner()
            .map_err(|e| error(&path, e))?
            .commit()
    }
}

/// The Arrow crates' Parquet writer, as the library asks for one.
#[derive(Clone, Copy, Debug, Default)]
pub struct ArrowParquet;

impl ParquetWriter for ArrowParquet {
    fn write_table(&self, path: &Path, table: &Table) -> Result<(), WriteError> {
        write_table(path, table)
    }

    fn rows(
        &self,
        path: &Path,
        columns: &[String],
    ) -> Result<Box<dyn eulerdisk::ParquetRows>, WriteError> {
        Ok(Box::new(ParquetRows::create(path, columns)?))
    }
}

/// Installs [`ArrowParquet`] as the library's Parquet writer (`eulerdisk::install_parquet`),
/// unless one is installed already: from then on scenes and flags may ask for Parquet.
pub fn install() {
    static WRITER: ArrowParquet = ArrowParquet;
    eulerdisk::install_parquet(&WRITER);
}

/// Rows gathered before a batch goes to a streamed file.
pub const BATCH_ROWS: usize = 8192;

/// A table streamed row by row: a time column `t_s`, a `mode` column of names, then one
/// `Float64` column per value. Rows are gathered into batches of [`BATCH_ROWS`] and handed to
/// the file, which keeps at most one row group in memory.
#[derive(Debug)]
pub struct ParquetRows {
    file: ParquetFile,
    t: Vec<f64>,
    modes: Vec<&'static str>,
    values: Vec<Vec<f64>>,
}

impl ParquetRows {
    /// Starts writing `path` with the columns `t_s`, `mode` and `columns`.
    pub fn create(path: &Path, columns: &[String]) -> Result<ParquetRows, WriteError> {
        let mut fields = vec![
            Field::new("t_s", DataType::Float64, false),
            Field::new("mode", DataType::Utf8, false),
        ];
        fields.extend(
            columns
                .iter()
                .map(|c| Field::new(c.as_str(), DataType::Float64, false)),
        );
        Ok(ParquetRows {
            file: ParquetFile::create(path, fields)?,
            t: Vec::with_capacity(BATCH_ROWS),
            modes: Vec::with_capacity(BATCH_ROWS),
            values: vec![Vec::with_capacity(BATCH_ROWS); columns.len()],
        })
    }

    /// Appends one row: its time, its mode's name and one value per column.
    pub fn push(
        &mut self,
        t: f64,
        mode: &'static str,
        values: impl IntoIterator<Item = f64>,
    ) -> Result<(), WriteError> {
        self.t.push(t);
        self.modes.push(mode);
        for (column, v) in self.values.iter_mut().zip(values) {
            column.push(v);
        }
        if self.t.len() >= BATCH_ROWS {
            self.flush()?;
        }
        Ok(())
    }

    /// Writes the rows gathered so far.
    fn flush(&mut self) -> Result<(), WriteError> {
        if self.t.is_empty() {
            return Ok(());
        }
        let mut columns: Vec<ArrayRef> = vec![
            Arc::new(Float64Array::from(std::mem::take(&mut self.t))),
            Arc::new(StringArray::from_iter_values(self.modes.drain(..))),
        ];
        for column in &mut self.values {
            columns.push(Arc::new(Float64Array::from(std::mem::take(column))));
        }
        self.file.write(columns)
    }

    /// Writes the last rows and the footer, and gives the file its name.
    pub fn commit(mut self) -> Result<(), WriteError> {
        self.flush()?;
        self.file.commit()
    }
}

impl eulerdisk::ParquetRows for ParquetRows {
    fn push(
        &mut self,
        t: f64,
        mode: &'static str,
        values: &mut dyn Iterator<Item = f64>,
    ) -> Result<(), WriteError> {
        ParquetRows::push(self, t, mode, values)
    }

    fn commit(self: Box<Self>) -> Result<(), WriteError> {
        ParquetRows::commit(*self)
    }
}

/// A Parquet or Arrow error while writing `path`.
fn error(path: &Path, e: impl std::error::Error + Send + Sync + 'static) -> WriteError {
    WriteError {
        path: path.to_path_buf(),
        source: std::io::Error::other(e),
    }
}

/// The type a column of cells gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Int,
    Float,
    Bool,
    Text,
}

impl Kind {
    /// The type of a column holding `cells` (see the module docs).
    fn of<'c>(cells: impl IntoIterator<Item = &'c Cell>) -> Kind {
        let mut kind = None;
        for cell in cells {
            let this = match cell {
                Cell::Null => continue,
                Cell::Int(_) => Kind::Int,
                Cell::Float(_) => Kind::Float,
                Cell::Bool(_) => Kind::Bool,
                Cell::Text(_) => Kind::Text,
            };
            kind = Some(match (kind, this) {
                (None, k) => k,
                (Some(a), b) if a == b => a,
                (Some(Kind::Int | Kind::Float), Kind::Int | Kind::Float) => Kind::Float,
                _ => Kind::Text,
            });
        }
        kind.unwrap_or(Kind::Float)
    }

    fn data_type(self) -> DataType {
        match self {
            Kind::Int => DataType::Int64,
            Kind::Float => DataType::Float64,
            Kind::Bool => DataType::Boolean,
            Kind::Text => DataType::Utf8,
        }
    }

    /// The cells as an array of this type (every cell fits it, by [`Kind::of`]).
    fn array<'c>(self, cells: impl Iterator<Item = &'c Cell>) -> ArrayRef {
        match self {
            Kind::Int => Arc::new(Int64Array::from_iter(cells.map(|c| match c {
                Cell::Int(i) => Some(*i),
                _ => None,
            }))),
            Kind::Float => Arc::new(Float64Array::from_iter(cells.map(|c| match c {
                Cell::Int(i) => Some(*i as f64),
                Cell::Float(f) => Some(*f),
                _ => None,
            }))),
            Kind::Bool => Arc::new(BooleanArray::from_iter(cells.map(|c| match c {
                Cell::Bool(b) => Some(*b),
                _ => None,
            }))),
            Kind::Text => Arc::new(StringArray::from_iter(cells.map(|c| match c {
                Cell::Null => None,
                Cell::Int(i) => Some(i.to_string()),
                Cell::Float(f) => Some(Number(*f).to_string()),
                Cell::Bool(b) => Some(b.to_string()),
                Cell::Text(s) => Some(s.clone()),
            }))),
        }
    }
}

/// Writes `table` as the Parquet file `path`, atomically, each column typed by its cells.
pub fn write_table(path: &Path, table: &Table) -> Result<(), WriteError> {
    let kinds: Vec<Kind> = (0..table.header.len())
        .map(|i| Kind::of(table.column(i)))
        .collect();
    let fields = table
        .header
        .iter()
        .zip(&kinds)
        .map(|(name, kind)| Field::new(name.as_str(), kind.data_type(), true))
        .collect();
    let mut file = ParquetFile::create(path, fields)?;
    let columns = kinds
        .iter()
        .enumerate()
        .map(|(i, kind)| kind.array(table.column(i)))
        .collect();
    file.write(columns)?;
    file.commit()
}

/// Why a Parquet file could not be read back.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The file cannot be opened.
    #[error("cannot read {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The file is not Parquet, or is damaged.
    #[error("{} is not a readable Parquet file: {message}", path.display())]
    Parquet {
        /// The file.
        path: PathBuf,
        /// The reader's message.
        message: String,
    },
    /// A column has a type that no table of this program has.
    #[error("{}: column `{column}` has type {data_type}, not one this program writes", path.display())]
    Type {
        /// The file.
        path: PathBuf,
        /// The column.
        column: String,
        /// Its type.
        data_type: DataType,
    },
}

/// Reads a Parquet file this program wrote back into a table of cells (for checks, and for
/// comparing it with the CSV of the same table).
pub fn read_table(path: &Path) -> Result<Table, ReadError> {
    let parquet = |e: &dyn std::fmt::Display| ReadError::Parquet {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    let file = File::open(path).map_err(|source| ReadError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let reader = ParquetRecordBatchReaderBuilder::try_new(file)
        .and_then(|b| b.build())
        .map_err(|e| parquet(&e))?;
    let mut table = Table::new(reader.schema().fields().iter().map(|f| f.name().clone()));
    for batch in reader {
        let batch = batch.map_err(|e| parquet(&e))?;
        let mut rows = vec![Vec::with_capacity(batch.num_columns()); batch.num_rows()];
        for (field, column) in batch.schema().fields().iter().zip(batch.columns()) {
            let cells = cells(column.as_ref()).ok_or_else(|| ReadError::Type {
                path: path.to_path_buf(),
                column: field.name().clone(),
                data_type: field.data_type().clone(),
            })?;
            for (row, cell) in rows.iter_mut().zip(cells) {
                row.push(cell);
            }
        }
        table.rows.extend(rows);
    }
    Ok(table)
}

/// An array's values as cells (`None` for a type no table of this program has).
fn cells(array: &dyn Array) -> Option<Vec<Cell>> {
    let any = array.as_any();
    let at = |i: usize, cell: &dyn Fn(usize) -> Cell| {
        if array.is_null(i) {
            Cell::Null
        } else {
            cell(i)
        }
    };
    let n = array.len();
    let out = if let Some(a) = any.downcast_ref::<Float64Array>() {
        (0..n)
            .map(|i| at(i, &|i| Cell::Float(a.value(i))))
            .collect()
    } else if let Some(a) = any.downcast_ref::<Int64Array>() {
        (0..n).map(|i| at(i, &|i| Cell::Int(a.value(i)))).collect()
    } else if let Some(a) = any.downcast_ref::<BooleanArray>() {
        (0..n).map(|i| at(i, &|i| Cell::Bool(a.value(i)))).collect()
    } else if let Some(a) = any.downcast_ref::<StringArray>() {
        (0..n).map(|i| at(i, &|i| Cell::text(a.value(i)))).collect()
    } else {
        return None;
    };
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_round_trips_with_typed_columns() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.parquet");
        let mut t = Table::new(["n", "x", "mixed", "ok", "word", "empty"]);
        t.rows.push(vec![
            Cell::Int(1),
            Cell::Float(0.1),
            Cell::Int(2),
            Cell::Bool(true),
            Cell::text("a, \"b\""),
            Cell::Null,
        ]);
        t.rows.push(vec![
            Cell::Null,
            Cell::Float(f64::MIN_POSITIVE),
            Cell::Float(2.5),
            Cell::Null,
            Cell::Int(3),
            Cell::Null,
        ]);
        write_table(&path, &t).unwrap();
        let back = read_table(&path).unwrap();
        assert_eq!(back.header, t.header);
        // Integers among numbers are widened; a number in a text column is its text.
        assert_eq!(back.rows[0][2], Cell::Float(2.0));
        assert_eq!(back.rows[1][4], Cell::text("3"));
        assert_eq!(back.rows[1][1], Cell::Float(f64::MIN_POSITIVE));
        assert_eq!(back.rows[0][..2], t.rows[0][..2]);
        assert_eq!(back.rows[0][3..5], t.rows[0][3..5]);
        assert_eq!(back.rows[1][5], Cell::Null);
        let names: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names, ["t.parquet"], "no temporary file left");
    }

    #[test]
    fn a_file_that_is_not_parquet_is_an_error_naming_it() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.parquet");
        std::fs::write(&path, "t_s\n1\n").unwrap();
        let err = read_table(&path).unwrap_err();
        assert!(err.to_string().contains("x.parquet"), "{err}");
    }
}
