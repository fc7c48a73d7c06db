//! Forward-mode symbolic differentiation over the DAG.
//!
//! One engine serves three needs: the partial derivative of an expression by one symbol, the
//! time derivative `der(f) = Σ ∂f/∂y_i der(y_i) + ∂f/∂t` of the DSL, and the Jacobian of the
//! solved system, where a symbol defined earlier (a solved derivative) has a derivative that was
//! itself computed earlier. The caller says what the derivative of each leaf symbol is; the
//! engine applies the chain rule node by node, children before parents, each node once (the
//! memo is keyed by node, so shared subexpressions are differentiated once).

use crate::hash::HashMap;

use crate::expr::{ExprId, Node, Pool, Sym};
use crate::spec::Func;

/// The derivative of `root`, given the derivative of every symbol by `leaf`.
///
/// `memo` may be reused across calls that differentiate by the same variable.
pub fn derivative(
    pool: &mut Pool,
    memo: &mut HashMap<ExprId, ExprId>,
    root: ExprId,
    leaf: &mut dyn FnMut(&mut Pool, Sym) -> ExprId,
) -> ExprId {
    if let Some(&d) = memo.get(&root) {
        return d;
    }
    for id in pool.reachable(&[root]) {
        if memo.contains_key(&id) {
            continue;
        }
        let d = node_derivative(pool, memo, id, leaf);
        memo.insert(id, d);
    }
    memo[&root]
}

/// The partial derivative of `root` by the symbol `by` (the compiler differentiates by all
/// derivatives at once; the tests check single partials).
#[cfg(test)]
pub fn partial(pool: &mut Pool, root: ExprId, by: Sym) -> ExprId {
    let mut memo = HashMap::default();
    derivative(pool, &mut memo, root, &mut |_, s| {
        if s == by {
            ExprId::ONE
        } else {
            ExprId::ZERO
        }
    })
}

/// The time derivative of an expression of the states and `t`: each state `y_i` has the
/// derivative `der(y_i)`, `t` has `1`, parameters `0`. A `der(..)` inside `root` has no known
/// derivative: the caller must reject that first (this returns `None`).
pub fn time_derivative(pool: &mut Pool, root: ExprId) -> Option<ExprId> {
    if pool.has_der(root) || pool.symbols(root).iter().any(|s| matches!(s, Sym::Aux(_))) {
        return None;
    }
    let mut memo = HashMap::default();
    Some(derivative(pool, &mut memo, root, &mut |pool, s| match s {
        Sym::State(i) => pool.sym(Sym::Der(i)),
        Sym::Time => ExprId::ONE,
        _ => ExprId::ZERO,
    }))
}

