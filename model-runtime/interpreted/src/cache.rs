//! A cache on disk of compiled models, so that reading the same file again skips the compiler.
//!
//! Compiling a big model (the 20-link chain: the symbolic solve of a 40-state system and its
//! Jacobian) takes seconds; its result, the solved programs, is data. An entry holds that data
//! (never machine code: nothing read from the cache runs as code), keyed by a hash of the
//! compiler's version and the file's text. Nothing in an entry is trusted because of its name:
//!
//! * an entry starts with a header naming the format and the compiler's version (a hash of the
//!   sources of the stages that derive programs, made by `build.rs`) and a checksum of the
//!   rest; an entry of another version, or whose checksum does not match (truncated, edited,
//!   corrupted), is ignored;
//! * the entry holds the whole text it was compiled from and whether it was read as Rust, and
//!   is used only when both equal the file's now (so even two texts with the same key cannot
//!   be confused);
//! * the models are checked against the text parsed again (their number and names).
//!
//! An entry that fails any check is a miss: the file is compiled and the entry rewritten.
//! Entries are written to a temporary file in the same directory and renamed into place, so a
//! reader sees a whole entry or none, and two processes writing the same entry at once leave
//! one of two identical entries. The directory is `$XDG_CACHE_HOME/eulerdisk/models`, else
//! `$HOME/.cache/eulerdisk/models`, created readable by its owner only (mode 0700). A cache
//! that cannot be read or written is no error: the file is compiled as without one.

use std::hash::{DefaultHasher, Hash, Hasher};
use std::io::Write;
use std::path::{Path, PathBuf};

use model_algebra::CompiledModel;
use model_dsl::{CompiledSwitched, Source};
use serde::{Deserialize, Serialize};

use crate::file::ModelFile;

/// The entry format; part of every entry's header.
const FORMAT: &str = "eulerdisk-compiled-model-1";

/// The compiler's version: a hash of its sources (see `build.rs`).
const COMPILER: &str = env!("MODEL_COMPILER_HASH");

/// Where compiled models are kept.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ModelCache {
    dir: PathBuf,
}

/// What an entry holds: the text and the compiled models.
#[derive(Serialize, Deserialize)]
struct Entry {
    /// The text compiled.
    text: String,
    /// Whether it was read as a Rust file holding `model!`.
    rust: bool,
    /// The compiled models.
    models: Models,
}

/// A file's models as kept: a smooth model's compiled models (the model, then its charts; the
/// syntax trees are parsed again on a hit), or a switched model.
#[derive(Serialize, Deserialize)]
enum Models {
    Smooth(Vec<CompiledModel>),
    Switched(CompiledSwitched),
}

impl ModelCache {
    /// The cache in `dir` (created when first written).
    pub fn at(dir: impl Into<PathBuf>) -> Self {
        ModelCache { dir: dir.into() }
    }

    /// The user's cache: `$XDG_CACHE_HOME/eulerdisk/models`, else
    /// `$HOME/.cache/eulerdisk/models`; `None` when neither variable is set (to an absolute
    /// path).
    pub fn user() -> Option<Self> {
        let absolute = |var: &str| {
            std::env::var_os(var)
                .map(PathBuf::from)
                .filter(|p| p.is_absolute())
        };
        let base =
            (absolute("XDG_CACHE_HOME")).or_else(|| absolute("HOME").map(|h| h.join(".cache")))?;
        Some(ModelCache::at(base.join("eulerdisk").join("models")))
    }

    /// The directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The entry's path for `key`.
    fn path(&self, key: &Key) -> PathBuf {
        let key = |salt: u8| {
            let mut hasher = DefaultHasher::new();
            (salt, FORMAT, COMPILER, key.source.rust, &key.text).hash(&mut hasher);
            hasher.finish()
        };
        self.dir
            .join(format!("{:016x}{:016x}.json", key(1), key(2)))
    }

    /// The file compiled from the source of `key`, if a valid entry for it is kept.
    pub(crate) fn get(&self, key: &Key) -> Option<ModelFile> {
        let source = key.source;
        let bytes = std::fs::read(self.path(key)).ok()?;
        let entry = decode(&bytes)?;
        if entry.text != key.text || entry.rust != source.rust {
            return None;
        }
        match entry.models {
            Models::Smooth(models) => source.with_compiled(models).map(ModelFile::Smooth),
            Models::Switched(mut model) => {
                // The warnings name the file the entry was written from: name this one (an
                // included file's keep their names, which its text fixed).
                for warning in &mut model.warnings {
                    if !key.included.contains(&warning.name) {
                        warning.name.clone_from(&source.name);
                    }
                }
                Some(ModelFile::Switched(model))
            }
        }
    }

