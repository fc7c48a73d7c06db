//! The only way to build expressions: constructors that keep every node simplified and canonical.
//!
//! Simplifying on construction means no later pass has to find `x*0` or `x - x`: a term that
//! cancels during the solve disappears the moment it is formed, so the elimination sees the true
//! sparsity and never divides by a pivot that is identically zero. The rules are local and cheap:
//! constant folding (only when the result is finite), `x+0`, `x*1`, `x*0`, `x^1`, `x^0`, `--x`,
//! like terms collected (`2x + 3x = 5x`), like factors collected (`x^2 * x^-1 = x`), integer
//! powers distributed over products, numeric factors distributed over sums inside sums, and
//! `c*M*sin(u)^2 + c*M*cos(u)^2 = c*M`, and a `hypot`'s exact symmetries (its arguments' signs
//! and order). Nothing is expanded, so nothing swells.

use crate::hash::HashMap;

use crate::expr::{call_value, integer_exponent, pow_value, ExprId, Node, Pool, Sym};
use crate::spec::Func;

impl Pool {
    /// A constant.
    pub fn num(&mut self, v: f64) -> ExprId {
        self.intern(Node::Const(v.to_bits()))
    }

    /// A symbol.
    pub fn sym(&mut self, s: Sym) -> ExprId {
        self.intern(Node::Sym(s))
    }

    /// `a + b`
    pub fn add2(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.add(&[a, b])
    }

    /// `a - b`
    pub fn sub(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let nb = self.neg(b);
        self.add(&[a, nb])
    }

    /// `-a`
    pub fn neg(&mut self, a: ExprId) -> ExprId {
        self.mul(&[ExprId::MINUS_ONE, a])
    }

    /// `a * b`
    pub fn mul2(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.mul(&[a, b])
    }

    /// `a / b`
    pub fn div(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let inv = self.pow(b, ExprId::MINUS_ONE);
        self.mul(&[a, inv])
    }

    /// `a ^ n` for a numeric exponent.
    pub fn powf(&mut self, a: ExprId, n: f64) -> ExprId {
        let e = self.num(n);
        self.pow(a, e)
    }

    /// Splits a term into its numeric coefficient and the rest (`3*x*y` into `3` and `x*y`).
    pub fn split_coefficient(&mut self, id: ExprId) -> (f64, ExprId) {
        match self.node(id) {
            Node::Const(bits) => (f64::from_bits(*bits), ExprId::ONE),
            Node::Mul(fs) => match self.node(fs[0]).as_const() {
                Some(c) => {
                    let rest: Vec<ExprId> = fs[1..].to_vec();
                    let rest = if rest.len() == 1 {
                        rest[0]
                    } else {
                        self.intern(Node::Mul(rest.into()))
                    };
                    (c, rest)
                }
                None => (1.0, id),
            },
            _ => (1.0, id),
        }
    }

    /// The sum of `terms`.
    pub fn add(&mut self, terms: &[ExprId]) -> ExprId {
        let mut constant = 0.0;
        let mut order: Vec<ExprId> = Vec::new();
        let mut coeffs: HashMap<ExprId, f64> = HashMap::default();
        let mut stack: Vec<(ExprId, f64)> = terms.iter().rev().map(|&t| (t, 1.0)).collect();
        while let Some((t, scale)) = stack.pop() {
            match self.node(t) {
                Node::Const(bits) => constant += scale * f64::from_bits(*bits),
                Node::Add(ts) => stack.extend(ts.iter().rev().map(|&x| (x, scale))),
                _ => {
                    let (c, rest) = self.split_coefficient(t);
                    if let Node::Add(ts) = self.node(rest) {
                        stack.extend(ts.iter().rev().map(|&x| (x, scale * c)));
                        continue;
                    }
                    let entry = coeffs.entry(rest).or_insert_with(|| {
                        order.push(rest);
                        0.0
                    });
                    *entry += scale * c;
                }
            }
        }
        constant += self.pythagoras(&mut order, &mut coeffs);
        let mut out: Vec<ExprId> = Vec::with_capacity(order.len() + 1);
        for rest in order {
            let c = coeffs[&rest];
            if c != 0.0 {
                let cid = self.num(c);
                out.push(self.mul(&[cid, rest]));
            }
        }
        if constant != 0.0 || out.is_empty() {
            out.push(self.num(constant));
        }
        if out.len() == 1 {
            return out[0];
        }
        out.sort_unstable();
        self.intern(Node::Add(out.into()))
    }

