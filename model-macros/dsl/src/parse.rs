//! The DSL's items: module, sections, statements.
//!
//! Parsing recovers at statement and section boundaries (`;` and `{..}`), so one typo does not
//! hide the next: every syntax error of the invocation is collected and reported together.

use crate::ast::{Chart, Equation, ModelAst, Variant};
use crate::expr::{parse_default, parse_expr, parse_signed_number, range_of};
use crate::span::{Errors, SpanRange, Spans};
use model_algebra::Named;
use proc_macro2::{TokenStream, TokenTree};
use std::collections::BTreeMap;
use syn::parse::{ParseStream, Parser};
use syn::{token, Token};

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
/// still declares every name that did parse, so code using them reports nothing more.
pub fn parse_model_recovering(tokens: TokenStream) -> Parsed {
    let mut errors = Errors::default();
    let parsed = (|input: ParseStream| parse_module(input, &mut errors)).parse2(tokens);
    let (model, fatal) = match parsed {
        Ok(model) => (Some(model), None),
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
}

fn parse_module(input: ParseStream, errors: &mut Errors) -> syn::Result<ModelAst> {
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
            "expected `params`, `states`, `let`, `equations`, `outputs`, `variant`, `chart` or `options`",
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
            recover_section(&content, errors, |input| {
                parse_list(input, &mut model.states, |input| {
                    parse_documented_name(input, &mut model.spans, &mut model.docs)
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
        "variant" => {
            let variant = parse_variant(input, attrs, &mut model.spans, errors)?;
            model.variants.push(variant);
        }
        "chart" => {
            let chart = parse_chart(input, attrs, model, errors)?;
            model.charts.push(chart);
        }
        other => {
            return Err(syn::Error::new(
                keyword.span(),
                format!(
                    "unknown section `{other}`: expected `params`, `states`, `let`, `equations`, `outputs`, `variant`, `chart` or `options`"
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

/// `label: lhs = rhs;` or `lhs = rhs;`
fn parse_equation(input: ParseStream, spans: &mut Spans) -> syn::Result<Equation> {
    let label = if input.peek(syn::Ident) && input.peek2(Token![:]) && !input.peek2(Token![::]) {
        let label = parse_name(input, spans)?;
        input.parse::<Token![:]>()?;
        Some(label)
    } else {
        None
    };
    let lhs = parse_expr(input, spans)?;
    if input.peek(Token![==]) {
        let eqeq: Token![==] = input.parse()?;
        return Err(syn::Error::new_spanned(
            eqeq,
            "`==` is not an equation sign here: an equation reads `lhs = rhs;` with a single `=`",
        ));
    }
    input
        .parse::<Token![=]>()
        .map_err(|_| input.error("expected `=`: an equation reads `lhs = rhs;`"))?;
    let rhs = parse_expr(input, spans)?;
    input.parse::<Token![;]>()?;
    let start = match &label {
        Some(label) => spans.get(label.id),
        None => spans.get(lhs.id()),
    };
    let end = range_of(spans, &rhs);
    let id = spans.push(start.map_or(end, |start| start.to(end)));
    Ok(Equation {
        label,
        id,
        lhs,
        rhs,
    })
}

/// `NAME = EXPR` (without the `;`).
fn parse_binding(input: ParseStream, spans: &mut Spans) -> syn::Result<Named<crate::ast::Expr>> {
    let name = parse_name(input, spans)?;
    input.parse::<Token![=]>()?;
    let value = parse_expr(input, spans)?;
    Ok(with_value(name, value))
}

fn parse_name(input: ParseStream, spans: &mut Spans) -> syn::Result<Named<()>> {
    let ident: syn::Ident = input.parse()?;
    Ok(Named {
        name: ident.to_string(),
        id: spans.push(SpanRange::single(ident.span())),
        value: (),
    })
}

/// A name with the doc comments written before it (kept in `docs` under the name).
fn parse_documented_name(
    input: ParseStream,
    spans: &mut Spans,
    docs: &mut BTreeMap<String, Vec<syn::Attribute>>,
) -> syn::Result<Named<()>> {
    let attrs = input.call(syn::Attribute::parse_outer)?;
    let name = parse_name(input, spans)?;
    if !attrs.is_empty() {
        docs.insert(name.name.clone(), attrs);
    }
    Ok(name)
}

fn with_value<T>(name: Named<()>, value: T) -> Named<T> {
    Named {
        name: name.name,
        id: name.id,
        value,
    }
}

/// `item, item, ...` with an optional trailing comma, up to the end of `input`, appended to
/// `items` as they parse (so the items before an error are kept).
fn parse_list<T>(
    input: ParseStream,
    items: &mut Vec<T>,
    mut item: impl FnMut(ParseStream) -> syn::Result<T>,
) -> syn::Result<()> {
    while !input.is_empty() {
        items.push(item(input)?);
        if input.is_empty() {
            break;
        }
        input.parse::<Token![,]>()?;
    }
    Ok(())
}

fn braced<'a>(input: ParseStream<'a>) -> syn::Result<syn::parse::ParseBuffer<'a>> {
    if !input.peek(token::Brace) {
        return Err(input.error("expected `{`"));
    }
    let content;
    syn::braced!(content in input);
    Ok(content)
}

/// Runs one `;`-terminated statement; on error records it and skips past the next `;`.
fn recover_statement(
    input: ParseStream,
    errors: &mut Errors,
    statement: impl FnOnce(ParseStream) -> syn::Result<()>,
) {
    if let Err(error) = statement(input) {
        errors.push(error);
        skip_past_semicolon(input);
    }
}

/// Runs a whole `{..}` section; on error records it and skips the rest of the section.
fn recover_section(
    input: ParseStream,
    errors: &mut Errors,
    section: impl FnOnce(ParseStream) -> syn::Result<()>,
) {
    if let Err(error) = section(input) {
        errors.push(error);
        skip_all(input);
    }
}

fn skip_past_semicolon(input: ParseStream) {
    let _ = input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((tree, next)) = rest.token_tree() {
            rest = next;
            if matches!(&tree, TokenTree::Punct(p) if p.as_char() == ';') {
                break;
            }
        }
        Ok(((), rest))
    });
}

/// Consumes the rest of `input` (after an error inside a group, so that the group's unparsed
/// tokens add no second error).
pub(crate) fn skip_all(input: ParseStream) {
    let _ = input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((_, next)) = rest.token_tree() {
            rest = next;
        }
        Ok(((), rest))
    });
}

fn once(slot: &mut Option<SpanRange>, range: SpanRange, section: &str, errors: &mut Errors) {
    if slot.is_some() {
        errors.at(
            range,
            format!("`{section}` is written twice: declare everything in one section"),
        );
    } else {
        *slot = Some(range);
    }
}

fn check_docs_only(attrs: &[syn::Attribute], errors: &mut Errors) {
    for attr in attrs {
        if !attr.path().is_ident("doc") {
            errors.push(syn::Error::new_spanned(
                attr,
                "only doc comments (`/// ..`) are allowed in a model",
            ));
        }
    }
}

fn no_docs_here(attrs: &[syn::Attribute], what: &str, errors: &mut Errors) {
    if let Some(attr) = attrs.iter().find(|attr| attr.path().is_ident("doc")) {
        errors.push(syn::Error::new_spanned(
            attr,
            format!(
                "doc comments go on the module, a variant, a parameter, a state or an output, not on {what}; use `//` here"
            ),
        ));
    }
}
