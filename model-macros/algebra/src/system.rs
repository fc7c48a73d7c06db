//! The solved system: named values defined in dependency order.
//!
//! Solutions are kept as *definitions* of symbols (`der(x) := ...`), not substituted into each
//! other: a later block reads `der(x)` as a symbol, the Jacobian differentiates through the
//! definitions by the chain rule, and the emitter computes each definition once. This is what
//! keeps a cascade of blocks from multiplying out into one huge expression.

use crate::hash::{HashMap, HashSet};
use std::collections::BTreeSet;

use crate::expr::{ExprId, Node, Pool, Sym};

/// A pivot that must be checked (nonzero, finite) at run time before its block is used.
#[derive(Clone, Debug, PartialEq)]
pub struct Pivot {
    /// The pivot's value.
    pub value: ExprId,
    /// The pivot in the user's terms.
    pub text: String,
}

/// How a group defines its symbols.
#[derive(Clone, Debug, PartialEq)]
pub enum Body {
    /// Each symbol by an expression, in order (later ones may read earlier ones).
    Symbolic(Vec<(Sym, ExprId)>),
    /// The symbols are the solution `x` of `matrix · x = rhs`, solved at run time.
    Numeric {
        /// Row-major `n × n`.
        matrix: Vec<ExprId>,
        /// `n` entries.
        rhs: Vec<ExprId>,
        /// The symbols receiving `x`.
        results: Vec<Sym>,
        /// The block named by its derivatives.
        text: String,
    },
}

/// Definitions that belong together (one block of the solve, or one piece of a Jacobian).
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// Pivots checked before any of the group's values is used.
    pub pivots: Vec<Pivot>,
    /// The definitions.
    pub body: Body,
}

impl Group {
    /// The symbols this group defines.
    pub fn defines(&self) -> Vec<Sym> {
        match &self.body {
            Body::Symbolic(defs) => defs.iter().map(|(s, _)| *s).collect(),
            Body::Numeric { results, .. } => results.clone(),
        }
    }

    /// Every expression the group evaluates.
    pub fn expressions(&self) -> Vec<ExprId> {
        let mut out: Vec<ExprId> = self.pivots.iter().map(|p| p.value).collect();
        match &self.body {
            Body::Symbolic(defs) => out.extend(defs.iter().map(|(_, e)| *e)),
            Body::Numeric { matrix, rhs, .. } => {
                out.extend(matrix);
                out.extend(rhs);
            }
        }
        out
    }
}

/// Definitions in dependency order, with an index from symbol to group.
#[derive(Clone, Debug, Default)]
pub struct System {
    /// The groups, each reading only inputs and symbols of earlier groups (or earlier
    /// definitions of its own).
    pub groups: Vec<Group>,
    owner: HashMap<Sym, usize>,
}

impl System {
    /// Appends a group.
    pub fn push(&mut self, group: Group) {
        for s in group.defines() {
            self.owner.insert(s, self.groups.len());
        }
        self.groups.push(group);
    }

    /// The group defining `s`, if any (inputs have none).
    pub fn owner(&self, s: Sym) -> Option<usize> {
        self.owner.get(&s).copied()
    }

    /// The definition of `s` when it is defined by an expression.
    pub fn expression_of(&self, s: Sym) -> Option<ExprId> {
        let g = self.owner(s)?;
        match &self.groups[g].body {
            Body::Symbolic(defs) => defs.iter().find(|(d, _)| *d == s).map(|(_, e)| *e),
            Body::Numeric { .. } => None,
        }
    }

    /// The input symbols (states, parameters, time, undefined derivatives) that `roots` read,
    /// directly or through definitions.
    pub fn inputs_read(&self, pool: &Pool, roots: &[ExprId]) -> BTreeSet<Sym> {
        self.reachable_nodes(pool, roots)
            .into_iter()
            .filter_map(|n| match pool.node(n) {
                Node::Sym(s) if self.owner(*s).is_none() => Some(*s),
                _ => None,
            })
            .collect()
    }

    /// Every node that computing `roots` evaluates: through the definitions of the symbols it
    /// reads, with the pivots of their groups (and all of a numeric group's entries).
    pub fn reachable_nodes(&self, pool: &Pool, roots: &[ExprId]) -> HashSet<ExprId> {
        let mut nodes = HashSet::default();
        let mut seen_groups = vec![false; self.groups.len()];
        let mut seen_syms: HashSet<Sym> = HashSet::default();
        let mut todo: Vec<ExprId> = roots.to_vec();
        while let Some(e) = todo.pop() {
            for n in pool.reachable(&[e]) {
                if !nodes.insert(n) {
                    continue;
                }
                let Node::Sym(s) = pool.node(n) else {
                    continue;
                };
                let Some(g) = self.owner(*s) else {
                    continue;
                };
                if !seen_groups[g] {
                    seen_groups[g] = true;
                    let group = &self.groups[g];
                    todo.extend(group.pivots.iter().map(|p| p.value));
                    if let Body::Numeric { .. } = group.body {
                        todo.extend(group.expressions());
                    }
                }
                if seen_syms.insert(*s) {
                    todo.extend(self.expression_of(*s));
                }
            }
        }
        nodes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inputs_are_followed_through_definitions() {
        // der(y0) := y1 * p0 ; der(y2) := der(y0) + t (reads y1, p0 through der(y0)).
        let mut pool = Pool::new();
        let (y1, p0, t) = (
            pool.sym(Sym::State(1)),
            pool.sym(Sym::Param(0)),
            pool.sym(Sym::Time),
        );
        let d0 = pool.mul2(y1, p0);
        let d0s = pool.sym(Sym::Der(0));
        let d2 = pool.add2(d0s, t);
        let mut system = System::default();
        system.push(Group {
            pivots: vec![],
            body: Body::Symbolic(vec![(Sym::Der(0), d0)]),
        });
        system.push(Group {
            pivots: vec![],
            body: Body::Symbolic(vec![(Sym::Der(2), d2)]),
        });
        let d2s = pool.sym(Sym::Der(2));
        let inputs: Vec<Sym> = system.inputs_read(&pool, &[d2s]).into_iter().collect();
        assert_eq!(inputs, vec![Sym::Time, Sym::State(1), Sym::Param(0)]);
        assert_eq!(system.owner(Sym::Der(2)), Some(1));
        assert_eq!(system.expression_of(Sym::Der(0)), Some(d0));
    }
}
