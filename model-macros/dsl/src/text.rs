//! A model read from text: a `.dsl` file holding what goes inside `model! { .. }`.
//!
//! Outside a procedural macro, `proc_macro2` lexes text itself, and with its `span-locations`
//! feature every token knows its line and column. So a file goes through exactly the parser and
//! validator the macro uses, and each error the macro would draw under a token becomes
//! `file:line:col: message` followed by the source line and a caret under that token — the
//! form compilers and editors understand.

use crate::compile::compile_all;
use crate::include::file_of;
use crate::included::IncludedFile;
use crate::located::{Located, LocatedErrors};
use crate::parse::parse_model_in;
use crate::span::{Errors, Spans};
use crate::switched::validate_switched;
use crate::switched_compile::{compile_switched, CompiledSwitched};
use crate::validate::validate;
use crate::warnings::warnings;
use crate::ModelAst;
extern crate proc_macro;
use model_algebra::CompiledModel;
use proc_macro2::{Delimiter, Span, TokenStream, TokenTree};
use std::path::Path;

/// The text of a model and the name it is reported under.
#[derive(Clone, Debug)]
pub struct Source {
    /// The name shown in messages (usually the file's path).
    pub name: String,
    /// The text: `mod NAME { .. }`, optionally with doc comments before it; or Rust source
    /// holding a `model! { .. }` invocation.
    pub text: String,
    /// Whether `text` is Rust source whose first `model! { .. }` holds the model.
    pub rust: bool,
}

/// One model of a source (the model itself or one of its charts), compiled.
#[derive(Clone, Debug)]
pub struct TextModel {
    /// The model as written.
    pub ast: ModelAst,
    /// What the compiler derived from it.
    pub compiled: CompiledModel,
}

impl Source {
    /// A source named `name` holding `text`.
    pub fn new(name: impl Into<String>, text: impl Into<String>) -> Self {
        Source {
            name: name.into(),
            text: text.into(),
            rust: false,
        }
    }

    /// A Rust source file whose first `model! { .. }` (or `model_macros::model! { .. }`) holds
    /// the model; messages give lines and columns in the Rust file.
    pub fn rust(name: impl Into<String>, text: impl Into<String>) -> Self {
        Source {
            rust: true,
            ..Source::new(name, text)
        }
    }

    /// Reads the file at `path` (a `.rs` file as Rust source holding `model!`); the path is
    /// the name shown in messages.
    pub fn read(path: &std::path::Path) -> std::io::Result<Self> {
        let text = std::fs::read_to_string(path)?;
        let name = path.display().to_string();
        Ok(match path.extension().is_some_and(|e| e == "rs") {
            true => Source::rust(name, text),
            false => Source::new(name, text),
        })
    }

    /// The model's tokens; a lexical error (an unclosed brace, a stray quote) is located.
    ///
    /// Lexing text records it on the current thread to give every token its line and column;
    /// each call first releases what earlier calls recorded there, so that a long-lived
    /// process reading model after model keeps only the last. The spans of what an earlier
    /// call returned (a [`ModelAst`], a `syn::Error`) are then no longer valid: use them (or
    /// keep the [`Located`] errors, which are plain text) before reading the next source on
    /// the same thread.
    pub fn tokens(&self) -> Result<TokenStream, LocatedErrors> {
        release_earlier_texts();
        let tokens = self.text.parse::<TokenStream>().map_err(|error| {
            let located = match crate::lexical::first_problem(&self.text, self.rust) {
                Some(problem) => self.located_at(problem),
                None => locate(&self.name, &self.text, error.span(), &error.to_string()),
            };
            LocatedErrors(vec![located])
        })?;
        if !self.rust {
            return Ok(tokens);
        }
        macro_body(tokens).ok_or_else(|| {
            let message = "no `model! { .. }` in this file";
            LocatedErrors(vec![locate(
                &self.name,
                &self.text,
                Span::call_site(),
                message,
            )])
        })
    }

    /// The model as written, its `include`s read (their paths relative to the folder of the
    /// file `name` names); every syntax error, located (an included file's in that file).
    pub fn parse(&self) -> Result<ModelAst, LocatedErrors> {
        let parsed = parse_model_in(self.tokens()?, Some(Path::new(&self.name)));
        match (parsed.errors, parsed.model) {
            (None, Some(model)) => Ok(model),
            (Some(errors), Some(model)) => Err(self.locate_in(&model.spans, errors)),
            (Some(errors), None) => Err(self.locate_all(errors)),
            (None, None) => Err(self.locate_all(syn::Error::new(
                Span::call_site(),
                "expected `mod NAME { .. }`",
            ))),
        }
    }

    /// Parses, validates and compiles the model, as `model!` does: the model, then the model
    /// in each of its charts; every error, located.
    pub fn compile(&self) -> Result<Vec<TextModel>, LocatedErrors> {
        let ast = self.parse()?;
        let locate = |errors| self.locate_in(&ast.spans, errors);
        let validated = validate(&ast).map_err(locate)?;
        let compiled = compile_all(&validated).map_err(locate)?;
        Ok(validated
            .into_iter()
            .zip(compiled)
            .map(|(model, compiled)| TextModel {
                ast: model.ast,
                compiled,
            })
            .collect())
    }

