//! The statements and lists every section of the DSL is made of, and how parsing recovers
//! after an error inside one: shared by the model's sections (`parse`) and a switched model's
//! modes and events (`switching`).

use crate::ast::Equation;
use crate::expr::{parse_expr, range_of};
use crate::skip::{skip_all, skip_past_semicolon};
use crate::span::{Errors, SpanRange, Spans};
use model_algebra::Named;
use std::collections::BTreeMap;
use syn::ext::IdentExt as _;
use syn::parse::ParseStream;
use syn::{token, Token};

/// `label: lhs = rhs;` or `lhs = rhs;`
pub(crate) fn parse_equation(input: ParseStream, spans: &mut Spans) -> syn::Result<Equation> {
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
pub(crate) fn parse_binding(
    input: ParseStream,
    spans: &mut Spans,
) -> syn::Result<Named<crate::ast::Expr>> {
    let name = parse_name(input, spans)?;
    compound_assignment(input, &name.name)?;
    input
        .parse::<Token![=]>()
        .map_err(|_| input.error(format!("expected `=`: write `{} = EXPR`", name.name)))?;
    let value = parse_expr(input, spans)?;
    Ok(with_value(name, value))
}

/// A Rust compound assignment (`n += 1`) where the DSL wants `NAME = EXPR`: an error at the
/// operator that says what to write instead.
fn compound_assignment(input: ParseStream, name: &str) -> syn::Result<()> {
    let operator = if input.peek(Token![+=]) {
        "+"
    } else if input.peek(Token![-=]) {
        "-"
    } else if input.peek(Token![*=]) {
        "*"
    } else if input.peek(Token![/=]) {
        "/"
    } else {
        return Ok(());
    };
    Err(input.error(format!(
        "`{operator}=` is not an assignment of the DSL: write `{name} = {name} {operator} EXPR` \
         (the right side reads the value before the assignment)"
    )))
}

pub(crate) fn parse_name(input: ParseStream, spans: &mut Spans) -> syn::Result<Named<()>> {
    let ident = parse_any_name(input, spans)?;
    Ok(Named {
        name: ident.to_string(),
        id: spans.push(SpanRange::single(ident.span())),
        value: (),
    })
}

/// A name with the doc comments written before it (kept in `docs` under the name).
pub(crate) fn parse_documented_name(
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

pub(crate) fn with_value<T>(name: Named<()>, value: T) -> Named<T> {
    Named {
        name: name.name,
        id: name.id,
        value,
    }
}

/// `item, item, ...` with an optional trailing comma, up to the end of `input`, appended to
/// `items` as they parse (so the items before an error are kept).
pub(crate) fn parse_list<T>(
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

pub(crate) fn braced<'a>(input: ParseStream<'a>) -> syn::Result<syn::parse::ParseBuffer<'a>> {
    if !input.peek(token::Brace) {
        return Err(input.error("expected `{`"));
    }
    let content;
    syn::braced!(content in input);
    Ok(content)
}

/// Runs one `;`-terminated statement; on error records it and skips past the next `;`.
pub(crate) fn recover_statement(
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
pub(crate) fn recover_section(
    input: ParseStream,
    errors: &mut Errors,
    section: impl FnOnce(ParseStream) -> syn::Result<()>,
) {
    if let Err(error) = section(input) {
        errors.push(error);
        skip_all(input);
    }
}

pub(crate) fn once(
    slot: &mut Option<SpanRange>,
    range: SpanRange,
    section: &str,
    errors: &mut Errors,
) {
    if slot.is_some() {
        errors.at(
            range,
            format!("`{section}` is written twice: declare everything in one section"),
        );
    } else {
        *slot = Some(range);
    }
}

pub(crate) fn check_docs_only(attrs: &[syn::Attribute], errors: &mut Errors) {
    for attr in attrs {
        if !attr.path().is_ident("doc") {
            errors.push(syn::Error::new_spanned(
                attr,
                "only doc comments (`/// ..`) are allowed in a model",
            ));
        }
    }
}

pub(crate) fn no_docs_here(attrs: &[syn::Attribute], what: &str, errors: &mut Errors) {
    if let Some(attr) = attrs.iter().find(|attr| attr.path().is_ident("doc")) {
        errors.push(syn::Error::new_spanned(
            attr,
            format!(
                "doc comments go on the module, a variant, a parameter, a state or an output, not on {what}; use `//` here"
            ),
        ));
    }
}

/// A name, which may be spelled like a Rust keyword: the keyword is read as the name (so that
/// its uses resolve and nothing else is reported) and refused once, here, since the generated
/// Rust code uses every name as an identifier.
pub(crate) fn parse_any_name(input: ParseStream, spans: &mut Spans) -> syn::Result<syn::Ident> {
    if input.peek(syn::Ident) || !input.peek(syn::Ident::peek_any) {
        return input.parse();
    }
    let ident = syn::Ident::parse_any(input)?;
    spans.deferred.push(syn::Error::new(
        ident.span(),
        format!(
            "`{ident}` is a Rust keyword, which cannot name anything in the DSL (the generated \
             Rust code uses every name as an identifier): choose another name, e.g. `{ident}_`"
        ),
    ));
    Ok(ident)
}

/// Whether `name` is a Rust keyword (and so cannot name anything in the DSL).
pub fn is_rust_keyword(name: &str) -> bool {
    syn::parse_str::<syn::Ident>(name).is_err()
        && syn::parse_str::<syn::Ident>(&format!("{name}_")).is_ok()
}
