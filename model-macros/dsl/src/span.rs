//! Where each node of the user's model came from.
//!
//! The algebra crate reports problems by [`NodeId`]; it never sees a span. The parser gives every
//! node an id and records the source range here, so any diagnostic — found by the front end or by
//! the compiler — can be drawn under the exact tokens the user wrote.

use model_algebra::NodeId;
use proc_macro2::{Punct, Spacing, Span, TokenStream};
use quote::{ToTokens, TokenStreamExt};

/// A source range: the first and the last token of a node.
///
/// A stable proc macro cannot join two spans, but `syn::Error::new_spanned` underlines from the
/// first to the last token of what it is given; emitting two tokens carrying these spans gets the
/// same result.
#[derive(Clone, Copy, Debug)]
pub struct SpanRange {
    /// The first token's span.
    pub first: Span,
    /// The last token's span.
    pub last: Span,
}

impl SpanRange {
    /// A range covering one token.
    pub fn single(span: Span) -> Self {
        SpanRange {
            first: span,
            last: span,
        }
    }

    /// From the start of `self` to the end of `other`.
    pub fn to(self, other: SpanRange) -> Self {
        SpanRange {
            first: self.first,
            last: other.last,
        }
    }

    /// An error underlining this range.
    pub fn error(self, message: impl std::fmt::Display) -> syn::Error {
        syn::Error::new_spanned(self, message)
    }
}

impl ToTokens for SpanRange {
    fn to_tokens(&self, tokens: &mut TokenStream) {
        let mut first = Punct::new('<', Spacing::Alone);
        first.set_span(self.first);
        let mut last = Punct::new('>', Spacing::Alone);
        last.set_span(self.last);
        tokens.append(first);
        tokens.append(last);
    }
}

/// The side table `NodeId -> SpanRange`, filled by the parser in the order ids are handed out.
#[derive(Clone, Debug, Default)]
pub struct Spans {
    ranges: Vec<SpanRange>,
    /// The depth of the expression each node roots (1 for a leaf).
    depths: Vec<u32>,
    /// How many expressions the parser is inside of (see [`crate::limits::MAX_DEPTH`]).
    pub(crate) nesting: u32,
    /// Errors found while a name was still read (a Rust keyword used as a name), reported
    /// with the syntax errors.
    pub(crate) deferred: Vec<syn::Error>,
    /// The files `include`s read, and those being read.
    pub(crate) includes: crate::included::Includes,
}

impl Spans {
    /// Hands out a fresh id for a node covering `range`.
    pub fn push(&mut self, range: SpanRange) -> NodeId {
        self.push_over(range, &[])
    }

    /// Hands out a fresh id for a node covering `range` whose operands are `children`.
    pub(crate) fn push_over(&mut self, range: SpanRange, children: &[NodeId]) -> NodeId {
        let id = NodeId(self.ranges.len() as u32);
        let below = children.iter().map(|&c| self.depth(c)).max().unwrap_or(0);
        self.ranges.push(range);
        self.depths.push(below.saturating_add(1));
        id
    }

    /// The depth of the expression node `id` roots: 1 for a number or a name, one more than
    /// its deepest operand otherwise (0 for an id this table never handed out).
    pub fn depth(&self, id: NodeId) -> u32 {
        self.depths.get(id.0 as usize).copied().unwrap_or(0)
    }

    /// The range of `id`; `None` for an id this table never handed out.
    pub fn get(&self, id: NodeId) -> Option<SpanRange> {
        self.ranges.get(id.0 as usize).copied()
    }

    /// The files the model's `include`s read, in the order read.
    pub fn included(&self) -> &[crate::included::IncludedFile] {
        &self.includes.files
    }

    /// The range of `id`, or the macro's call site for an id this table never handed out.
    pub fn range(&self, id: NodeId) -> SpanRange {
        self.get(id)
            .unwrap_or_else(|| SpanRange::single(Span::call_site()))
    }
}

/// Gathers every error of one model before failing (serde_derive's `Ctxt`, without the drop
/// check: the pipeline consumes it explicitly).
#[derive(Default)]
pub struct Errors {
    errors: Vec<syn::Error>,
}

impl Errors {
    /// Records one error.
    pub fn push(&mut self, error: syn::Error) {
        self.errors.push(error);
    }

    /// Records an error underlining `range`.
    pub fn at(&mut self, range: SpanRange, message: impl std::fmt::Display) {
        self.push(range.error(message));
    }

    /// Records every error of `other` after these.
    pub fn extend(&mut self, other: Errors) {
        self.errors.extend(other.errors);
    }

    /// `Ok(())` when nothing was recorded, otherwise all errors combined into one.
    pub fn finish(self) -> syn::Result<()> {
        let mut iter = self.errors.into_iter();
        match iter.next() {
            None => Ok(()),
            Some(mut first) => {
                for error in iter {
                    first.combine(error);
                }
                Err(first)
            }
        }
    }
}
