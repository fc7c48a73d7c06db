//! The DSL's items: module, sections, statements.
//!
//! Parsing recovers at statement and section boundaries (`;` and `{..}`), so one typo does not
//! hide the next: every syntax error of the invocation is collected and reported together.

use crate::ast::{Chart, ModelAst, Variant};
use crate::expr::{parse_default, parse_signed_number};
use crate::include::include_here;
use crate::skip::skip_all;
use crate::span::{Errors, SpanRange, Spans};
use crate::statements::{
    braced, check_docs_only, no_docs_here, once, parse_binding, parse_documented_name,
    parse_equation, parse_list, parse_name, recover_section, recover_statement, with_value,
};
use crate::switching::{parse_declared, parse_mode, parse_when, Declared, Events};
use proc_macro2::TokenStream;
use std::path::Path;
use syn::parse::{ParseStream, Parser};
use syn::Token;

/// Parses a whole `model!` invocation; `Err` carries every syntax error found.
pub fn parse_model(tokens: TokenStream) -> syn::Result<ModelAst> {
    let parsed = parse_model_recovering(tokens);
    match parsed.errors {
        None => parsed.model.ok_or_else(|| {
            syn::Error::new(proc_macro2::Span::call_site(), "expected `mod NAME { .. }`")
        }),
        Some(errors) => Err(errors),
    }
}

/// What parsing recovered: the model as far as it could be read, and every syntax error.
pub struct Parsed {
    /// The model, with the statements that failed to parse left out; `None` if even the
    /// header `mod NAME { .. }` is unreadable.
    pub model: Option<ModelAst>,
    /// Every syntax error, combined.
    pub errors: Option<syn::Error>,
}

/// Parses as much as can be read: after an error the placeholder emitted in the model's place
/// still declares every name that did parse, so code using them reports nothing more. Inside
/// `model!` an `include`'s path is relative to the invoking file's folder; read as text,
/// relative to the working folder (see [`parse_model_in`]).
pub fn parse_model_recovering(tokens: TokenStream) -> Parsed {
    parse_model_in(tokens, None)
}

/// [`parse_model_recovering`] for a model whose source is the file `origin` (if it has one):
/// the paths of its `include`s are relative to that file's folder.
pub fn parse_model_in(tokens: TokenStream, origin: Option<&Path>) -> Parsed {
    if let Err(error) = crate::limits::check_tokens(&tokens) {
        return Parsed {
            model: None,
            errors: Some(error),
        };
    }
    let mut errors = Errors::default();
    let parsed = (|input: ParseStream| parse_module(input, origin, &mut errors)).parse2(tokens);
    let (model, fatal) = match parsed {
        Ok(mut model) => {
            // Errors found while names were read come first: they are about declarations.
            let mut all = Errors::default();
            for error in std::mem::take(&mut model.spans.deferred) {
                all.push(error);
            }
            all.extend(errors);
            errors = all;
            (Some(model), None)
        }
        Err(error) => (None, Some(error)),
    };
    let errors = match (errors.finish(), fatal) {
        (Ok(()), fatal) => fatal,
        (Err(mut earlier), Some(fatal)) => {
            earlier.combine(fatal);
            Some(earlier)
        }
        (Err(earlier), None) => Some(earlier),
    };
    Parsed { model, errors }
}

/// Sections seen so far (each may be written once).
#[derive(Default)]
struct Seen {
    params: Option<SpanRange>,
    states: Option<SpanRange>,
    equations: Option<SpanRange>,
    outputs: Option<SpanRange>,
    options: Option<SpanRange>,
    discrete: Option<SpanRange>,
}

