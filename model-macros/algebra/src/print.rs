//! Expressions printed back in DSL syntax, with the user's names, or as LaTeX.
//!
//! A pivot that vanishes at run time is reported as text (`sin(theta)`), so the user can
//! recognise the singular configuration in their own notation; the solved equations are printed
//! in both notations so that a physicist can set them beside a paper's. One traversal serves
//! both: the [`Notation`] decides only how each form is spelled.

use crate::expr::{integer_exponent, ExprId, Node, Pool, Sym};
use crate::spec::Func;

/// Binding strength of the printed forms, loosest first.
#[derive(Clone, Copy, PartialEq, PartialOrd)]
enum Prec {
    Sum,
    Product,
    Unary,
    Power,
    Atom,
}

/// How the printed forms are spelled.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Notation {
    /// The DSL's own syntax: `a*b/(c*d)`, `x^2`, `sqrt(x)`, `sin(x)`.
    Dsl,
    /// LaTeX math: `\frac{a b}{c d}`, `x^{2}`, `\sqrt{x}`, `\sin\left(x\right)`.
    Latex,
}

impl Notation {
    fn paren(self, text: &str) -> String {
        match self {
            Notation::Dsl => format!("({text})"),
            Notation::Latex => format!("\\left({text}\\right)"),
        }
    }

    fn sqrt(self, text: &str) -> String {
        match self {
            Notation::Dsl => format!("sqrt({text})"),
            Notation::Latex => format!("\\sqrt{{{text}}}"),
        }
    }

    fn power(self, base: &str, exponent: &str) -> String {
        match self {
            Notation::Dsl => format!("{base}^{exponent}"),
            Notation::Latex => format!("{{{base}}}^{{{exponent}}}"),
        }
    }

    fn call(self, func: Func, args: &[String]) -> String {
        match self {
            Notation::Dsl => format!("{}({})", func.name(), args.join(", ")),
            Notation::Latex => {
                let name = match func {
                    Func::Sin | Func::Cos | Func::Tan | Func::Exp | Func::Ln => {
                        format!("\\{}", func.name())
                    }
                    Func::Sqrt => return self.sqrt(&args.join(", ")),
                    Func::Abs => return format!("\\left|{}\\right|", args.join(", ")),
                    Func::Atan2 | Func::Sign => format!("\\operatorname{{{}}}", func.name()),
                    Func::Min | Func::Max => format!("\\{}", func.name()),
                };
                format!("{name}{}", self.paren(&args.join(", ")))
            }
        }
    }

    /// `then` where `condition` holds, else `otherwise`.
    fn select(self, condition: &str, then: &str, otherwise: &str) -> String {
        match self {
            Notation::Dsl => format!("if({condition}, {then}, {otherwise})"),
            Notation::Latex => format!(
                "\\begin{{cases}} {then} & \\text{{if }} {condition} \\\\ {otherwise} & \\text{{otherwise}} \\end{{cases}}"
            ),
        }
    }

    /// `num / den`, each a list of factors already printed.
    fn quotient(self, num: &[String], den: &[String]) -> String {
        let (times, group) = match self {
            Notation::Dsl => ("*", Notation::Dsl),
            Notation::Latex => (" ", Notation::Latex),
        };
        let top = num.join(times);
        match (self, den.len()) {
            (_, 0) => top,
            (Notation::Dsl, 1) => format!("{top}/{}", den[0]),
            (Notation::Dsl, _) => format!("{top}/{}", group.paren(&den.join(times))),
            (Notation::Latex, _) => format!("\\frac{{{top}}}{{{}}}", den.join(times)),
        }
    }
}

/// Prints `id` in DSL syntax; `name` spells each symbol.
pub fn to_dsl(pool: &Pool, id: ExprId, name: &dyn Fn(Sym) -> String) -> String {
    print(Notation::Dsl, pool, id, name).0
}

/// Prints `id` as LaTeX math; `name` spells each symbol (in LaTeX, e.g. `\dot{\theta}`).
pub fn to_latex(pool: &Pool, id: ExprId, name: &dyn Fn(Sym) -> String) -> String {
    print(Notation::Latex, pool, id, name).0
}

fn number(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{}", v as i64)
    } else {
        format!("{v}")
    }
}

