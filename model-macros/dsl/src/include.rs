//! `include "rows.dsl";`: rows written once, in a file of their own, and read wherever a model
//! needs them.
//!
//! A model that shares rows with another (a mode of a switched model that is the equations of a
//! smooth model, two models with the same body) would otherwise restate them, and a fix to one
//! copy would miss the other. The included file holds items — `let`s, `equations`, `outputs`,
//! events, even whole sections — exactly as they would be written where the `include` stands
//! (in the model, or in a mode); they are parsed there, as if written in place. The names they
//! use are the including model's: the same rows read `k_F` as the air's drag where the model
//! defines `let k_F = mu_a*pi*a^2;` and as nothing where it says `let k_F = 0;`.
//!
//! A path is relative to the folder of the file that holds the `include` (the Rust file that
//! invokes `model!`, the `.dsl` file read at run time, or the included file for a nested
//! include), as for Rust's `include_str!`. Errors inside an included file are that file's: read
//! as text, `file:line:col` in it with a caret under the token; inside `model!`, where the
//! compiler can only underline Rust source, at the `include` that read it, naming the file
//! (see [`in_included_files`]). The files read are kept ([`Spans::included`]), so that
//! `model!` can make the compiler track them (a changed row re-expands the model) and a cache
//! of compiled models can key on their text.

use crate::included::{IncludedFile, Includes};
use crate::limits::{check_tokens, MAX_TOKENS};
use crate::skip::skip_all;
use crate::span::{Errors, Spans};
use crate::statements::recover_statement;
use proc_macro2::{Group, Span, TokenStream, TokenTree};
use syn::parse::{ParseStream, Parser};
use syn::Token;
extern crate proc_macro;

/// The largest file an `include` reads (far more than [`MAX_TOKENS`] tokens take).
const MAX_FILE_BYTES: u64 = 64 << 20;

/// After the keyword `include`: `"PATH";`. The file's items are parsed here, each by `item`
/// (as if written in place, with `context`, which holds the model's [`Spans`]), then the rest
/// of the model is read on: a file that cannot be read, or an item that cannot, is one error.
pub(crate) fn include_here<C>(
    input: ParseStream,
    context: &mut C,
    spans: fn(&mut C) -> &mut Spans,
    errors: &mut Errors,
    mut item: impl FnMut(ParseStream, &mut C, &mut Errors) -> syn::Result<()>,
) {
    let mut literal = None;
    recover_statement(input, errors, |input| {
        literal = Some(input.parse::<syn::LitStr>().map_err(|error| {
            syn::Error::new(
                error.span(),
                "expected the path of the file to include, in quotes: `include \"rows.dsl\";`",
            )
        })?);
        input.parse::<Token![;]>()?;
        Ok(())
    });
    let Some(literal) = literal else { return };
    let tokens = match read(&literal, &mut spans(context).includes) {
        Ok(tokens) => tokens,
        Err(error) => return errors.push(error),
    };
    let parsed = (|input: ParseStream| {
        while !input.is_empty() {
            if let Err(error) = item(input, context, errors) {
                errors.push(error);
                // The item's extent is unknown: give up on the rest of the file.
                skip_all(input);
            }
        }
        Ok(())
    })
    .parse2(tokens);
    spans(context).includes.reading.pop();
    if let Err(error) = parsed {
        errors.push(error);
    }
}

