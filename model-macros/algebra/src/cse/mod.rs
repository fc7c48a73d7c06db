//! From the DAG to a straight-line [`Program`]: each distinct subexpression computed once.
//!
//! Because expressions are interned, common subexpression elimination is a memoised walk: a
//! node already emitted is read from its temporary. Definitions of the solved system are pulled
//! in on first use (with their block's pivot checks in front), so a reduced variant computes only
//! what its stores need. Two small analyses of everything reachable run first: arguments whose
//! sine and cosine are both needed get one `SinCos`, and a reciprocal `1/p` (or `1/sqrt(p)`) used
//! by two or more products is computed once and multiplied, while one used once becomes a
//! division.

use crate::hash::{HashMap, HashSet};

use crate::expr::{integer_exponent, ExprId, Node, Pool, Sym};
use crate::program::{Node as Op, Operand, Program, Stmt, Target};
use crate::spec::Func;
use crate::system::{Body, System};

mod factor;
mod pivots;

/// A symbol with no definition and no input slot (a bug in the caller's selection).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Unbound(pub Sym);

/// A program being emitted.
pub struct Emitter<'a> {
    pool: &'a mut Pool,
    system: &'a System,
    input: &'a dyn Fn(Sym) -> Option<Operand>,
    stmts: Vec<Stmt>,
    value: HashMap<ExprId, Operand>,
    sym_value: HashMap<Sym, Operand>,
    group_started: Vec<bool>,
    next_tmp: u32,
    sincos: HashSet<ExprId>,
    shared_reciprocals: HashSet<ExprId>,
    factor_uses: HashMap<ExprId, u32>,
    numbered: HashMap<ValueKey, Operand>,
    pivot_tolerance: f64,
    /// Texts of the pivots checked, in order.
    pub pivots: Vec<String>,
    /// Texts of the blocks solved numerically, in order.
    pub numeric_blocks: Vec<String>,
}