    /// Keeps `file`, compiled from the source of `key` (silently not, if the cache cannot be
    /// written).
    pub(crate) fn put(&self, key: &Key, file: &ModelFile) {
        let models = match file {
            ModelFile::Smooth(models) => {
                Models::Smooth(models.iter().map(|m| m.compiled.clone()).collect())
            }
            ModelFile::Switched(model) => Models::Switched(model.clone()),
        };
        let entry = Entry {
            text: key.text.clone(),
            rust: key.source.rust,
            models,
        };
        let _ = self.write(&self.path(key), &encode(&entry));
    }

    /// Writes `bytes` to `path` through a temporary file renamed into place.
    fn write(&self, path: &Path, bytes: &[u8]) -> std::io::Result<()> {
        create_private(&self.dir)?;
        let unique = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos());
        let temporary = path.with_extension(format!("{}.{unique}.tmp", std::process::id()));
        let written = std::fs::File::create(&temporary).and_then(|mut f| {
            f.write_all(bytes)?;
            f.sync_all()
        });
        let renamed = written.and_then(|()| std::fs::rename(&temporary, path));
        if renamed.is_err() {
            let _ = std::fs::remove_file(&temporary);
        }
        renamed
    }
}

/// Creates `dir` and its parents, readable by its owner only.
/// What an entry is kept for: a source and the whole text it is compiled from, its own and
/// that of every file its `include`s read (so an edited included file is a miss, never a
/// stale model). Built once per load: reading the includes lexes the text again, which
/// releases the places of what an earlier read of it returned (`Source::tokens`).
pub(crate) struct Key<'a> {
    source: &'a Source,
    text: String,
    /// The names of the included files, as their errors and warnings give them.
    included: Vec<String>,
}

impl<'a> Key<'a> {
    /// The key of `source` (just its text when it includes nothing, or cannot be read).
    pub(crate) fn of(source: &'a Source) -> Self {
        let files = source.included().unwrap_or_default();
        let mut text = source.text.clone();
        for file in &files {
            text.push_str(&format!("\n\0include {}\n{}", file.name, file.text));
        }
        Key {
            source,
            text,
            included: files.into_iter().map(|file| file.name).collect(),
        }
    }
}

fn create_private(dir: &Path) -> std::io::Result<()> {
    let mut builder = std::fs::DirBuilder::new();
    builder.recursive(true);
    #[cfg(unix)]
    std::os::unix::fs::DirBuilderExt::mode(&mut builder, 0o700);
    builder.create(dir)
}

/// The checksum of an entry's body.
fn checksum(body: &[u8]) -> u64 {
    let mut hasher = DefaultHasher::new();
    body.hash(&mut hasher);
    hasher.finish()
}

/// `FORMAT COMPILER CHECKSUM\n` then the entry as JSON.
fn encode(entry: &Entry) -> Vec<u8> {
    let body = serde_json::to_vec(entry).unwrap_or_default();
    let mut bytes = format!("{FORMAT} {COMPILER} {:016x}\n", checksum(&body)).into_bytes();
    bytes.extend(body);
    bytes
}