/// Reads the file `literal` names, checks its tokens and records it as being read.
fn read(literal: &syn::LitStr, includes: &mut Includes) -> syn::Result<TokenStream> {
    let written = literal.value();
    let at = literal.span();
    let error = |message: String| syn::Error::new(at, message);
    let name = includes.folder().join(&written);
    let refused = |problem: &dyn std::fmt::Display| {
        error(format!(
            "cannot read the included file `{written}`: {problem} (a path is relative to the \
             folder of the file that holds the `include`)"
        ))
    };
    let path = name.canonicalize().map_err(|e| refused(&e))?;
    let size = std::fs::metadata(&path).map_err(|e| refused(&e))?;
    if !size.is_file() {
        return Err(refused(&"it is not a file"));
    }
    if size.len() > MAX_FILE_BYTES {
        return Err(refused(&format!(
            "it is larger than the {MAX_FILE_BYTES} bytes an included file may have"
        )));
    }
    if let Some(chain) = includes.cycle(&path, &written) {
        return Err(error(format!(
            "`{written}` is already being read: the includes {chain} form a cycle"
        )));
    }
    let text = std::fs::read_to_string(&path).map_err(|e| refused(&e))?;
    let name = name.display().to_string();
    let tokens = text.parse::<TokenStream>().map_err(|_| {
        let what = match crate::lexical::first_problem(&text, false) {
            Some(p) => format!("line {}, column {}: {}", p.line, p.column, p.message),
            None => "its text does not split into tokens".into(),
        };
        error(format!("in the included file `{written}`, {what}"))
    })?;
    check_tokens(&tokens).map_err(|e| error(format!("in the included file `{written}`: {e}")))?;
    includes.tokens += count(&tokens);
    if includes.tokens > MAX_TOKENS {
        return Err(error(format!(
            "model too large: its included files hold more than {MAX_TOKENS} tokens (the \
             DSL's limit MAX_TOKENS)"
        )));
    }
    // Inside `model!` the tokens of a string carry the invocation's span; they are given the
    // `include`'s, so that what is wrong in them is shown there.
    let tokens = match proc_macro::is_available() {
        true => respan(tokens, at),
        false => tokens,
    };
    includes.files.push(IncludedFile {
        written,
        name,
        path,
        text,
        at,
        anchor: tokens.clone().into_iter().next().map(|tree| tree.span()),
        parent: includes.reading.last().copied(),
    });
    includes.reading.push(includes.files.len() - 1);
    Ok(tokens)
}

/// How many tokens `tokens` holds, every level of brackets counted.
fn count(tokens: &TokenStream) -> usize {
    (tokens.clone().into_iter())
        .map(|tree| match tree {
            TokenTree::Group(group) => 1 + count(&group.stream()),
            _ => 1,
        })
        .sum()
}

/// `tokens`, every one carrying `span`.
fn respan(tokens: TokenStream, span: Span) -> TokenStream {
    (tokens.into_iter())
        .map(|tree| match tree {
            TokenTree::Group(group) => {
                let mut new = Group::new(group.delimiter(), respan(group.stream(), span));
                new.set_span(span);
                TokenTree::Group(new)
            }
            mut other => {
                other.set_span(span);
                other
            }
        })
        .collect()
}

/// The file among `files` that holds the token at `span`, when the model is read as text (each
/// text's tokens have places of their own); `None` for the model's own text, and always inside
/// `model!`.
pub(crate) fn file_of(files: &[IncludedFile], span: Span) -> Option<&IncludedFile> {
    if proc_macro::is_available() {
        return None;
    }
    (files.iter()).find(|file| {
        file.anchor
            .is_some_and(|anchor| anchor.join(span).is_some())
    })
}

/// The errors of a model expanded by `model!`, each error inside an included file said to be
/// there: the compiler can underline only Rust source, so such an error stands at the
/// `include` that read the file (the outermost one, for a nested include), and its message
/// names the file (`in `rows.dsl`, included here: unknown name `kk``). Outside `model!`
/// (text, where an included file's errors are located in it) the errors are returned as they
/// are.
pub fn in_included_files(errors: syn::Error, spans: &Spans) -> syn::Error {
    let files = spans.included();
    if files.is_empty() || !proc_macro::is_available() {
        return errors;
    }
    let place = |span: Span| (span.start(), span.end());
    let mut out: Option<syn::Error> = None;
    for error in errors {
        let span = error.span();
        let file = (files.iter().enumerate())
            .find(|(_, f)| f.parent.is_none() && place(f.at) == place(span));
        let error = match file {
            Some((k, file)) => {
                let nested = files.iter().any(|f| f.parent == Some(k));
                let which = match nested {
                    true => format!("`{}` (or a file it includes)", file.written),
                    false => format!("`{}`", file.written),
                };
                syn::Error::new(span, format!("in {which}, included here: {error}"))
            }
            None => error,
        };
        match &mut out {
            Some(all) => all.combine(error),
            None => out = Some(error),
        }
    }
    out.expect("a syn::Error holds at least one error")
}
