//! Models from DSL text, through the one front end.

use model_algebra::ModelSpec;
use model_dsl::{spec_unchecked, validate, CompiledSwitched, Located, Source, Validated};

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

/// The folder of the disk's models.
const MODELS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../equations/src/models");

/// The `model!` invocation of a Rust file of the workspace's `equations/src/models`, as text
/// that can be read from anywhere (its `include`s' paths made absolute).
fn disk_model(name: &str, file: &str) -> String {
    let tokens = Source::rust(name, file).tokens();
    let text = tokens.unwrap_or_else(|e| panic!("{e}")).to_string();
    text.replace("include \"", &format!("include \"{MODELS}/"))
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

/// The switched model `text`, compiled (a panic shows its errors).
pub fn compile_switched(text: &str) -> CompiledSwitched {
    match Source::new("m.dsl", text).compile_switched() {
        Ok(model) => model,
        Err(errors) => panic!("{errors}"),
    }
}

/// The errors of the switched model `text`, which must be rejected.
pub fn switched_errors(text: &str) -> Vec<Located> {
    Source::new("bad.dsl", text)
        .compile_switched()
        .expect_err("must be rejected")
        .0
}

/// The errors' messages.
pub fn messages(found: &[Located]) -> Vec<String> {
    found.iter().map(|e| e.message.clone()).collect()
}

/// The error whose message contains `needle`.
pub fn find<'a>(found: &'a [Located], needle: &str) -> &'a Located {
    found
        .iter()
        .find(|e| e.message.contains(needle))
        .unwrap_or_else(|| panic!("no `{needle}` in {:#?}", messages(found)))
}

/// The text under an error's caret, `len` characters of it.
pub fn underlined(error: &Located, len: usize) -> String {
    (error.source_line.chars())
        .skip(error.column - 1)
        .take(len)
        .collect()
}
