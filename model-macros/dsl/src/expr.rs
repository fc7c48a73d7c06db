//! Expressions of the DSL, parsed by precedence climbing.
//!
//! Precedence, loosest first: `+ -`, `* /`, unary `-`, `^`. The power binds tighter than the unary
//! minus and associates to the right, as in mathematics: `-x^2 = -(x^2)`, `a^b^c = a^(b^c)`, and
//! an exponent may itself be negated, `2^-x = 2^(-x)`.

use crate::ast::{Call, Expr, RelOp, Relation};
use crate::limits::{too_deep, MAX_DEPTH};
use crate::span::{SpanRange, Spans};
use model_algebra::{BinOp, NodeId};
use syn::ext::IdentExt as _;
use syn::parse::ParseStream;
use syn::{token, Token};

/// Parses one expression; stops before the first token that cannot continue it (`;`, `=`, `,`).
pub fn parse_expr(input: ParseStream, spans: &mut Spans) -> syn::Result<Expr> {
    let mut lhs = parse_product(input, spans)?;
    loop {
        let op = if input.peek(Token![+]) {
            input.parse::<Token![+]>()?;
            BinOp::Add
        } else if input.peek(Token![-]) && !input.peek(Token![->]) {
            input.parse::<Token![-]>()?;
            BinOp::Sub
        } else {
            return Ok(lhs);
        };
        let rhs = parse_product(input, spans)?;
        lhs = binary(spans, op, lhs, rhs)?;
    }
}

/// Parses a comparison `EXPR OP EXPR` with `OP` one of `<`, `<=`, `>`, `>=`, `==`.
pub fn parse_relation(input: ParseStream, spans: &mut Spans) -> syn::Result<Relation> {
    let lhs = parse_expr(input, spans)?;
    relation_after(input, spans, lhs)
}

/// The comparison operator and right-hand side of a relation whose left-hand side is parsed.
fn relation_after(input: ParseStream, spans: &mut Spans, lhs: Expr) -> syn::Result<Relation> {
    let op = if input.peek(Token![<=]) {
        input.parse::<Token![<=]>()?;
        RelOp::Le
    } else if input.peek(Token![>=]) {
        input.parse::<Token![>=]>()?;
        RelOp::Ge
    } else if input.peek(Token![==]) {
        input.parse::<Token![==]>()?;
        RelOp::Eq
    } else if input.peek(Token![<]) {
        input.parse::<Token![<]>()?;
        RelOp::Lt
    } else if input.peek(Token![>]) {
        input.parse::<Token![>]>()?;
        RelOp::Gt
    } else if input.peek(Token![=]) {
        let eq: Token![=] = input.parse()?;
        return Err(syn::Error::new(
            eq.span,
            "a condition compares with `<`, `<=`, `>`, `>=` or `==`, not `=`",
        ));
    } else {
        return Err(input.error("expected a comparison: `<`, `<=`, `>`, `>=` or `==`"));
    };
    let rhs = parse_expr(input, spans)?;
    let range = range_of(spans, &lhs).to(range_of(spans, &rhs));
    Ok(Relation {
        id: node(spans, range, &[lhs.id(), rhs.id()])?,
        lhs,
        op,
        rhs,
    })
}

fn parse_product(input: ParseStream, spans: &mut Spans) -> syn::Result<Expr> {
    let mut lhs = parse_unary(input, spans)?;
    loop {
        let op = if input.peek(Token![*]) {
            let star: Token![*] = input.parse()?;
            if input.peek(Token![*]) {
                let second: Token![*] = input.parse()?;
                let range = SpanRange::single(star.span).to(SpanRange::single(second.span));
                return Err(range.error(
                    "`**` is not an operator of the DSL: write a power with `^`, e.g. `x^2`",
                ));
            }
            BinOp::Mul
        } else if input.peek(Token![/]) {
            input.parse::<Token![/]>()?;
            BinOp::Div
        } else {
            return Ok(lhs);
        };
        let rhs = parse_unary(input, spans)?;
        lhs = binary(spans, op, lhs, rhs)?;
    }
}

/// Every nested expression goes through here (a parenthesis, an argument, a sign, an
/// exponent), so this is where the parser's own recursion is bounded by [`MAX_DEPTH`].
fn parse_unary(input: ParseStream, spans: &mut Spans) -> syn::Result<Expr> {
    if spans.nesting >= MAX_DEPTH {
        return Err(too_deep(SpanRange::single(input.span())));
    }
    spans.nesting += 1;
    let parsed = parse_unary_nested(input, spans);
    spans.nesting -= 1;
    parsed
}

