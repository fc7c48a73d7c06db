//! The Jacobian `∂f_i/∂y_j` of the solved system, by the chain rule through its definitions.
//!
//! The solved right-hand side is a chain of definitions (`der(x) := ...`, later ones reading
//! earlier ones), so each column `j` is computed in the same order: the derivative of every
//! definition by `y_j`, reading the derivatives of the symbols defined before it. Each
//! non-trivial derivative becomes a definition of its own (an auxiliary symbol), so the
//! column is a chain as short as the solve itself.
//!
//! A block solved numerically at run time (`A x = b`) is differentiated by the implicit-function
//! identity `A ∂x/∂y_j = ∂b/∂y_j - (∂A/∂y_j) x`: one more numeric solve with the same matrix per
//! column in which the block's inputs depend on `y_j`. The result is exact (no finite
//! differences), like the symbolic columns.

use crate::hash::HashMap;

use crate::diff::derivative;
use crate::expr::{ExprId, Node, Pool, Sym};
use crate::system::{Body, Group, System};

/// One entry of the Jacobian that is not identically zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JacobianEntry {
    /// The row: the state whose derivative is differentiated.
    pub row: usize,
    /// The column: the state differentiated by.
    pub col: usize,
    /// `∂der(y_row)/∂y_col`.
    pub value: ExprId,
}

/// Appends to `system` the definitions of `∂der(y_i)/∂y_j` for `i` in `rows`, `j` in `cols`
/// (state indices) and returns the entries that are not identically zero, row-major.
pub fn jacobian(
    pool: &mut Pool,
    system: &mut System,
    rows: &[usize],
    cols: &[usize],
) -> Vec<JacobianEntry> {
    let readers = readers(pool, &system.groups);
    let is_row: std::collections::HashSet<usize> = rows.iter().copied().collect();
    let mut entries = Vec::new();
    for &j in cols {
        let mut memo: HashMap<ExprId, ExprId> = HashMap::default();
        let mut dsym: HashMap<Sym, ExprId> = HashMap::default();
        // Only the groups that read `y_j`, directly or through what other such groups define,
        // have a derivative by `y_j` that is not zero: a column costs what depends on `y_j`,
        // not the whole system (decoupled states would make the Jacobian quadratic).
        for g in affected(&readers, &system.groups, j) {
            let group = system.groups[g].clone();
            match group.body {
                Body::Symbolic(defs) => {
                    for (s, e) in defs {
                        let d = derivative(pool, &mut memo, e, &mut |_, leaf| {
                            leaf_derivative(&dsym, j, leaf)
                        });
                        let d = name_if_large(pool, system, d);
                        dsym.insert(s, d);
                    }
                }
                Body::Numeric {
                    matrix,
                    rhs,
                    results,
                    text,
                } => {
                    let n = results.len();
                    let mut new_rhs = Vec::with_capacity(n);
                    for k in 0..n {
                        let mut terms =
                            vec![derivative(pool, &mut memo, rhs[k], &mut |_, leaf| {
                                leaf_derivative(&dsym, j, leaf)
                            })];
                        for (l, &x) in results.iter().enumerate() {
                            let da =
                                derivative(pool, &mut memo, matrix[k * n + l], &mut |_, leaf| {
                                    leaf_derivative(&dsym, j, leaf)
                                });
                            if da != ExprId::ZERO {
                                let xs = pool.sym(x);
                                let p = pool.mul2(da, xs);
                                terms.push(pool.neg(p));
                            }
                        }
                        new_rhs.push(pool.add(&terms));
                    }
                    if new_rhs.iter().all(|&r| r == ExprId::ZERO) {
                        for &x in &results {
                            dsym.insert(x, ExprId::ZERO);
                        }
                        continue;
                    }
                    let aux: Vec<Sym> = (0..n).map(|_| pool.fresh_aux()).collect();
                    for (&x, &a) in results.iter().zip(&aux) {
                        dsym.insert(x, pool.sym(a));
                    }
                    system.push(Group {
                        pivots: Vec::new(),
                        body: Body::Numeric {
                            matrix,
                            rhs: new_rhs,
                            results: aux,
                            text,
                        },
                    });
                }
            }
        }
        // The column's entries are what was differentiated (not a lookup per row).
        for (&s, &v) in &dsym {
            match s {
                Sym::Der(i) if v != ExprId::ZERO && is_row.contains(&i) => {
                    entries.push(JacobianEntry {
                        row: i,
                        col: j,
                        value: v,
                    })
                }
                _ => {}
            }
        }
    }
    entries.sort_by_key(|e| (e.row, e.col));
    entries
}

/// For each symbol, the groups whose expressions read it.
fn readers(pool: &Pool, groups: &[Group]) -> HashMap<Sym, Vec<usize>> {
    let mut readers: HashMap<Sym, Vec<usize>> = HashMap::default();
    for (g, group) in groups.iter().enumerate() {
        let roots: Vec<ExprId> = match &group.body {
            Body::Symbolic(defs) => defs.iter().map(|&(_, e)| e).collect(),
            Body::Numeric { matrix, rhs, .. } => matrix.iter().chain(rhs).copied().collect(),
        };
        for e in pool.reachable(&roots) {
            if let Node::Sym(s) = *pool.node(e) {
                readers.entry(s).or_default().push(g);
            }
        }
    }
    readers
}

/// The groups that depend on state `j`, in order.
fn affected(readers: &HashMap<Sym, Vec<usize>>, groups: &[Group], j: usize) -> Vec<usize> {
    let mut found = std::collections::BTreeSet::new();
    let mut stack: Vec<usize> = readers.get(&Sym::State(j)).cloned().unwrap_or_default();
    while let Some(g) = stack.pop() {
        if found.insert(g) {
            for s in groups[g].defines() {
                stack.extend(readers.get(&s).into_iter().flatten());
            }
        }
    }
    found.into_iter().collect()
}

fn leaf_derivative(dsym: &HashMap<Sym, ExprId>, j: usize, leaf: Sym) -> ExprId {
    match leaf {
        Sym::State(k) if k == j => ExprId::ONE,
        Sym::Der(_) | Sym::Aux(_) => dsym.get(&leaf).copied().unwrap_or(ExprId::ZERO),
        _ => ExprId::ZERO,
    }
}

/// A constant or a single symbol stays inline; anything else becomes an auxiliary definition.
fn name_if_large(pool: &mut Pool, system: &mut System, d: ExprId) -> ExprId {
    if matches!(pool.node(d), Node::Const(_) | Node::Sym(_)) {
        return d;
    }
    let aux = pool.fresh_aux();
    system.push(Group {
        pivots: Vec::new(),
        body: Body::Symbolic(vec![(aux, d)]),
    });
    pool.sym(aux)
}
