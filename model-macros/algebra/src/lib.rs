//! Symbolic algebra for the equation compiler.
//!
//! A model arrives as a [`spec::ModelSpec`] (the front end's parse, with a node id on every
//! part) and leaves as a [`program::CompiledModel`]: straight-line programs for the explicit
//! right-hand side, its Jacobian and the outputs. In between, one stage per module:
//! [`lower`] (syntax tree to interned expressions, with diagnostics at the user's nodes),
//! [`linear`] (each equation as coefficients of the derivatives), [`structure`] (matching and
//! block triangular form), [`solve`] (symbolic elimination per block into the definitions of
//! [`system`], or a numeric block when that would swell or no safe pivot exists), [`trig`]
//! (identities that take `atan2` and `sin_cos` calls out of the solution), [`jacobian`] (chain
//! rule through the solution), [`cse`] (the DAG as a program, counted by [`ops`]) and
//! [`variant`] (reduced models), chained by [`compile()`]. [`expr`], [`simplify`], [`expand`],
//! [`diff`] and [`print`](mod@print) are the algebra underneath; [`eval`] interprets a program, so the
//! emitted code can be tested without compiling it.
//!
//! ```
//! use model_algebra::spec::{Ast, BinOp, EquationSpec, ModelSpec, Named, NodeId};
//! use model_algebra::{compile, CompileOptions, Inputs};
//!
//! // `der(x*x) = -k*x*x`, i.e. `2 x der(x) = -k x^2`: the compiler solves for `der(x)`.
//! let name = |n: &str| Ast::Name(NodeId(0), n.into());
//! let mul = |a, b| Ast::Bin(NodeId(0), BinOp::Mul, Box::new(a), Box::new(b));
//! let named = |n: &str| Named { name: n.into(), id: NodeId(0), value: () };
//! let spec = ModelSpec {
//!     name: "decay".into(),
//!     params: vec![Named { name: "k".into(), id: NodeId(0), value: Some(0.5) }],
//!     states: vec![named("x")],
//!     lets: vec![],
//!     equations: vec![EquationSpec {
//!         label: "decay".into(),
//!         id: NodeId(1),
//!         lhs: Ast::Der(NodeId(0), Box::new(mul(name("x"), name("x")))),
//!         rhs: Ast::Neg(NodeId(0), Box::new(mul(name("k"), mul(name("x"), name("x"))))),
//!     }],
//!     outputs: vec![],
//!     variants: vec![],
//! };
//! let model = compile(&spec, &CompileOptions::default()).expect("compiles");
//! // The pivot `2*x` is checked at run time, named as the user would write it.
//! assert_eq!(model.pivots, vec!["2*x"]);
//! let inputs = Inputs { t: 0.0, states: &[3.0], params: &[0.5], ders: &[] };
//! let dy = model.rhs.eval(&inputs).unwrap().ders(1);
//! assert!((dy[0] - -0.75).abs() < 1e-15); // -k x / 2
//! ```
#![warn(missing_docs)]

pub mod compile;
pub mod cse;
pub mod diff;
mod display;
pub mod eval;
pub mod expand;
pub mod explain;
pub mod expr;
mod interpret;
pub mod jacobian;
pub mod linear;
pub mod lower;
pub mod ops;
pub mod print;
pub mod program;
pub mod simplify;
pub mod solve;
pub mod spec;
pub mod structure;
mod structure_messages;
pub mod system;
pub mod trig;
pub mod variant;

pub use compile::{compile, CompileOptions, PIVOT_TOLERANCE};
pub use eval::{EvalFailure, Inputs, Stores};

#[cfg(test)]
mod tests;