fn wrap(notation: Notation, text: (String, Prec), at_least: Prec) -> String {
    if text.1 >= at_least {
        text.0
    } else {
        notation.paren(&text.0)
    }
}

type Name<'a> = &'a dyn Fn(Sym) -> String;

fn print(n: Notation, pool: &Pool, id: ExprId, name: Name) -> (String, Prec) {
    match pool.node(id) {
        Node::Const(bits) => {
            let v = f64::from_bits(*bits);
            let prec = if v < 0.0 { Prec::Unary } else { Prec::Atom };
            (number(v), prec)
        }
        Node::Sym(s) => (name(*s), Prec::Atom),
        Node::Add(ts) => {
            let mut out = String::new();
            for (k, &t) in ts.iter().enumerate() {
                let (c, negated) = negated_term(n, pool, t, name);
                match (k, negated) {
                    (0, true) => out.push_str(&format!("-{}", c)),
                    (0, false) => out.push_str(&c),
                    (_, true) => out.push_str(&format!(" - {}", c)),
                    (_, false) => out.push_str(&format!(" + {}", c)),
                }
            }
            (out, Prec::Sum)
        }
        Node::Mul(_) => {
            let (text, negated) = product(n, pool, id, name);
            if negated {
                (format!("-{text}"), Prec::Unary)
            } else {
                (text, Prec::Product)
            }
        }
        Node::Pow([b, e]) => {
            let ev = pool.as_const(*e);
            if ev == Some(0.5) {
                return (n.sqrt(&print(n, pool, *b, name).0), Prec::Atom);
            }
            if ev.is_some_and(|v| v < 0.0) {
                let (text, _) = product(n, pool, id, name);
                return (text, Prec::Product);
            }
            let base = wrap(n, print(n, pool, *b, name), Prec::Atom);
            let exp = match n {
                // LaTeX braces the exponent: no parentheses needed.
                Notation::Latex => print(n, pool, *e, name).0,
                Notation::Dsl => wrap(n, print(n, pool, *e, name), Prec::Power),
            };
            (n.power(&base, &exp), Prec::Power)
        }
        Node::Call(f, [a]) => (n.call(*f, &[print(n, pool, *a, name).0]), Prec::Atom),
        Node::Atan2([y, x]) => (
            n.call(
                Func::Atan2,
                &[print(n, pool, *y, name).0, print(n, pool, *x, name).0],
            ),
            Prec::Atom,
        ),
        Node::Select([l, r, a, b]) => {
            let text = |e: &ExprId| print(n, pool, *e, name).0;
            if let Some((f, x, y)) = pool.as_min_max(id) {
                return (n.call(f, &[text(&x), text(&y)]), Prec::Atom);
            }
            let condition = format!("{} > {}", text(l), text(r));
            (n.select(&condition, &text(a), &text(b)), Prec::Atom)
        }
    }
}

/// A term of a sum printed without its sign, and whether it was negative.
fn negated_term(n: Notation, pool: &Pool, t: ExprId, name: Name) -> (String, bool) {
    match pool.node(t) {
        Node::Const(bits) if f64::from_bits(*bits) < 0.0 => (number(-f64::from_bits(*bits)), true),
        Node::Mul(_) => product(n, pool, t, name),
        _ => (wrap(n, print(n, pool, t, name), Prec::Product), false),
    }
}

