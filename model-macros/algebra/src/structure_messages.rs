//! What the user reads when the equations cannot be solved for the derivatives: which equation
//! holds no derivative at all, which state is left without an equation, which equations compete
//! for too few derivatives.
//!
//! The structure analysis ([`crate::structure`]) works on indices; this turns its findings into
//! messages in the model's own words, each pointing at the node a fix starts from (the state
//! that needs an equation, the equation that is one too many).

use crate::linear::LinearForm;
use crate::spec::{Diagnostic, ModelSpec};
use crate::structure::StructureError;

/// `der(x), der(y)`.
pub(crate) fn derivatives(spec: &ModelSpec, vars: &[usize]) -> String {
    vars.iter()
        .map(|&v| format!("der({})", spec.states[v].name))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `first, second`.
pub(crate) fn labels(spec: &ModelSpec, equations: &[usize]) -> String {
    equations
        .iter()
        .map(|&e| spec.equations[e].label.clone())
        .collect::<Vec<_>>()
        .join(", ")
}

/// `1 equation`, `2 derivatives`.
fn count(n: usize, what: &str) -> String {
    format!("{n} {what}{}", if n == 1 { "" } else { "s" })
}

/// One diagnostic per equation that contains no derivative once `der(..)` is expanded: the
/// compiler solves for derivatives, so an algebraic constraint has to be differentiated first.
pub(crate) fn algebraic_equations(spec: &ModelSpec, forms: &[LinearForm]) -> Vec<Diagnostic> {
    forms
        .iter()
        .zip(&spec.equations)
        .filter(|(form, _)| form.coefficients.is_empty())
        .map(|(_, equation)| Diagnostic {
            id: equation.id,
            message: format!(
                "{} contains no derivative: algebraic equations (constraints) are not supported; \
                 differentiate the constraint in time, writing `lhs = rhs` as \
                 `der(lhs - rhs) = 0` (the chain rule is applied for you), and keep \
                 `lhs - rhs` as an output to watch its drift",
                equation.label,
            ),
        })
        .collect()
}

/// The diagnostics of a structure that admits no one-to-one assignment of equations to
/// derivatives.
pub(crate) fn structure_error(spec: &ModelSpec, error: &StructureError) -> Vec<Diagnostic> {
    match error {
        StructureError::Unused(vars) => vars
            .iter()
            .map(|&v| Diagnostic {
                id: spec.states[v].id,
                message: format!(
                    "no equation contains der({0}), so nothing determines `{0}`: \
                     each state needs an equation",
                    spec.states[v].name
                ),
            })
            .collect(),
        StructureError::Singular {
            surplus: Some(surplus),
            equations,
            vars,
            undetermined,
        } => {
            let mut message = format!(
                "structurally singular: {} ({}) contain only {} ({}), so `{}` is one \
                 equation too many",
                labels(spec, equations),
                count(equations.len(), "equation"),
                derivatives(spec, vars),
                count(vars.len(), "derivative"),
                spec.equations[*surplus].label,
            );
            if !undetermined.is_empty() {
                message.push_str(&format!(
                    ", and nothing is left to determine {}",
                    one_of(spec, undetermined)
                ));
            }
            vec![Diagnostic {
                id: spec.equations[*surplus].id,
                message,
            }]
        }
        StructureError::Singular {
            surplus: None,
            equations,
            undetermined,
            ..
        } => {
            // Each undetermined derivative is contained in an equation (else it is unused),
            // so `equations` is not empty.
            vec![Diagnostic {
                id: spec.states[undetermined[0]].id,
                message: format!(
                    "too few equations: {} share {} ({}); add an equation for {}",
                    derivatives(spec, undetermined),
                    count(equations.len(), "equation"),
                    labels(spec, equations),
                    one_of(spec, undetermined),
                ),
            }]
        }
    }
}

/// `der(x)` or `one of der(x), der(y)`.
fn one_of(spec: &ModelSpec, vars: &[usize]) -> String {
    if vars.len() == 1 {
        derivatives(spec, vars)
    } else {
        format!("one of {}", derivatives(spec, vars))
    }
}