    /// Replaces `c*M*sin(u)^2 + c*M*cos(u)^2` by `c*M`, repeatedly; returns the constant the
    /// pairs without any other factor add up to.
    ///
    /// The terms are matched by `u`, `c` and a hash of `M` that is the hash of the term's
    /// factors less the squared one's (a sum of the factors' hashes), so a term costs its
    /// factors once, not once per squared sine or cosine among them; a match is then compared
    /// factor by factor.
    fn pythagoras(&mut self, order: &mut Vec<ExprId>, coeffs: &mut HashMap<ExprId, f64>) -> f64 {
        let mut constant = 0.0;
        loop {
            let mut seen: HashMap<SquareKey, Vec<Square>> = HashMap::default();
            let mut found = None;
            'outer: for &rest in order.iter() {
                let c = coeffs[&rest];
                if c == 0.0 {
                    continue;
                }
                let factors = self.factors_of(rest);
                let whole = factors
                    .iter()
                    .fold(0u64, |h, &f| h.wrapping_add(factor_hash(f)));
                for (k, &f) in factors.iter().enumerate() {
                    let Node::Pow([base, e]) = self.node(f) else {
                        continue;
                    };
                    if self.as_const(*e) != Some(2.0) {
                        continue;
                    }
                    let Node::Call(func @ (Func::Sin | Func::Cos), [u]) = self.node(*base) else {
                        continue;
                    };
                    let (func, u) = (*func, *u);
                    let key = (u, c.to_bits(), whole.wrapping_sub(factor_hash(f)));
                    let candidates = seen.entry(key).or_default();
                    for &(other_func, other_rest, other_k) in candidates.iter() {
                        let other = self.factors_of(other_rest);
                        if other_func != func && without(&other, other_k).eq(without(&factors, k)) {
                            let others: Vec<ExprId> = without(&factors, k).collect();
                            found = Some((rest, other_rest, others, c));
                            break 'outer;
                        }
                    }
                    candidates.push((func, rest, k));
                }
            }
            let Some((a, b, others, c)) = found else {
                return constant;
            };
            coeffs.insert(a, 0.0);
            coeffs.insert(b, 0.0);
            let merged = self.mul(&others);
            let (mc, mrest) = self.split_coefficient(merged);
            if mrest == ExprId::ONE {
                constant += c * mc;
            } else {
                let entry = coeffs.entry(mrest).or_insert_with(|| {
                    order.push(mrest);
                    0.0
                });
                *entry += c * mc;
            }
        }
    }

    /// The factors of a product, or the expression itself as the one factor.
    fn factors_of(&self, id: ExprId) -> Vec<ExprId> {
        match self.node(id) {
            Node::Mul(fs) => fs.to_vec(),
            _ => vec![id],
        }
    }

    /// The product of `factors`.
    pub fn mul(&mut self, factors: &[ExprId]) -> ExprId {
        let mut coefficient = 1.0;
        let mut bases: Vec<ExprId> = Vec::new();
        let mut exponents: HashMap<ExprId, Vec<ExprId>> = HashMap::default();
        let mut stack: Vec<ExprId> = factors.iter().rev().copied().collect();
        while let Some(f) = stack.pop() {
            let (base, exponent) = match self.node(f) {
                Node::Const(bits) => {
                    coefficient *= f64::from_bits(*bits);
                    continue;
                }
                Node::Mul(fs) => {
                    stack.extend(fs.iter().rev());
                    continue;
                }
                Node::Pow([b, e]) => (*b, *e),
                _ => (f, ExprId::ONE),
            };
            exponents
                .entry(base)
                .or_insert_with(|| {
                    bases.push(base);
                    Vec::new()
                })
                .push(exponent);
        }
        if coefficient == 0.0 {
            return ExprId::ZERO;
        }
        let mut out: Vec<ExprId> = Vec::with_capacity(bases.len());
        for base in bases {
            let es = &exponents[&base];
            let e = if es.len() == 1 {
                es[0]
            } else {
                self.add(&es.clone())
            };
            let p = self.pow(base, e);
            match self.node(p) {
                Node::Const(bits) => coefficient *= f64::from_bits(*bits),
                Node::Mul(fs) => {
                    // A power of a base that was itself a product (a constant base to a
                    // symbolic power never distributes, so this is rare): keep its factors.
                    for &g in fs.iter() {
                        match self.as_const(g) {
                            Some(c) => coefficient *= c,
                            None => out.push(g),
                        }
                    }
                }
                _ => out.push(p),
            }
        }
        if coefficient == 0.0 {
            return ExprId::ZERO;
        }
        out.sort_unstable();
        match (coefficient == 1.0, out.len()) {
            (_, 0) => self.num(coefficient),
            (true, 1) => out[0],
            (true, _) => self.intern(Node::Mul(out.into())),
            (false, _) => {
                let c = self.num(coefficient);
                out.insert(0, c);
                self.intern(Node::Mul(out.into()))
            }
        }
    }

    /// `base ^ exponent`.
    pub fn pow(&mut self, base: ExprId, exponent: ExprId) -> ExprId {
        let Some(e) = self.as_const(exponent) else {
            if self.as_const(base) == Some(1.0) {
                return ExprId::ONE;
            }
            return self.intern(Node::Pow([base, exponent]));
        };
        if e == 0.0 {
            return ExprId::ONE;
        }
        if e == 1.0 {
            return base;
        }
        if let Some(b) = self.as_const(base) {
            let v = pow_value(b, e);
            if v.is_finite() {
                return self.num(v);
            }
            return self.intern(Node::Pow([base, exponent]));
        }
        if integer_exponent(e).is_some() {
            match self.node(base).clone() {
                Node::Pow([b, be]) => {
                    let ne = self.mul(&[be, exponent]);
                    return self.pow(b, ne);
                }
                Node::Mul(fs) => {
                    let powered: Vec<ExprId> = fs.iter().map(|&f| self.pow(f, exponent)).collect();
                    return self.mul(&powered);
                }
                _ => {}
            }
        }
        self.intern(Node::Pow([base, exponent]))
    }

    /// `f(arg)` for a one-argument function (`sqrt` becomes a power of one half).
    pub fn call(&mut self, f: Func, arg: ExprId) -> ExprId {
        if f == Func::Sign {
            return self.sign(arg);
        }
        if f == Func::Sqrt {
            let half = self.num(0.5);
            return self.pow(arg, half);
        }
        if let Some(a) = self.as_const(arg) {
            let v = call_value(f, a);
            if v.is_finite() {
                return self.num(v);
            }
        }
        if f == Func::Abs {
            if let Node::Call(Func::Abs, _) = self.node(arg) {
                return arg;
            }
        }
        self.intern(Node::Call(f, [arg]))
    }

    /// `f(a, b)` for a two-argument function of a [`Node::Call2`] (`atan2` or `hypot`; `min`
    /// and `max` are [`Pool::min_max`]).
    pub fn call2(&mut self, f: Func, a: ExprId, b: ExprId) -> ExprId {
        match f {
            Func::Hypot => self.hypot(a, b),
            _ => {
                debug_assert_eq!(f, Func::Atan2, "not a `Call2` function");
                self.atan2(a, b)
            }
        }
    }

    /// `atan2(y, x)`.
    pub fn atan2(&mut self, y: ExprId, x: ExprId) -> ExprId {
        if let (Some(a), Some(b)) = (self.as_const(y), self.as_const(x)) {
            return self.num(a.atan2(b));
        }
        self.intern(Node::Call2(Func::Atan2, [y, x]))
    }

    /// `hypot(x, y)`, rewritten only by identities that `f64::hypot` keeps to the bit (C's
    /// `hypot` is specified so), so the value is the call's: the arguments' signs do not
    /// matter (a negative coefficient or an `abs` is dropped), nor does their order (they are sorted, so `hypot(x, y)`
    /// and `hypot(y, x)` are one node), `hypot(x, 0)` is `abs(x)`, and constants fold where
    /// the result is finite. Nothing turns `sqrt(x^2 + y^2)` into a `hypot` or back: the two
    /// round differently.
    pub fn hypot(&mut self, x: ExprId, y: ExprId) -> ExprId {
        let (x, y) = (self.unsigned(x), self.unsigned(y));
        if let (Some(a), Some(b)) = (self.as_const(x), self.as_const(y)) {
            let v = a.hypot(b);
            if v.is_finite() {
                return self.num(v);
            }
        }
        if y == ExprId::ZERO {
            return self.call(Func::Abs, x);
        }
        if x == ExprId::ZERO {
            return self.call(Func::Abs, y);
        }
        let (x, y) = (x.min(y), x.max(y));
        self.intern(Node::Call2(Func::Hypot, [x, y]))
    }

    /// `x` without a sign that dropping changes only in sign: a negative constant or
    /// coefficient turned positive (`-2*u` is `2*u`, which rounds to the same magnitude), an
    /// `abs` removed. For the arguments of an even function such as `hypot`.
    fn unsigned(&mut self, x: ExprId) -> ExprId {
        match self.node(x) {
            Node::Const(bits) => self.num(f64::from_bits(*bits).abs()),
            Node::Call(Func::Abs, [u]) => *u,
            Node::Mul(_) => match self.split_coefficient(x) {
                (c, rest) if c < 0.0 => {
                    let c = self.num(-c);
                    self.mul2(c, rest)
                }
                _ => x,
            },
            _ => x,
        }
    }
}

