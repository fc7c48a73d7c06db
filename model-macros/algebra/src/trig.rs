//! Trigonometric identities that take transcendental calls out of the solved system.
//!
//! A model written in the user's natural variables often takes the sine and cosine of an angle
//! it computes from Cartesian components with `atan2`, or of a difference of two angles. Both
//! are algebraic in what the program computes anyway, and a call (`atan2`, `sin_cos`) costs as
//! much as ten or twenty multiplications:
//!
//! - `sin(atan2(y, x)) = y / √(x² + y²)` and `cos(atan2(y, x)) = x / √(x² + y²)`. The square root
//!   is shared with any `sqrt(x^2 + y^2)` the model has, and products collect powers of one base,
//!   so a speed times the cosine of its own direction, `√r · x/√r`, is just `x`.
//! - `sin(a ± b)` and `cos(a ± b)` become products of the sines and cosines of `a` and `b`:
//!   two multiplications and an addition each instead of one `sin_cos` of the sum.
//!
//! An expansion pays only when it does not bring new calls: it is made when every part of the
//! sum is *free* (its sine or cosine is computed anyway by the program being emitted, or it is an
//! `atan2` and so algebraic), or when exactly one part is not free but another is an `atan2` (the
//! one new `sin_cos` replaces the one of the sum, and the `atan2` disappears). Otherwise the sum
//! keeps its call: expanding `sin(a + b)` into two new `sin_cos` to save one would double the
//! work. What "computed anyway" means depends on what is emitted (a reduced variant may drop
//! the equations that needed `sin(psi)`), so the pass runs per emitted model, on the solved
//! definitions, before the common subexpressions are shared.
//!
//! `atan2(0, 0)` is `0`, while `0/√0` is not a number: the radicand `x² + y²` becomes a pivot
//! of every group that divides by it, so the singular point is reported by name instead of
//! surfacing as a non-finite derivative.

use crate::hash::{HashMap, HashSet};

use crate::expr::{ExprId, Node, Pool};
use crate::spec::Func;
use crate::system::{Body, Group, Pivot, System};

/// The solved definitions and outputs with the identities applied.
pub struct Rewritten {
    /// The definitions, groups in the same order; a group that divides by a radicand the pass
    /// introduced has it as its first pivot.
    pub system: System,
    /// The outputs, in the same order.
    pub outputs: Vec<ExprId>,
}

/// Applies the identities to everything in `system` and `outputs`, judging which sines and
/// cosines are free by what `roots` (the values to be emitted) evaluate; `text` names a new
/// pivot in the user's terms.
pub fn rewrite(
    pool: &mut Pool,
    system: &System,
    outputs: &[ExprId],
    roots: &[ExprId],
    text: &dyn Fn(&Pool, ExprId) -> String,
) -> Rewritten {
    let reachable = system.reachable_nodes(pool, roots);
    let mut pass = Identities::new(pool, &reachable);
    let mut out = System::default();
    for group in &system.groups {
        let pivots: Vec<Pivot> = group
            .pivots
            .iter()
            .map(|p| Pivot {
                value: pass.apply(p.value),
                text: p.text.clone(),
            })
            .collect();
        let body = match &group.body {
            Body::Symbolic(defs) => {
                Body::Symbolic(defs.iter().map(|&(s, e)| (s, pass.apply(e))).collect())
            }
            Body::Numeric {
                matrix,
                rhs,
                results,
                text,
            } => Body::Numeric {
                matrix: matrix.iter().map(|&e| pass.apply(e)).collect(),
                rhs: rhs.iter().map(|&e| pass.apply(e)).collect(),
                results: results.clone(),
                text: text.clone(),
            },
        };
        out.push(Group { pivots, body });
    }
    let outputs = outputs.iter().map(|&e| pass.apply(e)).collect();
    let radicands = pass.radicands;
    for group in &mut out.groups {
        guard_radicands(pool, group, &radicands, text);
    }
    Rewritten {
        system: out,
        outputs,
    }
}

