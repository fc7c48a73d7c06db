//! The trajectory file, written row by row while the run goes on, so that writing overlaps
//! the simulation instead of following it: `trajectory.csv`, or `trajectory.parquet` when the
//! scene's `output.format` says so (typed columns, the same names and units).
//!
//! The Parquet writer gathers the rows into batches of [`BATCH_ROWS`] and hands each to the
//! file, which keeps at most one row group in memory: a 20 kHz run of 100 s streams through
//! bounded memory in either format.

use std::io::Write;
use std::path::Path;
use std::sync::Arc;

use arrow_array::{ArrayRef, Float64Array, StringArray};
use arrow_schema::{DataType, Field};
use equations::{DiskParams, Mode};

use crate::output::atomic::{AtomicFile, WriteError};
use crate::output::format::TableFormat;
use crate::output::parquet::ParquetFile;
use crate::output::tables::{trajectory_header, write_trajectory_row};
use equations::record::Quantity;
use equations::record::Sample;

/// Rows gathered before a batch goes to the Parquet file.
pub const BATCH_ROWS: usize = 8192;

/// The file's stem: `trajectory.csv`, `trajectory.parquet`.
pub const STEM: &str = "trajectory";

/// The trajectory's columns gathered for the next Parquet batch.
#[derive(Debug, Default)]
struct Batch {
    t: Vec<f64>,
    modes: Vec<Mode>,
    values: Vec<Vec<f64>>,
}

/// Where the rows go.
#[derive(Debug)]
enum Sink {
    Csv(AtomicFile),
    Parquet(Box<ParquetFile>, Batch),
}

/// The trajectory file of a run, being written.
#[derive(Debug)]
pub struct TrajectoryFile {
    sink: Sink,
    quantities: Vec<Quantity>,
    params: DiskParams,
}

impl TrajectoryFile {
    /// Starts `dir/trajectory.<format>` (under its temporary name): the CSV with its header,
    /// the Parquet file with its schema (`t_s`, `mode`, then one `Float64` per quantity).
    pub fn create(
        dir: &Path,
        format: TableFormat,
        quantities: &[Quantity],
        params: DiskParams,
    ) -> Result<TrajectoryFile, WriteError> {
        let path = dir.join(format.file(STEM));
        let sink = match format {
            TableFormat::Csv => {
                let mut file = AtomicFile::create(&path)?;
                writeln!(file.writer(), "{}", trajectory_header(quantities))
                    .map_err(|e| file.error(e))?;
                Sink::Csv(file)
            }
            TableFormat::Parquet => {
                let mut fields = vec![
                    Field::new("t_s", DataType::Float64, false),
                    Field::new("mode", DataType::Utf8, false),
                ];
                fields.extend(
                    quantities
                        .iter()
                        .map(|q| Field::new(q.column(), DataType::Float64, false)),
                );
                let batch = Batch {
                    values: vec![Vec::new(); quantities.len()],
                    ..Batch::default()
                };
                Sink::Parquet(Box::new(ParquetFile::create(&path, fields)?), batch)
            }
        };
        Ok(TrajectoryFile {
            sink,
            quantities: quantities.to_vec(),
            params,
        })
    }

    /// Appends one sample.
    pub fn row(&mut self, s: &Sample) -> Result<(), WriteError> {
        match &mut self.sink {
            Sink::Csv(file) => {
                write_trajectory_row(file.writer(), &self.quantities, s, &self.params)
                    .map_err(|e| file.error(e))
            }
            Sink::Parquet(file, batch) => {
                batch.t.push(s.t);
                batch.modes.push(s.mode);
                for (q, column) in self.quantities.iter().zip(&mut batch.values) {
                    column.push(q.value(s, &self.params));
                }
                if batch.t.len() >= BATCH_ROWS {
                    flush(file, batch)?;
                }
                Ok(())
            }
        }
    }

    /// Flushes the file and gives it its name.
    pub fn commit(self) -> Result<(), WriteError> {
        match self.sink {
            Sink::Csv(file) => file.commit(),
            Sink::Parquet(mut file, mut batch) => {
                flush(&mut file, &mut batch)?;
                file.commit()
            }
        }
    }
}

/// Hands the gathered rows to the Parquet file and empties the batch.
fn flush(file: &mut ParquetFile, batch: &mut Batch) -> Result<(), WriteError> {
    if batch.t.is_empty() {
        return Ok(());
    }
    let mut columns: Vec<ArrayRef> = vec![
        Arc::new(Float64Array::from(std::mem::take(&mut batch.t))),
        Arc::new(StringArray::from_iter_values(
            batch.modes.drain(..).map(Mode::name),
        )),
    ];
    for column in &mut batch.values {
        columns.push(Arc::new(Float64Array::from(std::mem::take(column))));
    }
    file.write(columns)
}
