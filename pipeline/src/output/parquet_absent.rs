//! Parquet in a build without the `parquet` feature: the format is still a name scenes and
//! flags may write, so a scene that asks for it is refused by its key (`output.format`) before
//! anything is written. The writers below exist so the callers need no feature gates of their
//! own; they cannot be reached past that check, and if they were, they fail with an error that
//! says why instead of writing another format.

use std::path::Path;

use super::atomic::WriteError;
use super::cells::Table;
use super::format::PARQUET_UNAVAILABLE as UNAVAILABLE;

/// The error of a writer asked for a Parquet file at `path`.
fn unavailable(path: &Path) -> WriteError {
    WriteError {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::Unsupported, UNAVAILABLE),
    }
}

/// A streamed Parquet table, which this build cannot make: the type has no values.
#[derive(Debug)]
pub enum ParquetRows {}

impl ParquetRows {
    /// Fails: this build has no Parquet writer.
    pub fn create(path: &Path, _columns: &[String]) -> Result<ParquetRows, WriteError> {
        Err(unavailable(path))
    }

    /// Never called: no value of this type exists.
    pub fn push(
        &mut self,
        _t: f64,
        _mode: &'static str,
        _values: impl IntoIterator<Item = f64>,
    ) -> Result<(), WriteError> {
        match *self {}
    }

    /// Never called: no value of this type exists.
    pub fn commit(self) -> Result<(), WriteError> {
        match self {}
    }
}

/// Fails: this build has no Parquet writer.
pub fn write_table(path: &Path, _table: &Table) -> Result<(), WriteError> {
    Err(unavailable(path))
}
