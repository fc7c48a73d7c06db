//! Symbolic algebra for the equation compiler.
//!
//! A model arrives as a [`ModelSpec`] (the front end's parse, with a node id on every part) and
//! leaves as a [`CompiledModel`]: straight-line [`Program`]s for the explicit right-hand side,
//! its Jacobian and the outputs, and the solved equations printed ([`Explanation`]). The API is
//! this crate root; the stages are private modules, one per stage: `lower` (syntax tree to
//! interned expressions, with diagnostics at the user's nodes), `linear` (each equation as
//! coefficients of the derivatives), `structure` (matching and block triangular form), `solve`
//! (symbolic elimination per block into the definitions of `system`, or a numeric block when
//! that would swell or no safe pivot exists), `trig` (identities that take `atan2` and
//! `sin_cos` calls out of the solution), `jacobian` (chain rule through the solution), `cse`
//! (the DAG as a program, counted by `ops`), `solved` (the model after the algebra) and
//! `variant` (reduced models), chained by [`compile()`]. `expr`, `simplify`, `select` (the
//! non-smooth `sign`, `min`, `max` and `if`), `expand`, `diff` and `print` are the algebra
//! underneath; the interpreter ([`Program::eval`],
//! [`CompiledModel::derivatives`]) runs a program, so the emitted code can be tested without
//! compiling it and a model can be evaluated without compiling Rust.
//!
//! ```
//! use model_algebra::{compile, Ast, BinOp, CompileOptions, EquationSpec, Inputs, ModelSpec, Named, NodeId};
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

mod compile;
mod cse;
mod diff;
mod display;
mod eval;
mod expand;
mod explain;
mod expr;
mod flat;
mod hash;
mod interpret;
mod jacobian;
mod linear;
mod lower;
mod ops;
mod options;
mod print;
mod program;
mod program_part;
mod select;
mod simplify;
mod solve;
mod solved;
mod spec;
mod structure;
mod structure_messages;
mod system;
mod trig;
mod variant;

pub use compile::compile;
pub use eval::{solve_dense_in, EvalFailure, Inputs, Stores};
pub use explain::{is_internal, latex_name};
pub use expr::{call2_value, call_value, pow_value, select_value};
pub use flat::{
    Binary, Block, Check, FlatError, FlatProgram, Layout, Op, Scratch, Shape, Sink, Slot, Unary,
};
pub use interpret::FlatModel;
pub use model_ops::OpCounts;
pub use options::{CompileOptions, PIVOT_TOLERANCE};
pub use program::{CompiledModel, Explanation, Node, Operand, Program, Stmt, SumCheck, Target};
pub use program_part::Reads;
pub use spec::{
    Ast, BinOp, CmpOp, Condition, Diagnostic, EquationSpec, Func, ModelSpec, Named, NodeId,
    VariantSpec,
};

#[cfg(test)]
mod tests;
