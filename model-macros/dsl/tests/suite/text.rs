//! A model read from text: every error located at its token, as `file:line:col`, with the line
//! and a caret; a model inside a Rust file located in that file.

use model_dsl::{Located, Source};

fn errors(source: &Source) -> Vec<Located> {
    source.compile().expect_err("must be rejected").0
}

#[test]
fn every_error_is_located_at_its_token() {
    let text = "mod m {\n    states { x, y }\n    equations {\n        der(x) = -kk * x;\n        der(y) = sine(x);\n    }\n}\n";
    let found = errors(&Source::new("two.dsl", text));
    let places: Vec<(usize, usize, usize)> =
        found.iter().map(|e| (e.line, e.column, e.width)).collect();
    assert_eq!(places, [(4, 19, 2), (5, 18, 4)], "{found:#?}");
    assert!(found[0].message.starts_with("unknown name `kk`"));
    assert!(found[1]
        .message
        .starts_with("unknown function `sine` (did you mean `sin`?)"));
    let shown = found[0].to_string();
    assert_eq!(
        shown.lines().collect::<Vec<_>>(),
        [
            &*format!("two.dsl:4:19: {}", found[0].message),
            "  |",
            "4 |         der(x) = -kk * x;",
            "  |                   ^^",
        ]
    );
}

#[test]
fn a_range_is_underlined_whole_and_compiler_errors_are_located_too() {
    // The compiler (not the validator) finds the product of two derivatives.
    let text = "mod m { states { x, y } equations { der(x) * der(y) = 1; der(y) = x; } }";
    let found = errors(&Source::new("product.dsl", text));
    assert_eq!(found.len(), 1, "{found:#?}");
    let at = text.find("der(x) * der(y)").unwrap();
    assert_eq!((found[0].line, found[0].column), (1, at + 1));
    assert_eq!(found[0].width, "der(x) * der(y)".len());
}

#[test]
fn lexical_errors_and_empty_text_are_errors_not_panics() {
    let unclosed = errors(&Source::new("open.dsl", "mod m {\n    states { x }\n"));
    assert_eq!(unclosed.len(), 1);
    assert_eq!(unclosed[0].name, "open.dsl");
    let empty = errors(&Source::new("empty.dsl", ""));
    assert_eq!(empty.len(), 1);
    assert_eq!(empty[0].line, 1);
    let garbage = errors(&Source::new("garbage.dsl", "\"unterminated"));
    assert_eq!(garbage.len(), 1);
}

#[test]
fn a_model_in_a_rust_file_is_located_in_that_file() {
    let rust = "//! A crate.\n\nmodel_macros::model! {\n    pub mod m {\n        states { x }\n        equations { der(x) = -q; }\n    }\n}\n\nfn main() {}\n";
    let found = errors(&Source::rust("lib.rs", rust));
    assert_eq!((found[0].line, found[0].column), (6, 31), "{found:#?}");
    let fine = rust.replace("-q", "-x");
    let models = Source::rust("lib.rs", fine).compile().unwrap();
    assert_eq!(models[0].compiled.name, "m");
    let none = errors(&Source::rust("empty.rs", "fn main() {}"));
    assert_eq!(none[0].message, "no `model! { .. }` in this file");
}

#[test]
fn a_chart_is_compiled_after_its_model() {
    let text = "mod osc {
        params { w = 2 }
        states { x, v }
        equations { der(x) = v; der(v) = -w^2 * x; }
        chart polar { states { r, phi } replace { x, v } let x = r * cos(phi); let v = -w * r * sin(phi); }
    }";
    let models = Source::new("osc.dsl", text).compile().unwrap();
    let names: Vec<&str> = models.iter().map(|m| m.compiled.name.as_str()).collect();
    assert_eq!(names, ["osc", "polar"]);
    assert_eq!(models[1].compiled.states, ["r", "phi"]);
    // The chart turns at constant amplitude and rate w.
    let der = models[1]
        .compiled
        .derivatives(0.0, &[1.5, 0.3], &[2.0])
        .unwrap();
    assert!(
        der[0].abs() < 1e-14 && (der[1] - 2.0).abs() < 1e-14,
        "{der:?}"
    );
    // A mistake in a shared row is reported once, not once per chart.
    let broken = text.replace("-w^2 * x", "-w^2 * xx");
    assert_eq!(errors(&Source::new("osc.dsl", broken)).len(), 1);
}
