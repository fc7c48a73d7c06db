//! The layering ARCHITECTURE.md promises, checked against the manifests, the lock files and
//! the code.
//!
//! Three invariants hold the workspace together. The compiler and the runtime are generic:
//! they know no disk, so a user's model gets the same machinery the disk gets, and a change to
//! the disk cannot break them. The crates form layers with edges in one direction only, so each
//! can be read, tested and changed with only what is below it. And the front ends are thin:
//! the flags, the terminal and Ctrl-C are the command line's, so the library under it (and the
//! Python package over that library) links none of their crates. All are easy to break with
//! one innocent `use` or one line of a `Cargo.toml`; this file says where, by name.

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
        name: "model-macros-ui",
        dir: "model-macros/ui",
        may_use: &[],
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
    Layer {
        name: "eulerdisk-pipeline",
        dir: "pipeline",
        may_use: &[
            "model-dsl",
            "model-runtime",
            "model-interpreted",
            "equations",
        ],
        generic: false,
    },
    Layer {
        name: "eulerdisk-parquet",
        dir: "pipeline/parquet",
        may_use: &["eulerdisk-pipeline", "equations"],
        generic: false,
    },
];

/// The command line's own crates: flags, the terminal's progress bars, Ctrl-C. Only the
/// `eulerdisk` binary may link them.
const COMMAND_LINE_CRATES: &[&str] = &["clap", "indicatif", "ctrlc"];

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
    let front_ends = ["eulerdisk", "eulerdisk-fuzz", "eulerdisk-python"];
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

/// The dependency lists of a lock file's packages, by name (every version's, joined): the
/// names of the packages each may link.
fn locked_dependencies(lock: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let text = std::fs::read_to_string(lock).unwrap();
    let doc: toml::Table = toml::from_str(&text).unwrap();
    let mut out: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for package in doc["package"].as_array().unwrap() {
        let name = package["name"].as_str().unwrap().to_string();
        let deps = out.entry(name).or_default();
        for dep in package
            .get("dependencies")
            .and_then(|d| d.as_array())
            .into_iter()
            .flatten()
        {
            // `name` or, where two versions are locked, `name version`.
            let dep = dep.as_str().unwrap();
            deps.insert(dep.split(' ').next().unwrap().to_string());
        }
    }
    out
}

/// The packages a workspace crate links: its normal and build dependencies from the
/// manifests for the workspace's crates (the lock file lists their dev-dependencies too),
/// and from `Cargo.lock` below them. Optional dependencies count, whatever the features.
fn linked_by(name: &str) -> BTreeSet<String> {
    let crates = workspace_crates();
    let locked = locked_dependencies(&root().join("Cargo.lock"));
    let mut seen = BTreeSet::new();
    let mut todo = vec![name.to_string()];
    while let Some(package) = todo.pop() {
        if !seen.insert(package.clone()) {
            continue;
        }
        let deps = match crates.get(&package) {
            Some(dir) => normal_deps(&dir.join("Cargo.toml")),
            None => locked.get(&package).cloned().unwrap_or_default(),
        };
        todo.extend(deps);
    }
    seen.remove(name);
    seen
}

/// The packages a manifest names in its normal and build dependencies.
fn normal_deps(manifest: &Path) -> BTreeSet<String> {
    let doc: toml::Table = toml::from_str(&std::fs::read_to_string(manifest).unwrap()).unwrap();
    let mut out = BTreeSet::new();
    for table in ["dependencies", "build-dependencies"] {
        for (key, spec) in doc
            .get(table)
            .and_then(|t| t.as_table())
            .into_iter()
            .flatten()
        {
            let renamed = spec.get("package").and_then(|p| p.as_str());
            out.insert(renamed.unwrap_or(key).to_string());
        }
    }
    out
}

/// The command line's crates among `packages`.
fn command_line_crates<'a>(packages: impl IntoIterator<Item = &'a String>) -> Vec<&'a str> {
    (packages.into_iter())
        .map(String::as_str)
        .filter(|p| COMMAND_LINE_CRATES.contains(p))
        .collect()
}

