//! The compiler's version for the cache of compiled models: a hash of the sources of every
//! stage that derives a model's programs from its text (the front end, the equation compiler
//! and this crate), so that an entry written by another build is never read as this one's.

use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::{Path, PathBuf};

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs" || e == "toml") {
            out.push(path);
        }
    }
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dirs = [
        root.join("src"),
        root.join("Cargo.toml"),
        root.join("../../model-macros/algebra/src"),
        root.join("../../model-macros/algebra/Cargo.toml"),
        root.join("../../model-macros/dsl/src"),
        root.join("../../model-macros/dsl/Cargo.toml"),
        root.join("../ops/src"),
    ];
    let mut files = Vec::new();
    for dir in &dirs {
        println!("cargo::rerun-if-changed={}", dir.display());
        match dir.is_dir() {
            true => sources(dir, &mut files),
            false => files.push(dir.clone()),
        }
    }
    files.sort();
    let mut hasher = DefaultHasher::new();
    for file in &files {
        let relative = file.strip_prefix(root).unwrap_or(file);
        relative.to_string_lossy().hash(&mut hasher);
        std::fs::read(file).unwrap_or_default().hash(&mut hasher);
    }
    println!(
        "cargo::rustc-env=MODEL_COMPILER_HASH={:016x}",
        hasher.finish()
    );
}
