//! The trajectory file, written row by row while the run goes on, so that writing overlaps
//! the simulation instead of following it: `trajectory.csv`, or `trajectory.parquet` when the
//! scene's `output.format` says so (typed columns, the same names and units).
//!
//! The Parquet writer gathers the rows into batches and keeps at most one row group in
//! memory: a 20 kHz run of 100 s streams through bounded memory in either format.

use std::io::Write;
use std::path::Path;

use equations::DiskParams;

use crate::output::atomic::{AtomicFile, WriteError};
use crate::output::format::TableFormat;
use crate::output::parquet::{writer_for, ParquetRows};
use crate::output::tables::{trajectory_header, write_trajectory_row};
use equations::record::Quantity;
use equations::record::Sample;

/// The file's stem: `trajectory.csv`, `trajectory.parquet`.
pub const STEM: &str = "trajectory";

/// Where the rows go.
#[derive(Debug)]
enum Sink {
    Csv(AtomicFile),
    Parquet(Box<dyn ParquetRows>),
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
                let columns: Vec<String> = quantities.iter().map(|q| q.column()).collect();
                Sink::Parquet(writer_for(&path)?.rows(&path, &columns)?)
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
            Sink::Parquet(rows) => {
                let mut values = self.quantities.iter().map(|q| q.value(s, &self.params));
                rows.push(s.t, s.mode.name(), &mut values)
            }
        }
    }

    /// Flushes the file and gives it its name.
    pub fn commit(self) -> Result<(), WriteError> {
        match self.sink {
            Sink::Csv(file) => file.commit(),
            Sink::Parquet(rows) => rows.commit(),
        }
    }
}
