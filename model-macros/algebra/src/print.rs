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
    fn open(self) -> &'static str {
        match self {
            Notation::Dsl => "(",
            Notation::Latex => "\\left(",
        }
    }

    fn close(self) -> &'static str {
        match self {
            Notation::Dsl => ")",
            Notation::Latex => "\\right)",
        }
    }

    /// What separates the factors of a product.
    fn times(self) -> &'static str {
        match self {
            Notation::Dsl => "*",
            Notation::Latex => " ",
        }
    }

    /// The text before and after a square root's radicand.
    fn sqrt(self) -> (&'static str, &'static str) {
        match self {
            Notation::Dsl => ("sqrt(", ")"),
            Notation::Latex => ("\\sqrt{", "}"),
        }
    }

    /// The text before a power's base, between base and exponent, and after the exponent.
    fn power(self) -> [&'static str; 3] {
        match self {
            Notation::Dsl => ["", "^", ""],
            Notation::Latex => ["{", "}^{", "}"],
        }
    }

    /// The text before a call's arguments, and after them.
    fn call(self, func: Func) -> (String, &'static str) {
        match self {
            Notation::Dsl => (format!("{}(", func.name()), ")"),
            Notation::Latex => match func {
                Func::Sin | Func::Cos | Func::Tan | Func::Exp | Func::Ln => {
                    (format!("\\{}\\left(", func.name()), "\\right)")
                }
                Func::Sqrt => ("\\sqrt{".into(), "}"),
                Func::Abs => ("\\left|".into(), "\\right|"),
                Func::Atan2 | Func::Hypot | Func::Sign => (
                    format!("\\operatorname{{{}}}\\left(", func.name()),
                    "\\right)",
                ),
                Func::Min | Func::Max => (format!("\\{}\\left(", func.name()), "\\right)"),
            },
        }
    }
}

/// Prints `id` in DSL syntax; `name` spells each symbol.
pub fn to_dsl(pool: &Pool, id: ExprId, name: &dyn Fn(Sym) -> String) -> String {
    let mut out = String::new();
    Printer::new(Notation::Dsl, pool, name, &mut out).print(id);
    out
}

/// Prints `id` as LaTeX math; `name` spells each symbol (in LaTeX, e.g. `\dot{\theta}`).
pub fn to_latex(pool: &Pool, id: ExprId, name: &dyn Fn(Sym) -> String) -> String {
    let mut out = String::new();
    Printer::new(Notation::Latex, pool, name, &mut out).print(id);
    out
}

fn number(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{}", v as i64)
    } else {
        format!("{v}")
    }
}

type Name<'a> = &'a dyn Fn(Sym) -> String;

/// One traversal writing into one text: each node's text is written once, where it goes, so
/// printing costs the length of the text however deep the expression nests (returning each
/// subexpression's text to be copied into its parent's cost the depth times the length).
struct Printer<'a> {
    n: Notation,
    pool: &'a Pool,
    name: Name<'a>,
    out: &'a mut String,
}

impl<'a> Printer<'a> {
    fn new(n: Notation, pool: &'a Pool, name: Name<'a>, out: &'a mut String) -> Self {
        Printer { n, pool, name, out }
    }

    /// How tightly the printed form of `id` binds (known before it is printed, so that the
    /// parentheses around it can be written first).
    fn prec(&self, id: ExprId) -> Prec {
        match self.pool.node(id) {
            Node::Const(bits) if f64::from_bits(*bits) < 0.0 => Prec::Unary,
            Node::Const(_) | Node::Sym(_) => Prec::Atom,
            Node::Add(_) => Prec::Sum,
            Node::Mul(_) if self.coefficient(id) < 0.0 => Prec::Unary,
            Node::Mul(_) => Prec::Product,
            Node::Pow([_, e]) => match self.pool.as_const(*e) {
                Some(0.5) => Prec::Atom,
                Some(v) if v < 0.0 => Prec::Product,
                _ => Prec::Power,
            },
            Node::Call(..) | Node::Call2(..) | Node::Select(_) => Prec::Atom,
        }
    }

