//! Unit tests of the front end's stages, run on `proc_macro2` tokens.

mod nonsmooth;
mod parse;
mod validate;

use crate::ast::Expr;
use model_algebra::BinOp;

/// The expression fully parenthesised, to check precedence and associativity.
pub fn show(expr: &Expr) -> String {
    match expr {
        Expr::Num(_, value) => format!("{value}"),
        Expr::Name(_, name) => name.clone(),
        Expr::Neg(_, arg) => format!("(-{})", show(arg)),
        Expr::Bin(_, op, lhs, rhs) => {
            let op = match op {
                BinOp::Add => "+",
                BinOp::Sub => "-",
                BinOp::Mul => "*",
                BinOp::Div => "/",
                BinOp::Pow => "^",
            };
            format!("({}{op}{})", show(lhs), show(rhs))
        }
        Expr::Call(call) => {
            let args: Vec<String> = call.args.iter().map(show).collect();
            format!("{}({})", call.func, args.join(","))
        }
        Expr::If {
            cond,
            then,
            otherwise,
            ..
        } => format!(
            "if({}{}{},{},{})",
            show(&cond.lhs),
            cond.op.symbol(),
            show(&cond.rhs),
            show(then),
            show(otherwise)
        ),
    }
}

/// Every message of a (possibly combined) error.
pub fn messages(error: syn::Error) -> Vec<String> {
    error.into_iter().map(|e| e.to_string()).collect()
}