/// The entry in `bytes`, if its header is this build's and its checksum matches.
fn decode(bytes: &[u8]) -> Option<Entry> {
    let newline = bytes.iter().position(|&b| b == b'\n')?;
    let (header, body) = (
        std::str::from_utf8(&bytes[..newline]).ok()?,
        &bytes[newline + 1..],
    );
    let mut fields = header.split(' ');
    let valid = fields.next() == Some(FORMAT)
        && fields.next() == Some(COMPILER)
        && fields.next() == Some(&format!("{:016x}", checksum(body)))
        && fields.next().is_none();
    valid.then(|| serde_json::from_slice(body).ok())?
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::CacheUse;

    const BALL: &str = include_str!("../../../model-macros/examples/bouncing_ball.dsl");
    const TOP: &str = include_str!("../../../model-macros/examples/heavy_top.dsl");

    /// A fresh cache directory for one test.
    fn cache(test: &str) -> ModelCache {
        let dir = std::env::temp_dir().join(format!("model-cache-{}-{test}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        ModelCache::at(dir.join("models"))
    }

    fn compiled(file: &ModelFile) -> String {
        match file {
            ModelFile::Smooth(models) => format!(
                "{:?}",
                models.iter().map(|m| &m.compiled).collect::<Vec<_>>()
            ),
            ModelFile::Switched(model) => format!("{model:?}"),
        }
    }

    fn entries(cache: &ModelCache) -> Vec<PathBuf> {
        let mut paths: Vec<PathBuf> = (std::fs::read_dir(cache.dir()).unwrap())
            .map(|e| e.unwrap().path())
            .collect();
        paths.sort();
        paths
    }

    /// A model whose equation is in a file it includes: editing that file (and nothing of the
    /// model's own text) must miss the cache, and the new load must see the edit.
    #[test]
    fn an_edited_included_file_is_a_miss() {
        let cache = cache("included");
        let dir = cache.dir().parent().unwrap().join("sources");
        std::fs::create_dir_all(&dir).unwrap();
        let rows = dir.join("rows.dsl");
        let model = dir.join("decay.dsl");
        std::fs::write(
            &model,
            "mod decay { params { k = 2 } states { x } include \"rows.dsl\"; }",
        )
        .unwrap();
        let rate = |file: &ModelFile| match file {
            ModelFile::Smooth(models) => {
                models[0].compiled.derivatives(0.0, &[1.0], &[2.0]).unwrap()[0]
            }
            ModelFile::Switched(_) => unreachable!("a smooth model"),
        };
        std::fs::write(&rows, "equations { der(x) = -k*x; }").unwrap();
        let first = ModelFile::read_with(&model, Some(&cache)).unwrap();
        let again = ModelFile::read_with(&model, Some(&cache)).unwrap();
        assert_eq!(entries(&cache).len(), 1, "one entry, hit the second time");
        assert_eq!(compiled(&first), compiled(&again));
        std::fs::write(&rows, "equations { der(x) = -3*k*x; }").unwrap();
        let edited = ModelFile::read_with(&model, Some(&cache)).unwrap();
        assert_eq!(
            entries(&cache).len(),
            2,
            "the edit missed and was kept apart"
        );
        assert_eq!((rate(&first), rate(&edited)), (-2.0, -6.0));
    }

    #[test]
    fn a_second_load_hits_and_gives_the_same_models() {
        let cache = cache("hit");
        for (name, text) in [("top.dsl", TOP), ("ball.dsl", BALL)] {
            let source = Source::new(name, text);
            assert!(
                cache.get(&Key::of(&source)).is_none(),
                "{name}: empty cache"
            );
            let fresh = ModelFile::compile(&source).unwrap();
            cache.put(&Key::of(&source), &fresh);
            let kept = cache.get(&Key::of(&source)).expect("a hit");
            // The compiled programs, constants and texts come back exactly.
            assert_eq!(compiled(&kept), compiled(&fresh), "{name}");
            if let (ModelFile::Smooth(a), ModelFile::Smooth(b)) = (&kept, &fresh) {
                let (a, b) = (&a[0].compiled, &b[0].compiled);
                assert_eq!(a, b);
            }
        }
        assert_eq!(entries(&cache).len(), 2);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(cache.dir()).unwrap().permissions().mode();
            assert_eq!(mode & 0o777, 0o700);
        }
    }

    /// A text given by value goes through the cache as a file does: the first compile keeps
    /// its entry, and a second load under another name is that entry (what it returns comes
    /// from the entry, changed here to tell).
    #[test]
    fn a_text_by_value_is_kept_and_found() {
        let cache = cache("text");
        let first = ModelFile::from_text_with("top.dsl", TOP, Some(&cache)).unwrap();
        assert_eq!(entries(&cache).len(), 1);
        let source = Source::new("top.dsl", TOP);
        let ModelFile::Smooth(models) = first else {
            panic!("smooth")
        };
        let mut changed: Vec<CompiledModel> = models.iter().map(|m| m.compiled.clone()).collect();
        changed[0].explanation.markdown = "kept".into();
        let entry = Entry {
            text: TOP.into(),
            rust: false,
            models: Models::Smooth(changed),
        };
        cache
            .write(&cache.path(&Key::of(&source)), &encode(&entry))
            .unwrap();
        let Ok(ModelFile::Smooth(again)) =
            ModelFile::from_text_with("other.dsl", TOP, Some(&cache))
        else {
            panic!("a hit")
        };
        assert_eq!(again[0].compiled.explanation.markdown, "kept");
        let Ok(ModelFile::Smooth(fresh)) = ModelFile::from_text_with("top.dsl", TOP, None) else {
            panic!("compiled")
        };
        assert_ne!(fresh[0].compiled.explanation.markdown, "kept");
    }

    #[test]
    fn a_load_says_what_the_cache_did() {
        let cache = cache("reporting");
        let load = |cache| ModelFile::from_text_reporting("top.dsl", TOP, cache).unwrap();
        assert_eq!(load(None).cache, CacheUse::Off);
        assert!(!cache.dir().exists());
        assert_eq!(load(Some(&cache)).cache, CacheUse::Miss);
        assert_eq!(entries(&cache).len(), 1);
        assert_eq!(load(Some(&cache)).cache, CacheUse::Hit);
        // A file's text is the same entry as the text given by value.
        let dir = cache.dir().parent().unwrap().join("reporting-file");
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("top.dsl");
        std::fs::write(&path, TOP).unwrap();
        let read = ModelFile::read_reporting(&path, Some(&cache)).unwrap();
        assert_eq!(read.cache, CacheUse::Hit);
        // An entry that no longer checks is a miss, and is written again.
        for entry in entries(&cache) {
            std::fs::write(entry, "not an entry").unwrap();
        }
        assert_eq!(load(Some(&cache)).cache, CacheUse::Miss);
        assert_eq!(load(Some(&cache)).cache, CacheUse::Hit);
    }

    #[test]
    fn what_a_hit_returns_comes_from_the_entry() {
        let cache = cache("from-entry");
        let source = Source::new("top.dsl", TOP);
        let ModelFile::Smooth(models) = ModelFile::compile(&source).unwrap() else {
            panic!("smooth")
        };
        let mut changed: Vec<CompiledModel> = models.iter().map(|m| m.compiled.clone()).collect();
        changed[0].explanation.markdown = "kept".into();
        let entry = Entry {
            text: TOP.into(),
            rust: false,
            models: Models::Smooth(changed),
        };
        cache
            .write(&cache.path(&Key::of(&source)), &encode(&entry))
            .unwrap();
        let Some(ModelFile::Smooth(kept)) = cache.get(&Key::of(&source)) else {
            panic!("a hit")
        };
        assert_eq!(kept[0].compiled.explanation.markdown, "kept");
    }

    #[test]
    fn corrupted_foreign_and_stale_entries_are_ignored() {
        let cache = cache("bad");
        let source = Source::new("top.dsl", TOP);
        let file = ModelFile::compile(&source).unwrap();
        cache.put(&Key::of(&source), &file);
        let path = cache.path(&Key::of(&source));
        let good = std::fs::read(&path).unwrap();
        let check = |bytes: &[u8], what: &str| {
            std::fs::write(&path, bytes).unwrap();
            assert!(cache.get(&Key::of(&source)).is_none(), "{what} was trusted");
        };
        // One byte of the body changed (a digit of a constant: still valid JSON).
        let digit = good.iter().rposition(|b| b.is_ascii_digit()).unwrap();
        let mut flipped = good.clone();
        flipped[digit] = if good[digit] == b'7' { b'8' } else { b'7' };
        check(&flipped, "a changed digit");
        check(&good[..good.len() / 2], "a truncated entry");
        check(b"", "an empty entry");
        let other =
            String::from_utf8(good.clone())
                .unwrap()
                .replacen(COMPILER, "0123456789abcdef", 1);
        check(other.as_bytes(), "another compiler's entry");
        // A whole valid entry of another text, under this text's name.
        let ball = Source::new("ball.dsl", BALL);
        cache.put(&Key::of(&ball), &ModelFile::compile(&ball).unwrap());
        check(
            &std::fs::read(cache.path(&Key::of(&ball))).unwrap(),
            "another text's entry",
        );
        // The same text read as Rust is another source.
        std::fs::write(&path, &good).unwrap();
        assert!(cache.get(&Key::of(&Source::rust("top.rs", TOP))).is_none());
        assert!(
            cache.get(&Key::of(&source)).is_some(),
            "the good entry is used"
        );
    }

    #[test]
    fn racing_writers_leave_one_valid_entry() {
        let cache = cache("race");
        let want = compiled(&ModelFile::compile(&Source::new("ball.dsl", BALL)).unwrap());
        std::thread::scope(|scope| {
            for _ in 0..8 {
                scope.spawn(|| {
                    // Each writer compiles on its own thread (a syntax tree stays on its own).
                    let source = Source::new("ball.dsl", BALL);
                    let file = ModelFile::compile(&source).unwrap();
                    for _ in 0..20 {
                        cache.put(&Key::of(&source), &file);
                        // A reader racing the writers sees a whole entry or none.
                        if let Some(kept) = cache.get(&Key::of(&source)) {
                            assert_eq!(compiled(&kept), want);
                        }
                    }
                });
            }
        });
        let source = Source::new("ball.dsl", BALL);
        assert_eq!(
            entries(&cache),
            vec![cache.path(&Key::of(&source))],
            "no temporary left"
        );
        assert_eq!(compiled(&cache.get(&Key::of(&source)).unwrap()), want);
    }
}
