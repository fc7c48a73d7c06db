//! Hash-consed expressions: every distinct subexpression exists once, so equality is an id
//! comparison and sharing is free.
//!
//! The solve multiplies and subtracts the same coefficients many times; interning keeps the
//! result a DAG whose size grows with the number of *distinct* subexpressions instead of with
//! the size of the written-out trees. Sums and products are n-ary with their operands in a
//! canonical order, so `a*b` and `b*a` are the same node. Nodes are only ever built through the
//! simplifying constructors of [`crate::simplify`], which keep this canonical form.

use crate::hash::{HashMap, HashSet};
use std::collections::BTreeSet;

use crate::spec::Func;

/// An interned expression (an index into its [`Pool`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ExprId(pub(crate) u32);

impl ExprId {
    /// The constant `0`.
    pub const ZERO: ExprId = ExprId(0);
    /// The constant `1`.
    pub const ONE: ExprId = ExprId(1);
    /// The constant `-1`.
    pub const MINUS_ONE: ExprId = ExprId(2);
}

/// A leaf symbol.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Sym {
    /// The time `t`.
    Time,
    /// State `y[i]`.
    State(usize),
    /// Parameter `p[i]`.
    Param(usize),
    /// The derivative of state `i`: an unknown of the equations, a solved value in the right-hand
    /// side, an input of the outputs.
    Der(usize),
    /// An auxiliary value defined by the compiler (e.g. one column of a Jacobian).
    Aux(u32),
}

/// One node of the DAG.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A constant, stored by its bits (`-0.0` is stored as `0.0`).
    Const(u64),
    /// A symbol.
    Sym(Sym),
    /// A sum of at least two terms, in canonical order.
    Add(Box<[ExprId]>),
    /// A product of at least two factors: an optional constant first, then the rest in
    /// canonical order. No factor is itself a product.
    Mul(Box<[ExprId]>),
    /// `[base, exponent]`.
    Pow([ExprId; 2]),
    /// A one-argument function (never `sqrt`, which is a power, nor a two-argument one).
    Call(Func, [ExprId; 1]),
    /// A two-argument function, `atan2` (`[y, x]` of `atan2(y, x)`) or `hypot` (`[x, y]`),
    /// with its arguments in the order written (`min` and `max` are [`Node::Select`]s).
    Call2(Func, [ExprId; 2]),
    /// `[lhs, rhs, then, otherwise]`: `then` where `lhs > rhs`, else `otherwise`; NaN when
    /// `lhs` or `rhs` is NaN (see [`select_value`]). Every condition of the DSL, and `min` and
    /// `max`, are this one comparison, with the operands or the branches swapped.
    Select([ExprId; 4]),
}

impl Node {
    /// The node's operands.
    pub fn children(&self) -> &[ExprId] {
        match self {
            Node::Const(_) | Node::Sym(_) => &[],
            Node::Add(ts) | Node::Mul(ts) => ts,
            Node::Pow(ab) | Node::Call2(_, ab) => ab,
            Node::Call(_, a) => a,
            Node::Select(s) => s,
        }
    }

    /// The constant value, if this is a constant.
    pub fn as_const(&self) -> Option<f64> {
        match self {
            Node::Const(bits) => Some(f64::from_bits(*bits)),
            _ => None,
        }
    }

    /// The operations this node costs when emitted on its own (n-ary nodes cost one
    /// operation per extra operand).
    pub fn own_ops(&self) -> u32 {
        match self {
            Node::Const(_) | Node::Sym(_) => 0,
            Node::Add(ts) | Node::Mul(ts) => ts.len() as u32 - 1,
            Node::Pow(_) | Node::Call(..) | Node::Call2(..) | Node::Select(_) => 1,
        }
    }
}

/// Facts about a node computed once when it is interned.
#[derive(Clone, Copy, Debug, Default)]
struct Info {
    /// Contains a [`Sym::Der`].
    has_der: bool,
    /// Contains any symbol.
    has_sym: bool,
}

/// The store of all expressions of one compilation.
#[derive(Clone, Debug)]
pub struct Pool {
    nodes: Vec<Node>,
    info: Vec<Info>,
    index: HashMap<Node, ExprId>,
    next_aux: u32,
}

impl Default for Pool {
    fn default() -> Self {
        Self::new()
    }
}

impl Pool {
    /// An empty pool holding only the constants `0`, `1`, `-1`.
    pub fn new() -> Pool {
        let mut pool = Pool {
            nodes: Vec::new(),
            info: Vec::new(),
            index: HashMap::default(),
            next_aux: 0,
        };
        for v in [0.0, 1.0, -1.0] {
            pool.intern(Node::Const(f64::to_bits(v)));
        }
        pool
    }