fn parse_module(
    input: ParseStream,
    origin: Option<&Path>,
    errors: &mut Errors,
) -> syn::Result<ModelAst> {
    let attrs = input.call(syn::Attribute::parse_outer)?;
    check_docs_only(&attrs, errors);
    let vis: syn::Visibility = input.parse()?;
    input.parse::<Token![mod]>()?;
    let name: syn::Ident = input.parse()?;
    let body;
    syn::braced!(body in input);
    if !input.is_empty() {
        return Err(
            input.error("one `model!` holds exactly one module: unexpected tokens after it")
        );
    }
    let mut model = ModelAst::empty(attrs, vis, name);
    model.spans.includes.origin = origin.map(Path::to_path_buf);
    let mut seen = Seen::default();
    while !body.is_empty() {
        if let Err(error) = parse_item(&body, &mut model, &mut seen, errors) {
            errors.push(error);
            // The item's extent is unknown: give up on the rest of the body.
            skip_all(&body);
        }
    }
    Ok(model)
}

fn parse_item(
    input: ParseStream,
    model: &mut ModelAst,
    seen: &mut Seen,
    errors: &mut Errors,
) -> syn::Result<()> {
    let attrs = input.call(syn::Attribute::parse_outer)?;
    check_docs_only(&attrs, errors);
    if input.peek(Token![let]) {
        no_docs_here(&attrs, "a `let`", errors);
        recover_statement(input, errors, |input| {
            input.parse::<Token![let]>()?;
            let binding = parse_binding(input, &mut model.spans)?;
            input.parse::<Token![;]>()?;
            model.lets.push(binding);
            Ok(())
        });
        return Ok(());
    }
    let keyword: syn::Ident = input.parse().map_err(|_| {
        input.error(
            "expected `params`, `states`, `discrete`, `let`, `equations`, `outputs`, `mode`, `when`, `variant`, `chart`, `options` or `include`",
        )
    })?;
    let range = SpanRange::single(keyword.span());
    match keyword.to_string().as_str() {
        "params" => {
            no_docs_here(&attrs, "`params`", errors);
            once(&mut seen.params, range, "params", errors);
            let content = braced(input)?;
            // A default that is not a literal is reported without losing the parameter.
            let mut bad_defaults = Vec::new();
            recover_section(&content, errors, |input| {
                parse_list(input, &mut model.params, |input| {
                    let name = parse_documented_name(input, &mut model.spans, &mut model.docs)?;
                    let default = if input.peek(Token![=]) {
                        input.parse::<Token![=]>()?;
                        Some(parse_default(input).unwrap_or_else(|error| {
                            bad_defaults.push(error);
                            0.0
                        }))
                    } else {
                        None
                    };
                    Ok(with_value(name, default))
                })
            });
            bad_defaults.into_iter().for_each(|error| errors.push(error));
        }
        "states" => {
            no_docs_here(&attrs, "`states`", errors);
            once(&mut seen.states, range, "states", errors);
            let content = braced(input)?;
            let initial = &mut model.initial;
            recover_section(&content, errors, |input| {
                parse_list(input, &mut model.states, |input| {
                    let name = parse_documented_name(input, &mut model.spans, &mut model.docs)?;
                    // An initial value: where a run starts unless told otherwise.
                    if input.peek(Token![=]) {
                        input.parse::<Token![=]>()?;
                        let value = parse_default(input)?;
                        initial.push(with_value(name.clone(), value));
                    }
                    Ok(name)
                })
            });
        }
        "equations" => {
            no_docs_here(&attrs, "`equations`", errors);
            once(&mut seen.equations, range, "equations", errors);
            let content = braced(input)?;
            while !content.is_empty() {
                recover_statement(&content, errors, |input| {
                    let equation = parse_equation(input, &mut model.spans)?;
                    model.equations.push(equation);
                    Ok(())
                });
            }
        }
        "outputs" => {
            no_docs_here(&attrs, "`outputs`", errors);
            once(&mut seen.outputs, range, "outputs", errors);
            let content = braced(input)?;
            while !content.is_empty() {
                recover_statement(&content, errors, |input| {
                    let attrs = input.call(syn::Attribute::parse_outer)?;
                    let binding = parse_binding(input, &mut model.spans)?;
                    input.parse::<Token![;]>()?;
                    if !attrs.is_empty() {
                        model.docs.insert(binding.name.clone(), attrs);
                    }
                    model.outputs.push(binding);
                    Ok(())
                });
            }
        }
        "options" => {
            no_docs_here(&attrs, "`options`", errors);
            once(&mut seen.options, range, "options", errors);
            let content = braced(input)?;
            recover_section(&content, errors, |input| {
                parse_list(input, &mut model.options, |input| {
                    let name = parse_name(input, &mut model.spans)?;
                    input.parse::<Token![=]>()?;
                    Ok(with_value(name, parse_signed_number(input)?))
                })
            });
        }
        "include" => {
            no_docs_here(&attrs, "an `include`", errors);
            include_here(
                input,
                model,
                |model| &mut model.spans,
                errors,
                |input, model, errors| parse_item(input, model, seen, errors),
            );
        }
        "variant" => {
            let variant = parse_variant(input, attrs, &mut model.spans, errors)?;
            model.variants.push(variant);
        }
        "chart" => {
            let chart = parse_chart(input, attrs, model, errors)?;
            model.charts.push(chart);
        }
        "mode" => {
            let mode = parse_mode(input, attrs, &mut model.spans, errors)?;
            model.modes.push(mode);
        }
        "discrete" => {
            no_docs_here(&attrs, "`discrete`", errors);
            once(&mut seen.discrete, range, "discrete", errors);
            let content = braced(input)?;
            recover_section(&content, errors, |input| {
                parse_list(input, &mut model.discrete, |input| {
                    let name = parse_documented_name(input, &mut model.spans, &mut model.docs)?;
                    if !input.peek(Token![=]) {
                        return Err(input.error(format!(
                            "expected `= VALUE` after `{}`: a discrete value starts at a value written here",
                            name.name
                        )));
                    }
                    input.parse::<Token![=]>()?;
                    Ok(with_value(name, parse_default(input)?))
                })
            });
        }
        word if Declared::of(word).is_some() => {
            let what = Declared::of(word).expect("matched");
            no_docs_here(&attrs, &format!("`{word}`"), errors);
            recover_statement(input, errors, |input| {
                let mut slot = what.model_slot(model).take();
                let result = parse_declared(input, &keyword, &mut model.spans, &mut slot, what);
                *what.model_slot(model) = slot;
                result
            });
        }
        "when" => {
            let mut events = Events {
                events: &mut model.events,
                accumulations: &mut model.accumulations,
            };
            recover_statement(input, errors, |input| {
                parse_when(input, attrs, &mut model.spans, &mut events)
            });
        }
        other => {
            return Err(syn::Error::new(
                keyword.span(),
                format!(
                    "unknown section `{other}`: expected `params`, `states`, `discrete`, `let`, `equations`, `outputs`, `mode`, `when`, `time_scale`, `first_step`, `variant`, `chart`, `options` or `include`"
                ),
            ))
        }
    }
    Ok(())
}

