//! How long an expansion takes, stage by stage, on the crate docs' example (printed with
//! `cargo test -p model-macros --lib timing -- --nocapture`).

use crate::expand::expand_timed;
use proc_macro2::TokenStream;

/// The body of the `model!` call in the crate docs.
pub fn docs_example() -> TokenStream {
    let docs = include_str!("../../DSL.md");
    let start = docs
        .find("model_macros::model! {")
        .expect("the docs hold an example");
    let body = &docs[start + "model_macros::model! {".len()..];
    let end = body.find("\n}\n").expect("the example's call is closed");
    body[..end].parse().expect("the example tokenizes")
}

#[test]
fn expansion_of_the_docs_example_is_timed_and_valid_rust() {
    let (output, timing) = expand_timed(docs_example());
    println!("{timing}");
    if std::env::var_os("MODEL_MACROS_PRINT").is_some() {
        println!("{output}");
    }
    let stages: Vec<&str> = timing.stages.iter().map(|s| s.stage).collect();
    assert_eq!(stages, ["parse", "validate", "compile", "emit"]);
    syn::parse2::<syn::File>(output).expect("the expansion parses as Rust");
}