fn parse_unary_nested(input: ParseStream, spans: &mut Spans) -> syn::Result<Expr> {
    if input.peek(Token![-]) {
        let minus: Token![-] = input.parse()?;
        let arg = parse_unary(input, spans)?;
        let range = SpanRange::single(minus.span).to(range_of(spans, &arg));
        return Ok(Expr::Neg(node(spans, range, &[arg.id()])?, Box::new(arg)));
    }
    parse_power(input, spans)
}

fn parse_power(input: ParseStream, spans: &mut Spans) -> syn::Result<Expr> {
    let base = parse_atom(input, spans)?;
    if input.peek(Token![.]) {
        return Err(method_call(input, &base));
    }
    if input.peek(Token![^]) {
        input.parse::<Token![^]>()?;
        // The exponent may be negated and is itself a power: right-associative.
        let exponent = parse_unary(input, spans)?;
        return binary(spans, BinOp::Pow, base, exponent);
    }
    Ok(base)
}

fn parse_atom(input: ParseStream, spans: &mut Spans) -> syn::Result<Expr> {
    if input.peek(token::Paren) {
        let content;
        syn::parenthesized!(content in input);
        let inner = parse_expr(&content, spans)?;
        if !content.is_empty() {
            return Err(content.error("expected an operator or `)`"));
        }
        return Ok(inner);
    }
    if input.peek(Token![if]) {
        return parse_if(input, spans);
    }
    if input.peek(syn::Lit) {
        let (value, span) = parse_number(input)?;
        return Ok(Expr::Num(spans.push(SpanRange::single(span)), value));
    }
    if input.peek(syn::Ident::peek_any) {
        // A keyword is read as a name here: its declaration is where it is refused.
        let ident = syn::Ident::parse_any(input)?;
        let name_range = SpanRange::single(ident.span());
        let name = ident.to_string();
        if !input.peek(token::Paren) {
            return Ok(Expr::Name(spans.push(name_range), name));
        }
        let func_id = spans.push(name_range);
        let content;
        let parens = syn::parenthesized!(content in input);
        let mut args = Vec::new();
        while !content.is_empty() {
            args.push(parse_expr(&content, spans)?);
            if content.is_empty() {
                break;
            }
            content.parse::<Token![,]>()?;
        }
        let range = name_range.to(SpanRange::single(parens.span.close()));
        let ids: Vec<_> = args.iter().map(Expr::id).collect();
        return Ok(Expr::Call(Call {
            id: node(spans, range, &ids)?,
            func: name,
            func_id,
            args,
        }));
    }
    Err(input.error("expected a number, a name, `(` or `-`"))
}

/// `if(COND, then, otherwise)`, where `COND` is an ordering comparison (`==` is refused at its
/// token: computed values are practically never exactly equal).
fn parse_if(input: ParseStream, spans: &mut Spans) -> syn::Result<Expr> {
    let keyword: Token![if] = input.parse()?;
    let start = SpanRange::single(keyword.span);
    if !input.peek(token::Paren) {
        return Err(start.error("`if` is written like a function: `if(x > y, a, b)`"));
    }
    let content;
    let parens = syn::parenthesized!(content in input);
    let parsed = parse_if_arguments(&content, spans);
    if parsed.is_err() {
        crate::skip::skip_all(&content);
    }
    let (cond, values) = parsed?;
    let range = start.to(SpanRange::single(parens.span.close()));
    let [then, otherwise]: [Expr; 2] = values.try_into().map_err(|values: Vec<Expr>| {
        range.error(format!(
            "`if` takes a condition and 2 values, `if(x > y, a, b)`, found {} value(s)",
            values.len()
        ))
    })?;
    let ids = [cond.id, then.id(), otherwise.id()];
    Ok(Expr::If {
        id: node(spans, range, &ids)?,
        cond: Box::new(cond),
        then: Box::new(then),
        otherwise: Box::new(otherwise),
    })
}

/// The condition and the values inside `if(..)`.
fn parse_if_arguments(input: ParseStream, spans: &mut Spans) -> syn::Result<(Relation, Vec<Expr>)> {
    let cond = parse_condition(input, spans)?;
    let mut values = Vec::new();
    while !input.is_empty() {
        input.parse::<Token![,]>()?;
        values.push(parse_expr(input, spans)?);
    }
    Ok((cond, values))
}

