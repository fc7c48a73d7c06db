//! Each residual `lhs - rhs` split into `Σ_j c_j der(y_j) + r`.
//!
//! The coefficients `c_j` are the entries of the mass matrix row, `r` the negated right-hand
//! side. Lowering has already rejected nonlinear uses of derivatives at the user's node; the
//! split still refuses them (returning the offending subexpression) so that it is total on
//! any input.

use crate::hash::HashMap;
use std::collections::{BTreeMap, BTreeSet};

use crate::expr::{ExprId, Node, Pool, Sym};

/// `Σ_j coefficients[j] * der(y_j) + rest`.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearForm {
    /// The nonzero coefficient of each derivative, by state index.
    pub coefficients: BTreeMap<usize, ExprId>,
    /// What remains (free of derivatives).
    pub rest: ExprId,
}

/// A subexpression in which a derivative occurs nonlinearly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NonLinear(pub ExprId);

/// Splits `e` into coefficients of the derivatives and a remainder.
pub fn split(pool: &mut Pool, e: ExprId) -> Result<LinearForm, NonLinear> {
    let mut memo = HashMap::default();
    split_memo(pool, &mut memo, e)
}

fn split_memo(
    pool: &mut Pool,
    memo: &mut HashMap<ExprId, LinearForm>,
    e: ExprId,
) -> Result<LinearForm, NonLinear> {
    if !pool.has_der(e) {
        return Ok(LinearForm {
            coefficients: BTreeMap::new(),
            rest: e,
        });
    }
    if let Some(f) = memo.get(&e) {
        return Ok(f.clone());
    }
    let form = match pool.node(e).clone() {
        Node::Sym(Sym::Der(i)) => LinearForm {
            coefficients: BTreeMap::from([(i, ExprId::ONE)]),
            rest: ExprId::ZERO,
        },
        Node::Add(ts) => {
            let mut coefficients: BTreeMap<usize, Vec<ExprId>> = BTreeMap::new();
            let mut rests = Vec::new();
            for t in ts.iter() {
                let f = split_memo(pool, memo, *t)?;
                for (j, c) in f.coefficients {
                    coefficients.entry(j).or_default().push(c);
                }
                rests.push(f.rest);
            }
            LinearForm {
                coefficients: coefficients
                    .into_iter()
                    .map(|(j, cs)| (j, pool.add(&cs)))
                    .filter(|(_, c)| *c != ExprId::ZERO)
                    .collect(),
                rest: pool.add(&rests),
            }
        }
        Node::Mul(fs) => {
            let mut with_der = fs.iter().filter(|f| pool.has_der(**f));
            let (Some(&d), None) = (with_der.next(), with_der.next()) else {
                return Err(NonLinear(e));
            };
            let others: Vec<ExprId> = fs.iter().copied().filter(|&f| f != d).collect();
            let scale = pool.mul(&others);
            let f = split_memo(pool, memo, d)?;
            LinearForm {
                coefficients: f
                    .coefficients
                    .into_iter()
                    .map(|(j, c)| (j, pool.mul2(scale, c)))
                    .filter(|(_, c)| *c != ExprId::ZERO)
                    .collect(),
                rest: pool.mul2(scale, f.rest),
            }
        }
        // A derivative in a branch (not in the comparison) is linear piecewise: each
        // coefficient is the select of the branches' coefficients.
        Node::Select([l, r, a, b]) if !pool.has_der(l) && !pool.has_der(r) => {
            let (fa, fb) = (split_memo(pool, memo, a)?, split_memo(pool, memo, b)?);
            let vars: BTreeSet<usize> = fa
                .coefficients
                .keys()
                .chain(fb.coefficients.keys())
                .copied()
                .collect();
            let coefficient =
                |f: &LinearForm, j| f.coefficients.get(&j).copied().unwrap_or(ExprId::ZERO);
            LinearForm {
                coefficients: vars
                    .into_iter()
                    .map(|j| {
                        (
                            j,
                            pool.select(l, r, coefficient(&fa, j), coefficient(&fb, j)),
                        )
                    })
                    .filter(|(_, c)| *c != ExprId::ZERO)
                    .collect(),
                rest: pool.select(l, r, fa.rest, fb.rest),
            }
        }
        _ => return Err(NonLinear(e)),
    };
    memo.insert(e, form.clone());
    Ok(form)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::{CmpOp, Func};

    #[test]
    fn splits_a_mass_matrix_row() {
        let mut p = Pool::new();
        let th = p.sym(Sym::State(0));
        let w = p.sym(Sym::State(1));
        let dth = p.sym(Sym::Der(0));
        let dw = p.sym(Sym::Der(1));
        let s = p.call(Func::Sin, th);
        // sin(th) * (der(th) + w*der(w)) - w
        let wd = p.mul2(w, dw);
        let inner = p.add2(dth, wd);
        let prod = p.mul2(s, inner);
        let e = p.sub(prod, w);
        let f = split(&mut p, e).unwrap();
        let sw = p.mul2(s, w);
        assert_eq!(f.coefficients, BTreeMap::from([(0, s), (1, sw)]));
        assert_eq!(f.rest, p.neg(w));
    }

    #[test]
    fn rejects_nonlinear_forms() {
        let mut p = Pool::new();
        let dx = p.sym(Sym::Der(0));
        let dy = p.sym(Sym::Der(1));
        let cases = [
            p.mul2(dx, dy),
            p.call(Func::Sin, dx),
            p.powf(dx, 2.0),
            p.div(ExprId::ONE, dx),
            p.call(Func::Sign, dx),
            p.min_max(Func::Max, dx, ExprId::ZERO),
            p.compare(dx, CmpOp::Gt, ExprId::ZERO, ExprId::ONE, dy),
        ];
        for e in cases {
            assert_eq!(split(&mut p, e), Err(NonLinear(e)));
        }
    }

    #[test]
    fn derivatives_in_branches_are_linear_piecewise() {
        // if(x > 0, 2 der(x), der(y) - x): coefficients if(x > 0, 2, 0), if(x > 0, 0, 1).
        let mut p = Pool::new();
        let x = p.sym(Sym::State(0));
        let (dx, dy) = (p.sym(Sym::Der(0)), p.sym(Sym::Der(1)));
        let two = p.num(2.0);
        let a = p.mul2(two, dx);
        let b = p.sub(dy, x);
        let e = p.compare(x, CmpOp::Gt, ExprId::ZERO, a, b);
        let f = split(&mut p, e).unwrap();
        let c0 = p.compare(x, CmpOp::Gt, ExprId::ZERO, two, ExprId::ZERO);
        let c1 = p.compare(x, CmpOp::Gt, ExprId::ZERO, ExprId::ZERO, ExprId::ONE);
        assert_eq!(f.coefficients, BTreeMap::from([(0, c0), (1, c1)]));
        let nx = p.neg(x);
        assert_eq!(
            f.rest,
            p.compare(x, CmpOp::Gt, ExprId::ZERO, ExprId::ZERO, nx)
        );
    }

    #[test]
    fn cancelling_derivatives_leave_no_coefficient() {
        let mut p = Pool::new();
        let x = p.sym(Sym::State(0));
        let dx = p.sym(Sym::Der(0));
        let a = p.mul2(x, dx);
        let e = p.sub(a, a);
        let f = split(&mut p, e).unwrap();
        assert!(f.coefficients.is_empty());
    }
}