    /// The numeric coefficient of a product (one if it has none).
    fn coefficient(&self, id: ExprId) -> f64 {
        match self.pool.node(id) {
            Node::Mul(fs) => fs
                .iter()
                .rev()
                .find_map(|&f| self.pool.as_const(f))
                .unwrap_or(1.0),
            _ => 1.0,
        }
    }

    fn push(&mut self, text: &str) {
        self.out.push_str(text);
    }

    /// `id`, in parentheses if it binds less tightly than `at_least`.
    fn wrapped(&mut self, id: ExprId, at_least: Prec) {
        if self.prec(id) >= at_least {
            self.print(id);
        } else {
            self.push(self.n.open());
            self.print(id);
            self.push(self.n.close());
        }
    }

    fn print(&mut self, id: ExprId) {
        let (n, pool) = (self.n, self.pool);
        match pool.node(id) {
            Node::Const(bits) => self.push(&number(f64::from_bits(*bits))),
            Node::Sym(s) => {
                let text = (self.name)(*s);
                self.push(&text);
            }
            Node::Add(ts) => {
                for (k, &t) in ts.iter().enumerate() {
                    let negated = self.negated(t);
                    match (k, negated) {
                        (0, true) => self.push("-"),
                        (0, false) => {}
                        (_, true) => self.push(" - "),
                        (_, false) => self.push(" + "),
                    }
                    self.unsigned_term(t);
                }
            }
            Node::Mul(_) => {
                if self.coefficient(id) < 0.0 {
                    self.push("-");
                }
                self.product(id);
            }
            Node::Pow([b, e]) => {
                let ev = pool.as_const(*e);
                if ev == Some(0.5) {
                    let (open, close) = n.sqrt();
                    self.push(open);
                    self.print(*b);
                    self.push(close);
                    return;
                }
                if ev.is_some_and(|v| v < 0.0) {
                    self.product(id);
                    return;
                }
                let [open, between, close] = n.power();
                self.push(open);
                self.wrapped(*b, Prec::Atom);
                self.push(between);
                match n {
                    // LaTeX braces the exponent: no parentheses needed.
                    Notation::Latex => self.print(*e),
                    Notation::Dsl => self.wrapped(*e, Prec::Power),
                }
                self.push(close);
            }
            Node::Call(f, [a]) => self.call(*f, &[*a]),
            Node::Call2(f, [a, b]) => self.call(*f, &[*a, *b]),
            Node::Select([l, r, a, b]) => {
                if let Some((f, x, y)) = pool.as_min_max(id) {
                    return self.call(f, &[x, y]);
                }
                match n {
                    Notation::Dsl => {
                        self.push("if(");
                        self.print(*l);
                        self.push(" > ");
                        self.print(*r);
                        self.push(", ");
                        self.print(*a);
                        self.push(", ");
                        self.print(*b);
                        self.push(")");
                    }
                    Notation::Latex => {
                        self.push("\\begin{cases} ");
                        self.print(*a);
                        self.push(" & \\text{if } ");
                        self.print(*l);
                        self.push(" > ");
                        self.print(*r);
                        self.push(" \\\\ ");
                        self.print(*b);
                        self.push(" & \\text{otherwise} \\end{cases}");
                    }
                }
            }
        }
    }

    fn call(&mut self, f: Func, args: &[ExprId]) {
        let (open, close) = self.n.call(f);
        self.push(&open);
        for (k, &a) in args.iter().enumerate() {
            if k > 0 {
                self.push(", ");
            }
            self.print(a);
        }
        self.push(close);
    }

    /// Whether a term of a sum is printed with a minus sign.
    fn negated(&self, t: ExprId) -> bool {
        match self.pool.node(t) {
            Node::Const(bits) => f64::from_bits(*bits) < 0.0,
            Node::Mul(_) => self.coefficient(t) < 0.0,
            _ => false,
        }
    }

