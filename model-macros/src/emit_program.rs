//! One compiled [`Program`] turned into the body of an emitted function, statement by statement.
//!
//! The translation is deliberately dumb: the compiler already did all the algebra, shared every
//! subexpression and decided which pivots to check, so each statement becomes one line of Rust.
//! The emitted bodies read `t`, `y`, `p` (the parameters) and, for outputs, `dy`; they write `dy`,
//! `out` or `jac`, and refer to the model's name through a `MODEL_NAME` constant.
//!
//! The body is written as text and handed to the compiler's lexer once: inside rustc every token
//! built one by one is a round trip through the proc-macro bridge, and a large model's programs
//! have thousands of statements.

use model_algebra::Func;
use model_algebra::{Node, Operand, Program, Stmt, Target};
use proc_macro2::TokenStream;
use std::fmt::Write;

/// The statements of `program`, as Rust.
pub fn statements(program: &Program) -> TokenStream {
    let mut text = String::new();
    for stmt in &program.stmts {
        statement(&mut text, stmt);
        text.push('\n');
    }
    lex(&text)
}

/// Every target `program` stores to.
pub fn stored_targets(program: &Program) -> Vec<Target> {
    program
        .stmts
        .iter()
        .filter_map(|stmt| match stmt {
            Stmt::Store { target, .. } => Some(*target),
            _ => None,
        })
        .collect()
}

/// `dst = 0.0;` for every place of `all` the program does not store to.
pub fn zero_unstored(program: &Program, all: impl Iterator<Item = Target>) -> TokenStream {
    let stored = stored_targets(program);
    let mut text = String::new();
    for target in all.filter(|target| !stored.contains(target)) {
        let _ = writeln!(text, "{} = 0.0;", place(target));
    }
    lex(&text)
}

/// An `f64` constant as a token that survives any surrounding operator (negatives in parens).
pub fn constant(value: f64) -> TokenStream {
    lex(&constant_text(value))
}

