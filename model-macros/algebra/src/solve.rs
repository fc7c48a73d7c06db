//! Solving one block `A x = b` for its derivatives, symbolically when that stays small.
//!
//! Gaussian elimination on expressions. There are no values at compile time, so the pivot is
//! chosen by structure, guarded by magnitude at a few sample points (typical parameter values,
//! states spread over `[0.2, 1.2]`): among the candidates that are not small compared with
//! their column at every sample (threshold pivoting, as sparse LU codes do), a constant pivot
//! first, then the one with the fewest operations, ties broken by position. Without the guard,
//! the cheapest entry of a column may be a tiny coupling term, and the solution would lose
//! digits. Every non-constant pivot is recorded, to be
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

/// How many sample points guard the pivot choice.
pub const SAMPLES: usize = 3;

/// A pivot is acceptable when it is at least this fraction of its column's largest entry at
/// every sample point.
pub const PIVOT_THRESHOLD: f64 = 0.1;

/// What the solve needs besides the block.
pub struct SolveContext<'a> {
    /// Prints a pivot in the user's terms.
    pub text: &'a dyn Fn(&Pool, ExprId) -> String,
    /// The value of a symbol at sample point `k < SAMPLES`.
    pub sample: &'a dyn Fn(Sym, usize) -> f64,
    /// The most operations a symbolic solution may cost.
    pub swell_bound: usize,
}

/// Sample values for a model: states spread over `[0.2, 1.2]`, parameters at `param(i)`.
pub fn default_sample(s: Sym, k: usize, param: &dyn Fn(usize) -> f64) -> f64 {
    let spread = |i: usize| 0.2 + ((i * 7 + k * 3 + 1) as f64 * 0.618_033_988_75).fract();
    match s {
        Sym::State(i) => spread(i),
        Sym::Param(i) => param(i),
        Sym::Time => 0.5 + k as f64,
        Sym::Der(i) => spread(i + 101),
        Sym::Aux(i) => spread(i as usize + 211),
    }
}

/// Solves `block` symbolically, or numerically if the symbolic solution would cost more than
/// `ctx.swell_bound` operations.
pub fn solve_block(
    pool: &mut Pool,
    block: &BlockSystem,
    ctx: &SolveContext,
) -> Result<Solution, SingularBlock> {
    let (text, swell_bound) = (ctx.text, ctx.swell_bound);
    let n = block.vars.len();
    let Elimination { pivots, defs } = eliminate(pool, block, ctx.sample)?;
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

/// How a candidate pivot ranks: large enough first, then constants, then the cheapest, then
/// by position.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct PivotRank {
    small: bool,
    not_constant: bool,
    ops: u32,
    row: usize,
    col: usize,
}

/// Symbolic elimination with structurally chosen pivots, then back substitution.
fn eliminate(
    pool: &mut Pool,
    block: &BlockSystem,
    sample: &dyn Fn(Sym, usize) -> f64,
) -> Result<Elimination, SingularBlock> {
    let n = block.vars.len();
    let mut a = block.matrix.clone();
    let mut b = block.rhs.clone();
    let mut row_done = vec![false; n];
    let mut col_done = vec![false; n];
    let mut steps: Vec<(usize, usize, ExprId)> = Vec::with_capacity(n);
    let mut pivots = Vec::new();
    for _ in 0..n {
        let magnitudes: Vec<Vec<f64>> = (0..SAMPLES)
            .map(|k| {
                pool.eval_many(&a, &|s| sample(s, k))
                    .into_iter()
                    .map(f64::abs)
                    .collect()
            })
            .collect();
        let small = |r: usize, c: usize| {
            magnitudes.iter().any(|m| {
                let column = (0..n)
                    .filter(|&i| !row_done[i])
                    .map(|i| m[i * n + c])
                    .fold(0.0, f64::max);
                let entry = m[r * n + c];
                entry.is_nan() || entry < PIVOT_THRESHOLD * column
            })
        };
        let mut best: Option<PivotRank> = None;
        for r in (0..n).filter(|&r| !row_done[r]) {
            for c in (0..n).filter(|&c| !col_done[c]) {
                let p = a[r * n + c];
                if p == ExprId::ZERO {
                    continue;
                }
                let rank = PivotRank {
                    small: small(r, c),
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
