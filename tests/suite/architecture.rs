//! The layering ARCHITECTURE.md promises, checked against the manifests and the code.
//!
//! Two invariants hold the workspace together. The compiler and the runtime are generic: they
//! know no disk, so a user's model gets the same machinery the disk gets, and a change to the
//! disk cannot break them. And the crates form layers with edges in one direction only, so each
//! can be read, tested and changed with only what is below it. Both are easy to break with one
//! innocent `use` or one line of a `Cargo.toml`; this file says where, by name.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use super::imports::{code_only, rust_files, tokens, without_test_items};

/// A workspace crate: its name and folder, and the workspace crates it may use (normal and
/// build dependencies; tests and benches may use more).
struct Layer {
    name: &'static str,
    dir: &'static str,
    may_use: &'static [&'static str],
    /// Generic: no disk in its code or its dependencies.
    generic: bool,
}

/// The crate graph, bottom to top (ARCHITECTURE.md, "Code map").
const LAYERS: &[Layer] = &[
    Layer {
        name: "model-ops",
        dir: "model-runtime/ops",
        may_use: &[],
        generic: true,
    },
    Layer {
        name: "model-algebra",
        dir: "model-macros/algebra",
        may_use: &["model-ops"],
        generic: true,
    },
    Layer {
        name: "model-dsl",
        dir: "model-macros/dsl",
        may_use: &["model-algebra"],
        generic: true,
    },
    Layer {
        name: "model-macros",
        dir: "model-macros",
        may_use: &["model-algebra", "model-dsl"],
        generic: true,
    },
    Layer {
        name: "model-runtime",
        dir: "model-runtime",
        may_use: &["model-ops"],
        generic: true,
    },
    Layer {
        name: "model-jit",
        dir: "model-runtime/jit",
        may_use: &["model-algebra"],
        generic: true,
    },
    Layer {
        name: "model-interpreted",
        dir: "model-runtime/interpreted",
        may_use: &[
            "model-algebra",
            "model-dsl",
            "model-runtime",
            "model-ops",
            "model-jit",
        ],
        generic: true,
    },
    Layer {
        name: "equations",
        dir: "equations",
        may_use: &["model-macros", "model-runtime"],
        generic: false,
    },
];

/// The disk's crates: a generic crate's code may not name a path into them.
const DISK_CRATES: &[&str] = &["equations", "eulerdisk"];

/// Words that belong to the disk: its types, its parameters and its paper's quantities. None of
/// them may be an identifier in a generic crate's code (comments may still say "the disk").
const DISK_WORDS: &[&str] = &[
    "DiskParams",
    "DiskScene",
    "mu_st",
    "mu_d",
    "Omega_x",
    "Omega_y",
    "Omega_z",
    "rolling",
    "sliding",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The workspace crates named in a manifest's normal and build dependencies.
fn workspace_deps(manifest: &Path, known: &BTreeSet<&str>) -> BTreeSet<String> {
    let text = std::fs::read_to_string(manifest).unwrap();
    let doc: toml::Table = toml::from_str(&text).unwrap();
    let mut out = BTreeSet::new();
    for table in ["dependencies", "build-dependencies"] {
        if let Some(deps) = doc.get(table).and_then(|t| t.as_table()) {
            out.extend(deps.keys().filter(|k| known.contains(k.as_str())).cloned());
        }
    }
    out
}

/// Every workspace crate's name, from the root manifest's members.
fn workspace_crates() -> BTreeMap<String, PathBuf> {
    let text = std::fs::read_to_string(root().join("Cargo.toml")).unwrap();
    let doc: toml::Table = toml::from_str(&text).unwrap();
    let members = doc["workspace"]["members"].as_array().unwrap();
    members
        .iter()
        .map(|m| {
            let dir = root().join(m.as_str().unwrap());
            let manifest: toml::Table =
                toml::from_str(&std::fs::read_to_string(dir.join("Cargo.toml")).unwrap()).unwrap();
            (
                manifest["package"]["name"].as_str().unwrap().to_string(),
                dir,
            )
        })
        .collect()
}

/// The edges of `layers` that their manifests have and the layering forbids.
fn wrong_edges(layers: &[Layer]) -> Vec<String> {
    let crates = workspace_crates();
    let known: BTreeSet<&str> = crates.keys().map(String::as_str).collect();
    let mut wrong = Vec::new();
    for layer in layers {
        let manifest = root().join(layer.dir).join("Cargo.toml");
        for dep in workspace_deps(&manifest, &known) {
            if !layer.may_use.contains(&dep.as_str()) {
                wrong.push(format!("{} uses {dep}", layer.name));
            }
        }
    }
    wrong
}

#[test]
fn crates_use_only_the_layers_below_them() {
    let wrong = wrong_edges(LAYERS);
    assert!(
        wrong.is_empty(),
        "edges against the layering (ARCHITECTURE.md): {wrong:?}"
    );
}

#[test]
fn every_library_crate_has_a_layer() {
    // A new crate must be placed in the layering, or the check above says nothing about it.
    let placed: BTreeSet<&str> = LAYERS.iter().map(|l| l.name).collect();
    let front_ends = ["eulerdisk", "eulerdisk-fuzz"];
    let unplaced: Vec<String> = workspace_crates()
        .into_keys()
        .filter(|c| !placed.contains(c.as_str()) && !front_ends.contains(&c.as_str()))
        .collect();
    assert!(
        unplaced.is_empty(),
        "crates missing from LAYERS: {unplaced:?}"
    );
}

/// The disk words used as identifiers in a crate's code, with the file.
fn disk_words_in(dir: &Path) -> Vec<String> {
    let mut files = Vec::new();
    rust_files(&dir.join("src"), &mut files);
    // Unit-test files (`src/tests/`, `tests.rs`) may compare against anything.
    files.retain(|f| !f.components().any(|c| c.as_os_str() == "tests") && !f.ends_with("tests.rs"));
    let mut found = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        let toks = tokens(&without_test_items(&code_only(&text)));
        for (i, token) in toks.iter().enumerate() {
            let crate_path =
                DISK_CRATES.contains(&token.as_str()) && toks.get(i + 1).is_some_and(|t| t == "::");
            if crate_path || DISK_WORDS.contains(&token.as_str()) {
                let file = file.strip_prefix(root()).unwrap().display();
                found.push(format!("{file}: `{token}`"));
            }
        }
    }
    found
}

#[test]
fn the_generic_crates_know_no_disk() {
    let mut found = Vec::new();
    for layer in LAYERS.iter().filter(|l| l.generic) {
        found.extend(disk_words_in(&root().join(layer.dir)));
    }
    assert!(
        found.is_empty(),
        "disk words in the generic crates' code: {found:?}"
    );
}

#[test]
fn the_disk_check_sees_the_disk() {
    // The same scan over the disk's crate finds its words: the check above can fail.
    let found = disk_words_in(&root().join("equations"));
    assert!(found.iter().any(|f| f.contains("`mu_st`")), "{found:?}");
    assert!(
        found.iter().any(|f| f.contains("`DiskParams`")),
        "{found:?}"
    );
}

#[test]
fn the_layer_check_sees_a_wrong_edge() {
    // Were the disk's crate a layer that may use only the runtime, its use of the macros
    // would be reported: the check above can fail.
    let strict = [Layer {
        name: "equations",
        dir: "equations",
        may_use: &["model-runtime"],
        generic: false,
    }];
    assert_eq!(
        wrong_edges(&strict),
        vec!["equations uses model-macros".to_string()]
    );
}