fn parse_variant(
    input: ParseStream,
    attrs: Vec<syn::Attribute>,
    spans: &mut Spans,
    errors: &mut Errors,
) -> syn::Result<Variant> {
    let name: syn::Ident = input.parse()?;
    let id = spans.push(SpanRange::single(name.span()));
    let content = braced(input)?;
    let mut keep = None;
    let mut fix = None;
    let result = (|| -> syn::Result<()> {
        while !content.is_empty() {
            let keyword: syn::Ident = content
                .parse()
                .map_err(|_| content.error("expected `keep { .. }` or `fix { .. }`"))?;
            let inner = braced(&content)?;
            match keyword.to_string().as_str() {
                "keep" if keep.is_none() => {
                    let kept = keep.insert(Vec::new());
                    parse_list(&inner, kept, |input| parse_name(input, spans))?;
                }
                "fix" if fix.is_none() => {
                    let fixed = fix.insert(Vec::new());
                    parse_list(&inner, fixed, |input| {
                        let name = parse_name(input, spans)?;
                        input.parse::<Token![=]>()?;
                        let value = parse_signed_number(input)?;
                        Ok(with_value(name, value))
                    })?;
                }
                "keep" | "fix" => {
                    return Err(syn::Error::new(
                        keyword.span(),
                        format!("`{keyword}` is written twice in variant `{name}`"),
                    ))
                }
                _ => {
                    return Err(syn::Error::new(
                        keyword.span(),
                        format!(
                        "unknown section `{keyword}` in variant `{name}`: expected `keep` or `fix`"
                    ),
                    ))
                }
            }
        }
        Ok(())
    })();
    if let Err(error) = result {
        errors.push(error);
        skip_all(&content);
    }
    let keep = match keep {
        Some(keep) => keep,
        None => {
            errors.push(syn::Error::new(
                name.span(),
                format!(
                    "variant `{name}` has no `keep {{ .. }}`: name the states and outputs it keeps"
                ),
            ));
            Vec::new()
        }
    };
    Ok(Variant {
        attrs,
        name,
        id,
        keep,
        fix: fix.unwrap_or_default(),
    })
}

