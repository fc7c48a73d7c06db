//! Distributing products over sums, used only where it makes an expression smaller.
//!
//! The constructors never expand (that is how expressions swell). But the elimination forms
//! entries like `b_8 - m a sinθ cosψ b_4 - m a sinθ sinψ b_5 - m a cosθ b_6` whose expanded
//! terms cancel pairwise (through like terms and `sin² + cos² = 1`) down to a few products.
//! [`expand_if_smaller`] tries the expansion, bounded in the number of terms, and keeps it only
//! when it costs no more operations than the original.

use crate::hash::HashMap;

use crate::expr::{integer_exponent, ExprId, Node, Pool};

/// The most terms one expanded product may have.
pub const TERM_LIMIT: usize = 96;

/// `e` with products distributed over sums, or `None` if some product would exceed
/// [`TERM_LIMIT`] terms.
pub fn expand(pool: &mut Pool, e: ExprId) -> Option<ExprId> {
    let mut memo = HashMap::default();
    expand_memo(pool, &mut memo, e)
}

/// The cheapest of `e`, its expansion, and either with the factors common to all terms
/// pulled out (which lets `S^-1 * (a + b)` cancel when `S = a + b`). A tie goes to the
/// expansion (more canonical, so later cancellations are found), not to a factored form.
pub fn expand_if_smaller(pool: &mut Pool, e: ExprId) -> ExprId {
    if !matches!(pool.node(e), Node::Add(_) | Node::Mul(_)) {
        return e;
    }
    let mut best = e;
    let mut best_ops = pool.dag_ops(&[e]);
    let mut consider = |pool: &mut Pool, x: ExprId, tie_wins: bool| {
        let ops = pool.dag_ops(&[x]);
        if ops < best_ops || (tie_wins && ops == best_ops) {
            best = x;
            best_ops = ops;
        }
    };
    let common = factor_common(pool, e);
    consider(pool, common, false);
    if let Some(x) = expand(pool, e) {
        consider(pool, x, true);
        let common = factor_common(pool, x);
        consider(pool, common, false);
    }
    best
}

/// A sum with the factors shared by all its terms pulled out: `a*x*S^-1 + b*y*S^-1` becomes
/// `S^-1 * (a*x + b*y)`, whose product the constructors may then simplify. Anything else is
/// returned as is.
pub fn factor_common(pool: &mut Pool, e: ExprId) -> ExprId {
    let Node::Add(terms) = pool.node(e).clone() else {
        return e;
    };
    let factors_of = |pool: &mut Pool, t: ExprId| -> (f64, Vec<ExprId>) {
        let (c, rest) = pool.split_coefficient(t);
        match pool.node(rest) {
            Node::Mul(fs) => (c, fs.to_vec()),
            Node::Const(_) => (c, Vec::new()),
            _ => (c, vec![rest]),
        }
    };
    let split: Vec<(f64, Vec<ExprId>)> = terms.iter().map(|&t| factors_of(pool, t)).collect();
    let mut common: Vec<ExprId> = split[0].1.clone();
    for (_, fs) in &split[1..] {
        common.retain(|f| fs.contains(f));
    }
    if common.is_empty() {
        return e;
    }
    let inner: Vec<ExprId> = split
        .into_iter()
        .map(|(c, fs)| {
            let mut rest: Vec<ExprId> = fs.into_iter().filter(|f| !common.contains(f)).collect();
            rest.push(pool.num(c));
            pool.mul(&rest)
        })
        .collect();
    let inner = pool.add(&inner);
    common.push(inner);
    pool.mul(&common)
}

/// The terms of `e` as a sum (one term if it is not a sum).
fn terms(pool: &Pool, e: ExprId) -> Vec<ExprId> {
    match pool.node(e) {
        Node::Add(ts) => ts.to_vec(),
        _ => vec![e],
    }
}

