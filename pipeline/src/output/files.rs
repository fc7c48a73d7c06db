//! A table written in the format a scene, a sweep or a flag chose: the one place that picks
//! the writer.

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
    write_table_at(table, &path, format)?;
    Ok(path)
}

/// Writes `table` in `format` to the file `path`, whatever its name, atomically.
pub fn write_table_at(table: &Table, path: &Path, format: TableFormat) -> Result<(), WriteError> {
    match format {
        TableFormat::Csv => write_atomic(path, |w| table.write_csv(w)),
        TableFormat::Parquet => super::parquet::writer_for(path)?.write_table(path, table),
    }
}
