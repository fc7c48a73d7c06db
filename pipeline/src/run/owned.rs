//! The files `eulerdisk run` owns in its output directory, and clearing them for a rerun.
//!
//! A rerun into the same directory must not leave files of an earlier run beside the new ones
//! (old figures after `--no-figures`, or CSV tables after a rerun with `--format parquet`).
//! The run removes exactly the names it writes — `trajectory`, `events` and `extrema` as
//! `.csv` and `.parquet`, `summary.json`, the paper figures' PNG and SVG files — and
//! partial files an interrupted writer of those names left behind; anything else in the
//! directory is not the run's and stays.

use std::io;
use std::path::{Path, PathBuf};

use crate::figures::paper::FIGURE_STEMS;
use crate::output::atomic::WriteError;
use crate::output::format::TableFormat;

/// Prefix of the temporary names of files being written (`output::atomic`).
const PARTIAL_PREFIX: &str = ".partial-";

/// The file names a run may write into its output directory.
pub fn owned_names() -> Vec<String> {
    let mut names = vec!["summary.json".to_string()];
    for format in TableFormat::ALL {
        for stem in ["trajectory", "events", "extrema"] {
            names.push(format.file(stem));
        }
    }
    for stem in FIGURE_STEMS {
        names.push(format!("{stem}.png"));
        names.push(format!("{stem}.svg"));
    }
    names
}

/// Whether `file` is a temporary name `.partial-<pid>-<name>` of an owned `name`.
fn is_owned_partial(file: &str, owned: &[String]) -> bool {
    let Some(rest) = file.strip_prefix(PARTIAL_PREFIX) else {
        return false;
    };
    let Some((pid, name)) = rest.split_once('-') else {
        return false;
    };
    !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit()) && owned.iter().any(|n| n == name)
}

/// Removes every file of `dir` that a run owns (see the module docs); returns the paths
/// removed. Files the run does not own are never touched.
pub fn clear_owned(dir: &Path) -> Result<Vec<PathBuf>, WriteError> {
    let owned = owned_names();
    let entries = match std::fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(source) => {
            return Err(WriteError {
                path: dir.to_path_buf(),
                source,
            })
        }
    };
    let mut removed = Vec::new();
    for entry in entries {
        let entry = entry.map_err(|source| WriteError {
            path: dir.to_path_buf(),
            source,
        })?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let is_file = entry.file_type().is_ok_and(|t| t.is_file());
        if is_file && (owned.contains(&name) || is_owned_partial(&name, &owned)) {
            let path = entry.path();
            match std::fs::remove_file(&path) {
                Ok(()) => removed.push(path),
                Err(e) if e.kind() == io::ErrorKind::NotFound => {}
                Err(source) => return Err(WriteError { path, source }),
            }
        }
    }
    removed.sort();
    Ok(removed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_runs_own_files_are_cleared() {
        let dir = tempfile::tempdir().unwrap();
        let mine = [
            "trajectory.csv",
            "summary.json",
            "fig08b_normal_force.png",
            "fig10_normal_force_last_second.svg",
            ".partial-4242-events.csv",
        ];
        let theirs = [
            "notes.txt",
            "trajectory.csv.bak",
            "fig08b_normal_force.pdf",
            "rattle.wav",
            ".partial-x-events.csv",
            ".partial-12-notes.txt",
        ];
        for name in mine.iter().chain(&theirs) {
            std::fs::write(dir.path().join(name), b"x").unwrap();
        }
        // A directory with an owned name is not a file the run wrote.
        std::fs::create_dir(dir.path().join("events.csv")).unwrap();
        let removed = clear_owned(dir.path()).unwrap();
        assert_eq!(removed.len(), mine.len(), "{removed:?}");
        for name in mine {
            assert!(!dir.path().join(name).exists(), "{name} left behind");
        }
        for name in theirs {
            assert!(dir.path().join(name).exists(), "{name} removed");
        }
        assert!(dir.path().join("events.csv").is_dir());
        // A missing directory has nothing to clear.
        assert_eq!(
            clear_owned(&dir.path().join("absent")).unwrap(),
            Vec::<PathBuf>::new()
        );
    }

    #[test]
    fn the_owned_names_are_what_a_run_writes() {
        let names = owned_names();
        // summary.json, three tables in two formats, the figures as PNG and SVG.
        assert_eq!(names.len(), 1 + 3 * 2 + 2 * FIGURE_STEMS.len());
        assert!(names.contains(&"fig01a_theta.png".to_string()));
        assert!(names.contains(&"extrema.csv".to_string()));
        assert!(names.contains(&"trajectory.parquet".to_string()));
    }
}
