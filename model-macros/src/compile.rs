//! The algebra, seen from the front end: run the compiler, point its diagnostics at the user's
//! tokens.

use crate::span::{Errors, Spans};
use crate::validate::range;
use model_algebra::program::CompiledModel;
use model_algebra::spec::ModelSpec;
use model_algebra::CompileOptions;

/// Compiles a validated model; a diagnostic of the compiler becomes an error under the tokens of
/// the node it names, and all of them are reported together.
pub fn compile(spec: &ModelSpec, spans: &Spans) -> syn::Result<CompiledModel> {
    model_algebra::compile(spec, &CompileOptions::default()).map_err(|diagnostics| {
        let mut errors = Errors::default();
        for diagnostic in diagnostics {
            errors.at(range(spans, diagnostic.id), diagnostic.message);
        }
        match errors.finish() {
            Err(error) => error,
            // The compiler failed without saying why: still fail, at the module's name.
            Ok(()) => syn::Error::new(
                proc_macro2::Span::call_site(),
                format!("the equations of `{}` could not be compiled", spec.name),
            ),
        }
    })
}
