//! The run-time pivot checks: each pivot of a group before the group's first value, with the
//! sums inside it whose cancellation would leave it round-off (see
//! [`crate::CompileOptions::pivot_tolerance`]).

use crate::expr::{integer_exponent, ExprId, Node, Sym};
use crate::program::{Node as Op, Operand, Stmt, SumCheck};
use crate::spec::Func;
use crate::system::Body;

use super::{EmittedSum, Emitter, Unbound};

impl Emitter<'_> {
    /// Emits the pivot checks of group `g` (once).
    pub(super) fn check_pivots(&mut self, g: usize) -> Result<(), Unbound> {
        if self.group_started[g] {
            return Ok(());
        }
        self.group_started[g] = true;
        let system = self.system;
        for p in &system.groups[g].pivots {
            if self.pivots.contains(&p.text) {
                // The same pivot guards another group already checked.
                continue;
            }
            let value = self.operand(p.value)?;
            let sums = if self.pivot_tolerance > 0.0 {
                self.sum_checks(p.value)?
            } else {
                Vec::new()
            };
            self.stmts.push(Stmt::CheckPivot {
                value,
                text: p.text.clone(),
                sums,
                tolerance: self.pivot_tolerance,
            });
            self.pivots.push(p.text.clone());
        }
        Ok(())
    }

    /// Emits the pivot checks of the symbolic group defining `s`, even if `s` itself is never
    /// read (a program that reads only what its definition was inlined into, like a Jacobian
    /// column, must still refuse a singular point).
    pub fn check_pivots_of(&mut self, s: Sym) -> Result<(), Unbound> {
        match self.system.owner(s) {
            Some(g) if matches!(self.system.groups[g].body, Body::Symbolic(_)) => {
                self.check_pivots(g)
            }
            _ => Ok(()),
        }
    }

    /// The sums of pivot `e` whose cancellation makes it singular: `e` itself if it is a sum,
    /// else the sums it is a product or positive power of (a cancelling denominator makes a
    /// pivot large, not singular); a sine, cosine or tangent counts as a sum of magnitude
    /// `|argument|`, since at a root its argument has cancelled against a multiple of `π`. Each comes with `Σ |term|` over the operands the emitted
    /// sum adds; all of them are computed already, so the test costs one `abs` and one
    /// addition per term.
    fn sum_checks(&mut self, e: ExprId) -> Result<Vec<SumCheck>, Unbound> {
        Ok(match self.pool.node(e).clone() {
            Node::Add(terms) if self.same_sign(&terms) => Vec::new(),
            Node::Add(terms) => match self.emitted_sum(&terms)? {
                EmittedSum::Refactored(f) => self.sum_checks(f)?,
                EmittedSum::Added {
                    value,
                    parts,
                    terms,
                } => {
                    let magnitude = self.magnitude(&parts, &terms)?;
                    vec![SumCheck {
                        sum: value,
                        magnitude,
                    }]
                }
            },
            Node::Mul(factors) => {
                let mut checks = Vec::new();
                for &f in factors.iter() {
                    checks.extend(self.sum_checks(f)?);
                }
                checks
            }
            Node::Pow([base, k]) if self.pool.as_const(k).is_some_and(|k| k > 0.0) => {
                self.sum_checks(base)?
            }
            Node::Call(func @ (Func::Sin | Func::Cos | Func::Tan), [arg]) => {
                // Near a root `nπ` (or `π/2 + nπ`) a sine is `±sin(x - nπ)`: the argument has
                // cancelled against the root, and what is left is the argument's rounding
                // error, of order `eps * |x|`. So the sine is a sum whose magnitude is `|x|`,
                // tested like any other: `sin(x)` at `x = π` (1.2e-16) is refused.
                let value = self.operand(e)?;
                let argument = self.operand(arg)?;
                let magnitude = self.abs(argument);
                let mut checks = vec![SumCheck {
                    sum: value,
                    magnitude,
                }];
                if func != Func::Cos {
                    // Near zero a sine or tangent is its argument: a cancelled argument is a
                    // cancelled pivot.
                    checks.extend(self.sum_checks(arg)?);
                }
                checks
            }
            _ => Vec::new(),
        })
    }

    /// Whether the terms provably share one sign (constants and coefficients times even
    /// powers), so that their sum cannot cancel.
    fn same_sign(&mut self, terms: &[ExprId]) -> bool {
        let mut signs = terms.iter().map(|&t| {
            let (c, rest) = self.pool.split_coefficient(t);
            let factors = match self.pool.node(rest) {
                Node::Mul(fs) => fs.to_vec(),
                _ => vec![rest],
            };
            let even = |f: &ExprId| match self.pool.node(*f) {
                Node::Const(_) => true,
                Node::Pow([_, k]) => integer_exponent(self.pool.as_const(*k).unwrap_or(1.0))
                    .is_some_and(|n| n % 2 == 0),
                _ => false,
            };
            factors.iter().all(even).then_some(c > 0.0)
        });
        let Some(Some(first)) = signs.next() else {
            return false;
        };
        signs.all(|s| s == Some(first))
    }

    /// `Σ |part|`, where a term that holds a sum of its own (a common factor was pulled out
    /// of it, `m1 + m2*(1 - cos(d)^2)`) counts with that sum's magnitude, not its value: the
    /// terms as written before the factoring can cancel as much as the sum shown.
    fn magnitude(&mut self, parts: &[Operand], terms: &[ExprId]) -> Result<Operand, Unbound> {
        let mut acc: Option<Operand> = None;
        for (&p, &t) in parts.iter().zip(terms) {
            let a = if self.holds_sum(t) {
                self.bound(t)?
            } else {
                self.abs(p)
            };
            acc = Some(match acc {
                None => a,
                Some(s) => self.let_(Op::Add(s, a)),
            });
        }
        Ok(acc.unwrap_or(Operand::Const(0.0)))
    }

    /// Whether `e` is a sum whose terms can cancel, or a product or positive integer power of
    /// one.
    fn holds_sum(&mut self, e: ExprId) -> bool {
        match self.pool.node(e).clone() {
            Node::Add(terms) => !self.same_sign(&terms),
            Node::Mul(factors) => factors.iter().any(|&f| self.holds_sum(f)),
            Node::Pow([base, k]) => {
                let k = self.pool.as_const(k).and_then(integer_exponent);
                k.is_some_and(|k| k > 0) && self.holds_sum(base)
            }
            _ => false,
        }
    }

    /// The magnitude of `e` with every sum inside it replaced by `Σ |term|`: a bound on what
    /// its rounding error is relative to.
    fn bound(&mut self, e: ExprId) -> Result<Operand, Unbound> {
        if !self.holds_sum(e) {
            let v = self.operand(e)?;
            return Ok(self.abs(v));
        }
        Ok(match self.pool.node(e).clone() {
            Node::Add(terms) => {
                let mut acc = self.bound(terms[0])?;
                for &t in &terms[1..] {
                    let b = self.bound(t)?;
                    acc = self.let_(Op::Add(acc, b));
                }
                acc
            }
            Node::Mul(factors) => {
                let mut acc = self.bound(factors[0])?;
                for &f in &factors[1..] {
                    let b = self.bound(f)?;
                    acc = self.let_(Op::Mul(acc, b));
                }
                acc
            }
            Node::Pow([base, k]) => {
                let k = self
                    .pool
                    .as_const(k)
                    .and_then(integer_exponent)
                    .unwrap_or(1);
                let b = self.bound(base)?;
                self.let_(Op::Powi(b, k))
            }
            _ => {
                let v = self.operand(e)?;
                self.abs(v)
            }
        })
    }

    /// `|v|`.
    fn abs(&mut self, v: Operand) -> Operand {
        match v {
            Operand::Const(c) => Operand::Const(c.abs()),
            other => self.let_(Op::Call(Func::Abs, other)),
        }
    }
}
