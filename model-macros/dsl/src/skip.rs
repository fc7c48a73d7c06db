//! Skipping tokens after a syntax error, so that parsing resumes at the next statement or
//! section and one mistake is reported once (shared by every parser of the front end).

use proc_macro2::TokenTree;
use syn::parse::ParseStream;

/// Consumes tokens up to and including the next `;` (after an error inside a statement).
pub(crate) fn skip_past_semicolon(input: ParseStream) {
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