/// Text the generator wrote is Rust by construction; should the lexer still refuse it, the user
/// gets a compile error rather than a panic.
fn lex(text: &str) -> TokenStream {
    text.parse().unwrap_or_else(|error| {
        let message = format!("the model's generated code does not lex ({error}): this is a bug");
        quote::quote! { ::core::compile_error!(#message); }
    })
}

fn statement(out: &mut String, stmt: &Stmt) {
    // Writing into a String cannot fail.
    let _ = match stmt {
        Stmt::Let { tmp, node: value } => writeln!(out, "let t{tmp}: f64 = {};", node(value)),
        Stmt::SinCos { sin, cos, arg } => {
            writeln!(out, "let (t{sin}, t{cos}) = {}.sin_cos();", operand(arg))
        }
        Stmt::CheckPivot {
            value,
            text,
            sums,
            tolerance,
        } => {
            let value = operand(value);
            let tolerance = constant_text(*tolerance);
            let cancelled: String = sums
                .iter()
                .map(|c| {
                    format!(
                        " || {}.abs() <= {tolerance} * {}",
                        operand(&c.sum),
                        operand(&c.magnitude)
                    )
                })
                .collect();
            writeln!(
                out,
                "if !({value} != 0.0 && {value}.is_finite()){cancelled} {{ \
                 return ::core::result::Result::Err(\
                 ::model_runtime::EvalError::singular(MODEL_NAME, {text:?}, {value})); }}"
            )
        }
        Stmt::SolveBlock {
            n,
            matrix,
            rhs,
            result,
            text,
        } => {
            let rows: Vec<String> = matrix
                .chunks((*n).max(1))
                .map(|row| format!("[{}]", list(row.iter().map(operand))))
                .collect();
            let result = list(result.iter().map(|tmp| format!("t{tmp}")));
            writeln!(
                out,
                "let [{result}] = ::model_runtime::solve_block::<{n}>([{}], [{}], MODEL_NAME, {text:?})?;",
                rows.join(", "),
                list(rhs.iter().map(operand)),
            )
        }
        Stmt::Store { target, value } => writeln!(out, "{} = {};", place(*target), operand(value)),
    };
}

/// Where a [`Target`] lives in the emitted function.
fn place(target: Target) -> String {
    match target {
        Target::Der(i) => format!("dy[{i}]"),
        Target::Output(k) => format!("out[{k}]"),
        Target::Jac(i, j) => format!("jac[{i}][{j}]"),
    }
}

fn node(node: &Node) -> String {
    match node {
        Node::Copy(a) => operand(a),
        Node::Neg(a) => format!("-{}", operand(a)),
        Node::Add(a, b) => format!("{} + {}", operand(a), operand(b)),
        Node::Sub(a, b) => format!("{} - {}", operand(a), operand(b)),
        Node::Mul(a, b) => format!("{} * {}", operand(a), operand(b)),
        Node::Div(a, b) => format!("{} / {}", operand(a), operand(b)),
        Node::Powi(a, n) => format!("{}.powi({n})", operand(a)),
        Node::Powf(a, b) => format!("{}.powf({})", operand(a), operand(b)),
        Node::Call(Func::Sign, a) => {
            // `f64::signum` is 1 at zero; the DSL's `sign` is 0 there (and NaN stays NaN).
            let a = operand(a);
            format!("if {a} > 0.0 {{ 1.0 }} else if {a} < 0.0 {{ -1.0 }} else {{ {a} }}")
        }
        Node::Call(func, a) => {
            let method = match func {
                Func::Sin => "sin",
                Func::Cos => "cos",
                Func::Tan => "tan",
                Func::Sqrt => "sqrt",
                Func::Exp => "exp",
                Func::Ln => "ln",
                Func::Abs => "abs",
                Func::Atan2 | Func::Hypot | Func::Min | Func::Max | Func::Sign => {
                    return format!(
                    "::core::compile_error!(\"the equation compiler emitted a one-argument `{}`\")",
                    func.name()
                )
                }
            };
            format!("{}.{method}()", operand(a))
        }
        // `f64::atan2`, `f64::hypot`: the method has the function's name.
        Node::Call2(func, a, b) => format!("{}.{}({})", operand(a), func.name(), operand(b)),
        // NaN when the comparison has no answer, so a NaN input is not hidden by the branch
        // taken (`f64::max(NaN, 1.0)` would be 1.0): the finiteness checks still see it.
        Node::Select(a, b, then, otherwise) => {
            let (a, b) = (operand(a), operand(b));
            format!(
                "if {a} > {b} {{ {} }} else if {a} <= {b} {{ {} }} else {{ f64::NAN }}",
                operand(then),
                operand(otherwise)
            )
        }
    }
}

fn operand(operand: &Operand) -> String {
    match *operand {
        Operand::Const(value) => constant_text(value),
        Operand::State(i) => format!("y[{i}]"),
        Operand::Param(i) => format!("p[{i}]"),
        Operand::Der(i) => format!("dy[{i}]"),
        Operand::Time => "t".to_string(),
        Operand::Tmp(tmp) => format!("t{tmp}"),
    }
}

/// `value` as a Rust `f64` literal: `Debug` prints the shortest text that reads back exactly
/// (with a `.` or an exponent, so it is a float literal); negatives go in parentheses.
fn constant_text(value: f64) -> String {
    if value.is_nan() {
        "f64::NAN".to_string()
    } else if value.is_infinite() {
        if value > 0.0 {
            "f64::INFINITY"
        } else {
            "f64::NEG_INFINITY"
        }
        .to_string()
    } else if value.is_sign_negative() {
        format!("(-{:?}_f64)", -value)
    } else {
        format!("{value:?}_f64")
    }
}

fn list(items: impl Iterator<Item = String>) -> String {
    items.collect::<Vec<_>>().join(", ")
}
