#![doc = include_str!("../DSL.md")]
#![warn(missing_docs)]

mod emit;
mod emit_named;
mod emit_program;
mod emit_switched;
mod expand;
mod placeholder;

#[cfg(test)]
mod tests;

/// Compiles a model written as implicit equations into explicit Rust; see the crate docs for the
/// language and for what is emitted.
#[proc_macro]
pub fn model(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    expand::expand(input.into()).into()
}
