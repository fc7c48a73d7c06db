//! Solving one block `A x = b` for its derivatives, symbolically when that stays small and safe.
//!
//! Gaussian elimination on expressions. There are no values at compile time, so pivots are
//! chosen by structure, guarded by magnitude at sample points: a few typical ones (parameters
//! at their defaults, states spread over `[0.2, 1.2]`) and, for each state, one where it is `0`
//! and one where it is `π/2` (where sines, cosines and the state itself vanish). A candidate is
//! safe when, at every sample, it is not small compared with the largest entry of its column
//! (threshold pivoting, as sparse LU codes do). Among safe candidates: a constant first, then
//! the one with the fewest operations, ties broken by position. A pivot that vanishes where the
//! matrix does not (`u_X/|u|` of a slip velocity crossing an axis) would report a singularity
//! that is not there; when no safe pivot exists, a 2×2 block is solved by Cramer's rule (its
//! only pivot is the determinant, which vanishes only where the block is singular) and a larger
//! one numerically at run time, with partial pivoting.
//!
//! Every non-constant pivot is recorded, to be checked at run time with its text in the user's
//! terms. The reciprocal of each pivot is one shared node, so the emitted code divides once per
//! pivot and multiplies elsewhere. Back substitution reads the derivatives solved before it as
//! symbols, which keeps the solution a short chain instead of a nest. If the symbolic solution
//! would cost more than the caller's bound, the block is left to a numeric elimination at run
//! time as well.

use crate::expand::expand_if_smaller;
use crate::expr::{ExprId, Node, Pool, Sym};
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
    /// Operations of the symbolic solution beyond computing the entries (`None` when no
    /// symbolic solution with safe pivots exists).
    pub symbolic_ops: Option<u32>,
}

/// A pivot is acceptable when it is at least this fraction of its column's largest entry at
/// every sample point.
pub const PIVOT_THRESHOLD: f64 = 0.1;

/// Typical samples (before the ones with a state at `0` or `π/2`).
pub const TYPICAL_SAMPLES: usize = 3;

/// Where symbols are sampled to judge pivots.
pub struct Sampler<'a> {
    /// The sample value of parameter `i` (its default, say).
    pub param: &'a dyn Fn(usize) -> f64,
    /// How many states the model has.
    pub n_states: usize,
}

impl Sampler<'_> {
    /// The sample points that can tell `roots` apart: the typical ones, and those that put a
    /// state the expressions read at `0` or `π/2` (any other sample equals the last typical
    /// one there). A block costs what it reads, not the model's size.
    pub fn samples_for(&self, pool: &Pool, roots: &[ExprId]) -> Vec<usize> {
        let mut read: Vec<usize> = pool
            .reachable(roots)
            .into_iter()
            .filter_map(|e| match *pool.node(e) {
                Node::Sym(Sym::State(i)) if i < self.n_states => Some(i),
                _ => None,
            })
            .collect();
        read.sort_unstable();
        let special = [0, self.n_states]
            .into_iter()
            .flat_map(|offset| read.iter().map(move |&i| TYPICAL_SAMPLES + offset + i));
        (0..TYPICAL_SAMPLES).chain(special).collect()
    }

    /// The value of `s` at sample `k`.
    pub fn value(&self, s: Sym, k: usize) -> f64 {
        let typical = k.min(TYPICAL_SAMPLES - 1);
        let spread = |i: usize| 0.2 + ((i * 7 + typical * 3 + 1) as f64 * 0.618_033_988_75).fract();
        let special = k.checked_sub(TYPICAL_SAMPLES).map(|j| {
            let value = if j < self.n_states {
                0.0
            } else {
                std::f64::consts::FRAC_PI_2
            };
            (j % self.n_states.max(1), value)
        });
        match s {
            Sym::State(i) => match special {
                Some((state, value)) if state == i => value,
                _ => spread(i),
            },
            Sym::Param(i) => (self.param)(i),
            Sym::Time => 0.5 + typical as f64,
            Sym::Der(i) => spread(i + 101),
            Sym::Aux(i) => spread(i as usize + 211),
        }
    }
}

