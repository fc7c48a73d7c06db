//! A table written in the format a scene or sweep chose: the one place that picks the writer.

use std::path::{Path, PathBuf};

use super::atomic::{write_atomic, WriteError};
use super::cells::Table;
use super::format::TableFormat;

/// Writes `table` as `dir/<stem>.<format>`, atomically; returns the path.
pub fn write_table(
    table: &Table,
    dir: &Path,
    stem: &str,
    format: TableFormat,
) -> Result<PathBuf, WriteError> {
    let path = dir.join(format.file(stem));
    match format {
        TableFormat::Csv => write_atomic(&path, |w| table.write_csv(w))?,
        TableFormat::Parquet => super::parquet::write_table(&path, table)?,
    }
    Ok(path)
}
