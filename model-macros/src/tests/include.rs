//! An expansion that includes files makes the compiler track each of them, so that an edited
//! row expands the model again.

use crate::expand::expand_in;

#[test]
fn every_included_file_is_tracked_by_include_str() {
    let dir = std::env::temp_dir().join(format!("macro-include-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("rows")).unwrap();
    std::fs::write(
        dir.join("rows/decay.dsl"),
        "include \"rate.dsl\";\nequations { der(x) = -r*x; }",
    )
    .unwrap();
    std::fs::write(dir.join("rows/rate.dsl"), "let r = 2*k;").unwrap();
    let tokens = "mod m { params { k = 1 } states { x } include \"rows/decay.dsl\"; }";
    let output = expand_in(tokens.parse().unwrap(), Some(&dir.join("m.rs"))).to_string();
    assert!(!output.contains("compile_error"), "{output}");
    for file in ["rows/decay.dsl", "rows/rate.dsl"] {
        let path = dir.join(file).canonicalize().unwrap();
        let tracked = format!(
            "const _ : & str = include_str ! ({:?}) ;",
            path.display().to_string()
        );
        assert!(output.contains(&tracked), "{file} is not tracked: {output}");
    }
    // An expansion that fails still tracks what it read: the fix is in the file.
    std::fs::write(dir.join("rows/rate.dsl"), "let r = 2*kk;").unwrap();
    let output = expand_in(tokens.parse().unwrap(), Some(&dir.join("m.rs"))).to_string();
    assert!(
        output.contains("compile_error") && output.contains("rate.dsl"),
        "{output}"
    );
}