/// `chart NAME { states { .. } replace { .. } let ..; outputs [after NAME] { .. } }`; the new
/// states' doc comments join the model's.
fn parse_chart(
    input: ParseStream,
    attrs: Vec<syn::Attribute>,
    model: &mut ModelAst,
    errors: &mut Errors,
) -> syn::Result<Chart> {
    let name: syn::Ident = input.parse()?;
    let id = model.spans.push(SpanRange::single(name.span()));
    let content = braced(input)?;
    let mut chart = Chart {
        attrs,
        name,
        id,
        states: Vec::new(),
        replace: Vec::new(),
        lets: Vec::new(),
        outputs: Vec::new(),
        after: None,
    };
    let spans = &mut model.spans;
    while !content.is_empty() {
        if content.peek(Token![let]) {
            recover_statement(&content, errors, |input| {
                input.parse::<Token![let]>()?;
                chart.lets.push(parse_binding(input, spans)?);
                input.parse::<Token![;]>()?;
                Ok(())
            });
            continue;
        }
        let keyword: syn::Ident = content.parse().map_err(|_| {
            content.error(
                "expected `states { .. } replace { .. }`, `let` or `outputs { .. }` in a chart",
            )
        })?;
        match keyword.to_string().as_str() {
            "states" => {
                let states = braced(&content)?;
                parse_list(&states, &mut chart.states, |input| {
                    parse_documented_name(input, spans, &mut model.docs)
                })?;
                let replace: syn::Ident = content.parse()?;
                if replace != "replace" {
                    return Err(syn::Error::new(
                        replace.span(),
                        "expected `replace { .. }`: a chart's states replace states of the model",
                    ));
                }
                let replaced = braced(&content)?;
                parse_list(&replaced, &mut chart.replace, |input| parse_name(input, spans))?;
            }
            "outputs" => {
                if content.peek(syn::Ident) {
                    let after: syn::Ident = content.parse()?;
                    if after != "after" {
                        return Err(syn::Error::new(
                            after.span(),
                            "expected `after NAME` or `{`",
                        ));
                    }
                    chart.after = Some(parse_name(&content, spans)?);
                }
                let outputs = braced(&content)?;
                while !outputs.is_empty() {
                    recover_statement(&outputs, errors, |input| {
                        let attrs = input.call(syn::Attribute::parse_outer)?;
                        let binding = parse_binding(input, spans)?;
                        if !attrs.is_empty() {
                            model.docs.insert(binding.name.clone(), attrs);
                        }
                        chart.outputs.push(binding);
                        input.parse::<Token![;]>()?;
                        Ok(())
                    });
                }
            }
            other => {
                return Err(syn::Error::new(
                    keyword.span(),
                    format!("unknown section `{other}` in chart `{}`: expected `states`, `let` or `outputs`", chart.name),
                ))
            }
        }
    }
    Ok(chart)
}
