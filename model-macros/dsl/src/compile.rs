//! The algebra, seen from the front end: run the compiler, point its diagnostics at the user's
//! tokens.

use crate::span::Errors;
use crate::validate::Validated;
use model_algebra::{CompiledModel, Named};

/// Compiles every model (a model and its charts), reporting the errors of all together.
pub fn compile_all(models: &[Validated]) -> syn::Result<Vec<CompiledModel>> {
    let mut errors = Errors::default();
    let mut compiled = Vec::new();
    for model in models {
        match compile(model) {
            Ok(model) => compiled.push(model),
            Err(error) => errors.push(error),
        }
    }
    errors.finish()?;
    Ok(compiled)
}

/// Compiles a validated model; a diagnostic of the compiler becomes an error under the tokens of
/// the node it names, and all of them are reported together.
pub fn compile(model: &Validated) -> syn::Result<CompiledModel> {
    let spec = &model.spec;
    let spans = &model.ast.spans;
    let mut compiled = model_algebra::compile(spec, &model.options).map_err(|diagnostics| {
        let mut errors = Errors::default();
        for diagnostic in diagnostics {
            errors.at(spans.range(diagnostic.id), diagnostic.message);
        }
        match errors.finish() {
            Err(error) => error,
            // The compiler failed without saying why: still fail, at the module's name.
            Ok(()) => syn::Error::new(
                proc_macro2::Span::call_site(),
                format!("the equations of `{}` could not be compiled", spec.name),
            ),
        }
    })?;
    with_initial(&mut compiled, &model.ast.initial);
    Ok(compiled)
}

/// The initial values written on the states (`states { x = 2 }`), given to the compiled
/// model and its variants by state name (the compiler knows nothing of them).
fn with_initial(compiled: &mut CompiledModel, initial: &[Named<f64>]) {
    compiled.initial = (compiled.states.iter())
        .map(|state| initial.iter().find(|i| &i.name == state).map(|i| i.value))
        .collect();
    for variant in &mut compiled.variants {
        with_initial(variant, initial);
    }
}
