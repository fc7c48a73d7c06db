//! One compiled [`Program`] turned into the body of an emitted function, statement by statement.
//!
//! The translation is deliberately dumb: the compiler already did all the algebra, shared every
//! subexpression and decided which pivots to check, so each statement becomes one line of Rust.
//! The emitted bodies read `t`, `y`, `p` (the parameters) and, for outputs, `dy`; they write `dy`,
//! `out` or `jac`, and refer to the model's name through a `MODEL_NAME` constant.

use model_algebra::program::{Node, Operand, Program, Stmt, Target};
use model_algebra::spec::Func;
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

/// The statements of `program`, as Rust.
pub fn statements(program: &Program) -> TokenStream {
    program.stmts.iter().map(statement).collect()
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

fn statement(stmt: &Stmt) -> TokenStream {
    match stmt {
        Stmt::Let { tmp, node: value } => {
            let name = tmp_ident(*tmp);
            let value = node(value);
            quote! { let #name: f64 = #value; }
        }
        Stmt::SinCos { sin, cos, arg } => {
            let (sin, cos, arg) = (tmp_ident(*sin), tmp_ident(*cos), operand(arg));
            quote! { let (#sin, #cos) = #arg.sin_cos(); }
        }
        Stmt::CheckPivot { value, text } => {
            let value = operand(value);
            quote! {
                if !(#value != 0.0 && #value.is_finite()) {
                    return ::core::result::Result::Err(::model_runtime::EvalError::SingularPivot {
                        model: MODEL_NAME,
                        pivot: #text,
                        value: #value,
                    });
                }
            }
        }
        Stmt::SolveBlock {
            n,
            matrix,
            rhs,
            result,
            text,
        } => {
            let rows = matrix.chunks(*n).map(|row| {
                let row = row.iter().map(operand);
                quote! { [#(#row),*] }
            });
            let rhs = rhs.iter().map(operand);
            let result = result.iter().map(|tmp| tmp_ident(*tmp));
            quote! {
                let [#(#result),*] = ::model_runtime::linalg::solve_block::<#n>(
                    [#(#rows),*],
                    [#(#rhs),*],
                    MODEL_NAME,
                    #text,
                )?;
            }
        }
        Stmt::Store { target, value } => {
            let target = target_place(*target);
            let value = operand(value);
            quote! { #target = #value; }
        }
    }
}

/// Where a [`Target`] lives in the emitted function.
pub fn target_place(target: Target) -> TokenStream {
    match target {
        Target::Der(i) => quote! { dy[#i] },
        Target::Output(k) => quote! { out[#k] },
        Target::Jac(i, j) => quote! { jac[#i][#j] },
    }
}

fn node(node: &Node) -> TokenStream {
    match node {
        Node::Copy(a) => operand(a),
        Node::Neg(a) => {
            let a = operand(a);
            quote! { -#a }
        }
        Node::Add(a, b) => binary(a, quote! { + }, b),
        Node::Sub(a, b) => binary(a, quote! { - }, b),
        Node::Mul(a, b) => binary(a, quote! { * }, b),
        Node::Div(a, b) => binary(a, quote! { / }, b),
        Node::Powi(a, n) => {
            let a = operand(a);
            quote! { #a.powi(#n) }
        }
        Node::Powf(a, b) => {
            let (a, b) = (operand(a), operand(b));
            quote! { #a.powf(#b) }
        }
        Node::Call(func, a) => {
            let a = operand(a);
            let method = match func {
                Func::Sin => "sin",
                Func::Cos => "cos",
                Func::Tan => "tan",
                Func::Sqrt => "sqrt",
                Func::Exp => "exp",
                Func::Ln => "ln",
                Func::Abs => "abs",
                Func::Atan2 => {
                    return quote! {
                        ::core::compile_error!("the equation compiler emitted a one-argument `atan2`")
                    }
                }
            };
            let method = Ident::new(method, Span::call_site());
            quote! { #a.#method() }
        }
        Node::Atan2(a, b) => {
            let (a, b) = (operand(a), operand(b));
            quote! { #a.atan2(#b) }
        }
    }
}

fn binary(a: &Operand, op: TokenStream, b: &Operand) -> TokenStream {
    let (a, b) = (operand(a), operand(b));
    quote! { #a #op #b }
}

fn operand(operand: &Operand) -> TokenStream {
    match *operand {
        Operand::Const(value) => constant(value),
        Operand::State(i) => quote! { y[#i] },
        Operand::Param(i) => quote! { p[#i] },
        Operand::Der(i) => quote! { dy[#i] },
        Operand::Time => quote! { t },
        Operand::Tmp(tmp) => {
            let tmp = tmp_ident(tmp);
            quote! { #tmp }
        }
    }
}

/// An `f64` constant as a token that survives any surrounding operator (negatives in parens).
pub fn constant(value: f64) -> TokenStream {
    if value.is_nan() {
        quote! { f64::NAN }
    } else if value == f64::INFINITY {
        quote! { f64::INFINITY }
    } else if value == f64::NEG_INFINITY {
        quote! { f64::NEG_INFINITY }
    } else if value.is_sign_negative() {
        let magnitude = Literal::f64_suffixed(-value);
        quote! { (-#magnitude) }
    } else {
        let literal = Literal::f64_suffixed(value);
        quote! { #literal }
    }
}

fn tmp_ident(tmp: u32) -> Ident {
    Ident::new(&format!("t{tmp}"), Span::call_site())
}