impl<'a> Emitter<'a> {
    /// An emitter for stores of `roots`, reading symbols defined by `system` or mapped by
    /// `input`; pivots are checked for cancellation with `pivot_tolerance`
    /// ([`crate::CompileOptions::pivot_tolerance`]).
    pub fn new(
        pool: &'a mut Pool,
        system: &'a System,
        input: &'a dyn Fn(Sym) -> Option<Operand>,
        roots: &[ExprId],
        pivot_tolerance: f64,
    ) -> Emitter<'a> {
        let mut e = Emitter {
            group_started: vec![false; system.groups.len()],
            pool,
            system,
            input,
            stmts: Vec::new(),
            value: HashMap::default(),
            sym_value: HashMap::default(),
            next_tmp: 0,
            sincos: HashSet::default(),
            shared_reciprocals: HashSet::default(),
            factor_uses: HashMap::default(),
            numbered: HashMap::default(),
            pivot_tolerance,
            pivots: Vec::new(),
            numeric_blocks: Vec::new(),
        };
        e.analyse(roots);
        e
    }

    /// Everything reachable from `roots` through definitions, children before parents.
    fn analyse(&mut self, roots: &[ExprId]) {
        let nodes = self.system.reachable_nodes(self.pool, roots);
        let mut reciprocal_uses: HashMap<ExprId, u32> = HashMap::default();
        for &n in &nodes {
            let node = self.pool.node(n);
            if let Node::Call(Func::Sin, [u]) = node {
                let cos = self.pool.lookup(&Node::Call(Func::Cos, [*u]));
                if cos.is_some_and(|c| nodes.contains(&c)) {
                    self.sincos.insert(*u);
                }
            }
            if let Node::Mul(fs) = node {
                for f in fs.iter() {
                    *self.factor_uses.entry(*f).or_default() += 1;
                }
            }
            for &c in node.children() {
                if let Node::Pow([_, e]) = self.pool.node(c) {
                    if self.pool.as_const(*e).is_some_and(|k| k < 0.0) {
                        *reciprocal_uses.entry(c).or_default() += 1;
                    }
                }
            }
        }
        self.shared_reciprocals = reciprocal_uses
            .into_iter()
            .filter(|(_, uses)| *uses >= 2)
            .map(|(c, _)| c)
            .collect();
    }

    /// Emits `target = value`.
    pub fn store(&mut self, target: Target, value: ExprId) -> Result<(), Unbound> {
        let value = self.operand(value)?;
        self.stmts.push(Stmt::Store { target, value });
        Ok(())
    }

    /// The finished program.
    pub fn finish(self) -> Program {
        Program { stmts: self.stmts }
    }

    fn tmp(&mut self) -> u32 {
        self.next_tmp += 1;
        self.next_tmp - 1
    }

    /// `let tK = node;`, unless an equal node was computed already (value numbering: this is
    /// what shares the partial products and sums of different n-ary nodes).
    fn let_(&mut self, node: Op) -> Operand {
        let key = ValueKey::of(&node);
        if let Some(&v) = self.numbered.get(&key) {
            return v;
        }
        let tmp = self.tmp();
        self.stmts.push(Stmt::Let { tmp, node });
        self.numbered.insert(key, Operand::Tmp(tmp));
        Operand::Tmp(tmp)
    }

    /// Factors ordered so that the most shared ones are multiplied first (their partial
    /// products are then shared by value numbering).
    fn order_factors(&self, factors: &mut [ExprId]) {
        factors.sort_by_key(|f| {
            (
                std::cmp::Reverse(self.factor_uses.get(f).copied().unwrap_or(0)),
                *f,
            )
        });
    }

    fn multiply_all(&mut self, factors: &[ExprId]) -> Result<Option<Operand>, Unbound> {
        let mut acc: Option<Operand> = None;
        for &f in factors {
            let v = self.operand(f)?;
            acc = Some(match acc {
                None => v,
                Some(a) => self.let_(Op::Mul(a, v)),
            });
        }
        Ok(acc)
    }

    /// The operand holding the value of `e`, emitting what it needs.
    pub fn operand(&mut self, e: ExprId) -> Result<Operand, Unbound> {
        if let Some(&v) = self.value.get(&e) {
            return Ok(v);
        }
        let v = match self.pool.node(e).clone() {
            Node::Const(bits) => Operand::Const(f64::from_bits(bits)),
            Node::Sym(s) => self.symbol(s)?,
            Node::Add(ts) => self.sum(&ts)?,
            Node::Mul(_) => self.product(e)?,
            Node::Pow([b, x]) => self.power(b, x)?,
            Node::Call(f, [a]) => {
                let a_op = self.operand(a)?;
                if matches!(f, Func::Sin | Func::Cos) && self.sincos.contains(&a) {
                    let (sin, cos) = (self.tmp(), self.tmp());
                    self.stmts.push(Stmt::SinCos {
                        sin,
                        cos,
                        arg: a_op,
                    });
                    let sin_id = self.pool.call(Func::Sin, a);
                    let cos_id = self.pool.call(Func::Cos, a);
                    self.value.insert(sin_id, Operand::Tmp(sin));
                    self.value.insert(cos_id, Operand::Tmp(cos));
                    return Ok(self.value[&e]);
                }
                self.let_(Op::Call(f, a_op))
            }
            Node::Call2(f, [a, b]) => {
                let (a, b) = (self.operand(a)?, self.operand(b)?);
                self.let_(Op::Call2(f, a, b))
            }
            Node::Select(s) => {
                let [a, b, c, d] = s.map(|x| self.operand(x));
                self.let_(Op::Select(a?, b?, c?, d?))
            }
        };
        self.value.insert(e, v);
        Ok(v)
    }

    fn symbol(&mut self, s: Sym) -> Result<Operand, Unbound> {
        if let Some(&v) = self.sym_value.get(&s) {
            return Ok(v);
        }
        let Some(g) = self.system.owner(s) else {
            return (self.input)(s).ok_or(Unbound(s));
        };
        let system = self.system;
        let group = &system.groups[g];
        if !self.group_started[g] {
            self.check_pivots(g)?;
            if let Body::Numeric {
                matrix,
                rhs,
                results,
                text,
            } = &group.body
            {
                let matrix = matrix
                    .iter()
                    .map(|&m| self.operand(m))
                    .collect::<Result<Vec<_>, _>>()?;
                let rhs = rhs
                    .iter()
                    .map(|&r| self.operand(r))
                    .collect::<Result<Vec<_>, _>>()?;
                let tmps: Vec<u32> = results.iter().map(|_| self.tmp()).collect();
                for (&r, &t) in results.iter().zip(&tmps) {
                    self.sym_value.insert(r, Operand::Tmp(t));
                }
                self.stmts.push(Stmt::SolveBlock {
                    n: results.len(),
                    matrix,
                    rhs,
                    result: tmps,
                    text: text.clone(),
                });
                self.numeric_blocks.push(text.clone());
            }
        }
        if let Some(&v) = self.sym_value.get(&s) {
            return Ok(v);
        }
        let e = system.expression_of(s).ok_or(Unbound(s))?;
        let v = self.operand(e)?;
        self.sym_value.insert(s, v);
        Ok(v)
    }

    /// The sum of `terms` with its common factors and coefficients pulled out (see
    /// [`factor`]), or `None` if its terms share none.
    fn factored(&mut self, terms: &[ExprId]) -> Option<ExprId> {
        factor::factored(self.pool, terms).expr
    }

    /// A sum: common factors pulled out, then positive terms added and negative ones
    /// subtracted.
    fn sum(&mut self, terms: &[ExprId]) -> Result<Operand, Unbound> {
        match self.emitted_sum(terms)? {
            EmittedSum::Refactored(e) => self.operand(e),
            EmittedSum::Added { value, .. } => Ok(value),
        }
    }

    /// The sum as it is emitted: either rewritten with a common factor pulled out (to be
    /// emitted as that expression), or added up from the operands of its terms.
    fn emitted_sum(&mut self, terms: &[ExprId]) -> Result<EmittedSum, Unbound> {
        if let Some(e) = self.factored(terms) {
            if !matches!(self.pool.node(e), Node::Add(ts) if **ts == *terms) {
                return Ok(EmittedSum::Refactored(e));
            }
        }
        let mut plus = Vec::new();
        // Each subtracted term: the term, and the magnitude that is subtracted.
        let mut minus = Vec::new();
        for &t in terms {
            let (c, rest) = self.pool.split_coefficient(t);
            if c >= 0.0 {
                plus.push(t);
            } else if c == -1.0 {
                minus.push((t, rest));
            } else if rest == ExprId::ONE {
                let m = self.pool.num(-c);
                minus.push((t, m));
            } else {
                let m = self.pool.num(-c);
                let magnitude = self.pool.mul2(m, rest);
                minus.push((t, magnitude));
            }
        }
        let mut parts = Vec::with_capacity(terms.len());
        let mut added = Vec::with_capacity(terms.len());
        let mut acc = match plus.first() {
            Some(&t) => {
                let v = self.operand(t)?;
                parts.push(v);
                added.push(t);
                v
            }
            None => {
                let (t, m) = minus.remove(0);
                let first = self.operand(m)?;
                parts.push(first);
                added.push(t);
                self.let_(Op::Neg(first))
            }
        };
        for &t in plus.iter().skip(1) {
            let v = self.operand(t)?;
            parts.push(v);
            added.push(t);
            acc = self.let_(Op::Add(acc, v));
        }
        for (t, m) in minus {
            let v = self.operand(m)?;
            parts.push(v);
            added.push(t);
            acc = self.let_(Op::Sub(acc, v));
        }
        Ok(EmittedSum::Added {
            value: acc,
            parts,
            terms: added,
        })
    }

    /// A product as `(a * b / (d * e)) * c`: the constant last, so products that differ only
    /// in their coefficient share everything else.
    fn product(&mut self, e: ExprId) -> Result<Operand, Unbound> {
        let Node::Mul(factors) = self.pool.node(e).clone() else {
            return self.operand(e);
        };
        let mut coefficient = 1.0;
        let mut num: Vec<ExprId> = Vec::new();
        let mut den: Vec<ExprId> = Vec::new();
        for &f in factors.iter() {
            if let Some(c) = self.pool.as_const(f) {
                coefficient = c;
                continue;
            }
            if let Node::Pow([b, x]) = *self.pool.node(f) {
                if let Some(k) = self.pool.as_const(x).filter(|k| *k < 0.0) {
                    if self.shared_reciprocals.contains(&f) {
                        num.push(f);
                    } else {
                        den.push(self.pool.powf(b, -k));
                    }
                    continue;
                }
            }
            num.push(f);
        }
        self.order_factors(&mut num);
        self.order_factors(&mut den);
        let mut acc = self.multiply_all(&num)?;
        if let Some(d) = self.multiply_all(&den)? {
            let n = acc.unwrap_or(Operand::Const(coefficient));
            if acc.is_none() {
                coefficient = 1.0;
            }
            acc = Some(self.let_(Op::Div(n, d)));
        }
        let acc = acc.unwrap_or(Operand::Const(1.0));
        Ok(match coefficient {
            1.0 => acc,
            -1.0 => self.let_(Op::Neg(acc)),
            c => self.let_(Op::Mul(Operand::Const(c), acc)),
        })
    }

    /// A power on its own (inside a product, negative powers become divisions instead).
    fn power(&mut self, base: ExprId, exponent: ExprId) -> Result<Operand, Unbound> {
        let b = self.operand(base)?;
        let Some(k) = self.pool.as_const(exponent) else {
            let x = self.operand(exponent)?;
            return Ok(self.let_(Op::Powf(b, x)));
        };
        if k < 0.0 {
            let positive = self.pool.powf(base, -k);
            let d = self.operand(positive)?;
            return Ok(self.let_(Op::Div(Operand::Const(1.0), d)));
        }
        Ok(match integer_exponent(k) {
            Some(n) => self.let_(Op::Powi(b, n)),
            None if k == 0.5 => self.let_(Op::Call(Func::Sqrt, b)),
            // b^(n + 1/2) as b^n * sqrt(b), sharing the root (a derivative of `sqrt(r)` has
            // `r^-1.5`).
            None if k > 0.0 && (k - 0.5).fract() == 0.0 && k < 1024.0 => {
                let root = self.pool.powf(base, 0.5);
                let whole = self.pool.powf(base, k - 0.5);
                let (r, w) = (self.operand(root)?, self.operand(whole)?);
                self.let_(Op::Mul(w, r))
            }
            None => self.let_(Op::Powf(b, Operand::Const(k))),
        })
    }
}