/// The condition of an `if`: a comparison other than `==`.
fn parse_condition(input: ParseStream, spans: &mut Spans) -> syn::Result<Relation> {
    // The left-hand side is parsed once (not on a fork first): a condition may hold an `if`
    // whose condition holds an `if`, and a second parse per level would be exponential.
    let lhs = parse_expr(input, spans)?;
    if input.peek(Token![==]) {
        let eq: Token![==] = input.parse()?;
        let range = SpanRange::single(eq.spans[0]).to(SpanRange::single(eq.spans[1]));
        return Err(range.error(
            "`if` cannot test `==`: computed values are practically never exactly equal; \
             compare with `<`, `<=`, `>` or `>=`",
        ));
    }
    relation_after(input, spans, lhs)
}

/// The error for `x.sin()`: the DSL has functions, not methods (Rust's spelling is a natural
/// slip when the model is written inside Rust code).
fn method_call(input: ParseStream, receiver: &Expr) -> syn::Error {
    let dot = match input.parse::<Token![.]>() {
        Ok(dot) => dot,
        Err(error) => return error,
    };
    let mut range = SpanRange::single(dot.span);
    let mut name = None;
    if let Ok(method) = input.parse::<syn::Ident>() {
        range = range.to(SpanRange::single(method.span()));
        name = Some(method.to_string());
    }
    if input.peek(token::Paren) {
        if let Ok(group) = input.parse::<proc_macro2::Group>() {
            range = range.to(SpanRange::single(group.span_close()));
        }
    }
    let receiver = match receiver {
        Expr::Name(_, name) => name.clone(),
        Expr::Num(_, value) => value.to_string(),
        _ => "x".to_string(),
    };
    match name {
        Some(name) => range.error(format!(
            "method syntax is not supported: write `{name}({receiver})`, not `{receiver}.{name}()`"
        )),
        None => range.error("`.` is not an operator of the DSL"),
    }
}

/// Parses an unsuffixed numeric literal (integer or float) as `f64`.
pub fn parse_number(input: ParseStream) -> syn::Result<(f64, proc_macro2::Span)> {
    let lit: syn::Lit = input.parse()?;
    let (value, suffix) = match &lit {
        syn::Lit::Int(int) => (int.base10_parse::<f64>(), int.suffix()),
        syn::Lit::Float(float) => (float.base10_parse::<f64>(), float.suffix()),
        _ => return Err(syn::Error::new(lit.span(), "expected a number")),
    };
    if !suffix.is_empty() {
        return Err(syn::Error::new(
            lit.span(),
            format!("number suffixes are not allowed (`{suffix}`): every quantity is an f64"),
        ));
    }
    let value = value?;
    if !value.is_finite() {
        return Err(syn::Error::new(
            lit.span(),
            "number is too large to be an f64",
        ));
    }
    Ok((value, lit.span()))
}

/// Parses a parameter's default: `NUMBER` or `-NUMBER`. Anything else is parsed as an
/// expression only to be refused under its whole extent (`w = 2*pi`): a default is a literal.
pub fn parse_default(input: ParseStream) -> syn::Result<f64> {
    let mut scratch = Spans::default();
    let expr = parse_expr(input, &mut scratch)?;
    match &expr {
        Expr::Num(_, value) => return Ok(*value),
        Expr::Neg(_, inner) => {
            if let Expr::Num(_, value) = **inner {
                return Ok(-value);
            }
        }
        _ => {}
    }
    Err(range_of(&scratch, &expr).error(
        "a parameter's default must be a number literal (e.g. `w = 6.283185307179586`), \
         not an expression; a derived quantity can be a `let` of the parameters",
    ))
}

/// Parses `NUMBER` or `-NUMBER`.
pub fn parse_signed_number(input: ParseStream) -> syn::Result<f64> {
    let negative = input.parse::<Option<Token![-]>>()?.is_some();
    let (value, _) = parse_number(input)?;
    Ok(if negative { -value } else { value })
}

/// The source range of an already-parsed expression.
pub fn range_of(spans: &Spans, expr: &Expr) -> SpanRange {
    spans
        .get(expr.id())
        .unwrap_or_else(|| SpanRange::single(proc_macro2::Span::call_site()))
}

fn binary(spans: &mut Spans, op: BinOp, lhs: Expr, rhs: Expr) -> syn::Result<Expr> {
    let range = range_of(spans, &lhs).to(range_of(spans, &rhs));
    let id = node(spans, range, &[lhs.id(), rhs.id()])?;
    Ok(Expr::Bin(id, op, Box::new(lhs), Box::new(rhs)))
}

/// A node over `children`, refused when it nests deeper than [`MAX_DEPTH`] (a chain of
/// operators nests one level per operator).
fn node(spans: &mut Spans, range: SpanRange, children: &[NodeId]) -> syn::Result<NodeId> {
    let id = spans.push_over(range, children);
    if spans.depth(id) > MAX_DEPTH {
        return Err(too_deep(range));
    }
    Ok(id)
}