    /// Interns a node as is (no simplification; use the constructors of
    /// [`crate::simplify`]).
    pub(crate) fn intern(&mut self, node: Node) -> ExprId {
        let node = match node {
            Node::Const(bits) if f64::from_bits(bits) == 0.0 => Node::Const(0),
            other => other,
        };
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let mut info = match &node {
            Node::Sym(s) => Info {
                has_der: matches!(s, Sym::Der(_)),
                has_sym: true,
            },
            _ => Info::default(),
        };
        for c in node.children() {
            let ci = self.info[c.0 as usize];
            info.has_der |= ci.has_der;
            info.has_sym |= ci.has_sym;
        }
        let id = ExprId(self.nodes.len() as u32);
        self.nodes.push(node.clone());
        self.info.push(info);
        self.index.insert(node, id);
        id
    }

    /// A sum of `terms` exactly as given (sorted, not simplified): for the emitter, which
    /// must keep a factored form that the simplifying constructor would distribute again.
    pub(crate) fn intern_sum(&mut self, mut terms: Vec<ExprId>) -> ExprId {
        if terms.len() == 1 {
            return terms[0];
        }
        terms.sort_unstable();
        self.intern(Node::Add(terms.into()))
    }

    /// The id of `node` if it was interned already (never creates it).
    pub fn lookup(&self, node: &Node) -> Option<ExprId> {
        self.index.get(node).copied()
    }

    /// The node behind an id.
    pub fn node(&self, id: ExprId) -> &Node {
        &self.nodes[id.0 as usize]
    }

    /// The number of distinct nodes interned so far (the tests check the interning).
    #[cfg(test)]
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// The constant value of `id`, if it is a constant.
    pub fn as_const(&self, id: ExprId) -> Option<f64> {
        self.node(id).as_const()
    }

    /// Whether `id` contains a derivative symbol.
    pub fn has_der(&self, id: ExprId) -> bool {
        self.info[id.0 as usize].has_der
    }

    /// Whether `id` contains any symbol (otherwise it is a constant expression).
    pub fn has_sym(&self, id: ExprId) -> bool {
        self.info[id.0 as usize].has_sym
    }

    /// A fresh auxiliary symbol.
    pub fn fresh_aux(&mut self) -> Sym {
        self.next_aux += 1;
        Sym::Aux(self.next_aux - 1)
    }

    /// Every node reachable from `roots` (children before parents).
    pub fn reachable(&self, roots: &[ExprId]) -> Vec<ExprId> {
        let mut seen = HashSet::default();
        let mut order = Vec::new();
        let mut stack: Vec<(ExprId, bool)> = roots.iter().rev().map(|&r| (r, false)).collect();
        while let Some((id, expanded)) = stack.pop() {
            if expanded {
                order.push(id);
                continue;
            }
            if !seen.insert(id) {
                continue;
            }
            stack.push((id, true));
            for &c in self.node(id).children().iter().rev() {
                if !seen.contains(&c) {
                    stack.push((c, false));
                }
            }
        }
        order
    }

    /// The operations needed to compute all of `roots`, each distinct node once.
    pub fn dag_ops(&self, roots: &[ExprId]) -> u32 {
        self.reachable(roots)
            .iter()
            .map(|&id| self.node(id).own_ops())
            .sum()
    }

    /// The symbols `id` reads.
    pub fn symbols(&self, id: ExprId) -> BTreeSet<Sym> {
        self.reachable(&[id])
            .into_iter()
            .filter_map(|n| match self.node(n) {
                Node::Sym(s) => Some(*s),
                _ => None,
            })
            .collect()
    }

    /// Evaluates `roots` with the symbol values given by `value`.
    pub fn eval_many(&self, roots: &[ExprId], value: &dyn Fn(Sym) -> f64) -> Vec<f64> {
        let mut memo: HashMap<ExprId, f64> = HashMap::default();
        for id in self.reachable(roots) {
            let arg = |k: usize| memo[&self.node(id).children()[k]];
            let v = match self.node(id) {
                Node::Const(bits) => f64::from_bits(*bits),
                Node::Sym(s) => value(*s),
                Node::Add(ts) => ts.iter().map(|t| memo[t]).sum(),
                Node::Mul(fs) => fs.iter().map(|f| memo[f]).product(),
                Node::Pow(_) => pow_value(arg(0), arg(1)),
                Node::Call(f, _) => call_value(*f, arg(0)),
                Node::Call2(f, _) => call2_value(*f, arg(0), arg(1)),
                Node::Select(_) => select_value(arg(0), arg(1), arg(2), arg(3)),
            };
            memo.insert(id, v);
        }
        roots.iter().map(|r| memo[r]).collect()
    }

    /// Evaluates one expression (the tests compare it with the compiled programs).
    #[cfg(test)]
    pub fn eval(&self, id: ExprId, value: &dyn Fn(Sym) -> f64) -> f64 {
        self.eval_many(&[id], value)[0]
    }
}