/// Puts each radicand that `group` divides by in front of its pivots.
fn guard_radicands(
    pool: &Pool,
    group: &mut Group,
    radicands: &[ExprId],
    text: &dyn Fn(&Pool, ExprId) -> String,
) {
    let nodes = pool.reachable(&group.expressions());
    let divides_by = |r: ExprId| {
        nodes.iter().any(|&n| match pool.node(n) {
            Node::Pow([b, k]) => *b == r && pool.as_const(*k).is_some_and(|k| k < 0.0),
            _ => false,
        })
    };
    for &r in radicands.iter().rev() {
        if divides_by(r) && !group.pivots.iter().any(|p| p.value == r) {
            group.pivots.insert(
                0,
                Pivot {
                    value: r,
                    text: text(pool, r),
                },
            );
        }
    }
}

/// The sine and cosine of an angle as `scale · sin` and `scale · cos` (the scale keeps the
/// common `1/√r` of an `atan2` outside the sums, where it can cancel against `√r`).
#[derive(Clone, Copy, Debug)]
struct Rotation {
    scale: ExprId,
    sin: ExprId,
    cos: ExprId,
}

/// How a part of a summed angle gets its sine and cosine.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Part {
    /// From an `atan2`, algebraically.
    Direction,
    /// A constant.
    Constant,
    /// A call the program makes anyway.
    Free,
    /// A new call.
    New,
}

/// The memoised rewrite.
struct Identities<'p> {
    pool: &'p mut Pool,
    /// Arguments whose sine or cosine the emitted program computes.
    free: HashSet<ExprId>,
    memo: HashMap<ExprId, ExprId>,
    /// `x² + y²` of every `atan2(y, x)` replaced, in order.
    radicands: Vec<ExprId>,
}