    /// The models of this text with what an earlier [`compile`](Self::compile) of the same
    /// text derived (kept by a cache), the text parsed and validated again (which is quick: the
    /// compiling is what takes time). `None` when the models do not fit the text (not as
    /// many, or named otherwise): then they were not derived from it.
    pub fn with_compiled(&self, compiled: Vec<CompiledModel>) -> Option<Vec<TextModel>> {
        let ast = self.parse().ok()?;
        let validated = validate(&ast).ok()?;
        let fits = validated.len() == compiled.len()
            && (validated.iter().zip(&compiled)).all(|(v, c)| v.ast.name == c.name);
        fits.then(|| {
            (validated.into_iter().zip(compiled))
                .map(|(model, compiled)| TextModel {
                    ast: model.ast,
                    compiled,
                })
                .collect()
        })
    }

    /// Parses, validates and compiles a switched model (one with `mode` or `when`), as `model!`
    /// does; every error, located. A model whose events compute their new state `by` a Rust
    /// function is rejected at each such name: only `model!` can call Rust, so read from text
    /// it can be neither shown with its resets nor run.
    pub fn compile_switched(&self) -> Result<CompiledSwitched, LocatedErrors> {
        let ast = self.parse()?;
        let mut errors = Errors::default();
        for function in ast.rust_calls() {
            errors.at(
                ast.spans.range(function.id),
                format!(
                    "`{0}` is a Rust function (`by {0}`): a model that calls one runs only \
                     compiled, inside `model!`, where `{0}` is in scope; a model read from a \
                     file cannot call Rust",
                    function.name
                ),
            );
        }
        let plan = validate_switched(&ast);
        if let Err(found) = &plan {
            errors.push(found.clone());
        }
        let locate = |errors| self.locate_in(&ast.spans, errors);
        errors.finish().map_err(locate)?;
        let plan = plan.map_err(locate)?;
        let mut compiled = compile_switched(&plan).map_err(locate)?;
        compiled.warnings = (warnings(&plan).into_iter())
            .filter_map(|warning| {
                let message = format!("warning: {}", warning.message);
                let located = locate(warning.range.error(&message)).0;
                located.into_iter().next()
            })
            .collect();
        Ok(compiled)
    }

    /// Every error of a (combined) `syn::Error`, located in this source.
    pub fn locate_all(&self, errors: syn::Error) -> LocatedErrors {
        self.locate_in(&Spans::default(), errors)
    }

    /// Every error of a (combined) `syn::Error` about the model read into `spans`, located in
    /// this source or in the file an `include` read it from.
    pub fn locate_in(&self, spans: &Spans, errors: syn::Error) -> LocatedErrors {
        LocatedErrors(
            (errors.into_iter())
                .map(|error| {
                    let message = error.to_string();
                    match file_of(spans.included(), error.span()) {
                        Some(file) => locate(&file.name, &file.text, error.span(), &message),
                        None => locate(&self.name, &self.text, error.span(), &message),
                    }
                })
                .collect(),
        )
    }

    /// The files this model's `include`s read (none when even its header is unreadable).
    pub fn included(&self) -> Result<Vec<IncludedFile>, LocatedErrors> {
        let parsed = parse_model_in(self.tokens()?, Some(Path::new(&self.name)));
        Ok(parsed
            .model
            .map_or_else(Vec::new, |model| model.spans.included().to_vec()))
    }

    /// A lexical problem, under its one character.
    fn located_at(&self, problem: crate::lexical::LexProblem) -> Located {
        Located {
            name: self.name.clone(),
            line: problem.line,
            column: problem.column,
            width: 1,
            message: problem.message,
            source_line: self
                .text
                .lines()
                .nth(problem.line - 1)
                .unwrap_or("")
                .to_string(),
        }
    }
}

/// One message under `span` in the text `text` named `name`. A span that is not in this text
/// (the call site, which a parse of text uses for "the whole model") points at the first line.
fn locate(name: &str, text: &str, span: Span, message: &str) -> Located {
    let (start, end) = (span.start(), span.end());
    let line = start.line.max(1);
    let source_line = text.lines().nth(line - 1).unwrap_or("").to_string();
    let width = if end.line == start.line && end.column > start.column {
        end.column - start.column
    } else {
        source_line
            .chars()
            .count()
            .saturating_sub(start.column)
            .max(1)
    };
    Located {
        name: name.to_string(),
        line,
        column: start.column + 1,
        width,
        message: message.to_string(),
        source_line,
    }
}

/// Releases the texts lexed earlier on this thread (outside a procedural macro, where the
/// compiler owns the spans and there is nothing to release).
fn release_earlier_texts() {
    if !proc_macro::is_available() {
        proc_macro2::extra::invalidate_current_thread_spans();
    }
}

/// The body of the first `model! { .. }` among `tokens` (at any depth).
fn macro_body(tokens: TokenStream) -> Option<TokenStream> {
    let trees: Vec<TokenTree> = tokens.into_iter().collect();
    for (k, tree) in trees.iter().enumerate() {
        if let [TokenTree::Ident(name), TokenTree::Punct(bang), TokenTree::Group(body), ..] =
            &trees[k..]
        {
            if name == "model" && bang.as_char() == '!' && body.delimiter() == Delimiter::Brace {
                return Some(body.stream());
            }
        }
        if let TokenTree::Group(group) = tree {
            if let Some(body) = macro_body(group.stream()) {
                return Some(body);
            }
        }
    }
    None
}