/// How a sum is emitted (see [`Emitter::emitted_sum`]).
enum EmittedSum {
    /// As this other expression (a common factor pulled out).
    Refactored(ExprId),
    /// Added up.
    Added {
        /// The sum.
        value: Operand,
        /// The operands added (subtracted ones by their magnitude).
        parts: Vec<Operand>,
        /// The term each operand comes from.
        terms: Vec<ExprId>,
    },
}

/// A statement's value, for value numbering: commutative operands in a fixed order.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum ValueKey {
    Unary(u8, OperandKey),
    Binary(u8, OperandKey, OperandKey),
    Powi(OperandKey, i32),
    Call(Func, OperandKey),
    Call2(Func, OperandKey, OperandKey),
    Select([OperandKey; 4]),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
enum OperandKey {
    Const(u64),
    State(usize),
    Param(usize),
    Der(usize),
    Time,
    Tmp(u32),
}

impl OperandKey {
    fn of(o: Operand) -> OperandKey {
        match o {
            Operand::Const(v) => OperandKey::Const(v.to_bits()),
            Operand::State(i) => OperandKey::State(i),
            Operand::Param(i) => OperandKey::Param(i),
            Operand::Der(i) => OperandKey::Der(i),
            Operand::Time => OperandKey::Time,
            Operand::Tmp(k) => OperandKey::Tmp(k),
        }
    }
}

impl ValueKey {
    fn of(node: &Op) -> ValueKey {
        let k = OperandKey::of;
        let sorted = |tag: u8, a: Operand, b: Operand| {
            let (a, b) = (k(a), k(b));
            ValueKey::Binary(tag, a.min(b), a.max(b))
        };
        match *node {
            Op::Copy(a) => ValueKey::Unary(0, k(a)),
            Op::Neg(a) => ValueKey::Unary(1, k(a)),
            Op::Add(a, b) => sorted(2, a, b),
            Op::Mul(a, b) => sorted(3, a, b),
            Op::Sub(a, b) => ValueKey::Binary(4, k(a), k(b)),
            Op::Div(a, b) => ValueKey::Binary(5, k(a), k(b)),
            Op::Powf(a, b) => ValueKey::Binary(6, k(a), k(b)),
            Op::Powi(a, n) => ValueKey::Powi(k(a), n),
            Op::Call(f, a) => ValueKey::Call(f, k(a)),
            Op::Call2(f, a, b) => ValueKey::Call2(f, k(a), k(b)),
            Op::Select(a, b, c, d) => ValueKey::Select([a, b, c, d].map(k)),
        }
    }
}

#[cfg(test)]
mod tests;
