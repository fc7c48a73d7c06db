//! Common factors pulled out of a sum, the whole nest at once: `Σ f·r_i + rest` becomes
//! `f·Σ r_i + rest` for the factor `f` shared by the most terms, then the same again inside
//! `Σ r_i` and among the rest, and finally a numeric coefficient shared by several terms is
//! pulled out the same way.
//!
//! A Jacobian entry of a nested chain (`der(sin(sin(..(x)..))) = ..`) is the triangular sum the
//! product rule makes, `Σ_k a_k · Π_{j>k} b_j`: its nest is n levels deep, and each level
//! holds all the terms below it. Splitting and counting the terms again at every level cost
//! n³ for a chain n deep, with only about n² factors in the sum. Here each group of terms
//! keeps the count of every factor it holds (and a heap that finds the most shared one); when a
//! group splits into the terms with the chosen factor and the others, only the smaller side
//! (by factors held) is counted afresh and the larger one takes over the group's counts less
//! the smaller side's. A term is thus counted again only when the group holding it halves,
//! and the whole nest costs about the size of the sum times its logarithm, plus one look at
//! each term of a group per factor pulled out of it. A pulled factor is not removed from the
//! terms (that would copy them at every level): it is left out of the counts and skipped when
//! a term's product is built, once, at the level where no factor is shared any more.

use crate::hash::{HashMap, HashSet};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

use crate::expr::{ExprId, Node, Pool};

/// One term of the sum: its numeric coefficient and its other factors, sorted.
struct Term {
    /// The term as it came.
    id: ExprId,
    coefficient: f64,
    factors: Vec<ExprId>,
}

/// How many terms of a group each factor is in, and a heap that finds the factor in the most
/// (outdated entries, whose count has changed since, are skipped when they come up).
#[derive(Default)]
struct Counts {
    of: HashMap<ExprId, usize>,
    heap: BinaryHeap<(usize, Reverse<ExprId>)>,
}

impl Counts {
    fn change(&mut self, f: ExprId, by: isize) {
        let n = self.of.entry(f).or_default();
        *n = n.saturating_add_signed(by);
        if *n >= 2 {
            self.heap.push((*n, Reverse(f)));
        }
    }

    /// The factor in the most terms (at least two; of those in equally many, the lowest id).
    fn most_shared(&mut self) -> Option<ExprId> {
        while let Some(&(n, Reverse(f))) = self.heap.peek() {
            if self.of.get(&f) == Some(&n) {
                return Some(f);
            }
            self.heap.pop();
        }
        None
    }

    /// These counts less `other`'s (of a subset of the terms).
    fn subtract(&mut self, other: &Counts) {
        for (&f, &n) in &other.of {
            self.change(f, -(n as isize));
        }
    }
}

/// The factoring of one sum.
pub(super) struct Factored {
    /// The sum with its common factors pulled out, or `None` if no factor or coefficient is
    /// shared by two terms.
    pub expr: Option<ExprId>,
    /// Factor occurrences counted and terms looked at while splitting groups: the work, which
    /// the tests hold to grow with the size of the sum, not with its nesting.
    #[cfg_attr(not(test), allow(dead_code))]
    pub work: usize,
}

/// Factors the sum of `terms` (see the module docs).
pub(super) fn factored(pool: &mut Pool, terms: &[ExprId]) -> Factored {
    let terms: Vec<Term> = terms
        .iter()
        .map(|&id| {
            let (coefficient, rest) = pool.split_coefficient(id);
            let mut factors = match pool.node(rest) {
                Node::Mul(fs) => fs.to_vec(),
                Node::Const(_) => Vec::new(),
                _ => vec![rest],
            };
            factors.sort_unstable();
            Term {
                id,
                coefficient,
                factors,
            }
        })
        .collect();
    let mut factoring = Factoring {
        pool,
        terms,
        pulled: HashSet::default(),
        work: 0,
    };
    let members: Vec<usize> = (0..factoring.terms.len()).collect();
    let mut counts = factoring.count(&members);
    // A sum with nothing to pull out (as every sum this builds) is left as it is, unbuilt.
    let shared =
        counts.most_shared().is_some() || !factoring.shared_coefficients(&members).is_empty();
    let expr = shared.then(|| factoring.group(members, counts));
    Factored {
        expr,
        work: factoring.work,
    }
}

struct Factoring<'p> {
    pool: &'p mut Pool,
    terms: Vec<Term>,
    /// The factors pulled out on the way down to the group being factored (in all its terms).
    pulled: HashSet<ExprId>,
    work: usize,
}

