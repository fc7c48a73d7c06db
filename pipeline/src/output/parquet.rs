//! Parquet as a writer a front end installs: the format is a name every scene and flag may
//! write, and the tables and the trajectory reach it through [`ParquetWriter`], but the Arrow
//! and Parquet crates that write it are not this library's. They are the largest part of the
//! build, and only the command line writes Parquet files (the Python package returns arrays,
//! which pandas writes as Parquet): `eulerdisk-parquet` (folder `pipeline/parquet`) holds the
//! writer, and the `eulerdisk` binary installs it at its start, as a program installs a logger.
//! One build of this library then serves every front end. Without a writer installed, a scene
//! that asks for Parquet is refused by its key (`output.format`) before anything is written.

use std::path::Path;
use std::sync::OnceLock;

use super::atomic::WriteError;
use super::cells::Table;
use super::format::PARQUET_UNAVAILABLE;

/// Writes Parquet files: whole tables, and a trajectory streamed row by row.
pub trait ParquetWriter: Send + Sync {
    /// Writes `table` as the Parquet file `path`, atomically, each column typed by its cells.
    fn write_table(&self, path: &Path, table: &Table) -> Result<(), WriteError>;

    /// Starts streaming `path` with the columns `t_s`, `mode` and `columns` (numbers).
    fn rows(&self, path: &Path, columns: &[String]) -> Result<Box<dyn ParquetRows>, WriteError>;
}

/// A Parquet table being streamed: it appears under its name on [`ParquetRows::commit`] and,
/// dropped before, leaves nothing.
pub trait ParquetRows: Send + std::fmt::Debug {
    /// Appends one row: its time, its mode's name and one value per column.
    fn push(
        &mut self,
        t: f64,
        mode: &'static str,
        values: &mut dyn Iterator<Item = f64>,
    ) -> Result<(), WriteError>;

    /// Writes the last rows and the footer, and gives the file its name.
    fn commit(self: Box<Self>) -> Result<(), WriteError>;
}

/// The writer installed, if any.
static WRITER: OnceLock<&'static dyn ParquetWriter> = OnceLock::new();

/// Installs `writer` for the rest of the process; `false` if one was installed already (which
/// stays).
pub fn install_parquet(writer: &'static dyn ParquetWriter) -> bool {
    WRITER.set(writer).is_ok()
}

/// The writer installed, if any.
pub fn parquet_writer() -> Option<&'static dyn ParquetWriter> {
    WRITER.get().copied()
}

/// The installed writer, or the error of a write to `path` that no writer can make (a scene
/// asking for Parquet is refused before it gets here; a direct call is not).
pub(crate) fn writer_for(path: &Path) -> Result<&'static dyn ParquetWriter, WriteError> {
    parquet_writer().ok_or_else(|| WriteError {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::Unsupported, PARQUET_UNAVAILABLE),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_a_writer_a_parquet_file_is_an_error_naming_it() {
        // No test of this library installs a writer (the writer's crate depends on this one).
        let path = Path::new("out/events.parquet");
        let err = writer_for(path).err().expect("no writer is installed");
        assert_eq!(err.path, path);
        assert!(err.to_string().contains("Parquet writer"), "{err}");
    }

    #[test]
    fn without_a_writer_a_scene_asking_for_parquet_is_refused_by_its_key() {
        let parquet = crate::Override::parse("output.format=parquet").unwrap();
        let err = crate::load_scene(crate::DEFAULT_SCENE, &[parquet]).unwrap_err();
        assert_eq!(err.keys(), ["output.format"], "{err}");
        assert!(err.to_string().contains("Parquet writer"), "{err}");
        let csv = crate::Override::parse("output.format=csv").unwrap();
        assert!(crate::load_scene(crate::DEFAULT_SCENE, &[csv]).is_ok());
    }
}