fn node_derivative(
    pool: &mut Pool,
    memo: &HashMap<ExprId, ExprId>,
    id: ExprId,
    leaf: &mut dyn FnMut(&mut Pool, Sym) -> ExprId,
) -> ExprId {
    let d = |c: &ExprId| memo[c];
    match pool.node(id).clone() {
        Node::Const(_) => ExprId::ZERO,
        Node::Sym(s) => leaf(pool, s),
        Node::Add(ts) => {
            let ds: Vec<ExprId> = ts.iter().map(d).collect();
            pool.add(&ds)
        }
        Node::Mul(fs) => {
            let mut terms = Vec::new();
            for (k, f) in fs.iter().enumerate() {
                let df = d(f);
                if df == ExprId::ZERO {
                    continue;
                }
                let mut factors: Vec<ExprId> = fs.to_vec();
                factors[k] = df;
                terms.push(pool.mul(&factors));
            }
            pool.add(&terms)
        }
        Node::Pow([base, exponent]) => {
            let (db, de) = (d(&base), d(&exponent));
            if de == ExprId::ZERO {
                if db == ExprId::ZERO {
                    return ExprId::ZERO;
                }
                // e * b^(e-1) * db
                let em1 = pool.sub(exponent, ExprId::ONE);
                let p = pool.pow(base, em1);
                pool.mul(&[exponent, p, db])
            } else {
                // b^e * (de * ln b + e * db / b)
                let ln = pool.call(Func::Ln, base);
                let t1 = pool.mul2(de, ln);
                let q = pool.div(db, base);
                let t2 = pool.mul2(exponent, q);
                let s = pool.add2(t1, t2);
                pool.mul2(id, s)
            }
        }
        Node::Call(f, [a]) => {
            let da = d(&a);
            if da == ExprId::ZERO {
                return ExprId::ZERO;
            }
            let outer = match f {
                Func::Sin => pool.call(Func::Cos, a),
                Func::Cos => {
                    let s = pool.call(Func::Sin, a);
                    pool.neg(s)
                }
                Func::Tan => {
                    let t2 = pool.powf(id, 2.0);
                    pool.add2(ExprId::ONE, t2)
                }
                Func::Exp => id,
                Func::Ln => pool.pow(a, ExprId::MINUS_ONE),
                // d|a| = sign(a) da (0 at a = 0, where |a| has a kink).
                Func::Abs => pool.call(Func::Sign, a),
                Func::Sqrt => {
                    let r = pool.powf(a, -0.5);
                    let half = pool.num(0.5);
                    pool.mul2(half, r)
                }
                // Piecewise constant: its derivative is zero wherever it exists.
                Func::Sign => return ExprId::ZERO,
                // Two-argument functions are never a `Call`.
                Func::Atan2 | Func::Hypot | Func::Min | Func::Max => ExprId::ZERO,
            };
            pool.mul2(outer, da)
        }
        Node::Call2(Func::Hypot, [x, y]) => {
            // (x dx + y dy) / hypot(x, y), dividing by the node itself (computed anyway). At
            // x = y = 0, where the cone has no tangent plane, it is 0/0, NaN, as `sqrt`'s
            // derivative at a zero argument is not finite: the finiteness checks report it.
            let (dx, dy) = (d(&x), d(&y));
            let a = pool.mul2(x, dx);
            let b = pool.mul2(y, dy);
            let num = pool.add2(a, b);
            pool.div(num, id)
        }
        Node::Call2(f, [y, x]) => {
            debug_assert_eq!(f, Func::Atan2, "not a `Call2` function");
            // (x dy - y dx) / (x² + y²)
            let (dy, dx) = (d(&y), d(&x));
            let a = pool.mul2(x, dy);
            let b = pool.mul2(y, dx);
            let num = pool.sub(a, b);
            let x2 = pool.powf(x, 2.0);
            let y2 = pool.powf(y, 2.0);
            let den = pool.add2(x2, y2);
            pool.div(num, den)
        }
        // The derivative of the branch taken (the comparison itself is piecewise constant).
        Node::Select([l, r, a, b]) => {
            let (da, db) = (d(&a), d(&b));
            pool.select(l, r, da, db)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_of_partials() {
        let mut p = Pool::new();
        let x = p.sym(Sym::State(0));
        let y = p.sym(Sym::State(1));
        let rows: Vec<(ExprId, ExprId)> = vec![
            // d(x*y)/dx = y
            (p.mul2(x, y), y),
            // d(x^3)/dx = 3x^2
            ({ p.powf(x, 3.0) }, {
                let x2 = p.powf(x, 2.0);
                let three = p.num(3.0);
                p.mul2(three, x2)
            }),
            // d(sin x)/dx = cos x
            (p.call(Func::Sin, x), p.call(Func::Cos, x)),
            // d(ln x)/dx = 1/x
            (p.call(Func::Ln, x), p.pow(x, ExprId::MINUS_ONE)),
            // d(y)/dx = 0
            (y, ExprId::ZERO),
        ];
        for (e, expected) in rows {
            assert_eq!(partial(&mut p, e, Sym::State(0)), expected);
        }
    }

    #[test]
    fn time_derivative_uses_der_symbols() {
        let mut p = Pool::new();
        let x = p.sym(Sym::State(0));
        let t = p.sym(Sym::Time);
        let e = p.mul2(x, t);
        let d = time_derivative(&mut p, e).unwrap();
        let dx = p.sym(Sym::Der(0));
        let a = p.mul2(dx, t);
        let expected = p.add2(a, x);
        assert_eq!(d, expected);
        assert_eq!(time_derivative(&mut p, dx), None);
    }

    #[test]
    fn atan2_derivative_matches_formula() {
        let mut p = Pool::new();
        let y = p.sym(Sym::State(0));
        let x = p.sym(Sym::State(1));
        let a = p.atan2(y, x);
        let dy = partial(&mut p, a, Sym::State(0));
        let v = p.eval(dy, &|s| if s == Sym::State(0) { 0.3 } else { 0.7 });
        assert!((v - 0.7 / (0.49 + 0.09)).abs() < 1e-15);
    }

    /// `∂ hypot(x, y)/∂x = x / hypot(x, y)`: against that formula, against a central finite
    /// difference of `f64::hypot` far from the tip, and NaN at the tip `x = y = 0`, where the
    /// cone has no derivative (as `sqrt`'s derivative at zero is not finite).
    #[test]
    fn hypot_derivative_matches_formula_and_finite_differences() {
        let mut p = Pool::new();
        let x = p.sym(Sym::State(0));
        let y = p.sym(Sym::State(1));
        let three = p.num(3.0);
        let x3 = p.mul2(three, x);
        let h = p.hypot(x3, y);
        let dx = partial(&mut p, h, Sym::State(0));
        let dy = partial(&mut p, h, Sym::State(1));
        for (xv, yv) in [
            (0.3f64, 0.7f64),
            (-2.0, 0.5),
            (1e-3, -4.0),
            (5.0, 0.0),
            (1e150, 3e150),
        ] {
            let at = |s: Sym| if s == Sym::State(0) { xv } else { yv };
            let r = (3.0 * xv).hypot(yv);
            let (gx, gy) = (p.eval(dx, &at), p.eval(dy, &at));
            assert!(
                (gx - 9.0 * xv / r).abs() <= 1e-15 * 3.0,
                "{gx} at ({xv}, {yv})"
            );
            assert!((gy - yv / r).abs() <= 1e-15, "{gy} at ({xv}, {yv})");
            let e = 1e-6 * xv.abs().max(yv.abs());
            let fx = ((3.0 * (xv + e)).hypot(yv) - (3.0 * (xv - e)).hypot(yv)) / (2.0 * e);
            let fy = ((3.0 * xv).hypot(yv + e) - (3.0 * xv).hypot(yv - e)) / (2.0 * e);
            assert!((gx - fx).abs() < 1e-6, "{gx} vs {fx} at ({xv}, {yv})");
            assert!((gy - fy).abs() < 1e-6, "{gy} vs {fy} at ({xv}, {yv})");
        }
        assert!(p.eval(dx, &|_| 0.0).is_nan());
        assert!(p.eval(dy, &|_| 0.0).is_nan());
        // Along one axis only: zero where the other argument does not move.
        let t = p.sym(Sym::Time);
        let ht = p.hypot(t, y);
        assert_eq!(partial(&mut p, ht, Sym::State(0)), ExprId::ZERO);
    }
}