impl Factoring<'_> {
    /// The counts of the factors of `members`, less the pulled ones.
    fn count(&mut self, members: &[usize]) -> Counts {
        let mut counts = Counts::default();
        for &t in members {
            self.work += self.terms[t].factors.len();
            for &f in &self.terms[t].factors {
                if !self.pulled.contains(&f) {
                    counts.change(f, 1);
                }
            }
        }
        counts
    }

    /// The factors held by `members` (pulled ones included), the cost of counting them.
    fn size(&self, members: &[usize]) -> usize {
        members.iter().map(|&t| self.terms[t].factors.len()).sum()
    }

    /// The sum of `members` (whose factors `counts` counts), factored.
    fn group(&mut self, members: Vec<usize>, mut counts: Counts) -> ExprId {
        let mut rest = members;
        let mut parts = Vec::new();
        while let Some(f) = counts.most_shared() {
            self.work += rest.len();
            let (with, without): (Vec<usize>, Vec<usize>) = rest
                .iter()
                .partition(|&&t| self.terms[t].factors.binary_search(&f).is_ok());
            let (mut inner, outer) = if self.size(&with) <= self.size(&without) {
                let small = self.count(&with);
                counts.subtract(&small);
                (small, counts)
            } else {
                let small = self.count(&without);
                counts.subtract(&small);
                (counts, small)
            };
            inner.of.remove(&f);
            self.pulled.insert(f);
            let sum = self.group(with, inner);
            self.pulled.remove(&f);
            parts.push(self.pool.mul2(f, sum));
            counts = outer;
            rest = without;
        }
        self.coefficients(&mut rest, &mut parts);
        for t in rest {
            let product = self.product(t, 1.0);
            parts.push(product);
        }
        // The parts are as simple as the terms they come from, and distinct: the sum
        // constructor would find nothing to collect (its search for `sin^2 + cos^2` costs the
        // square of a term's factors), and it would distribute the `c` of `c * (sum)` again.
        self.pool.intern_sum(parts)
    }

    /// The numeric coefficients shared (up to sign, other than one) by two or more of
    /// `members`, each with the terms that have it, the most shared first.
    fn shared_coefficients(&self, members: &[usize]) -> Vec<(u64, Vec<usize>)> {
        let mut by_magnitude: HashMap<u64, Vec<usize>> = HashMap::default();
        for &t in members {
            let term = &self.terms[t];
            let c = term.coefficient;
            // Only a finite coefficient can be pulled out: `c / common` is exactly `±1` for a
            // finite one, but NaN for an infinite one (`1e308*10` folds to inf), and a NaN
            // coefficient would be refactored again without end.
            let bare = term.factors.iter().all(|f| self.pulled.contains(f));
            if c.abs() != 1.0 && c.is_finite() && !bare {
                by_magnitude.entry(c.abs().to_bits()).or_default().push(t);
            }
        }
        let mut shared: Vec<(u64, Vec<usize>)> = by_magnitude
            .into_iter()
            .filter(|(_, ts)| ts.len() >= 2)
            .collect();
        // In the order they were pulled out one at a time (the order new nodes are made in).
        shared.sort_by_key(|(bits, ts)| (Reverse(ts.len()), *bits));
        shared
    }

    /// Pulls out each shared coefficient of `rest`, whose terms share no factor: their sums
    /// scaled go to `parts`, the others stay in `rest`.
    fn coefficients(&mut self, rest: &mut Vec<usize>, parts: &mut Vec<ExprId>) {
        let mut taken = HashSet::default();
        for (bits, members) in self.shared_coefficients(rest) {
            taken.extend(members.iter().copied());
            let magnitude = f64::from_bits(bits);
            let negative = members
                .iter()
                .filter(|&&t| self.terms[t].coefficient < 0.0)
                .count();
            let common = if 2 * negative > members.len() {
                -magnitude
            } else {
                magnitude
            };
            let inner: Vec<ExprId> = members.iter().map(|&t| self.product(t, common)).collect();
            let inner = self.pool.intern_sum(inner);
            let c = self.pool.num(common);
            parts.push(self.pool.intern(Node::Mul(vec![c, inner].into())));
        }
        rest.retain(|t| !taken.contains(t));
    }

    /// Term `t` divided by `divisor`, without the pulled factors.
    fn product(&mut self, t: usize, divisor: f64) -> ExprId {
        let term = &self.terms[t];
        if self.pulled.is_empty() && divisor == 1.0 {
            return term.id;
        }
        let mut factors: Vec<ExprId> = term
            .factors
            .iter()
            .copied()
            .filter(|f| !self.pulled.contains(f))
            .collect();
        let c = term.coefficient / divisor;
        factors.push(self.pool.num(c));
        self.pool.mul(&factors)
    }
}