/// `(u, coefficient bits, hash of the other factors)` of a term `c*M*sin(u)^2`.
type SquareKey = (ExprId, u64, u64);

/// A term seen with a squared sine or cosine: the function, the term (less its coefficient),
/// and the position of the squared factor among its factors.
type Square = (Func, ExprId, usize);

/// A factor's share of the hash of a product: the product's hash is the (wrapping) sum of its
/// factors' shares, so a product less one factor hashes without being built.
fn factor_hash(f: ExprId) -> u64 {
    // SplitMix64's finaliser: neighbouring ids get unrelated shares.
    let mut z = u64::from(f.0).wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// `factors` without the one at position `k`.
fn without(factors: &[ExprId], k: usize) -> impl Iterator<Item = ExprId> + '_ {
    factors
        .iter()
        .enumerate()
        .filter(move |&(i, _)| i != k)
        .map(|(_, &f)| f)
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Syms {
        x: ExprId,
        y: ExprId,
        z: ExprId,
    }

    fn setup() -> (Pool, Syms) {
        let mut p = Pool::new();
        let x = p.sym(Sym::State(0));
        let y = p.sym(Sym::State(1));
        let z = p.sym(Sym::Param(0));
        (p, Syms { x, y, z })
    }

    /// Each row: a name, an expression built with the constructors, an expected one.
    macro_rules! same {
        ($($name:ident: |$p:ident, $s:ident| $lhs:expr => $rhs:expr;)*) => {$(
            #[test]
            fn $name() {
                let (mut $p, $s) = setup();
                let _ = &$s;
                let lhs = $lhs;
                let rhs = $rhs;
                assert_eq!(lhs, rhs, "{:?} vs {:?}", $p.node(lhs), $p.node(rhs));
            }
        )*};
    }

    same! {
        add_zero: |p, s| p.add2(s.x, ExprId::ZERO) => s.x;
        mul_one: |p, s| p.mul2(s.x, ExprId::ONE) => s.x;
        mul_zero: |p, s| p.mul2(s.x, ExprId::ZERO) => ExprId::ZERO;
        pow_one: |p, s| p.pow(s.x, ExprId::ONE) => s.x;
        pow_zero: |p, s| p.pow(s.x, ExprId::ZERO) => ExprId::ONE;
        double_negation: |p, s| { let n = p.neg(s.x); p.neg(n) } => s.x;
        self_subtraction: |p, s| { let e = p.mul2(s.x, s.y); p.sub(e, e) } => ExprId::ZERO;
        commutative_sum: |p, s| p.add2(s.x, s.y) => p.add2(s.y, s.x);
        commutative_product: |p, s| p.mul(&[s.x, s.y, s.z]) => p.mul(&[s.z, s.x, s.y]);
        like_terms: |p, s| { let (two, three) = (p.num(2.0), p.num(3.0)); let a = p.mul2(two, s.x); let b = p.mul2(three, s.x); p.add2(a, b) }
            => { let c = p.num(5.0); p.mul2(c, s.x) };
        like_factors: |p, s| { let a = p.powf(s.x, 2.0); p.div(a, s.x) } => s.x;
        quotient_of_equal: |p, s| { let e = p.add2(s.x, s.y); p.div(e, e) } => ExprId::ONE;
        constant_folding: |p, _s| { let a = p.num(2.0); let b = p.num(3.0); let c = p.mul2(a, b); p.add2(c, ExprId::ONE) } => p.num(7.0);
        sqrt_squared: |p, s| { let r = p.call(Func::Sqrt, s.x); p.powf(r, 2.0) } => s.x;
        power_of_product: |p, s| { let m = p.mul2(s.x, s.y); p.powf(m, 2.0) }
            => { let a = p.powf(s.x, 2.0); let b = p.powf(s.y, 2.0); p.mul2(a, b) };
        numeric_factor_distributes_in_sum: |p, s| {
            let sum = p.add2(s.x, s.y);
            let two = p.num(2.0);
            let twice = p.mul2(two, sum);
            let m2 = p.num(-2.0);
            let m2x = p.mul2(m2, s.x);
            p.add2(twice, m2x)
        } => { let two = p.num(2.0); p.mul2(two, s.y) };
        pythagoras: |p, s| {
            let sn = p.call(Func::Sin, s.x); let cs = p.call(Func::Cos, s.x);
            let a = p.powf(sn, 2.0); let b = p.powf(cs, 2.0);
            let a = p.mul(&[s.z, a]); let b = p.mul(&[s.z, b]);
            p.add2(a, b)
        } => s.z;
        pythagoras_nested: |p, s| {
            // z*(sin(y)^2 cos(x)^2 + sin(y)^2 sin(x)^2 + cos(y)^2) = z
            let sx = p.call(Func::Sin, s.x); let cx = p.call(Func::Cos, s.x);
            let sy = p.call(Func::Sin, s.y); let cy = p.call(Func::Cos, s.y);
            let (sx2, cx2, sy2, cy2) = (p.powf(sx, 2.0), p.powf(cx, 2.0), p.powf(sy, 2.0), p.powf(cy, 2.0));
            let t1 = p.mul(&[s.z, sy2, cx2]); let t2 = p.mul(&[s.z, sy2, sx2]); let t3 = p.mul(&[s.z, cy2]);
            p.add(&[t1, t2, t3])
        } => s.z;
        pythagoras_constant: |p, s| {
            let sn = p.call(Func::Sin, s.x); let cs = p.call(Func::Cos, s.x);
            let a = p.powf(sn, 2.0); let b = p.powf(cs, 2.0);
            p.add(&[a, b, s.y])
        } => p.add2(s.y, ExprId::ONE);
        abs_idempotent: |p, s| { let a = p.call(Func::Abs, s.x); p.call(Func::Abs, a) } => p.call(Func::Abs, s.x);
        sin_of_constant: |p, _s| { let z = ExprId::ZERO; p.call(Func::Sin, z) } => ExprId::ZERO;
        hypot_of_zero_is_abs: |p, s| p.hypot(s.x, ExprId::ZERO) => p.call(Func::Abs, s.x);
        hypot_of_zero_first_is_abs: |p, s| { let m = p.neg(s.x); p.hypot(ExprId::ZERO, m) } => p.call(Func::Abs, s.x);
        hypot_is_symmetric: |p, s| p.hypot(s.x, s.y) => p.hypot(s.y, s.x);
        hypot_drops_signs: |p, s| {
            let m2 = p.num(-2.0);
            let a = p.mul(&[m2, s.x, s.z]);
            let b = p.call(Func::Abs, s.y);
            p.hypot(a, b)
        } => { let two = p.num(2.0); let a = p.mul(&[two, s.x, s.z]); p.hypot(s.y, a) };
        hypot_drops_a_negated_sum_sign: |p, s| { let d = p.sub(s.x, s.y); let m = p.neg(d); p.hypot(m, s.z) }
            => { let d = p.sub(s.x, s.y); p.hypot(d, s.z) };
        hypot_of_constants_folds: |p, _s| { let (a, b) = (p.num(-3.0), p.num(4.0)); p.hypot(a, b) } => p.num(5.0);
    }

    /// Arguments over the whole range: zeros, subnormals, the extremes, and random magnitudes
    /// and signs (a fixed xorshift sequence, so the points are the same every run).
    fn hypot_arguments() -> Vec<f64> {
        let mut values = vec![
            0.0, 1.0, 3.0, 4.0, 1e300, 1e-300, 5e-324, 1e-310, 1.7e308, 1e154, 1e-162, 0.1,
        ];
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..40 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let mantissa = 1.0 + (state >> 12) as f64 / (1u64 << 52) as f64;
            values.push(mantissa * 10f64.powi((state % 601) as i32 - 300));
        }
        let negated: Vec<f64> = values.iter().map(|v| -v).collect();
        values.extend(negated);
        values
    }

    /// The identities the constructor applies hold for `f64::hypot` to the bit, so the
    /// simplified expression evaluates (as emitted code does) to the call's bits.
    #[test]
    fn hypot_rewrites_keep_the_bits_of_f64_hypot() {
        let values = hypot_arguments();
        for &a in &values {
            assert_eq!(a.hypot(0.0).to_bits(), a.abs().to_bits(), "hypot({a:e}, 0)");
            for &b in &values {
                let want = a.hypot(b);
                assert_eq!(b.hypot(a).to_bits(), want.to_bits(), "({a:e}, {b:e})");
                assert_eq!((-a).hypot(b).to_bits(), want.to_bits(), "({a:e}, {b:e})");
            }
        }
        // Through the pool: `hypot(-3*x, abs(y))`, `hypot(y, x)` and `hypot(x, 0)` as built
        // and evaluated, against the call on the arguments as written.
        let (mut p, s) = setup();
        let m3 = p.num(-3.0);
        let a = p.mul2(m3, s.x);
        let b = p.call(Func::Abs, s.y);
        let first = p.hypot(a, b);
        let second = p.hypot(s.y, s.x);
        let zero = p.hypot(s.x, ExprId::ZERO);
        for &x in &values {
            for &y in &values[..30] {
                let at = |sym: Sym| if sym == Sym::State(0) { x } else { y };
                let bits = |e: ExprId| p.eval(e, &at).to_bits();
                assert_eq!(
                    bits(first),
                    (-3.0 * x).hypot(y.abs()).to_bits(),
                    "{x:e}, {y:e}"
                );
                assert_eq!(bits(second), y.hypot(x).to_bits(), "{x:e}, {y:e}");
                assert_eq!(bits(zero), x.hypot(0.0).to_bits(), "{x:e}");
            }
        }
    }

    #[test]
    fn hypot_overflowing_constants_are_not_folded() {
        let (mut p, _) = setup();
        let big = p.num(1.7e308);
        let h = p.hypot(big, big);
        assert!(p.as_const(h).is_none());
        assert!(p.eval(h, &|_| 0.0).is_infinite());
    }

    #[test]
    fn non_finite_constants_are_not_folded() {
        let (mut p, _) = setup();
        let inv = p.div(ExprId::ONE, ExprId::ZERO);
        assert!(p.as_const(inv).is_none());
        assert!(!p.has_sym(inv));
        let ln0 = p.call(Func::Ln, ExprId::ZERO);
        assert!(p.as_const(ln0).is_none());
    }

    #[test]
    fn product_keeps_constant_first() {
        let (mut p, s) = setup();
        let three = p.num(3.0);
        let e = p.mul(&[s.y, three, s.x]);
        let Node::Mul(fs) = p.node(e) else {
            panic!("not a product")
        };
        assert_eq!(p.as_const(fs[0]), Some(3.0));
        assert_eq!(p.split_coefficient(e).0, 3.0);
    }
}
