//! Solving one block `A x = b` for its derivatives, symbolically when that stays small.
//!
//! Gaussian elimination on expressions: at each step the pivot is chosen by structure, never by
//! value (there is no value at compile time): a constant pivot first, then the one with the
//! fewest operations, ties broken by position. Every non-constant pivot is recorded, to be
//! checked at run time with its text in the user's terms. The reciprocal of each pivot is one
//! shared node, so the emitted code divides once per pivot and multiplies elsewhere. Back
//! substitution reads the derivatives solved before it as symbols, which keeps the solution a
//! short chain instead of a nest. If the symbolic solution would cost more than the caller's
//! bound, the block is left to a numeric elimination at run time instead.

use crate::expand::expand_if_smaller;
use crate::expr::{ExprId, Pool, Sym};
use crate::system::{Body, Group, Pivot};

/// One block to solve: `matrix · x = rhs` with `x_k = der(y_{vars[k]})`.
#[derive(Clone, Debug)]
pub struct BlockSystem {
    /// Row-major `n × n` coefficients.
    pub matrix: Vec<ExprId>,
    /// The right-hand side.
    pub rhs: Vec<ExprId>,
    /// The state index of each unknown derivative.
    pub vars: Vec<usize>,
}

/// The block's matrix is singular whatever the values (an elimination step found only zeros).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SingularBlock {
    /// The unknowns (state indices) no remaining equation determines.
    pub vars: Vec<usize>,
}

/// How the block ended up being solved.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// The definitions of the block's derivatives.
    pub group: Group,
    /// Operations of the symbolic solution beyond computing the entries (measured even when
    /// the numeric fallback was taken).
    pub symbolic_ops: u32,
}

/// Solves `block`; `text` prints a pivot in the user's terms, `swell_bound` caps the
/// operations of a symbolic solution.
pub fn solve_block(
    pool: &mut Pool,
    block: &BlockSystem,
    text: &dyn Fn(&Pool, ExprId) -> String,
    swell_bound: usize,
) -> Result<Solution, SingularBlock> {
    let n = block.vars.len();
    let Elimination { pivots, defs } = eliminate(pool, block)?;
    let mut roots: Vec<ExprId> = defs.iter().map(|(_, e)| *e).collect();
    roots.extend(pivots.iter());
    let mut entries = block.matrix.clone();
    entries.extend(&block.rhs);
    let symbolic_ops = pool.dag_ops(&roots).saturating_sub(pool.dag_ops(&entries));
    let group = if n > 1 && symbolic_ops as usize > swell_bound {
        let ders: Vec<ExprId> = block.vars.iter().map(|&v| pool.sym(Sym::Der(v))).collect();
        Group {
            pivots: Vec::new(),
            body: Body::Numeric {
                matrix: block.matrix.clone(),
                rhs: block.rhs.clone(),
                results: block.vars.iter().map(|&v| Sym::Der(v)).collect(),
                text: ders
                    .iter()
                    .map(|&d| text(pool, d))
                    .collect::<Vec<_>>()
                    .join(", "),
            },
        }
    } else {
        Group {
            pivots: pivots
                .into_iter()
                .map(|p| Pivot {
                    value: p,
                    text: text(pool, p),
                })
                .collect(),
            body: Body::Symbolic(defs),
        }
    };
    Ok(Solution {
        group,
        symbolic_ops,
    })
}

/// The result of a symbolic elimination.
struct Elimination {
    /// The non-constant pivots, in elimination order.
    pivots: Vec<ExprId>,
    /// The definitions, in back-substitution order.
    defs: Vec<(Sym, ExprId)>,
}

/// How a candidate pivot ranks: constants first, then the cheapest, then by position.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct PivotRank {
    not_constant: bool,
    ops: u32,
    row: usize,
    col: usize,
}

/// Symbolic elimination with structurally chosen pivots, then back substitution.
fn eliminate(pool: &mut Pool, block: &BlockSystem) -> Result<Elimination, SingularBlock> {
    let n = block.vars.len();
    let mut a = block.matrix.clone();
    let mut b = block.rhs.clone();
    let mut row_done = vec![false; n];
    let mut col_done = vec![false; n];
    let mut steps: Vec<(usize, usize, ExprId)> = Vec::with_capacity(n);
    let mut pivots = Vec::new();
    for _ in 0..n {
        let mut best: Option<PivotRank> = None;
        for r in (0..n).filter(|&r| !row_done[r]) {
            for c in (0..n).filter(|&c| !col_done[c]) {
                let p = a[r * n + c];
                if p == ExprId::ZERO {
                    continue;
                }
                let rank = PivotRank {
                    not_constant: pool.as_const(p).is_none(),
                    ops: pool.dag_ops(&[p]),
                    row: r,
                    col: c,
                };
                if best.is_none_or(|b| rank < b) {
                    best = Some(rank);
                }
            }
        }
        let Some(PivotRank { row: r, col: c, .. }) = best else {
            return Err(SingularBlock {
                vars: (0..n)
                    .filter(|&c| !col_done[c])
                    .map(|c| block.vars[c])
                    .collect(),
            });
        };
        let p = a[r * n + c];
        if pool.as_const(p).is_none() {
            pivots.push(p);
        }
        let inv = pool.pow(p, ExprId::MINUS_ONE);
        for i in (0..n).filter(|&i| !row_done[i] && i != r) {
            let aic = a[i * n + c];
            if aic == ExprId::ZERO {
                continue;
            }
            let f = pool.mul2(aic, inv);
            for j in (0..n).filter(|&j| !col_done[j] && j != c) {
                let arj = a[r * n + j];
                if arj != ExprId::ZERO {
                    let fa = pool.mul2(f, arj);
                    let updated = pool.sub(a[i * n + j], fa);
                    a[i * n + j] = expand_if_smaller(pool, updated);
                }
            }
            if b[r] != ExprId::ZERO {
                let fb = pool.mul2(f, b[r]);
                let updated = pool.sub(b[i], fb);
                b[i] = expand_if_smaller(pool, updated);
            }
            a[i * n + c] = ExprId::ZERO;
        }
        row_done[r] = true;
        col_done[c] = true;
        steps.push((r, c, inv));
    }
    let mut defs = Vec::with_capacity(n);
    let mut solved: Vec<usize> = Vec::new();
    for &(r, c, inv) in steps.iter().rev() {
        let mut terms = vec![b[r]];
        for &j in &solved {
            let arj = a[r * n + j];
            if arj != ExprId::ZERO {
                let xj = pool.sym(Sym::Der(block.vars[j]));
                let prod = pool.mul2(arj, xj);
                terms.push(pool.neg(prod));
            }
        }
        let s = pool.add(&terms);
        let x = pool.mul2(s, inv);
        let x = expand_if_smaller(pool, x);
        defs.push((Sym::Der(block.vars[c]), x));
        solved.push(c);
    }
    Ok(Elimination { pivots, defs })
}
