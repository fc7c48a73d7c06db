//! From the user's syntax tree to interned expressions, diagnosing as it goes.
//!
//! This is the last place that still knows the user's nodes, so every problem that can be
//! pinned to a token is found here: a derivative used nonlinearly (`der(x)*der(y)`,
//! `sin(der(x))`, `1/der(x)`, `der(x)^2`, `max(der(x), 0)`, `if(der(x) > 0, ..)`), a division
//! by a literal zero, a constant subexpression that is not finite (`ln(0)`), a non-finite
//! literal, a name that does not resolve. Lets are substituted (they are macros), each lowered once; fixed parameters of a
//! variant become constants here, before any algebra, so terms they zero out never exist.

use crate::hash::HashMap;

use crate::diff::time_derivative;
use crate::expr::{ExprId, Pool, Sym};
use crate::spec::{Ast, BinOp, Diagnostic, Func, ModelSpec, NodeId};

/// What a name in the model stands for.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Binding {
    State(usize),
    Param(usize),
    Let(usize),
    Output(usize),
    Time,
    Pi,
}

/// Where an expression is being lowered (which decides what it may use).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Context {
    /// An equation: derivatives must appear linearly.
    Equation,
    /// A let: lowered once; its nonlinear uses of derivatives are reported where it is used
    /// in an equation.
    Let,
    /// Output `k`: may use outputs before `k` and derivatives freely.
    Output(usize),
}

/// A lowered expression with the nonlinear uses of derivatives found in it.
#[derive(Clone, Debug)]
struct Lowered {
    expr: ExprId,
    nonlinear: Vec<Diagnostic>,
}

#[derive(Clone, Debug)]
enum LetState {
    Pending,
    Active,
    Done(Lowered),
    Failed,
}

/// Lowers the expressions of one model into one pool.
pub struct Lowerer<'s> {
    spec: &'s ModelSpec,
    fixed: Vec<Option<f64>>,
    names: HashMap<&'s str, Binding>,
    lets: Vec<LetState>,
    outputs: Vec<Option<ExprId>>,
    /// The pool everything is interned in.
    pub pool: Pool,
    /// Everything found wrong so far.
    pub diags: Vec<Diagnostic>,
}

