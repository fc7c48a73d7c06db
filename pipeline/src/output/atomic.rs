//! Files that appear only when complete.
//!
//! Every output is written under a temporary name in its final directory and renamed when it
//! is complete and flushed, so a reader (or an interrupted run) never sees half a file: a
//! file is either the previous complete version, the new complete version, or absent.
//!
//! An output that already exists as something other than a regular file (`/dev/null`,
//! `/dev/stdout`, a named pipe) is written in place: renaming over it would replace the
//! device or the pipe with a regular file (as root, `-o /dev/null` would turn the system's
//! `/dev/null` into a file that keeps what is written to it).

use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// Why an output could not be written.
#[derive(Debug, thiserror::Error)]
#[error("cannot write {}: {source}", path.display())]
pub struct WriteError {
    /// The file.
    pub path: PathBuf,
    /// The I/O error.
    pub source: io::Error,
}

/// The temporary name used while `path` is being written: hidden, marked partial, and with
/// the same extension (encoders choose the format by it).
pub fn temporary_name(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".partial-{}-{name}", std::process::id()))
}

/// Lets `produce` write a file at a temporary path (for encoders that only write to a path),
/// then renames it to `path`; on failure the temporary file is removed.
pub fn produce_atomic<E, F>(path: &Path, produce: F) -> Result<(), WriteError>
where
    F: FnOnce(&Path) -> Result<(), E>,
    E: std::fmt::Display,
{
    let as_error = |e: E| io::Error::other(e.to_string());
    let result = if is_special(path) {
        produce(path).map_err(as_error)
    } else {
        let tmp = temporary_name(path);
        let result = produce(&tmp)
            .map_err(as_error)
            .and_then(|()| fs::rename(&tmp, path));
        if result.is_err() {
            let _ = fs::remove_file(&tmp);
        }
        result
    };
    result.map_err(|source| WriteError {
        path: path.to_path_buf(),
        source,
    })
}

/// A file written piece by piece (a trajectory streamed while the run goes on) that appears
/// under its name only when [`AtomicFile::commit`] has flushed it; dropped uncommitted (an
/// error, a panic), it leaves nothing but the previous version of `path`, if any.
#[derive(Debug)]
pub struct AtomicFile {
    path: PathBuf,
    /// The temporary name (`None`: a device or a pipe, written in place).
    tmp: Option<PathBuf>,
    writer: Option<BufWriter<File>>,
}

/// Whether `path` exists as something other than a regular file (a device, a pipe, a
/// socket, followed through symbolic links): written in place, never renamed over.
fn is_special(path: &Path) -> bool {
    fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

impl AtomicFile {
    /// Starts writing `path` (under its temporary name; a device or a pipe in place).
    pub fn create(path: &Path) -> Result<AtomicFile, WriteError> {
        let tmp = (!is_special(path)).then(|| temporary_name(path));
        let opened = match &tmp {
            Some(tmp) => File::create(tmp),
            None => fs::OpenOptions::new().write(true).open(path),
        };
        let file = opened.map_err(|source| WriteError {
            path: path.to_path_buf(),
            source,
        })?;
        Ok(AtomicFile {
            path: path.to_path_buf(),
            tmp,
            writer: Some(BufWriter::with_capacity(1 << 16, file)),
        })
    }

    /// Where to write the content.
    pub fn writer(&mut self) -> &mut BufWriter<File> {
        self.writer
            .as_mut()
            .expect("an AtomicFile is only consumed by commit")
    }

    /// Flushes the content to disk and gives the file its name.
    pub fn commit(mut self) -> Result<(), WriteError> {
        let writer = self
            .writer
            .take()
            .expect("an AtomicFile is only consumed by commit");
        let file = writer.into_inner().map_err(|e| e.into_error());
        let result = match &self.tmp {
            Some(tmp) => file
                .and_then(|file| file.sync_all())
                .and_then(|()| fs::rename(tmp, &self.path)),
            // A device or a pipe has nothing to sync (and a pipe refuses it).
            None => file.map(drop),
        };
        result.map_err(|source| WriteError {
            path: self.path.clone(),
            source,
        })
    }

    /// Wraps an I/O error of writing the content with the file's path.
    pub fn error(&self, source: io::Error) -> WriteError {
        WriteError {
            path: self.path.clone(),
            source,
        }
    }
}

/// Writes go to the content (so an encoder that owns its writer, Parquet's, can own the file
/// and hand it back for [`AtomicFile::commit`]).
impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.writer().write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.writer().flush()
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        // Committed files were renamed away; an uncommitted one is removed.
        if let Some(tmp) = &self.tmp {
            if self.writer.take().is_some() || tmp.exists() {
                let _ = fs::remove_file(tmp);
            }
        }
    }
}

/// Writes `path` through `fill`, atomically: the content goes to a temporary file that is
/// renamed to `path` only when `fill` succeeded and the data is flushed. On failure the
/// temporary file is removed and `path` is untouched.
pub fn write_atomic<F>(path: &Path, fill: F) -> Result<(), WriteError>
where
    F: FnOnce(&mut BufWriter<File>) -> io::Result<()>,
{
    let mut file = AtomicFile::create(path)?;
    match fill(file.writer()) {
        Ok(()) => file.commit(),
        Err(source) => Err(file.error(source)),
    }
}

/// Writes `path` from a complete byte buffer, atomically.
pub fn write_bytes_atomic(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    write_atomic(path, |w| w.write_all(bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn success_renames_and_failure_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.csv");
        write_atomic(&path, |w| w.write_all(b"x,y\n1,2\n")).unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "x,y\n1,2\n");
        let err = write_atomic(&path, |w| {
            w.write_all(b"half")?;
            Err(io::Error::other("interrupted"))
        })
        .unwrap_err();
        assert!(err.to_string().contains("a.csv"));
        // The previous complete version survives, and no temporary file is left behind.
        assert_eq!(fs::read_to_string(&path).unwrap(), "x,y\n1,2\n");
        let names: Vec<_> = fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names.len(), 1, "{names:?}");
    }

    /// A named pipe (as `/dev/null` or `/dev/stdout` would be) is written in place and stays a
    /// pipe: renamed over, it would have become a regular file.
    #[test]
    fn a_pipe_is_written_in_place_not_replaced() {
        use std::os::unix::ffi::OsStrExt;
        use std::os::unix::fs::FileTypeExt;
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("pipe.csv");
        let name = std::ffi::CString::new(path.as_os_str().as_bytes()).unwrap();
        // SAFETY: a valid NUL-terminated path; mkfifo only creates the pipe.
        assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o600) }, 0);
        for round in 0..2 {
            let reader = {
                let path = path.clone();
                std::thread::spawn(move || fs::read_to_string(path).unwrap())
            };
            if round == 0 {
                write_atomic(&path, |w| w.write_all(b"x,y\n1,2\n")).unwrap();
            } else {
                produce_atomic(&path, |p| fs::write(p, b"x,y\n1,2\n")).unwrap();
            }
            // First the kind: a pipe renamed over is never opened, and its reader would wait.
            let kind = fs::symlink_metadata(&path).unwrap().file_type();
            assert!(
                kind.is_fifo(),
                "round {round}: the pipe was replaced: {kind:?}"
            );
            assert_eq!(reader.join().unwrap(), "x,y\n1,2\n");
        }
        let names: Vec<_> = fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(names.len(), 1, "no temporary file is left: {names:?}");
    }
}
