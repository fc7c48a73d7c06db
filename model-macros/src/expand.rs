//! The pipeline: parse -> validate -> compile -> emit, timed stage by stage.
//!
//! Set `MODEL_MACROS_TIMING=1` in the environment of the build to have every expansion print
//! the time of each stage to stderr (expansion runs inside rustc, so this is the only place the
//! cost of the equation compiler can be seen).

use crate::emit::emit;
use crate::emit_switched::emit_switched;
use crate::placeholder::{placeholder, switched_placeholder};
use model_dsl::{
    compile_all, compile_switched, in_included_files, parse_model_in, validate, validate_switched,
    ModelAst,
};
use proc_macro2::TokenStream;
use std::time::{Duration, Instant};
use syn::parse::{ParseStream, Parser};
use syn::Token;

/// The environment variable that turns the timing report on.
pub const TIMING_VAR: &str = "MODEL_MACROS_TIMING";

/// Expands one `model!` invocation.
pub fn expand(tokens: TokenStream) -> TokenStream {
    let (output, timing) = expand_timed(tokens);
    if std::env::var_os(TIMING_VAR).is_some_and(|v| !v.is_empty() && v != "0") {
        eprintln!("{timing}");
    }
    output
}

/// How long one stage took.
#[derive(Clone, Copy, Debug)]
pub struct StageTime {
    /// The stage's name.
    pub stage: &'static str,
    /// Its duration.
    pub elapsed: Duration,
}

/// The stages of one expansion.
#[derive(Clone, Debug, Default)]
pub struct Timing {
    /// The model's name, once parsed.
    pub model: String,
    /// The stages run, in order.
    pub stages: Vec<StageTime>,
}

impl Timing {
    fn stage<T>(&mut self, stage: &'static str, run: impl FnOnce() -> T) -> T {
        let start = Instant::now();
        let result = run();
        self.stages.push(StageTime {
            stage,
            elapsed: start.elapsed(),
        });
        result
    }

    /// The sum of all stages.
    pub fn total(&self) -> Duration {
        self.stages.iter().map(|s| s.elapsed).sum()
    }
}

impl std::fmt::Display for Timing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "model!({}):", self.model)?;
        for stage in &self.stages {
            write!(f, " {} {:.3} ms,", stage.stage, millis(stage.elapsed))?;
        }
        write!(f, " total {:.3} ms", millis(self.total()))
    }
}

fn millis(duration: Duration) -> f64 {
    duration.as_secs_f64() * 1e3
}

/// Expands and reports how long each stage took.
pub fn expand_timed(tokens: TokenStream) -> (TokenStream, Timing) {
    expand_timed_in(tokens, None)
}

/// Expands a model whose source is the file `origin` (the folder its `include`s are relative
/// to; `None`: the invoking file, as the compiler names it).
#[cfg(test)]
pub fn expand_in(tokens: TokenStream, origin: Option<&std::path::Path>) -> TokenStream {
    expand_timed_in(tokens, origin).0
}

/// [`expand_timed`] with the model's source file; what the model's `include`s read is
/// tracked by the compiler (a changed file expands the model again) and named in the errors
/// found in it.
fn expand_timed_in(tokens: TokenStream, origin: Option<&std::path::Path>) -> (TokenStream, Timing) {
    let mut timing = Timing::default();
    let parsed = timing.stage("parse", || parse_model_in(tokens.clone(), origin));
    let Some(ast) = parsed.model else {
        let error = parsed.errors.unwrap_or_else(|| {
            syn::Error::new(proc_macro2::Span::call_site(), "expected `mod NAME { .. }`")
        });
        let placeholder = header(tokens).map_or_else(TokenStream::new, |ast| placeholder(&ast));
        return (failure(error, placeholder), timing);
    };
    timing.model = ast.name.to_string();
    let (mut output, timing) = expand_parsed(&ast, parsed.errors, timing);
    output.extend(tracked(&ast));
    (output, timing)
}

/// One `const _: &str = include_str!(..);` for each file the model's `include`s read, so that
/// the compiler expands the model again when one of them changes.
fn tracked(ast: &ModelAst) -> TokenStream {
    let paths = (ast.spans.included().iter()).map(|file| file.path.display().to_string());
    quote::quote! { #(const _: &str = include_str!(#paths);)* }
}

/// The expansion of a model that parsed (`errors`: its syntax errors).
fn expand_parsed(
    ast: &ModelAst,
    errors: Option<syn::Error>,
    mut timing: Timing,
) -> (TokenStream, Timing) {
    let failure = |error| failure(in_included_files(error, &ast.spans), placeholders(ast));
    if let Some(error) = errors {
        return (failure(error), timing);
    }
    if ast.is_switched() {
        let plan = timing.stage("validate", || validate_switched(ast));
        let compiled = plan.and_then(|plan| {
            let compiled = timing.stage("compile", || compile_switched(&plan))?;
            Ok((plan, compiled))
        });
        return match compiled {
            Ok((plan, compiled)) => {
                let modes: Vec<&ModelAst> = plan.modes.iter().map(|m| &m.model.ast).collect();
                let output = timing.stage("emit", || emit_switched(&plan.ast, &modes, &compiled));
                (output, timing)
            }
            Err(error) => (failure(error), timing),
        };
    }
    let validated = timing.stage("validate", || validate(ast));
    let compiled = validated.and_then(|models| {
        let compiled = timing.stage("compile", || compile_all(&models))?;
        Ok((models, compiled))
    });
    match compiled {
        Ok((models, compiled)) => {
            let output = timing.stage("emit", || {
                (models.iter().zip(&compiled))
                    .map(|(model, compiled)| emit(&model.ast, compiled))
                    .collect()
            });
            (output, timing)
        }
        Err(error) => (failure(error), timing),
    }
}

/// The placeholders of the model and of each chart with a name of its own (for a switched
/// model, the switched placeholder).
fn placeholders(ast: &ModelAst) -> TokenStream {
    if ast.is_switched() {
        return switched_placeholder(ast);
    }
    let mut names = std::collections::BTreeSet::from([ast.name.to_string()]);
    let charts = (ast.charts.iter())
        .filter(|chart| names.insert(chart.name.to_string()))
        .map(|chart| placeholder(&chart.apply(ast)));
    std::iter::once(placeholder(ast)).chain(charts).collect()
}

fn failure(error: syn::Error, placeholder: TokenStream) -> TokenStream {
    let mut output = error.to_compile_error();
    output.extend(placeholder);
    output
}

/// The header `mod NAME` of an invocation whose body could not be read, as an empty model (so
/// the placeholder still defines the module); `None` if even the header is unreadable.
fn header(tokens: TokenStream) -> Option<ModelAst> {
    let header = |input: ParseStream| {
        let attrs = input.call(syn::Attribute::parse_outer)?;
        let vis: syn::Visibility = input.parse()?;
        input.parse::<Token![mod]>()?;
        let name: syn::Ident = input.parse()?;
        input.parse::<TokenStream>()?;
        Ok(ModelAst::empty(attrs, vis, name))
    };
    header.parse2(tokens).ok()
}