impl<'s> Lowerer<'s> {
    /// A lowerer for `spec`, with `fixed[i]` the compile-time value of parameter `i`, if any.
    pub fn new(spec: &'s ModelSpec, fixed: Vec<Option<f64>>) -> Lowerer<'s> {
        let mut names = HashMap::default();
        names.insert("t", Binding::Time);
        names.insert("pi", Binding::Pi);
        for (i, p) in spec.params.iter().enumerate() {
            names.insert(p.name.as_str(), Binding::Param(i));
        }
        for (i, s) in spec.states.iter().enumerate() {
            names.insert(s.name.as_str(), Binding::State(i));
        }
        for (i, l) in spec.lets.iter().enumerate() {
            names.insert(l.name.as_str(), Binding::Let(i));
        }
        for (i, o) in spec.outputs.iter().enumerate() {
            names.insert(o.name.as_str(), Binding::Output(i));
        }
        Lowerer {
            spec,
            fixed,
            names,
            lets: vec![LetState::Pending; spec.lets.len()],
            outputs: vec![None; spec.outputs.len()],
            pool: Pool::new(),
            diags: Vec::new(),
        }
    }

    /// Lowers equation `k` to its residual `lhs - rhs`.
    pub fn equation(&mut self, k: usize) -> Option<ExprId> {
        let eq = &self.spec.equations[k];
        let lhs = self.lower(&eq.lhs, Context::Equation);
        let rhs = self.lower(&eq.rhs, Context::Equation);
        let (lhs, rhs) = (lhs?, rhs?);
        let mut nonlinear = lhs.nonlinear;
        nonlinear.extend(rhs.nonlinear);
        if !nonlinear.is_empty() {
            for d in nonlinear {
                if !self.diags.contains(&d) {
                    self.diags.push(d);
                }
            }
            return None;
        }
        Some(self.pool.sub(lhs.expr, rhs.expr))
    }

    /// Lowers output `k` (outputs must be lowered in order).
    pub fn output(&mut self, k: usize) -> Option<ExprId> {
        let spec = self.spec;
        let e = self
            .lower(&spec.outputs[k].value, Context::Output(k))
            .map(|l| l.expr);
        self.outputs[k] = e;
        e
    }

    fn diag(&mut self, id: NodeId, message: String) {
        self.diags.push(Diagnostic { id, message });
    }

    fn lower_let(&mut self, k: usize, use_site: NodeId) -> Option<Lowered> {
        match &self.lets[k] {
            LetState::Done(l) => return Some(l.clone()),
            LetState::Failed => return None,
            LetState::Active => {
                let name = self.spec.lets[k].name.clone();
                self.diag(use_site, format!("let `{name}` depends on itself"));
                self.lets[k] = LetState::Failed;
                return None;
            }
            LetState::Pending => {}
        }
        self.lets[k] = LetState::Active;
        let spec = self.spec;
        let result = self.lower(&spec.lets[k].value, Context::Let);
        if matches!(self.lets[k], LetState::Failed) {
            return None;
        }
        self.lets[k] = match &result {
            Some(l) => LetState::Done(l.clone()),
            None => LetState::Failed,
        };
        result
    }

    fn lower(&mut self, ast: &Ast, ctx: Context) -> Option<Lowered> {
        let mut children: Vec<Lowered> = Vec::new();
        let mut failed = false;
        for a in ast.children() {
            match self.lower(a, ctx) {
                Some(l) => children.push(l),
                None => failed = true,
            }
        }
        if failed {
            return None;
        }
        let mut nonlinear: Vec<Diagnostic> =
            children.iter().flat_map(|c| c.nonlinear.clone()).collect();
        let e: Vec<ExprId> = children.iter().map(|c| c.expr).collect();
        let id = ast.id();
        let has_der = |pool: &Pool, k: usize| pool.has_der(e[k]);
        let expr = match ast {
            Ast::Num(_, v) => {
                if !v.is_finite() {
                    self.diag(id, format!("the number {v} is not finite"));
                    return None;
                }
                self.pool.num(*v)
            }
            Ast::Name(_, name) => return self.name(id, name, ctx),
            Ast::Neg(..) => self.pool.neg(e[0]),
            Ast::Bin(_, op, ..) => {
                let pool = &mut self.pool;
                match op {
                    BinOp::Add => pool.add2(e[0], e[1]),
                    BinOp::Sub => pool.sub(e[0], e[1]),
                    BinOp::Mul => {
                        if has_der(pool, 0) && has_der(pool, 1) {
                            nonlinear.push(nonlinear_at(id, "a product of two derivatives"));
                        }
                        pool.mul2(e[0], e[1])
                    }
                    BinOp::Div => {
                        if pool.as_const(e[1]) == Some(0.0) {
                            self.diag(id, "division by zero".into());
                            return None;
                        }
                        if has_der(pool, 1) {
                            nonlinear.push(nonlinear_at(id, "a division by a derivative"));
                        }
                        pool.div(e[0], e[1])
                    }
                    BinOp::Pow => {
                        if has_der(pool, 1)
                            || (has_der(pool, 0) && pool.as_const(e[1]) != Some(1.0))
                        {
                            nonlinear.push(nonlinear_at(id, "a power of a derivative"));
                        }
                        pool.pow(e[0], e[1])
                    }
                }
            }
            Ast::Call(_, f, _) => {
                if e.len() != f.arity() {
                    self.diag(
                        id,
                        format!(
                            "`{}` takes {} argument(s), found {}",
                            f.name(),
                            f.arity(),
                            e.len()
                        ),
                    );
                    return None;
                }
                if (0..e.len()).any(|k| has_der(&self.pool, k)) {
                    let what = format!("`{}` of a derivative", f.name());
                    nonlinear.push(nonlinear_at(id, &what));
                }
                match f {
                    Func::Atan2 | Func::Hypot => self.pool.call2(*f, e[0], e[1]),
                    Func::Min | Func::Max => self.pool.min_max(*f, e[0], e[1]),
                    _ => self.pool.call(*f, e[0]),
                }
            }
            Ast::If(_, c, ..) => {
                // A derivative in a branch is linear piecewise; in the comparison it decides
                // which equation holds, which no linear solve can express.
                if has_der(&self.pool, 0) || has_der(&self.pool, 1) {
                    nonlinear.push(nonlinear_at(c.id, "a condition on a derivative"));
                }
                self.pool.compare(e[0], c.op, e[1], e[2], e[3])
            }
            Ast::Der(..) => match time_derivative(&mut self.pool, e[0]) {
                Some(d) => d,
                None => {
                    self.diag(
                        id,
                        "`der` of an expression that already contains `der` (only first \
                         derivatives are supported)"
                            .into(),
                    );
                    return None;
                }
            },
        };
        // Every child is finite (a child that is not was reported and returned `None`), so
        // a non-finite constant here was made by this node's folding: `1e308*10`, `2^1e16`,
        // or the coefficient `inf` of `x*1e308*10`.
        let infinite = |pool: &Pool, x: ExprId| pool.as_const(x).is_some_and(|v| !v.is_finite());
        let unfolded = |pool: &Pool, x: ExprId| !pool.has_sym(x) && pool.as_const(x).is_none();
        let fresh = !e.iter().any(|&c| unfolded(&self.pool, c));
        if fresh && (unfolded(&self.pool, expr) || infinite(&self.pool, expr)) {
            self.diag(id, "this constant expression is not finite".into());
            return None;
        }
        let operands = self.pool.node(expr).children();
        if operands.iter().any(|&c| infinite(&self.pool, c)) {
            self.diag(
                id,
                "a constant factor or term of this expression is not finite (it overflows \
                 an f64)"
                    .into(),
            );
            return None;
        }
        if ctx == Context::Equation || ctx == Context::Let {
            Some(Lowered { expr, nonlinear })
        } else {
            Some(Lowered {
                expr,
                nonlinear: Vec::new(),
            })
        }
    }

    fn name(&mut self, id: NodeId, name: &str, ctx: Context) -> Option<Lowered> {
        let plain = |expr| {
            Some(Lowered {
                expr,
                nonlinear: Vec::new(),
            })
        };
        let Some(&binding) = self.names.get(name) else {
            self.diag(id, format!("unknown name `{name}`"));
            return None;
        };
        match binding {
            Binding::State(i) => plain(self.pool.sym(Sym::State(i))),
            Binding::Param(i) => match self.fixed.get(i).copied().flatten() {
                Some(v) => plain(self.pool.num(v)),
                None => plain(self.pool.sym(Sym::Param(i))),
            },
            Binding::Time => plain(self.pool.sym(Sym::Time)),
            Binding::Pi => plain(self.pool.num(std::f64::consts::PI)),
            Binding::Let(k) => {
                let l = self.lower_let(k, id)?;
                match ctx {
                    Context::Output(_) => plain(l.expr),
                    _ => Some(l),
                }
            }
            Binding::Output(k) => match ctx {
                Context::Output(current) if k < current => plain(self.outputs[k]?),
                Context::Output(_) => {
                    self.diag(id, format!("output `{name}` is used before it is defined"));
                    None
                }
                _ => {
                    self.diag(
                        id,
                        format!("output `{name}` can only be used in later outputs"),
                    );
                    None
                }
            },
        }
    }
}

fn nonlinear_at(id: NodeId, what: &str) -> Diagnostic {
    Diagnostic {
        id,
        message: format!("the equation must be linear in the derivatives, but this is {what}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::{BinOp, EquationSpec, ModelSpec, Named};

    // Specs built by hand: the front end that reads DSL text depends on this crate, so the
    // stage's own unit tests spell their small models as trees.
    fn name(n: &str) -> Ast {
        Ast::Name(NodeId(0), n.into())
    }
    fn bin(op: BinOp, a: Ast, b: Ast) -> Ast {
        Ast::Bin(NodeId(0), op, Box::new(a), Box::new(b))
    }
    fn named<T>(n: &str, value: T) -> Named<T> {
        Named {
            name: n.into(),
            id: NodeId(0),
            value,
        }
    }
    fn der(a: Ast) -> Ast {
        Ast::Der(NodeId(0), Box::new(a))
    }
    /// A model with these parameters (no defaults), states, lets and equations.
    fn model(
        params: &[&str],
        states: &[&str],
        lets: Vec<Named<Ast>>,
        equations: Vec<(Ast, Ast)>,
    ) -> ModelSpec {
        ModelSpec {
            name: "test_model".into(),
            params: params.iter().map(|p| named(p, None)).collect(),
            states: states.iter().map(|s| named(s, ())).collect(),
            lets,
            equations: (equations.into_iter().enumerate())
                .map(|(k, (lhs, rhs))| EquationSpec {
                    label: format!("e{k}"),
                    id: NodeId(0),
                    lhs,
                    rhs,
                })
                .collect(),
            outputs: vec![],
            variants: vec![],
        }
    }

    #[test]
    fn lets_are_substituted_once_and_shared() {
        // let a = sin(x)*k; let b = a + a; der(x) = b*a
        let sin_x = Ast::Call(NodeId(0), Func::Sin, vec![name("x")]);
        let lets = vec![
            named("a", bin(BinOp::Mul, sin_x, name("k"))),
            named("b", bin(BinOp::Add, name("a"), name("a"))),
        ];
        let equation = (der(name("x")), bin(BinOp::Mul, name("b"), name("a")));
        let spec = model(&["k"], &["x"], lets, vec![equation]);
        let mut l = Lowerer::new(&spec, vec![None]);
        let r = l.equation(0).unwrap();
        let p = &mut l.pool;
        let (x, k) = (p.sym(Sym::State(0)), p.sym(Sym::Param(0)));
        let s = p.call(Func::Sin, x);
        let a = p.mul2(s, k);
        let two = p.num(2.0);
        let b = p.mul2(two, a);
        let ba = p.mul2(b, a);
        let d = p.sym(Sym::Der(0));
        let expected = p.sub(d, ba);
        assert_eq!(r, expected);
        assert!(l.diags.is_empty());
    }

    #[test]
    fn fixed_parameters_pi_and_time_become_what_they_are() {
        // der(x) = k*x + c*t + pi
        let kx = bin(BinOp::Mul, name("k"), name("x"));
        let ct = bin(BinOp::Mul, name("c"), name("t"));
        let rhs = bin(BinOp::Add, bin(BinOp::Add, kx, ct), name("pi"));
        let spec = model(&["k", "c"], &["x"], vec![], vec![(der(name("x")), rhs)]);
        let mut l = Lowerer::new(&spec, vec![Some(0.0), None]);
        let r = l.equation(0).unwrap();
        let p = &mut l.pool;
        let (c, t, d) = (p.sym(Sym::Param(1)), p.sym(Sym::Time), p.sym(Sym::Der(0)));
        let ct = p.mul2(c, t);
        let pi = p.num(std::f64::consts::PI);
        let rhs = p.add2(ct, pi);
        // k = 0 removed the k*x term before any algebra.
        assert_eq!(r, p.sub(d, rhs));
    }

    #[test]
    fn der_applies_the_chain_rule() {
        // der(x*y) = 0; der(y) = 1
        let zero = Ast::Num(NodeId(0), 0.0);
        let one = Ast::Num(NodeId(0), 1.0);
        let equations = vec![
            (der(bin(BinOp::Mul, name("x"), name("y"))), zero),
            (der(name("y")), one),
        ];
        let spec = model(&[], &["x", "y"], vec![], equations);
        let mut l = Lowerer::new(&spec, vec![]);
        let r = l.equation(0).unwrap();
        let p = &mut l.pool;
        let (x, y) = (p.sym(Sym::State(0)), p.sym(Sym::State(1)));
        let (dx, dy) = (p.sym(Sym::Der(0)), p.sym(Sym::Der(1)));
        let a = p.mul2(dx, y);
        let b = p.mul2(x, dy);
        assert_eq!(r, p.add2(a, b));
    }
}