/// What the solve needs besides the block.
pub struct SolveContext<'a> {
    /// Prints a pivot in the user's terms.
    pub text: &'a dyn Fn(&Pool, ExprId) -> String,
    /// Where pivots are judged.
    pub sampler: &'a Sampler<'a>,
    /// The most operations a symbolic solution may cost.
    pub swell_bound: usize,
}

/// Solves `block` symbolically, or numerically if no safe symbolic solution exists or it would
/// cost more than `ctx.swell_bound` operations.
pub fn solve_block(
    pool: &mut Pool,
    block: &BlockSystem,
    ctx: &SolveContext,
) -> Result<Solution, SingularBlock> {
    let text = ctx.text;
    let n = block.vars.len();
    let symbolic = match eliminate(pool, block, ctx.sampler)? {
        Some(e) => Some(e),
        None if n == 2 => cramer(pool, block),
        None => None,
    };
    let mut entries = block.matrix.clone();
    entries.extend(&block.rhs);
    let symbolic_ops = symbolic.as_ref().map(|e| {
        let mut roots: Vec<ExprId> = e.defs.iter().map(|(_, x)| *x).collect();
        roots.extend(e.pivots.iter());
        pool.dag_ops(&roots).saturating_sub(pool.dag_ops(&entries))
    });
    let group = match symbolic {
        Some(Elimination { pivots, defs })
            if n == 1 || symbolic_ops.is_some_and(|ops| ops as usize <= ctx.swell_bound) =>
        {
            Group {
                pivots: pivots
                    .into_iter()
                    .map(|p| {
                        // `-m` and `m` vanish together: check the one without a sign.
                        let value = if pool.split_coefficient(p).0 < 0.0 {
                            pool.neg(p)
                        } else {
                            p
                        };
                        Pivot {
                            value,
                            text: text(pool, value),
                        }
                    })
                    .collect(),
                body: Body::Symbolic(defs),
            }
        }
        _ => {
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
        }
    };
    Ok(Solution {
        group,
        symbolic_ops,
    })
}

/// Cramer's rule for a 2×2 block: the determinant is the only pivot. `None` if the
/// determinant is identically zero.
fn cramer(pool: &mut Pool, block: &BlockSystem) -> Option<Elimination> {
    let [a, b, c, d] = [0, 1, 2, 3].map(|k| block.matrix[k]);
    let [e, f] = [block.rhs[0], block.rhs[1]];
    let cross = |pool: &mut Pool, p: ExprId, q: ExprId, r: ExprId, s: ExprId| {
        let pq = pool.mul2(p, q);
        let rs = pool.mul2(r, s);
        let diff = pool.sub(pq, rs);
        expand_if_smaller(pool, diff)
    };
    let det = cross(pool, a, d, b, c);
    if det == ExprId::ZERO {
        return None;
    }
    let inv = pool.pow(det, ExprId::MINUS_ONE);
    let x0 = cross(pool, e, d, b, f);
    let x1 = cross(pool, a, f, e, c);
    let x0 = pool.mul2(x0, inv);
    let x1 = pool.mul2(x1, inv);
    let defs = vec![
        (Sym::Der(block.vars[0]), expand_if_smaller(pool, x0)),
        (Sym::Der(block.vars[1]), expand_if_smaller(pool, x1)),
    ];
    let pivots = if pool.as_const(det).is_some() {
        Vec::new()
    } else {
        vec![det]
    };
    Some(Elimination { pivots, defs })
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
/// `Ok(None)` when some step has no safe pivot.
fn eliminate(
    pool: &mut Pool,
    block: &BlockSystem,
    sampler: &Sampler,
) -> Result<Option<Elimination>, SingularBlock> {
    let n = block.vars.len();
    let mut a = block.matrix.clone();
    let mut b = block.rhs.clone();
    let mut row_done = vec![false; n];
    let mut col_done = vec![false; n];
    let mut steps: Vec<(usize, usize, ExprId)> = Vec::with_capacity(n);
    let mut pivots = Vec::new();
    let samples = sampler.samples_for(pool, &block.matrix);
    for _ in 0..n {
        let magnitudes: Vec<Vec<f64>> = samples
            .iter()
            .map(|&k| {
                pool.eval_many(&a, &|s| sampler.value(s, k))
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
        if n > 1 && best.is_some_and(|b| b.small) {
            return Ok(None);
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
    Ok(Some(Elimination { pivots, defs }))
}
