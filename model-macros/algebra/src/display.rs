//! Programs printed as readable pseudo-Rust, for debugging and snapshot tests.

use std::fmt;

use crate::program::{Node, Operand, Program, Stmt, Target};

impl fmt::Display for Operand {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Operand::Const(v) => write!(f, "{v:?}"),
            Operand::State(i) => write!(f, "y[{i}]"),
            Operand::Param(i) => write!(f, "p[{i}]"),
            Operand::Der(i) => write!(f, "dy[{i}]"),
            Operand::Time => write!(f, "t"),
            Operand::Tmp(k) => write!(f, "t{k}"),
        }
    }
}

impl fmt::Display for Node {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Node::Copy(a) => write!(f, "{a}"),
            Node::Neg(a) => write!(f, "-{a}"),
            Node::Add(a, b) => write!(f, "{a} + {b}"),
            Node::Sub(a, b) => write!(f, "{a} - {b}"),
            Node::Mul(a, b) => write!(f, "{a} * {b}"),
            Node::Div(a, b) => write!(f, "{a} / {b}"),
            Node::Powi(a, n) => write!(f, "{a}.powi({n})"),
            Node::Powf(a, b) => write!(f, "{a}.powf({b})"),
            Node::Call(func, a) => write!(f, "{a}.{}()", func.name()),
            Node::Call2(func, a, b) => write!(f, "{a}.{}({b})", func.name()),
            Node::Select(a, b, c, d) => write!(f, "if {a} > {b} {{ {c} }} else {{ {d} }}"),
        }
    }
}

impl fmt::Display for Target {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Target::Der(i) => write!(f, "dy[{i}]"),
            Target::Output(k) => write!(f, "out[{k}]"),
            Target::Jac(i, j) => write!(f, "jac[{i}][{j}]"),
        }
    }
}

impl fmt::Display for Program {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for s in &self.stmts {
            match s {
                Stmt::Let { tmp, node } => writeln!(f, "let t{tmp} = {node};")?,
                Stmt::SinCos { sin, cos, arg } => {
                    writeln!(f, "let (t{sin}, t{cos}) = {arg}.sin_cos();")?
                }
                Stmt::CheckPivot {
                    value,
                    text,
                    sums,
                    tolerance,
                } => {
                    write!(f, "check({value}, {text:?}")?;
                    for c in sums {
                        write!(f, ", |{}| > {tolerance:e} * {}", c.sum, c.magnitude)?;
                    }
                    writeln!(f, ")?;")?
                }
                Stmt::SolveBlock {
                    n,
                    matrix,
                    rhs,
                    result,
                    text,
                } => {
                    let list = |v: &[Operand]| {
                        v.iter()
                            .map(|o| o.to_string())
                            .collect::<Vec<_>>()
                            .join(", ")
                    };
                    let res: Vec<String> = result.iter().map(|r| format!("t{r}")).collect();
                    writeln!(
                        f,
                        "let [{}] = solve::<{n}>([{}], [{}], {text:?})?;",
                        res.join(", "),
                        list(matrix),
                        list(rhs)
                    )?
                }
                Stmt::Store { target, value } => writeln!(f, "{target} = {value};")?,
            }
        }
        Ok(())
    }
}
