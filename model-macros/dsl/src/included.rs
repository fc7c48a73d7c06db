//! What a model's `include`s read: the files, and the chain being read now.
//!
//! Kept apart from the parsing of `include` (module `include`), which needs the parser's
//! error and span tables, because those tables carry these records: a model's spans keep the
//! files its includes read (`Spans::included`).

use proc_macro2::Span;
use std::path::{Path, PathBuf};
extern crate proc_macro;

/// One file an `include` read.
#[derive(Clone, Debug)]
pub struct IncludedFile {
    /// The path as the `include` wrote it.
    pub written: String,
    /// The path joined to the including file's folder: the name messages about the file give.
    pub name: String,
    /// Where it was read, canonical (absolute).
    pub path: PathBuf,
    /// Its text.
    pub text: String,
    /// The span of the path in the `include` that read it (inside `model!`, every token of the
    /// file carries it, the compiler having no place in a file that is not Rust).
    pub at: Span,
    /// A span of one of its tokens, which tells its tokens from other files' when the model is
    /// read as text (`None` for a file with no tokens).
    pub(crate) anchor: Option<Span>,
    /// The file that included it (`None`: the model's own source).
    pub parent: Option<usize>,
}

/// The includes of one model being read: the files read so far and the chain of files being
/// read now (for relative paths and cycles).
#[derive(Clone, Debug, Default)]
pub(crate) struct Includes {
    /// The model's own source file, if it has one: relative paths start in its folder.
    pub origin: Option<PathBuf>,
    /// Every file read, in the order read.
    pub files: Vec<IncludedFile>,
    /// The files being read, outermost first (indices into `files`).
    pub reading: Vec<usize>,
    /// The tokens read from files so far (within the model's token limit together).
    pub tokens: usize,
}

impl Includes {
    /// The folder a path written in the file being read now is relative to.
    pub(crate) fn folder(&self) -> PathBuf {
        let including = match self.reading.last() {
            Some(&k) => Some(PathBuf::from(&self.files[k].name)),
            None => self.origin.clone().or_else(invoking_file),
        };
        match including.as_deref().and_then(Path::parent) {
            Some(folder) => folder.to_path_buf(),
            // A model with no file of its own (text given by value) reads relative to the
            // working folder; one expanded by `model!` where the compiler names no file, to
            // its crate's root.
            None => std::env::var_os("CARGO_MANIFEST_DIR")
                .filter(|_| proc_macro::is_available())
                .map(PathBuf::from)
                .unwrap_or_default(),
        }
    }

    /// The chain of includes that reads `path` again, if one does: `a.dsl -> b.dsl -> a.dsl`.
    pub(crate) fn cycle(&self, path: &Path, written: &str) -> Option<String> {
        let origin = self.origin.as_deref().and_then(|o| o.canonicalize().ok());
        let start = self
            .reading
            .iter()
            .position(|&k| self.files[k].path == path);
        let names = |from: usize| {
            (self.reading[from..].iter())
                .map(|&k| self.files[k].written.clone())
                .chain([written.to_string()])
                .collect::<Vec<_>>()
                .join(" -> ")
        };
        match start {
            Some(from) => Some(names(from)),
            None if origin.as_deref() == Some(path) => {
                let own = self.origin.as_deref().map(Path::display);
                let own = own.map_or_else(String::new, |o| format!("{o} -> "));
                Some(format!("{own}{}", names(0)))
            }
            None => None,
        }
    }
}

/// The Rust file that invokes `model!`, when the compiler names it.
fn invoking_file() -> Option<PathBuf> {
    proc_macro::is_available()
        .then(|| Span::call_site().local_file())
        .flatten()
}
