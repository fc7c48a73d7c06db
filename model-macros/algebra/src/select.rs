//! The constructors of the non-smooth functions: `sign`, and the one comparison that carries
//! `if`, `min` and `max`.
//!
//! Every condition becomes a [`Node::Select`] `lhs > rhs ? then : otherwise`: `<` swaps the
//! operands, `<=` the branches, `>=` both. That is exact because a select whose comparison has
//! no answer (an operand is NaN) is NaN, whichever way it is written
//! ([`crate::expr::select_value`]). `max(a, b)` is `a > b ? a : b` and `min(a, b)` is
//! `b > a ? a : b`, so they propagate a NaN too (unlike `f64::max`, which would hide it from the
//! finiteness checks), and their derivative is that of the selected argument with no extra
//! rule. Like the other constructors these fold what is known: a comparison of two constants
//! picks its branch, equal branches need no comparison, an expression is not greater than
//! itself, an inner select on the same comparison is decided by the outer one, and `max(b, a)`
//! is the same node as `max(a, b)`.

use crate::expr::{call_value, ExprId, Node, Pool};
use crate::spec::{CmpOp, Func};

impl Pool {
    /// `sign(x)`: `-1`, `0` or `1`.
    pub fn sign(&mut self, x: ExprId) -> ExprId {
        if let Some(v) = self.as_const(x) {
            return self.num(call_value(Func::Sign, v));
        }
        if let Node::Call(Func::Sign, _) = self.node(x) {
            return x;
        }
        // sign(c*x) = sign(c)*sign(x): `sign(-v)` shares `sign(v)`.
        let (c, rest) = self.split_coefficient(x);
        if c != 1.0 && c.is_finite() {
            let s = self.sign(rest);
            let sc = self.num(c.signum());
            return self.mul2(sc, s);
        }
        self.intern(Node::Call(Func::Sign, [x]))
    }

    /// `then` where `lhs > rhs`, `otherwise` where `lhs <= rhs` (NaN when neither holds).
    pub fn select(&mut self, lhs: ExprId, rhs: ExprId, then: ExprId, otherwise: ExprId) -> ExprId {
        if then == otherwise {
            return then;
        }
        if lhs == rhs {
            return otherwise;
        }
        if let (Some(l), Some(r)) = (self.as_const(lhs), self.as_const(rhs)) {
            return if l > r { then } else { otherwise };
        }
        // The same comparison inside a branch is already decided there.
        let then = self.branch(lhs, rhs, then, 2);
        let otherwise = self.branch(lhs, rhs, otherwise, 3);
        if then == otherwise {
            return then;
        }
        // `a > b ? a : b` and `b > a ? b : a` are both `max(a, b)`; likewise for `min`: one
        // operand order for both.
        let is_min_max = (then, otherwise) == (lhs, rhs) || (then, otherwise) == (rhs, lhs);
        if is_min_max && rhs < lhs {
            return self.intern(Node::Select([rhs, lhs, otherwise, then]));
        }
        self.intern(Node::Select([lhs, rhs, then, otherwise]))
    }

    /// A branch of `lhs > rhs ? .. : ..`: if it is itself a select on the same comparison, its
    /// own branch `k` (2 for `then`, 3 for `otherwise`).
    fn branch(&self, lhs: ExprId, rhs: ExprId, e: ExprId, k: usize) -> ExprId {
        match self.node(e) {
            Node::Select(s) if s[0] == lhs && s[1] == rhs => s[k],
            _ => e,
        }
    }

    /// `then` where `lhs op rhs` holds, else `otherwise`.
    pub fn compare(
        &mut self,
        lhs: ExprId,
        op: CmpOp,
        rhs: ExprId,
        then: ExprId,
        otherwise: ExprId,
    ) -> ExprId {
        match op {
            CmpOp::Gt => self.select(lhs, rhs, then, otherwise),
            CmpOp::Lt => self.select(rhs, lhs, then, otherwise),
            CmpOp::Ge => self.select(rhs, lhs, otherwise, then),
            CmpOp::Le => self.select(lhs, rhs, otherwise, then),
        }
    }

