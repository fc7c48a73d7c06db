//! One sweep at a time in a folder.
//!
//! Two sweeps started into one folder would both see the same points without a row and run
//! each of them twice (the rows are written whole, so nothing is corrupted, but the work is
//! doubled and the second run's row silently replaces the first). A sweep therefore holds
//! `sweep.lock` in its folder while it runs: the file is created exclusively and holds the
//! process id; it is removed when the sweep ends, however it ends short of a kill. A lock
//! whose process is no longer running on this machine (a killed sweep) is taken over, so
//! resuming after a kill needs nothing by hand.

use std::fs::{self, OpenOptions};
use std::io::{ErrorKind, Write};
use std::path::{Path, PathBuf};

/// The lock file's name in a sweep folder.
pub const LOCK_FILE: &str = "sweep.lock";

/// Why a folder could not be locked.
#[derive(Debug, thiserror::Error)]
pub enum LockError {
    /// Another running sweep holds the folder.
    #[error(
        "{}: another sweep (process {pid}) is running into this folder; wait for it to end, \
         or give another --out",
        dir.display()
    )]
    Held {
        /// The folder.
        dir: PathBuf,
        /// The process holding it.
        pid: u32,
    },
    /// The lock file cannot be created or read.
    #[error("cannot lock {}: {source}", path.display())]
    Io {
        /// The lock file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
}

/// A held folder lock; dropping it releases the folder.
#[derive(Debug)]
pub struct FolderLock {
    path: PathBuf,
}

impl FolderLock {
    /// Locks `dir` (creating it) for this process, taking over a lock whose process is gone.
    pub fn take(dir: &Path) -> Result<FolderLock, LockError> {
        let path = dir.join(LOCK_FILE);
        let io = |source| LockError::Io {
            path: path.clone(),
            source,
        };
        fs::create_dir_all(dir).map_err(io)?;
        // Two tries: the second after removing a stale lock.
        for _ in 0..2 {
            match OpenOptions::new().write(true).create_new(true).open(&path) {
                Ok(mut file) => {
                    write!(file, "{}", std::process::id()).map_err(io)?;
                    return Ok(FolderLock { path });
                }
                Err(e) if e.kind() == ErrorKind::AlreadyExists => {
                    let holder = fs::read_to_string(&path)
                        .ok()
                        .and_then(|text| text.trim().parse::<u32>().ok());
                    match holder {
                        Some(pid) if running(pid) => {
                            return Err(LockError::Held {
                                dir: dir.to_path_buf(),
                                pid,
                            })
                        }
                        _ => match fs::remove_file(&path) {
                            Ok(()) => {}
                            Err(e) if e.kind() == ErrorKind::NotFound => {}
                            Err(e) => return Err(io(e)),
                        },
                    }
                }
                Err(e) => return Err(io(e)),
            }
        }
        // Another sweep took the folder between our removal of a stale lock and our retry.
        let pid = fs::read_to_string(&path)
            .ok()
            .and_then(|text| text.trim().parse().ok())
            .unwrap_or(0);
        Err(LockError::Held {
            dir: dir.to_path_buf(),
            pid,
        })
    }
}

impl Drop for FolderLock {
    fn drop(&mut self) {
        let _ = fs::remove_file(&self.path);
    }
}

/// The process holding `dir`'s lock, if it is running (a lock left by a killed process does
/// not count).
pub fn running_holder(dir: &Path) -> Option<u32> {
    let text = fs::read_to_string(dir.join(LOCK_FILE)).ok()?;
    let pid = text.trim().parse::<u32>().ok()?;
    running(pid).then_some(pid)
}

/// Whether a process `pid` runs on this machine (signal 0 checks without sending anything;
/// "not permitted" means it runs under another user).
fn running(pid: u32) -> bool {
    let Ok(pid) = libc::pid_t::try_from(pid) else {
        return false;
    };
    if pid <= 0 {
        return false;
    }
    // SAFETY: kill with signal 0 sends nothing; it only reports whether the process exists.
    let status = unsafe { libc::kill(pid, 0) };
    status == 0 || std::io::Error::last_os_error().raw_os_error() == Some(libc::EPERM)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_running_holder_keeps_the_folder_and_a_gone_one_loses_it() {
        let dir = tempfile::tempdir().unwrap();
        let lock = FolderLock::take(dir.path()).unwrap();
        // This process holds it: a second sweep (here, a second take) is refused.
        let err = FolderLock::take(dir.path()).unwrap_err();
        assert!(
            matches!(err, LockError::Held { pid, .. } if pid == std::process::id()),
            "{err}"
        );
        drop(lock);
        assert!(!dir.path().join(LOCK_FILE).exists(), "released on drop");
        // A lock left by a process that has ended is taken over.
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let gone = child.id();
        child.wait().unwrap();
        fs::write(dir.path().join(LOCK_FILE), gone.to_string()).unwrap();
        let lock = FolderLock::take(dir.path()).unwrap();
        let held = fs::read_to_string(dir.path().join(LOCK_FILE)).unwrap();
        assert_eq!(held, std::process::id().to_string());
        drop(lock);
        // So is an unreadable one.
        fs::write(dir.path().join(LOCK_FILE), "not a pid").unwrap();
        assert!(FolderLock::take(dir.path()).is_ok());
    }
}
