//! The solved model as a person reads it: the explicit equations in solve order, block by
//! block, with the pivots each block divides by, and the outputs; in Markdown (DSL syntax) and
//! in LaTeX, so that the compiler's result can be set beside the equations of a paper.

use crate::expr::{ExprId, Sym};
use crate::print::{to_dsl, to_latex};
use crate::program::Explanation;
use crate::solved::{symbol_name, Solved};
use crate::spec::ModelSpec;
use crate::system::{Body, Group};
use std::fmt::Write;

/// Prints the blocks of `solved` (a model compiled from `spec`).
pub fn explain(solved: &Solved, spec: &ModelSpec) -> Explanation {
    let pool = &solved.pool;
    let dsl = |e: ExprId| to_dsl(pool, e, &|s| symbol_name(spec, s));
    let latex = |e: ExprId| to_latex(pool, e, &|s| latex_symbol(spec, s));
    let mut md = format!("# `{}`: the solved equations\n\n", spec.name);
    let mut tex = String::from("\\begin{align*}\n");
    // Writing into a String cannot fail.
    for (k, group) in solved.system.groups.iter().enumerate() {
        let defined: Vec<String> = group
            .defines()
            .into_iter()
            .map(|s| symbol_name(spec, s))
            .collect();
        let _ = writeln!(
            md,
            "## Block {}: {} ({})\n",
            k + 1,
            defined.join(", "),
            match group.body {
                Body::Symbolic(_) => "solved symbolically",
                Body::Numeric { .. } => "solved numerically at run time",
            }
        );
        pivots(&mut md, group);
        match &group.body {
            Body::Symbolic(definitions) => {
                for (s, e) in definitions {
                    let _ = writeln!(md, "    {} = {}", symbol_name(spec, *s), dsl(*e));
                    let _ = writeln!(tex, "{} &= {} \\\\", latex_symbol(spec, *s), latex(*e));
                }
            }
            Body::Numeric {
                matrix,
                rhs,
                results,
                ..
            } => {
                let n = results.len();
                for (i, row) in matrix.chunks(n.max(1)).enumerate() {
                    let terms = |print: &dyn Fn(ExprId) -> String,
                                 name: &dyn Fn(Sym) -> String,
                                 times: &str| {
                        row.iter()
                            .zip(results)
                            .map(|(&a, &x)| format!("({}){times}{}", print(a), name(x)))
                            .collect::<Vec<_>>()
                            .join(" + ")
                    };
                    let _ = writeln!(
                        md,
                        "    {} = {}",
                        terms(&dsl, &|s| symbol_name(spec, s), "*"),
                        dsl(rhs[i])
                    );
                    let _ = writeln!(
                        tex,
                        "{} &= {} \\\\",
                        terms(&latex, &|s| latex_symbol(spec, s), " "),
                        latex(rhs[i])
                    );
                }
            }
        }
        md.push('\n');
    }
    let outputs: Vec<(String, String)> =
        solved.outputs.iter().map(|&e| (dsl(e), latex(e))).collect();
    let shown = spec
        .outputs
        .iter()
        .zip(&outputs)
        .filter(|(o, _)| !is_internal(&o.name));
    for (k, (output, (text, tex_text))) in shown.enumerate() {
        if k == 0 {
            md.push_str("## Outputs\n\n");
        }
        let _ = writeln!(md, "    {} = {}", output.name, text);
        let _ = writeln!(tex, "{} &= {} \\\\", latex_name(&output.name), tex_text);
    }
    tex.push_str("\\end{align*}\n");
    Explanation {
        markdown: md,
        latex: tex,
        outputs,
    }
}

/// Whether an output is the front end's own (a name no user can write, such as a switched
/// model's guard `when:impact`): computed like any output, but not printed with the user's.
pub fn is_internal(name: &str) -> bool {
    name.contains(':')
}

fn pivots(md: &mut String, group: &Group) {
    if group.pivots.is_empty() {
        md.push_str("No pivot.\n\n");
    } else {
        let texts: Vec<String> = group
            .pivots
            .iter()
            .map(|p| format!("`{}`", p.text))
            .collect();
        let _ = writeln!(md, "Pivots checked at run time: {}.\n", texts.join(", "));
    }
}

/// A symbol in LaTeX: a derivative as a dot over its state.
fn latex_symbol(spec: &ModelSpec, s: Sym) -> String {
    match s {
        Sym::Der(i) => match spec.states.get(i) {
            Some(state) => format!("\\dot{{{}}}", latex_name(&state.name)),
            None => symbol_name(spec, s),
        },
        Sym::Aux(k) => format!("a_{{{k}}}"),
        other => latex_name(&symbol_name(spec, other)),
    }
}

const GREEK: [&str; 35] = [
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
    "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi",
    "omega", "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi",
    "Omega", "varphi",
];

/// A DSL name in LaTeX: `Omega_x` is `\Omega_{x}`, `theta` is `\theta`, `energy` is
/// `\mathrm{energy}`, a one-letter name stays as it is.
pub fn latex_name(name: &str) -> String {
    let word = |w: &str| {
        if GREEK.contains(&w) {
            format!("\\{w}")
        } else if w.chars().count() <= 1 {
            w.to_string()
        } else {
            format!("\\mathrm{{{}}}", w.replace('_', "\\_"))
        }
    };
    match name.split_once('_') {
        Some((base, sub)) if !base.is_empty() && !sub.is_empty() => {
            let sub = if GREEK.contains(&sub) {
                format!("\\{sub}")
            } else {
                sub.replace('_', "\\_")
            };
            format!("{}_{{{sub}}}", word(base))
        }
        _ => word(name),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_become_latex() {
        assert_eq!(latex_name("theta"), "\\theta");
        assert_eq!(latex_name("Omega_x"), "\\Omega_{x}");
        assert_eq!(latex_name("w_phi"), "w_{\\phi}");
        assert_eq!(latex_name("mu_st"), "\\mu_{st}");
        assert_eq!(latex_name("V_X"), "V_{X}");
        assert_eq!(latex_name("m"), "m");
        assert_eq!(latex_name("energy"), "\\mathrm{energy}");
        assert_eq!(latex_name("z_residual"), "z_{residual}");
    }
}
