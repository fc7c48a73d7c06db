//! The model as the compiler would see it if the validator let every mistake through.
//!
//! The compiler does not trust its input: it must turn a cycle among lets, an unknown name or a
//! variant keeping nothing known into a diagnostic, never a panic. Those defences are
//! unreachable through [`validate`](crate::validate), which reports such mistakes first, so
//! tests of the compiler build their specs here: the same text, the same parser, only the
//! checks left out.

use crate::ast::{Expr, ModelAst};
use crate::names::DER;
use model_algebra::{Ast, Condition, EquationSpec, Func, ModelSpec, Named, VariantSpec};

/// Converts the model to the compiler's spec without checking it. Only a call of a function
/// the DSL does not have and an `if` testing `==` (which the spec cannot express) are errors, at
/// the function's name or the comparison.
pub fn spec_unchecked(ast: &ModelAst) -> syn::Result<ModelSpec> {
    let named = |item: &Named<Expr>| -> syn::Result<Named<Ast>> {
        Ok(Named {
            name: item.name.clone(),
            id: item.id,
            value: convert(ast, &item.value)?,
        })
    };
    let equations = (ast.equations.iter().enumerate())
        .map(|(k, equation)| {
            Ok(EquationSpec {
                label: (equation.label.as_ref())
                    .map_or_else(|| format!("equation {}", k + 1), |l| l.name.clone()),
                id: equation.id,
                lhs: convert(ast, &equation.lhs)?,
                rhs: convert(ast, &equation.rhs)?,
            })
        })
        .collect::<syn::Result<_>>()?;
    Ok(ModelSpec {
        name: ast.name.to_string(),
        params: ast.params.clone(),
        states: ast.states.clone(),
        lets: ast.lets.iter().map(named).collect::<syn::Result<_>>()?,
        equations,
        outputs: ast.outputs.iter().map(named).collect::<syn::Result<_>>()?,
        variants: (ast.variants.iter())
            .map(|variant| VariantSpec {
                name: variant.name.to_string(),
                id: variant.id,
                keep: variant.keep.clone(),
                fix: variant.fix.clone(),
            })
            .collect(),
    })
}

fn convert(ast: &ModelAst, expr: &Expr) -> syn::Result<Ast> {
    let boxed = |expr: &Expr| convert(ast, expr).map(Box::new);
    Ok(match expr {
        Expr::Num(id, value) => Ast::Num(*id, *value),
        Expr::Name(id, name) => Ast::Name(*id, name.clone()),
        Expr::Neg(id, arg) => Ast::Neg(*id, boxed(arg)?),
        Expr::Bin(id, op, lhs, rhs) => Ast::Bin(*id, *op, boxed(lhs)?, boxed(rhs)?),
        Expr::Call(call) if call.func == DER && call.args.len() == 1 => {
            Ast::Der(call.id, boxed(&call.args[0])?)
        }
        Expr::Call(call) => {
            let func = Func::from_name(&call.func).ok_or_else(|| {
                (ast.spans.range(call.func_id)).error(format!("unknown function `{}`", call.func))
            })?;
            let args = call.args.iter().map(|arg| convert(ast, arg));
            Ast::Call(call.id, func, args.collect::<syn::Result<_>>()?)
        }
        Expr::If {
            id,
            cond,
            then,
            otherwise,
        } => {
            let op = cond
                .op
                .ordering()
                .ok_or_else(|| (ast.spans.range(cond.id)).error("`if` cannot test `==`"))?;
            let cond = Condition {
                id: cond.id,
                lhs: convert(ast, &cond.lhs)?,
                op,
                rhs: convert(ast, &cond.rhs)?,
            };
            Ast::If(*id, Box::new(cond), boxed(then)?, boxed(otherwise)?)
        }
    })
}
