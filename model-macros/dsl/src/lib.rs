//! The front end of the equation compiler: the DSL of `model!` as an ordinary library.
//!
//! The procedural macro and the tools that read a model from a file (the `eulerdisk model`
//! commands, tests) share this one parser and validator, so a model means the same thing, and
//! a mistake gets the same message, wherever it is read. The pipeline is
//! [`parse_model_recovering`] (tokens to a [`ModelAst`], every syntax error collected),
//! [`validate`] (names resolved, the user's mistakes found, a `model_algebra` spec out) and
//! [`compile`] (the algebra, with its diagnostics pointed back at the user's tokens). The
//! grammar is described in the macro crate's `DSL.md`.
//!
//! A model can be read from text as well as from the macro's tokens: [`Source`] parses a file's
//! text with line and column on every token, and renders an error as `file:line:col: message`
//! with the source line and a caret under the token.
//!
//! ```
//! use model_dsl::Source;
//!
//! let source = Source::new("decay.dsl", "mod decay { params { k = 0.5 } states { x } equations { der(x) = -k*x; } }");
//! let models = source.compile().expect("compiles");
//! assert_eq!(models[0].compiled.states, vec!["x"]);
//!
//! let typo = Source::new("typo.dsl", "mod decay { states { x } equations { der(x) = -kk*x; } }");
//! let error = typo.compile().unwrap_err().to_string();
//! assert!(error.starts_with("typo.dsl:1:48: unknown name `kk`"), "{error}");
//! ```
#![warn(missing_docs)]

mod ast;
mod chart;
mod compile;
mod expr;
mod include;
mod included;
mod lexical;
mod limits;
mod located;
mod names;
mod options;
mod parse;
mod skip;
mod span;
mod statements;
mod states;
mod switched;
mod switched_compile;
mod switched_show;
mod switching;
mod text;
mod unchecked;
mod validate;
mod warnings;

pub use ast::{
    Accumulates, Call, Chart, Equation, Expr, Mode, ModelAst, RelOp, Relation, Target, Variant,
    When,
};
pub use compile::{compile, compile_all};
pub use include::in_included_files;
pub use included::IncludedFile;
pub use limits::{MAX_DEPTH, MAX_TOKENS};
pub use located::{Located, LocatedErrors};
pub use parse::{parse_model, parse_model_in, parse_model_recovering, Parsed};
pub use span::{SpanRange, Spans};
pub use statements::is_rust_keyword;
pub use switched::{
    validate_switched, Action, Choice, Crossing, EventPlan, JumpPlan, ModePlan, SwitchedPlan,
};
pub use switched_compile::{
    compile_switched, Clock, CompiledEvent, CompiledMode, CompiledSwitched, Jump,
};
pub use switched_show::{switching_latex, switching_markdown};
pub use text::{Source, TextModel};
pub use unchecked::spec_unchecked;
pub use validate::{validate, Validated, RESERVED_MODULES};
pub use warnings::{warnings, Warning};

#[cfg(test)]
mod tests;
