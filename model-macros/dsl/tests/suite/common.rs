//! Models from DSL text, through the one front end.

use model_algebra::ModelSpec;
use model_dsl::{spec_unchecked, validate, Source, Validated};

/// The model `text` (`mod NAME { .. }`) and its charts, parsed and validated as `model!` does.
fn validated(text: &str) -> Vec<Validated> {
    let ast = Source::new("test", text)
        .parse()
        .unwrap_or_else(|e| panic!("{e}"));
    validate(&ast).unwrap_or_else(|e| panic!("{e}"))
}

/// The model `text`, parsed and validated.
pub fn model(text: &str) -> ModelSpec {
    validated(text).remove(0).spec
}

/// The model `text`, parsed but not validated: what the compiler must defend itself against.
pub fn unchecked(text: &str) -> ModelSpec {
    let ast = Source::new("test", text)
        .parse()
        .unwrap_or_else(|e| panic!("{e}"));
    spec_unchecked(&ast).expect("the functions exist")
}

/// The `model!` invocation of a Rust file of the workspace's `equations/src/models`, as text.
fn disk_model(name: &str, file: &str) -> String {
    let tokens = Source::rust(name, file).tokens();
    tokens.unwrap_or_else(|e| panic!("{e}")).to_string()
}

/// The rolling disk (Box 1) as the `equations` crate compiles it.
pub fn rolling() -> String {
    let file = include_str!("../../../../equations/src/models/box1_rolling.rs");
    disk_model("box1_rolling.rs", file)
}

/// The sliding disk (Box 3, with its Cartesian chart) as the `equations` crate compiles it.
pub fn sliding() -> String {
    let file = include_str!("../../../../equations/src/models/box3_sliding.rs");
    disk_model("box3_sliding.rs", file)
}

/// The model `text` in its chart `chart`, parsed and validated.
pub fn charted(text: &str, chart: &str) -> ModelSpec {
    let found = validated(text).into_iter().find(|m| m.spec.name == chart);
    found.expect("the chart exists").spec
}

/// The model `text` with one more variant (`variant NAME { .. }`) at its end.
pub fn with_variant(text: &str, variant: &str) -> String {
    let end = text.rfind('}').expect("the module is closed");
    format!("{}{variant}\n{}", &text[..end], &text[end..])
}
