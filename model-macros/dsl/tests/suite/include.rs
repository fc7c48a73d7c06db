//! `include "rows.dsl";`: a file's items parsed where the `include` stands, in a model or in a
//! mode; its errors located in it; a missing file, a cycle and a file that does not lex
//! refused at the `include` that reads it.

use model_dsl::{Located, Source};
use std::path::{Path, PathBuf};

/// A fresh folder holding `files` (path relative to it, text), for one test.
fn folder(test: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("dsl-include-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    for (path, text) in files {
        let path = dir.join(path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    dir
}

/// The source of the file `path`.
fn source(path: &Path) -> Source {
    Source::read(path).unwrap()
}

/// The errors of the model in `path`, which must be rejected.
fn errors(path: &Path) -> Vec<Located> {
    source(path).compile().expect_err("must be rejected").0
}

/// The derivatives of the first model of `source` at `y` with its parameters' defaults.
fn derivatives(source: &Source, y: &[f64], params: &[f64]) -> Vec<f64> {
    let models = source.compile().unwrap_or_else(|e| panic!("{e}"));
    models[0].compiled.derivatives(0.3, y, params).unwrap()
}

const ROWS: &str = "\
// A damped oscillator's rows: `c` is the including model's.
let spring = -k*x;
equations {
    der(x) = v;
    der(v) = spring - c*v;
}
";

#[test]
fn an_included_file_is_read_where_the_include_stands() {
    let inline = "mod osc { params { k = 4 } states { x, v } let spring = -k*x; let c = 0.5*k; \
                  equations { der(x) = v; der(v) = spring - c*v; } }";
    let dir = folder(
        "in-place",
        &[
            ("rows.dsl", ROWS),
            (
                "osc.dsl",
                "mod osc { params { k = 4 } states { x, v } let c = 0.5*k; include \"rows.dsl\"; }",
            ),
        ],
    );
    let y = [0.7, -1.3];
    let included = derivatives(&source(&dir.join("osc.dsl")), &y, &[4.0]);
    let written = derivatives(&Source::new("inline.dsl", inline), &y, &[4.0]);
    // der(v) = -k x - 0.5 k v, by hand.
    assert_eq!(included, [-1.3, -4.0 * 0.7 + 0.5 * 4.0 * 1.3]);
    assert_eq!(included, written);
    let files = source(&dir.join("osc.dsl")).included().unwrap();
    assert_eq!(files.len(), 1);
    assert_eq!(
        (files[0].written.as_str(), files[0].text.as_str()),
        ("rows.dsl", ROWS)
    );
}

/// The same rows in two models whose lets differ: one with the damping as an expression, one
/// with it zero at compile time (as the disk's mode graph reads the air's terms).
#[test]
fn the_rows_read_the_lets_of_the_model_that_includes_them() {
    let dir = folder(
        "lets",
        &[
            ("shared/rows.dsl", ROWS),
            (
                "damped.dsl",
                "mod damped { params { k = 4, mu = 0.1 } states { x, v } let c = mu*k; include \"shared/rows.dsl\"; }",
            ),
            (
                "free.dsl",
                "mod free { params { k = 4 } states { x, v } let c = 0; include \"shared/rows.dsl\"; }",
            ),
        ],
    );
    let y = [0.5, 2.0];
    let damped = derivatives(&source(&dir.join("damped.dsl")), &y, &[4.0, 0.1]);
    let free = derivatives(&source(&dir.join("free.dsl")), &y, &[4.0]);
    assert_eq!(damped, [2.0, -2.0 - 0.4 * 2.0]);
    assert_eq!(free, [2.0, -2.0]);
}

/// A switched model whose modes include their rows; an include in an included file is
/// relative to that file's folder.
#[test]
fn a_mode_includes_its_rows_and_includes_nest() {
    let dir = folder(
        "modes",
        &[
            (
                "rows/slow.dsl",
                "include \"decay.dsl\";\nwhen fast: x > 2 -> fast;",
            ),
            ("rows/decay.dsl", "equations { der(x) = r*x; }"),
            (
                "ball.dsl",
                "mod grow { params { r = 1 } states { x = 1 } \
                 mode slow { include \"rows/slow.dsl\"; } \
                 mode fast { equations { der(x) = 2*r*x; } } }",
            ),
        ],
    );
    let compiled = source(&dir.join("ball.dsl"))
        .compile_switched()
        .unwrap_or_else(|e| panic!("{e}"));
    let names: Vec<&str> = (compiled.modes.iter())
        .map(|m| m.model.name.as_str())
        .collect();
    assert_eq!(names, ["slow", "fast"]);
    let slow = compiled.modes[0]
        .model
        .derivatives(0.0, &[1.5], &[1.0])
        .unwrap();
    assert_eq!(slow, [1.5]);
    let events: Vec<&str> = (compiled.modes[0].events.iter())
        .map(|e| e.name.as_str())
        .collect();
    assert_eq!(events, ["fast"]);
    let files = source(&dir.join("ball.dsl")).included().unwrap();
    let written: Vec<&str> = files.iter().map(|f| f.written.as_str()).collect();
    assert_eq!(written, ["rows/slow.dsl", "decay.dsl"]);
    assert_eq!((files[0].parent, files[1].parent), (None, Some(0)));
}

/// An error inside an included file is that file's: its name, line and column, its line under
/// the caret; and it is reported once.
#[test]
fn an_error_in_an_included_file_is_located_in_it_once() {
    let rows = "equations {\n    der(x) = v;\n    der(v) = -kk*x;\n}\n";
    let dir = folder(
        "located",
        &[
            ("rows.dsl", rows),
            (
                "osc.dsl",
                "mod osc {\n    states { x, v }\n    include \"rows.dsl\";\n}\n",
            ),
        ],
    );
    let found = errors(&dir.join("osc.dsl"));
    assert_eq!(found.len(), 1, "{found:#?}");
    let error = &found[0];
    assert!(error.name.ends_with("rows.dsl"), "{error}");
    assert_eq!(
        (error.line, error.column, error.width),
        (3, 15, 2),
        "{error}"
    );
    assert_eq!(error.source_line, "    der(v) = -kk*x;");
    assert!(error.message.starts_with("unknown name `kk`"), "{error}");
}

/// A syntax error in an included file: located in it, and the rest of the model still read
/// (the error in the including file is found too).
#[test]
fn a_syntax_error_in_an_included_file_is_located_in_it() {
    let dir = folder(
        "syntax",
        &[
            ("rows.dsl", "equations {\n    der(x) = v\n    der(v) = -x;\n}\n"),
            ("osc.dsl", "mod osc {\n    states { x, v }\n    include \"rows.dsl\";\n    outputs { e = zz; }\n}\n"),
        ],
    );
    let found = errors(&dir.join("osc.dsl"));
    let places: Vec<(bool, usize)> = (found.iter())
        .map(|e| (e.name.ends_with("rows.dsl"), e.line))
        .collect();
    assert_eq!(places, [(true, 3)], "{found:#?}");
    assert!(found[0].message.contains("expected `;`"), "{}", found[0]);
}

#[test]
fn a_missing_file_is_refused_at_its_include_naming_the_path() {
    let dir = folder(
        "missing",
        &[("osc.dsl", "mod osc {\n    states { x }\n    include \"nowhere/rows.dsl\";\n    equations { der(x) = 1; }\n}\n")],
    );
    let found = errors(&dir.join("osc.dsl"));
    assert_eq!(found.len(), 1, "{found:#?}");
    assert!(found[0].name.ends_with("osc.dsl"));
    assert_eq!((found[0].line, found[0].column), (3, 13), "{}", found[0]);
    assert!(
        found[0]
            .message
            .starts_with("cannot read the included file `nowhere/rows.dsl`"),
        "{}",
        found[0]
    );
}

#[test]
fn an_include_cycle_is_refused_naming_the_chain() {
    let dir = folder(
        "cycle",
        &[
            ("a.dsl", "include \"b.dsl\";"),
            ("b.dsl", "let y = 1;\ninclude \"a.dsl\";"),
            (
                "m.dsl",
                "mod m { states { x } include \"a.dsl\"; equations { der(x) = y; } }",
            ),
            (
                "self.dsl",
                "mod s { states { x } include \"self.dsl\"; equations { der(x) = 1; } }",
            ),
        ],
    );
    let found = errors(&dir.join("m.dsl"));
    assert_eq!(found.len(), 1, "{found:#?}");
    assert!(
        found[0].name.ends_with("b.dsl"),
        "at the include that closes it: {}",
        found[0]
    );
    assert!(
        found[0]
            .message
            .contains("the includes a.dsl -> b.dsl -> a.dsl form a cycle"),
        "{}",
        found[0]
    );
    let own = errors(&dir.join("self.dsl"));
    assert!(own[0].message.contains("form a cycle"), "{}", own[0]);
}

#[test]
fn a_file_that_does_not_lex_is_refused_at_its_include_with_its_place() {
    let dir = folder(
        "lexical",
        &[
            ("rows.dsl", "let s = 1;\nequations { der(x) = (s; }\n"),
            ("m.dsl", "mod m { states { x } include \"rows.dsl\"; }"),
        ],
    );
    let found = errors(&dir.join("m.dsl"));
    assert_eq!(found.len(), 1, "{found:#?}");
    assert!(found[0].name.ends_with("m.dsl"));
    assert!(
        found[0].message.starts_with(
            "in the included file `rows.dsl`, line 2, column 22: this `(` is never closed"
        ),
        "{}",
        found[0]
    );
}

#[test]
fn an_include_without_a_path_is_a_syntax_error_and_the_rest_is_read() {
    let text = "mod m { states { x } include rows; equations { der(x) = 2 ** x; } }";
    let found = Source::new("m.dsl", text).parse().unwrap_err().0;
    let messages: Vec<&str> = found.iter().map(|e| e.message.as_str()).collect();
    assert_eq!(messages.len(), 2, "{messages:#?}");
    assert!(messages[0].starts_with("expected the path of the file to include"));
    assert!(
        messages[1].contains("`^`"),
        "the next statement is read: {messages:#?}"
    );
}

/// The disk's models, read as text from their Rust files: the rows come from the `.dsl`
/// files beside them, and both the smooth model and the mode graph compile.
#[test]
fn the_disk_reads_its_rows_from_the_files_beside_it() {
    let _large = crate::hostile::large();
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../equations/src");
    let rolling = source(&Path::new(root).join("models/box1_rolling.rs"));
    let files = rolling.included().unwrap();
    let written: Vec<&str> = files.iter().map(|f| f.written.as_str()).collect();
    assert_eq!(written, ["disk.dsl", "box1_rolling.dsl"]);
    assert!(files[1]
        .text
        .contains("R12: cos(theta)*der(psi) + der(phi) = Omega_z;"));
    assert_eq!(rolling.compile().unwrap()[0].compiled.states.len(), 12);
    let graph = source(&Path::new(root).join("hybrid/switching.rs"));
    let written: Vec<String> = (graph.included().unwrap().into_iter())
        .map(|f| f.written)
        .collect();
    assert_eq!(
        written,
        ["../models/box1_rolling.dsl", "../models/box3_sliding.dsl"]
    );
}