/// `base ^ exponent` as emitted code computes it (`powi` for integers, `sqrt` for one half).
pub fn pow_value(base: f64, exponent: f64) -> f64 {
    match integer_exponent(exponent) {
        Some(n) => base.powi(n),
        None if exponent == 0.5 => base.sqrt(),
        None if exponent == -0.5 => 1.0 / base.sqrt(),
        None => base.powf(exponent),
    }
}

/// The exponent as an `i32`, if it is a (not too large) integer.
pub fn integer_exponent(exponent: f64) -> Option<i32> {
    (exponent.fract() == 0.0 && exponent.abs() <= 1024.0).then_some(exponent as i32)
}

/// The value of a one-argument function.
pub fn call_value(f: Func, x: f64) -> f64 {
    match f {
        Func::Sin => x.sin(),
        Func::Cos => x.cos(),
        Func::Tan => x.tan(),
        Func::Sqrt => x.sqrt(),
        Func::Exp => x.exp(),
        Func::Ln => x.ln(),
        Func::Abs => x.abs(),
        Func::Sign => sign_value(x),
        // Not one-argument functions; never built as a `Call`.
        Func::Atan2 | Func::Hypot | Func::Min | Func::Max => f64::NAN,
    }
}

/// The value of a two-argument function of a [`Node::Call2`], as emitted code computes it:
/// `atan2(a, b)` is `a.atan2(b)`, `hypot(a, b)` is `a.hypot(b)`.
pub fn call2_value(f: Func, a: f64, b: f64) -> f64 {
    match f {
        Func::Atan2 => a.atan2(b),
        Func::Hypot => a.hypot(b),
        // One-argument functions, and `min`/`max` (selects): never built as a `Call2`.
        Func::Sin
        | Func::Cos
        | Func::Tan
        | Func::Sqrt
        | Func::Exp
        | Func::Ln
        | Func::Abs
        | Func::Sign
        | Func::Min
        | Func::Max => f64::NAN,
    }
}

/// `sign(x)` as emitted code computes it: `-1`, `1`, or `x` itself at zero (`±0`) and NaN.
pub fn sign_value(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        x
    }
}

/// A [`Node::Select`] as emitted code computes it: `then` where `lhs > rhs`, `otherwise` where
/// `lhs <= rhs`, NaN where the comparison has no answer (an operand is NaN). Propagating the NaN
/// keeps a bad input visible to the finiteness checks (a plain `if lhs > rhs` would pick
/// `otherwise` and hide it), and makes `lhs >= rhs ? a : b` the same as `rhs > lhs ? b : a`, so
/// every comparison is this one.
pub fn select_value(lhs: f64, rhs: f64, then: f64, otherwise: f64) -> f64 {
    if lhs > rhs {
        then
    } else if lhs <= rhs {
        otherwise
    } else {
        f64::NAN
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interning_shares_equal_nodes() {
        let mut pool = Pool::new();
        let x = pool.intern(Node::Sym(Sym::State(0)));
        let a = pool.intern(Node::Call(Func::Sin, [x]));
        let b = pool.intern(Node::Call(Func::Sin, [x]));
        assert_eq!(a, b);
        assert_eq!(pool.len(), 5);
        assert!(pool.has_sym(a) && !pool.has_der(a));
    }

    #[test]
    fn builtin_constants_and_negative_zero() {
        let mut pool = Pool::new();
        assert_eq!(pool.as_const(ExprId::ZERO), Some(0.0));
        assert_eq!(pool.as_const(ExprId::ONE), Some(1.0));
        assert_eq!(pool.as_const(ExprId::MINUS_ONE), Some(-1.0));
        assert_eq!(pool.intern(Node::Const((-0.0f64).to_bits())), ExprId::ZERO);
    }

    #[test]
    fn dag_ops_counts_shared_nodes_once() {
        let mut pool = Pool::new();
        let x = pool.intern(Node::Sym(Sym::State(0)));
        let y = pool.intern(Node::Sym(Sym::State(1)));
        let s = pool.intern(Node::Add(vec![x, y].into()));
        let p = pool.intern(Node::Mul(vec![s, s].into()));
        assert_eq!(pool.dag_ops(&[p, s]), 2);
        let der = pool.intern(Node::Sym(Sym::Der(0)));
        let q = pool.intern(Node::Mul(vec![der, p].into()));
        assert!(pool.has_der(q));
        assert_eq!(
            pool.symbols(q).into_iter().collect::<Vec<_>>(),
            vec![Sym::State(0), Sym::State(1), Sym::Der(0)]
        );
    }

    #[test]
    fn pow_value_matches_emitted_forms() {
        assert_eq!(pow_value(2.0, 3.0), 8.0);
        assert_eq!(pow_value(4.0, 0.5), 2.0);
        assert_eq!(pow_value(4.0, -0.5), 0.5);
        assert!((pow_value(2.0, 0.25) - 2f64.powf(0.25)).abs() < 1e-15);
    }
}