    /// A term of a sum without its sign.
    fn unsigned_term(&mut self, t: ExprId) {
        match self.pool.node(t) {
            Node::Const(bits) if f64::from_bits(*bits) < 0.0 => {
                self.push(&number(-f64::from_bits(*bits)))
            }
            Node::Mul(_) => self.product(t),
            _ => self.wrapped(t, Prec::Product),
        }
    }

    /// A product (or a lone negative power) as `c*a*b/(d*e)`, without its sign.
    fn product(&mut self, id: ExprId) {
        let (n, pool) = (self.n, self.pool);
        let factors: &[ExprId] = match pool.node(id) {
            Node::Mul(fs) => fs,
            _ => std::slice::from_ref(&id),
        };
        let mut coefficient = 1.0;
        let mut num: Vec<ExprId> = Vec::new();
        // Each divisor: its base and the magnitude of its exponent.
        let mut den: Vec<(ExprId, f64)> = Vec::new();
        for &f in factors {
            if let Some(c) = pool.as_const(f) {
                coefficient = c;
                continue;
            }
            if let Node::Pow([b, e]) = pool.node(f) {
                if let Some(ev) = pool.as_const(*e).filter(|v| *v < 0.0) {
                    den.push((*b, -ev));
                    continue;
                }
            }
            num.push(f);
        }
        let magnitude = coefficient.abs();
        let times = n.times();
        let mut first = true;
        let mut top = |p: &mut Self, write: &mut dyn FnMut(&mut Self)| {
            if !first {
                p.push(times);
            }
            first = false;
            write(p);
        };
        if n == Notation::Latex && !den.is_empty() {
            self.push("\\frac{");
        }
        if magnitude != 1.0 || num.is_empty() {
            top(self, &mut |p| p.push(&number(magnitude)));
        }
        for &f in &num {
            top(self, &mut |p| p.wrapped(f, Prec::Unary));
        }
        match (n, den.len()) {
            (_, 0) => {}
            (Notation::Dsl, 1) => {
                self.push("/");
                self.divisor(den[0]);
            }
            (Notation::Dsl, _) => {
                self.push("/(");
                self.divisors(&den);
                self.push(")");
            }
            (Notation::Latex, _) => {
                self.push("}{");
                self.divisors(&den);
                self.push("}");
            }
        }
    }

    fn divisors(&mut self, den: &[(ExprId, f64)]) {
        for (k, &d) in den.iter().enumerate() {
            if k > 0 {
                self.push(self.n.times());
            }
            self.divisor(d);
        }
    }

    /// `base^exponent`, a divisor of a product.
    fn divisor(&mut self, (base, exponent): (ExprId, f64)) {
        match integer_exponent(exponent) {
            Some(1) => self.wrapped(base, Prec::Atom),
            Some(k) => self.raised(base, &k.to_string()),
            None if exponent == 0.5 => {
                let (open, close) = self.n.sqrt();
                self.push(open);
                self.print(base);
                self.push(close);
            }
            None => self.raised(base, &number(exponent)),
        }
    }

    fn raised(&mut self, base: ExprId, exponent: &str) {
        let [open, between, close] = self.n.power();
        self.push(open);
        self.wrapped(base, Prec::Atom);
        self.push(between);
        self.push(exponent);
        self.push(close);
    }
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
    fn prints_hypot_and_atan2() {
        let mut p = Pool::new();
        let th = p.sym(Sym::State(0));
        let a = p.sym(Sym::Param(0));
        let two = p.num(2.0);
        let ta = p.mul2(two, a);
        let h = p.hypot(th, ta);
        assert_eq!(to_dsl(&p, h, &names), "hypot(theta, 2*p0)");
        assert_eq!(
            to_latex(&p, h, &names),
            "\\operatorname{hypot}\\left(theta, 2 p0\\right)"
        );
        let q = p.div(a, h);
        assert_eq!(to_dsl(&p, q, &names), "p0/hypot(theta, 2*p0)");
        let at = p.atan2(a, th);
        assert_eq!(to_dsl(&p, at, &names), "atan2(p0, theta)");
        assert_eq!(
            to_latex(&p, at, &names),
            "\\operatorname{atan2}\\left(p0, theta\\right)"
        );
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
