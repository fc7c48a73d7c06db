//! The DSL's size limits, stated once and enforced as a model is read, so that every later
//! stage (each of which walks expressions recursively) runs in bounded stack and time whatever
//! the text: a hostile or generated model gets an error naming the limit, never a stack
//! overflow.
//!
//! - [`MAX_DEPTH`]: how deep an expression may nest, counting every parenthesis, call, sign,
//!   power and every operator of a chain (`a + b + c` is two levels), and counting a `let`'s
//!   expression where the `let` is used;
//! - [`MAX_TOKENS`]: how many tokens a model may have.

use crate::ast::{Expr, ModelAst};
use crate::span::{Errors, SpanRange};
use model_algebra::Named;
use proc_macro2::{Span, TokenStream, TokenTree};
use std::collections::BTreeMap;

/// The deepest an expression may nest, lets substituted: every parenthesis, call, sign, power
/// and every operator of a chain counts one level, so one sum has at most this many terms (a
/// longer one is written as a sum of lets).
pub const MAX_DEPTH: u32 = 256;

/// The most tokens a model may have (a name, a number, an operator or a bracket each count
/// one).
pub const MAX_TOKENS: usize = 1_000_000;

/// The error for an expression nested deeper than [`MAX_DEPTH`], at `range`.
pub(crate) fn too_deep(range: SpanRange) -> syn::Error {
    range.error(format!(
        "expression nested too deeply: the DSL's limit MAX_DEPTH is {MAX_DEPTH} levels \
         (each parenthesis, call, sign, power and each operator of a chain `a + b + ..` counts \
         one); split it into lets"
    ))
}

/// Checks the token trees before they are parsed: bracket nesting within [`MAX_DEPTH`], the
/// token count within [`MAX_TOKENS`], and no `#` that is not an attribute (a comment from
/// another language). Iterative, so any nesting is measured without recursion.
pub(crate) fn check_tokens(tokens: &TokenStream) -> syn::Result<()> {
    let mut stack = vec![tokens.clone().into_iter()];
    let mut count = 0usize;
    let mut previous_hash: Option<Span> = None;
    while let Some(top) = stack.last_mut() {
        let Some(tree) = top.next() else {
            stack.pop();
            if let Some(span) = previous_hash.take() {
                return Err(stray_hash(span));
            }
            continue;
        };
        count += 1;
        if count > MAX_TOKENS {
            return Err(syn::Error::new(
                tree.span(),
                format!(
                    "model too large: more than {MAX_TOKENS} tokens (the DSL's limit MAX_TOKENS)"
                ),
            ));
        }
        if let Some(span) = previous_hash.take() {
            let attribute = match &tree {
                TokenTree::Group(g) => g.delimiter() == proc_macro2::Delimiter::Bracket,
                TokenTree::Punct(p) => p.as_char() == '!',
                _ => false,
            };
            if !attribute {
                return Err(stray_hash(span));
            }
        }
        match tree {
            TokenTree::Punct(p) if p.as_char() == '#' => previous_hash = Some(p.span()),
            TokenTree::Group(group) => {
                if stack.len() > MAX_DEPTH as usize {
                    return Err(too_deep(SpanRange::single(group.span_open())));
                }
                stack.push(group.stream().into_iter());
            }
            _ => {}
        }
    }
    Ok(())
}

fn stray_hash(span: Span) -> syn::Error {
    syn::Error::new(
        span,
        "`#` does not start a comment in the DSL: write `// ..` (or `/// ..` for documentation)",
    )
}

/// Checks that every `let`'s expression, with the lets it uses substituted, nests within
/// [`MAX_DEPTH`]; a `let` beyond it is reported at its name. Iterative over the lets (a chain
/// of any length is measured without recursion); a cycle counts as depth zero here (it is
/// reported as a cycle).
pub(crate) fn check_let_depth(ast: &ModelAst) -> syn::Result<()> {
    let index: BTreeMap<&str, usize> = ast
        .lets
        .iter()
        .enumerate()
        .map(|(k, l)| (l.name.as_str(), k))
        .collect();
    let refs = |l: &Named<Expr>| -> Vec<usize> {
        let mut found = Vec::new();
        l.value.walk(&mut |node| {
            if let Expr::Name(_, name) = node {
                if let Some(&k) = index.get(name.as_str()) {
                    found.push(k);
                }
            }
        });
        found
    };
    // `None`: not visited; `Some(None)`: in progress; `Some(Some(depth))`: done.
    let mut depth: Vec<Option<Option<u32>>> = vec![None; ast.lets.len()];
    let mut errors = Errors::default();
    for root in 0..ast.lets.len() {
        if depth[root].is_some() {
            continue;
        }
        depth[root] = Some(None);
        let mut path = vec![(root, refs(&ast.lets[root]), 0usize)];
        while let Some((k, targets, next)) = path.last_mut() {
            if let Some(&target) = targets.get(*next) {
                *next += 1;
                if depth[target].is_none() {
                    depth[target] = Some(None);
                    let targets = refs(&ast.lets[target]);
                    path.push((target, targets, 0));
                }
                continue;
            }
            let k = *k;
            let used = targets
                .iter()
                .filter_map(|&t| depth[t].flatten())
                .max()
                .unwrap_or(0);
            let own = ast.spans.depth(ast.lets[k].value.id());
            let total = own.saturating_add(used);
            if total > MAX_DEPTH && used <= MAX_DEPTH {
                // Reported once, at the first let of the chain beyond the limit.
                errors.at(
                    ast.spans.range(ast.lets[k].id),
                    format!(
                        "let `{}` nests {total} levels deep with the lets it uses substituted: \
                         the DSL's limit MAX_DEPTH is {MAX_DEPTH}",
                        ast.lets[k].name
                    ),
                );
            }
            depth[k] = Some(Some(total));
            path.pop();
        }
    }
    errors.finish()
}