impl<'p> Identities<'p> {
    fn new(pool: &'p mut Pool, reachable: &HashSet<ExprId>) -> Identities<'p> {
        let free = reachable
            .iter()
            .filter_map(|&n| match pool.node(n) {
                Node::Call(Func::Sin | Func::Cos, [u]) => Some(*u),
                _ => None,
            })
            .collect();
        Identities {
            pool,
            free,
            memo: HashMap::default(),
            radicands: Vec::new(),
        }
    }

    /// `e` with the identities applied everywhere in it (children before parents).
    fn apply(&mut self, e: ExprId) -> ExprId {
        for n in self.pool.reachable(&[e]) {
            if self.memo.contains_key(&n) {
                continue;
            }
            let node = self.pool.node(n).clone();
            let kids: Vec<ExprId> = node.children().iter().map(|c| self.memo[c]).collect();
            let changed = kids.as_slice() != node.children();
            let new = match node {
                Node::Call(f @ (Func::Sin | Func::Cos), _) => match self.rotation(kids[0]) {
                    Some(r) => {
                        let v = if f == Func::Sin { r.sin } else { r.cos };
                        self.pool.mul2(r.scale, v)
                    }
                    None => self.pool.call(f, kids[0]),
                },
                _ if !changed => n,
                Node::Const(_) | Node::Sym(_) => n,
                Node::Add(_) => self.pool.add(&kids),
                Node::Mul(_) => self.pool.mul(&kids),
                Node::Pow(_) => self.pool.pow(kids[0], kids[1]),
                Node::Call(f, _) => self.pool.call(f, kids[0]),
                Node::Call2(f, _) => self.pool.call2(f, kids[0], kids[1]),
                Node::Select(_) => self.pool.select(kids[0], kids[1], kids[2], kids[3]),
            };
            self.memo.insert(n, new);
        }
        self.memo[&e]
    }

    /// The sine and cosine of `angle` without a call, if an identity gives them cheaply.
    fn rotation(&mut self, angle: ExprId) -> Option<Rotation> {
        match self.pool.node(angle).clone() {
            Node::Call2(Func::Atan2, [y, x]) => Some(self.direction(y, x)),
            Node::Add(terms) => self.sum_rotation(&terms),
            _ => None,
        }
    }

    /// `sin` and `cos` of `atan2(y, x)`: `(y, x) / √(x² + y²)`.
    fn direction(&mut self, y: ExprId, x: ExprId) -> Rotation {
        let (x2, y2) = (self.pool.powf(x, 2.0), self.pool.powf(y, 2.0));
        let r = self.pool.add2(x2, y2);
        if !self.radicands.contains(&r) {
            self.radicands.push(r);
        }
        Rotation {
            scale: self.pool.powf(r, -0.5),
            sin: y,
            cos: x,
        }
    }

    /// The angle-sum expansion of `Σ ±part`, when it pays (module docs).
    fn sum_rotation(&mut self, terms: &[ExprId]) -> Option<Rotation> {
        let mut parts = Vec::with_capacity(terms.len());
        for &t in terms {
            let (c, base) = self.pool.split_coefficient(t);
            let kind = if base == ExprId::ONE {
                Part::Constant
            } else if c.abs() != 1.0 {
                return None;
            } else if matches!(self.pool.node(base), Node::Call2(Func::Atan2, _)) {
                Part::Direction
            } else if self.free.contains(&base) {
                Part::Free
            } else {
                Part::New
            };
            parts.push((c, base, kind));
        }
        let new_calls = parts.iter().filter(|p| p.2 == Part::New).count();
        let direction = parts.iter().any(|p| p.2 == Part::Direction);
        if !(new_calls == 0 || (new_calls == 1 && direction)) {
            return None;
        }
        let mut acc: Option<Rotation> = None;
        for (c, base, kind) in parts {
            let part = match kind {
                Part::Constant => Rotation {
                    scale: ExprId::ONE,
                    sin: self.pool.num(c.sin()),
                    cos: self.pool.num(c.cos()),
                },
                _ => {
                    let mut r = match self.pool.node(base).clone() {
                        Node::Call2(Func::Atan2, [y, x]) => self.direction(y, x),
                        _ => Rotation {
                            scale: ExprId::ONE,
                            sin: self.pool.call(Func::Sin, base),
                            cos: self.pool.call(Func::Cos, base),
                        },
                    };
                    if c < 0.0 {
                        r.sin = self.pool.neg(r.sin);
                    }
                    r
                }
            };
            acc = Some(match acc {
                None => part,
                Some(a) => self.compose(a, part),
            });
        }
        acc
    }

    /// `sin(a + b) = sin a cos b + cos a sin b`, `cos(a + b) = cos a cos b - sin a sin b`.
    fn compose(&mut self, a: Rotation, b: Rotation) -> Rotation {
        let p = &mut *self.pool;
        let (sa_cb, ca_sb) = (p.mul2(a.sin, b.cos), p.mul2(a.cos, b.sin));
        let (ca_cb, sa_sb) = (p.mul2(a.cos, b.cos), p.mul2(a.sin, b.sin));
        Rotation {
            scale: p.mul2(a.scale, b.scale),
            sin: p.add2(sa_cb, ca_sb),
            cos: p.sub(ca_cb, sa_sb),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::Sym;

    /// Evaluates `e` before and after the rewrite at a few points (states 0..4).
    fn same_values(pool: &mut Pool, before: ExprId, after: ExprId) {
        for k in 0..7 {
            let v = |s: Sym| match s {
                Sym::State(i) => ((i * 7 + k * 3) as f64 * 0.37).sin() * 2.0 - 0.3,
                _ => 0.0,
            };
            let (a, b) = (pool.eval(before, &v), pool.eval(after, &v));
            assert!((a - b).abs() <= 1e-14 * (1.0 + a.abs()), "{a} vs {b}");
        }
    }

    fn rewrite_one(pool: &mut Pool, e: ExprId) -> (ExprId, Vec<ExprId>) {
        let reachable = pool.reachable(&[e]).into_iter().collect();
        let mut pass = Identities::new(pool, &reachable);
        let r = pass.apply(e);
        (r, pass.radicands)
    }

    fn calls(pool: &Pool, e: ExprId) -> usize {
        pool.reachable(&[e])
            .iter()
            .filter(|&&n| matches!(pool.node(n), Node::Call(..) | Node::Call2(..)))
            .count()
    }

    #[test]
    fn sine_and_cosine_of_a_direction_are_algebraic_and_share_the_hypotenuse() {
        let mut p = Pool::new();
        let (x, y) = (p.sym(Sym::State(0)), p.sym(Sym::State(1)));
        let (nx, ny) = (p.neg(x), p.neg(y));
        let alpha = p.atan2(ny, nx);
        let (x2, y2) = (p.powf(x, 2.0), p.powf(y, 2.0));
        let r = p.add2(x2, y2);
        let speed = p.powf(r, 0.5);
        let c = p.call(Func::Cos, alpha);
        let s = p.call(Func::Sin, alpha);
        // speed * cos(alpha) + 3 sin(alpha): the first term is -x, exactly.
        let a = p.mul2(speed, c);
        let three = p.num(3.0);
        let b = p.mul2(three, s);
        let e = p.add2(a, b);
        let (after, radicands) = rewrite_one(&mut p, e);
        same_values(&mut p, e, after);
        assert_eq!(calls(&p, after), 0);
        assert_eq!(radicands, vec![r]);
        let minus_x = p.neg(x);
        let three_y_over_speed = {
            let inv = p.powf(r, -0.5);
            let m3 = p.num(-3.0);
            p.mul(&[m3, y, inv])
        };
        assert_eq!(after, p.add2(minus_x, three_y_over_speed));
    }

    #[test]
    fn a_difference_of_angles_expands_only_when_it_saves_calls() {
        let mut p = Pool::new();
        let (x, y, psi, phi) = (
            p.sym(Sym::State(0)),
            p.sym(Sym::State(1)),
            p.sym(Sym::State(2)),
            p.sym(Sym::State(3)),
        );
        let alpha = p.atan2(y, x);
        let d = p.sub(alpha, psi);
        let s = p.call(Func::Sin, d);
        let c = p.call(Func::Cos, d);
        let e = p.mul2(s, c);
        // atan2 - psi: psi's sine is new, but the atan2 goes: one call instead of two.
        let (after, _) = rewrite_one(&mut p, e);
        same_values(&mut p, e, after);
        assert_eq!(calls(&p, after), 2); // sin(psi), cos(psi): one sin_cos
                                         // psi - phi with neither computed elsewhere: kept as it is.
        let d2 = p.sub(psi, phi);
        let s2 = p.call(Func::Sin, d2);
        assert_eq!(rewrite_one(&mut p, s2).0, s2);
        // ... but expanded when sin(psi) and cos(phi) are computed anyway.
        let (sp, cf) = (p.call(Func::Sin, psi), p.call(Func::Cos, phi));
        let others = p.add2(sp, cf);
        let e2 = p.add2(s2, others);
        let (after2, _) = rewrite_one(&mut p, e2);
        same_values(&mut p, e2, after2);
        let args: HashSet<ExprId> = p
            .reachable(&[after2])
            .into_iter()
            .filter_map(|n| match p.node(n) {
                Node::Call(_, [u]) => Some(*u),
                _ => None,
            })
            .collect();
        assert_eq!(args, HashSet::from_iter([psi, phi]));
        // A constant shift and a scaled angle.
        let half_pi = p.num(std::f64::consts::FRAC_PI_2);
        let shifted = p.add2(alpha, half_pi);
        let cs = p.call(Func::Cos, shifted);
        let (after3, _) = rewrite_one(&mut p, cs);
        same_values(&mut p, cs, after3);
        assert_eq!(calls(&p, after3), 0);
        let two = p.num(2.0);
        let doubled = p.mul2(two, psi);
        let sum = p.add2(doubled, alpha);
        let s4 = p.call(Func::Sin, sum);
        let (after4, _) = rewrite_one(&mut p, s4);
        assert_eq!(calls(&p, after4), calls(&p, s4));
    }

    #[test]
    fn groups_dividing_by_a_radicand_are_guarded_by_it() {
        let mut p = Pool::new();
        let (x, y) = (p.sym(Sym::State(0)), p.sym(Sym::State(1)));
        let alpha = p.atan2(y, x);
        let s = p.call(Func::Sin, alpha);
        let mut system = System::default();
        system.push(Group {
            pivots: vec![],
            body: Body::Symbolic(vec![(Sym::Der(0), s)]),
        });
        system.push(Group {
            pivots: vec![],
            body: Body::Symbolic(vec![(Sym::Der(1), x)]),
        });
        let roots = [p.sym(Sym::Der(0)), p.sym(Sym::Der(1))];
        let out = rewrite(&mut p, &system, &[], &roots, &|_, _| "r".into());
        assert_eq!(out.system.groups[0].pivots.len(), 1);
        assert_eq!(out.system.groups[0].pivots[0].text, "r");
        assert!(out.system.groups[1].pivots.is_empty());
    }
}
