//! A model without states: reported first and alone, since every use of an undeclared state
//! would otherwise be reported as an unknown name before the cause.

use crate::ast::{Expr, ModelAst};
use crate::span::SpanRange;

/// The error for a model with no `states`, naming what the equations differentiate (the states
/// the user meant); `None` when the model has states.
pub(crate) fn missing_states(ast: &ModelAst) -> Option<syn::Error> {
    if !ast.states.is_empty() {
        return None;
    }
    let mut meant: Vec<String> = Vec::new();
    for equation in &ast.equations {
        for side in [&equation.lhs, &equation.rhs] {
            side.walk(&mut |node| {
                if let Expr::Call(call) = node {
                    if let [Expr::Name(_, name)] = call.args.as_slice() {
                        let shown = format!("`{name}`");
                        if call.func == "der" && !meant.contains(&shown) {
                            meant.push(shown);
                        }
                    }
                }
            });
        }
    }
    let hint = match meant.is_empty() {
        true => String::new(),
        false => format!(" (the equations differentiate {})", meant.join(", ")),
    };
    Some(SpanRange::single(ast.name.span()).error(format!(
        "the model has no states: declare them in `states {{ .. }}`{hint}"
    )))
}