    /// `min(a, b)` or `max(a, b)` (any other `f` is a bug of the caller: `a`).
    pub fn min_max(&mut self, f: Func, a: ExprId, b: ExprId) -> ExprId {
        match f {
            Func::Max => self.select(a, b, a, b),
            Func::Min => self.select(b, a, a, b),
            _ => a,
        }
    }

    /// Whether `id` is `min(a, b)` or `max(a, b)`, with `a` and `b`.
    pub fn as_min_max(&self, id: ExprId) -> Option<(Func, ExprId, ExprId)> {
        let Node::Select([l, r, then, otherwise]) = *self.node(id) else {
            return None;
        };
        if (then, otherwise) == (l, r) {
            Some((Func::Max, l, r))
        } else if (then, otherwise) == (r, l) {
            Some((Func::Min, l, r))
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::diff::partial;
    use crate::expr::{select_value, ExprId, Node, Pool, Sym};
    use crate::spec::{CmpOp, Func};

    fn setup() -> (Pool, ExprId, ExprId) {
        let mut p = Pool::new();
        let x = p.sym(Sym::State(0));
        let y = p.sym(Sym::State(1));
        (p, x, y)
    }

    /// Evaluates `e` at `x`, `y`.
    fn at(p: &Pool, e: ExprId, x: f64, y: f64) -> f64 {
        p.eval(e, &|s| if s == Sym::State(0) { x } else { y })
    }

    #[test]
    fn sign_folds_constants_and_repeats() {
        let (mut p, x, _) = setup();
        for (c, s) in [(2.5, 1.0), (-0.5, -1.0), (0.0, 0.0)] {
            let n = p.num(c);
            assert_eq!(p.call(Func::Sign, n), p.num(s), "sign({c})");
        }
        let s = p.call(Func::Sign, x);
        assert_eq!(p.call(Func::Sign, s), s);
        let minus_three = p.num(-3.0);
        let minus_three_x = p.mul2(minus_three, x);
        assert_eq!(p.call(Func::Sign, minus_three_x), p.neg(s));
        assert_eq!(
            select_value(f64::NAN, 0.0, 1.0, 2.0).to_bits(),
            f64::NAN.to_bits()
        );
        assert!(crate::expr::sign_value(f64::NAN).is_nan());
    }

    #[test]
    fn comparisons_of_constants_and_equal_branches_fold() {
        let (mut p, x, y) = setup();
        let (one, two) = (p.num(1.0), p.num(2.0));
        assert_eq!(p.compare(two, CmpOp::Gt, one, x, y), x);
        assert_eq!(p.compare(two, CmpOp::Lt, one, x, y), y);
        assert_eq!(p.compare(one, CmpOp::Ge, one, x, y), x);
        assert_eq!(p.compare(one, CmpOp::Le, two, x, y), x);
        assert_eq!(p.compare(one, CmpOp::Gt, one, x, y), y);
        assert_eq!(p.compare(x, CmpOp::Gt, y, two, two), two);
        assert_eq!(p.min_max(Func::Max, one, two), two);
        assert_eq!(p.min_max(Func::Min, one, two), one);
        assert_eq!(p.min_max(Func::Max, x, x), x);
    }

    #[test]
    fn every_comparison_is_one_select_with_the_values_written() {
        let (mut p, x, y) = setup();
        let (a, b) = (p.num(10.0), p.num(20.0));
        for op in [CmpOp::Lt, CmpOp::Le, CmpOp::Gt, CmpOp::Ge] {
            let e = p.compare(x, op, y, a, b);
            assert!(matches!(p.node(e), Node::Select(_)));
            for (xv, yv) in [(1.0, 2.0), (2.0, 1.0), (1.5, 1.5)] {
                let holds = match op {
                    CmpOp::Lt => xv < yv,
                    CmpOp::Le => xv <= yv,
                    CmpOp::Gt => xv > yv,
                    CmpOp::Ge => xv >= yv,
                };
                let expected = if holds { 10.0 } else { 20.0 };
                assert_eq!(
                    at(&p, e, xv, yv),
                    expected,
                    "x {} y at {xv}, {yv}",
                    op.symbol()
                );
            }
            assert!(at(&p, e, f64::NAN, 1.0).is_nan());
        }
        // `x >= y ? a : b` and `y > x ? b : a` are one node.
        assert_eq!(
            p.compare(x, CmpOp::Ge, y, a, b),
            p.compare(y, CmpOp::Gt, x, b, a)
        );
    }

    #[test]
    fn min_and_max_are_symmetric_and_propagate_nan() {
        let (mut p, x, y) = setup();
        for f in [Func::Min, Func::Max] {
            let e = p.min_max(f, x, y);
            assert_eq!(e, p.min_max(f, y, x));
            let (g, a, b) = p.as_min_max(e).expect("recognised");
            assert_eq!(g, f);
            assert_eq!((a.min(b), a.max(b)), (x.min(y), x.max(y)));
            for (xv, yv) in [(1.0f64, 2.0), (2.0, -1.0), (3.0, 3.0)] {
                let expected = if f == Func::Min {
                    xv.min(yv)
                } else {
                    xv.max(yv)
                };
                assert_eq!(at(&p, e, xv, yv), expected);
            }
            assert!(at(&p, e, f64::NAN, 1.0).is_nan());
            assert!(at(&p, e, 1.0, f64::NAN).is_nan());
        }
        let (a, b) = (p.num(1.0), p.num(2.0));
        let s = p.select(x, y, a, b);
        assert_eq!(p.as_min_max(s), None);
    }

    #[test]
    fn nested_selects_on_one_comparison_are_decided_by_the_outer() {
        let (mut p, x, y) = setup();
        let (a, b, c) = (p.num(1.0), p.num(2.0), p.num(3.0));
        let inner = p.select(x, y, a, b);
        assert_eq!(p.select(x, y, inner, c), p.select(x, y, a, c));
        assert_eq!(p.select(x, y, c, inner), p.select(x, y, c, b));
        assert_eq!(p.select(x, y, inner, b), inner);
    }

    #[test]
    fn derivatives_follow_the_selected_branch() {
        let (mut p, x, y) = setup();
        // d sign(x)/dx = 0; d|x|/dx = sign(x).
        let s = p.call(Func::Sign, x);
        assert_eq!(partial(&mut p, s, Sym::State(0)), ExprId::ZERO);
        let a = p.call(Func::Abs, x);
        assert_eq!(partial(&mut p, a, Sym::State(0)), s);
        // d max(x^2, y)/dx = 2x where x^2 > y, else 0.
        let x2 = p.powf(x, 2.0);
        let m = p.min_max(Func::Max, x2, y);
        let d = partial(&mut p, m, Sym::State(0));
        assert_eq!(at(&p, d, 3.0, 1.0), 6.0);
        assert_eq!(at(&p, d, 0.5, 1.0), 0.0);
        // d min(x*y, 1)/dy = x where x*y < 1, else 0.
        let xy = p.mul2(x, y);
        let m = p.min_max(Func::Min, xy, ExprId::ONE);
        let d = partial(&mut p, m, Sym::State(1));
        assert_eq!(at(&p, d, 0.5, 1.0), 0.5);
        assert_eq!(at(&p, d, 2.0, 1.0), 0.0);
        // d if(x > y, x*y, -x)/dy = x or 0.
        let nx = p.neg(x);
        let e = p.compare(x, CmpOp::Gt, y, xy, nx);
        let d = partial(&mut p, e, Sym::State(1));
        assert_eq!(at(&p, d, 2.0, 1.0), 2.0);
        assert_eq!(at(&p, d, 1.0, 2.0), 0.0);
        // Differences away from the kink agree with the partials.
        let m = p.min_max(Func::Max, x2, y);
        let dx = partial(&mut p, m, Sym::State(0));
        for (xv, yv) in [(1.3, 0.4), (0.2, 0.9), (-1.7, 0.5)] {
            let h = 1e-6;
            let fd = (at(&p, m, xv + h, yv) - at(&p, m, xv - h, yv)) / (2.0 * h);
            assert!((at(&p, dx, xv, yv) - fd).abs() < 1e-8, "at {xv}, {yv}");
        }
    }
}