fn expand_memo(
    pool: &mut Pool,
    memo: &mut HashMap<ExprId, Option<ExprId>>,
    e: ExprId,
) -> Option<ExprId> {
    if let Some(&r) = memo.get(&e) {
        return r;
    }
    let r = match pool.node(e).clone() {
        Node::Add(ts) => {
            let mut out = Vec::with_capacity(ts.len());
            for t in ts.iter() {
                out.push(expand_memo(pool, memo, *t)?);
            }
            Some(pool.add(&out))
        }
        Node::Mul(fs) => {
            let mut product: Vec<ExprId> = vec![ExprId::ONE];
            for f in fs.iter() {
                let x = expand_memo(pool, memo, *f)?;
                let ts = terms(pool, x);
                if product.len() * ts.len() > TERM_LIMIT {
                    return None;
                }
                let mut next = Vec::with_capacity(product.len() * ts.len());
                for &p in &product {
                    for &t in &ts {
                        next.push(pool.mul2(p, t));
                    }
                }
                product = next;
            }
            Some(pool.add(&product))
        }
        Node::Pow([b, x]) => match pool.as_const(x).and_then(integer_exponent) {
            Some(n @ 2..=4) if matches!(pool.node(b), Node::Add(_)) => {
                let base = expand_memo(pool, memo, b)?;
                let mut product = vec![ExprId::ONE];
                for _ in 0..n {
                    let ts = terms(pool, base);
                    if product.len() * ts.len() > TERM_LIMIT {
                        return None;
                    }
                    let mut next = Vec::with_capacity(product.len() * ts.len());
                    for &p in &product {
                        for &t in &ts {
                            next.push(pool.mul2(p, t));
                        }
                    }
                    product = next;
                }
                Some(pool.add(&product))
            }
            _ => Some(e),
        },
        _ => Some(e),
    };
    memo.insert(e, r);
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::Sym;
    use crate::spec::Func;

    #[test]
    fn expansion_reveals_cancellation() {
        let mut p = Pool::new();
        let x = p.sym(Sym::State(0));
        let y = p.sym(Sym::State(1));
        // (x + y)*(x - y) - x^2  ->  -y^2
        let s = p.add2(x, y);
        let d = p.sub(x, y);
        let prod = p.mul2(s, d);
        let x2 = p.powf(x, 2.0);
        let e = p.sub(prod, x2);
        let y2 = p.powf(y, 2.0);
        let expected = p.neg(y2);
        assert_eq!(expand_if_smaller(&mut p, e), expected);
    }

    #[test]
    fn expansion_with_pythagoras() {
        // c*(c*x) + s*(s*x) -> x, with s = sin(u), c = cos(u)
        let mut p = Pool::new();
        let u = p.sym(Sym::State(0));
        let x = p.sym(Sym::State(1));
        let y = p.sym(Sym::State(2));
        let s = p.call(Func::Sin, u);
        let c = p.call(Func::Cos, u);
        let cx = p.mul2(c, x);
        let sx = p.mul2(s, x);
        let a = p.add2(cx, y);
        let b = p.sub(sx, y);
        let ca = p.mul2(c, a);
        let sb = p.mul2(s, b);
        // c*(c x + y) + s*(s x - y) = x + y (c - s)
        let e = p.add2(ca, sb);
        let got = expand(&mut p, e).unwrap();
        let cms = p.sub(c, s);
        let ycms = p.mul2(y, cms);
        let expanded_ycms = expand(&mut p, ycms).unwrap();
        let expected = p.add2(x, expanded_ycms);
        assert_eq!(got, expected);
    }

    #[test]
    fn common_factors_cancel_against_a_reciprocal_sum() {
        // m^2*x^2/(x^2 + y^2) + m^2*y^2/(x^2 + y^2) = m^2
        let mut p = Pool::new();
        let m = p.sym(Sym::Param(0));
        let x = p.sym(Sym::State(0));
        let y = p.sym(Sym::State(1));
        let (m2, x2, y2) = (p.powf(m, 2.0), p.powf(x, 2.0), p.powf(y, 2.0));
        let s = p.add2(x2, y2);
        let a = p.mul(&[m2, x2]);
        let b = p.mul(&[m2, y2]);
        let a = p.div(a, s);
        let b = p.div(b, s);
        let e = p.add2(a, b);
        assert_eq!(expand_if_smaller(&mut p, e), m2);
    }

    #[test]
    fn expansion_that_grows_is_refused() {
        let mut p = Pool::new();
        let vars: Vec<ExprId> = (0..6).map(|i| p.sym(Sym::State(i))).collect();
        let s1 = p.add(&vars[0..3]);
        let s2 = p.add(&vars[3..6]);
        let e = p.mul2(s1, s2);
        assert_eq!(expand_if_smaller(&mut p, e), e);
    }
}