#[test]
fn the_library_links_no_command_line_crate() {
    let linked = linked_by("eulerdisk-pipeline");
    assert!(
        linked.contains("equations") && linked.contains("serde"),
        "{linked:?}"
    );
    let found = command_line_crates(&linked);
    assert!(
        found.is_empty(),
        "the library (pipeline/) links the command line's crates {found:?}: they belong to \
         the `eulerdisk` binary (src/)"
    );
}

#[test]
fn the_link_check_sees_the_command_line() {
    // The same walk from the binary finds all three: the check above can fail.
    let linked = linked_by("eulerdisk");
    let mut expected = COMMAND_LINE_CRATES.to_vec();
    expected.sort_unstable();
    assert_eq!(command_line_crates(&linked), expected);
}

#[test]
fn the_library_manifest_names_no_command_line_crate() {
    // Not even as a dev-dependency or for one target: the library's own tests run without a
    // command line.
    let text = std::fs::read_to_string(root().join("pipeline/Cargo.toml")).unwrap();
    let doc: toml::Table = toml::from_str(&text).unwrap();
    let sections = ["dependencies", "dev-dependencies", "build-dependencies"];
    let targets = doc.get("target").and_then(|t| t.as_table());
    let owners = std::iter::once(&doc)
        .chain((targets.into_iter().flat_map(|t| t.values())).filter_map(|t| t.as_table()));
    let tables = owners.flat_map(|t| sections.iter().filter_map(move |s| t.get(*s)?.as_table()));
    let named: Vec<&String> = tables.flat_map(|t| t.keys()).collect();
    assert!(named.iter().any(|n| *n == "equations"), "{named:?}");
    let found = command_line_crates(named);
    assert!(found.is_empty(), "pipeline/Cargo.toml names {found:?}");
}

#[test]
fn the_python_package_links_no_command_line_crate() {
    let linked = linked_by("eulerdisk-python");
    assert!(
        linked.contains("eulerdisk-pipeline") && linked.contains("pyo3"),
        "{linked:?}"
    );
    let found = command_line_crates(&linked);
    assert!(
        found.is_empty(),
        "the Python package (python/) links the command line's crates {found:?}: it must \
         depend on the library (pipeline/), not on the binary"
    );
}

/// Files `foo.rs` that sit beside a folder `foo/` under `dir`: a module written in the other
/// style. A module with children is a folder with its `mod.rs` (ARCHITECTURE.md, "Conventions").
fn files_beside_their_folder(dir: &Path) -> Vec<String> {
    let mut found = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return found;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name();
        if path.is_dir() {
            if name != "target" && !name.to_string_lossy().starts_with('.') {
                found.extend(files_beside_their_folder(&path));
            }
        } else if path.extension().is_some_and(|e| e == "rs") && path.with_extension("").is_dir() {
            found.push(path.display().to_string());
        }
    }
    found
}

#[test]
fn every_module_with_children_is_a_folder_with_its_mod_rs() {
    let mut found = Vec::new();
    for dir in workspace_crates()
        .into_values()
        .chain([root().join("python")])
    {
        for part in ["src", "tests", "benches", "examples"] {
            found.extend(files_beside_their_folder(&dir.join(part)));
        }
    }
    assert!(
        found.is_empty(),
        "modules written as `foo.rs` beside `foo/` (move them to `foo/mod.rs`): {found:?}"
    );
}

#[test]
fn the_module_style_check_sees_a_file_beside_its_folder() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("src/events")).unwrap();
    std::fs::write(dir.path().join("src/events.rs"), "mod tracker;").unwrap();
    std::fs::write(dir.path().join("src/events/tracker.rs"), "").unwrap();
    std::fs::create_dir_all(dir.path().join("src/hybrid")).unwrap();
    std::fs::write(dir.path().join("src/hybrid/mod.rs"), "").unwrap();
    let found = files_beside_their_folder(&dir.path().join("src"));
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].ends_with("events.rs"), "{found:?}");
}
