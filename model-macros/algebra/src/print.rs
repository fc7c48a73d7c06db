//! Expressions printed back in DSL syntax, with the user's names.
//!
//! A pivot that vanishes at run time is reported as text (`sin(theta)`), so the user can
//! recognise the singular configuration in their own notation.

use crate::expr::{integer_exponent, ExprId, Node, Pool, Sym};

/// Binding strength of the printed forms, loosest first.
#[derive(Clone, Copy, PartialEq, PartialOrd)]
enum Prec {
    Sum,
    Product,
    Unary,
    Power,
    Atom,
}

/// Prints `id` in DSL syntax; `name` spells each symbol.
pub fn to_dsl(pool: &Pool, id: ExprId, name: &dyn Fn(Sym) -> String) -> String {
    let (text, _) = print(pool, id, name);
    text
}

fn number(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{}", v as i64)
    } else {
        format!("{v}")
    }
}

fn wrap(text: (String, Prec), at_least: Prec) -> String {
    if text.1 >= at_least {
        text.0
    } else {
        format!("({})", text.0)
    }
}

fn print(pool: &Pool, id: ExprId, name: &dyn Fn(Sym) -> String) -> (String, Prec) {
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
                let (c, negated) = negated_term(pool, t, name);
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
            let (text, negated) = product(pool, id, name);
            if negated {
                (format!("-{text}"), Prec::Unary)
            } else {
                (text, Prec::Product)
            }
        }
        Node::Pow([b, e]) => {
            let ev = pool.as_const(*e);
            if ev == Some(0.5) {
                return (format!("sqrt({})", print(pool, *b, name).0), Prec::Atom);
            }
            if ev.is_some_and(|v| v < 0.0) {
                let (text, _) = product(pool, id, name);
                return (text, Prec::Product);
            }
            let base = wrap(print(pool, *b, name), Prec::Atom);
            let exp = wrap(print(pool, *e, name), Prec::Power);
            (format!("{base}^{exp}"), Prec::Power)
        }
        Node::Call(f, [a]) => (
            format!("{}({})", f.name(), print(pool, *a, name).0),
            Prec::Atom,
        ),
        Node::Atan2([y, x]) => (
            format!(
                "atan2({}, {})",
                print(pool, *y, name).0,
                print(pool, *x, name).0
            ),
            Prec::Atom,
        ),
    }
}

/// A term of a sum printed without its sign, and whether it was negative.
fn negated_term(pool: &Pool, t: ExprId, name: &dyn Fn(Sym) -> String) -> (String, bool) {
    match pool.node(t) {
        Node::Const(bits) if f64::from_bits(*bits) < 0.0 => (number(-f64::from_bits(*bits)), true),
        Node::Mul(_) => product(pool, t, name),
        _ => (wrap(print(pool, t, name), Prec::Product), false),
    }
}

/// A product (or a lone negative power) as `c*a*b/(d*e)`, without its sign.
fn product(pool: &Pool, id: ExprId, name: &dyn Fn(Sym) -> String) -> (String, bool) {
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
                let base = wrap(print(pool, *b, name), Prec::Atom);
                let text = match (ev, integer_exponent(-ev)) {
                    (_, Some(1)) => base,
                    (_, Some(n)) => format!("{base}^{n}"),
                    (-0.5, _) => format!("sqrt({})", print(pool, *b, name).0),
                    (v, None) => format!("{base}^{}", number(-v)),
                };
                den.push(text);
                continue;
            }
        }
        num.push(wrap(print(pool, f, name), Prec::Unary));
    }
    let negated = coefficient < 0.0;
    let magnitude = coefficient.abs();
    if magnitude != 1.0 || num.is_empty() {
        num.insert(0, number(magnitude));
    }
    let mut text = num.join("*");
    match den.len() {
        0 => {}
        1 => text = format!("{text}/{}", den[0]),
        _ => text = format!("{text}/({})", den.join("*")),
    }
    (text, negated)
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
}