/// A product (or a lone negative power) as `c*a*b/(d*e)`, without its sign.
fn product(n: Notation, pool: &Pool, id: ExprId, name: Name) -> (String, bool) {
    let factors: Vec<ExprId> = match pool.node(id) {
        Node::Mul(fs) => fs.to_vec(),
        _ => vec![id],
    };
    let mut coefficient = 1.0;
    let mut num: Vec<String> = Vec::new();
    let mut den: Vec<String> = Vec::new();
    for f in factors {
        if let Some(c) = pool.as_const(f) {
            coefficient = c;
            continue;
        }
        if let Node::Pow([b, e]) = pool.node(f) {
            if let Some(ev) = pool.as_const(*e).filter(|v| *v < 0.0) {
                let base = wrap(n, print(n, pool, *b, name), Prec::Atom);
                let text = match (ev, integer_exponent(-ev)) {
                    (_, Some(1)) => base,
                    (_, Some(k)) => n.power(&base, &k.to_string()),
                    (-0.5, _) => n.sqrt(&print(n, pool, *b, name).0),
                    (v, None) => n.power(&base, &number(-v)),
                };
                den.push(text);
                continue;
            }
        }
        num.push(wrap(n, print(n, pool, f, name), Prec::Unary));
    }
    let negated = coefficient < 0.0;
    let magnitude = coefficient.abs();
    if magnitude != 1.0 || num.is_empty() {
        num.insert(0, number(magnitude));
    }
    (n.quotient(&num, &den), negated)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::Func;

    fn names(s: Sym) -> String {
        match s {
            Sym::State(0) => "theta".into(),
            Sym::State(i) => format!("y{i}"),
            Sym::Param(i) => format!("p{i}"),
            Sym::Der(i) => format!("der(y{i})"),
            Sym::Time => "t".into(),
            Sym::Aux(k) => format!("aux{k}"),
        }
    }

    #[test]
    fn prints_in_dsl_syntax() {
        let mut p = Pool::new();
        let th = p.sym(Sym::State(0));
        let a = p.sym(Sym::Param(0));
        let s = p.call(Func::Sin, th);
        assert_eq!(to_dsl(&p, s, &names), "sin(theta)");
        let two = p.num(2.0);
        let a2 = p.powf(a, 2.0);
        let prod = p.mul(&[two, a2, s]);
        let sum = p.sub(ExprId::ONE, prod);
        let text = to_dsl(&p, sum, &names);
        assert_eq!(text, "1 - 2*sin(theta)*p0^2");
        let q = p.div(a, s);
        assert_eq!(to_dsl(&p, q, &names), "p0/sin(theta)");
        let r = p.call(Func::Sqrt, a);
        assert_eq!(to_dsl(&p, r, &names), "sqrt(p0)");
        let inv = p.pow(s, ExprId::MINUS_ONE);
        assert_eq!(to_dsl(&p, inv, &names), "1/sin(theta)");
        let m = p.neg(a);
        let mm = p.mul2(m, s);
        assert_eq!(to_dsl(&p, mm, &names), "-p0*sin(theta)");
    }

    #[test]
    fn prints_in_latex() {
        let mut p = Pool::new();
        let th = p.sym(Sym::State(0));
        let a = p.sym(Sym::Param(0));
        let s = p.call(Func::Sin, th);
        assert_eq!(to_latex(&p, s, &names), "\\sin\\left(theta\\right)");
        let q = p.div(a, s);
        assert_eq!(
            to_latex(&p, q, &names),
            "\\frac{p0}{\\sin\\left(theta\\right)}"
        );
        let a2 = p.powf(a, 2.0);
        let sum = p.add(&[ExprId::ONE, a2]);
        let r = p.call(Func::Sqrt, sum);
        assert_eq!(to_latex(&p, r, &names), "\\sqrt{1 + {p0}^{2}}");
        let two = p.num(2.0);
        let prod = p.mul(&[two, a2, th]);
        let diff = p.sub(ExprId::ONE, prod);
        assert_eq!(to_latex(&p, diff, &names), "1 - 2 theta {p0}^{2}");
    }

    #[test]
    fn prints_sign_min_max_and_conditions() {
        let mut p = Pool::new();
        let th = p.sym(Sym::State(0));
        let a = p.sym(Sym::Param(0));
        let s = p.call(Func::Sign, th);
        assert_eq!(to_dsl(&p, s, &names), "sign(theta)");
        assert_eq!(
            to_latex(&p, s, &names),
            "\\operatorname{sign}\\left(theta\\right)"
        );
        let m = p.min_max(Func::Max, ExprId::ZERO, a);
        assert_eq!(to_dsl(&p, m, &names), "max(0, p0)");
        assert_eq!(to_latex(&p, m, &names), "\\max\\left(0, p0\\right)");
        let m = p.min_max(Func::Min, a, th);
        assert_eq!(to_dsl(&p, m, &names), "min(theta, p0)");
        let two = p.num(2.0);
        let c = p.compare(th, crate::spec::CmpOp::Ge, a, two, s);
        assert_eq!(to_dsl(&p, c, &names), "if(p0 > theta, sign(theta), 2)");
        assert_eq!(
            to_latex(&p, c, &names),
            "\\begin{cases} \\operatorname{sign}\\left(theta\\right) & \\text{if } p0 > theta \\\\ 2 & \\text{otherwise} \\end{cases}"
        );
    }
}
