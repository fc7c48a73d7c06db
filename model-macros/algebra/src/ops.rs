//! Operation counts of emitted programs.
//!
//! The counts are the contract for "fast": tests pin them exactly, so a change that makes the
//! emitted code bigger fails a test instead of slipping through.

use crate::program::{Node, Program, Stmt};
use crate::spec::Func;
use crate::OpCounts;

/// Counts a call of `f` in `ops`.
fn count_call(ops: &mut OpCounts, f: Func) {
    match f {
        Func::Sin | Func::Cos | Func::Tan | Func::Atan2 => ops.trig += 1,
        // `hypot` is a square root of a sum of squares, scaled against overflow.
        Func::Sqrt | Func::Hypot => ops.sqrt += 1,
        Func::Exp | Func::Ln => ops.transcendental += 1,
        // A comparison (two for `sign`, taken as one) costs what a subtraction does.
        Func::Sign | Func::Min | Func::Max => ops.add += 1,
        Func::Abs => {}
    }
}

/// Multiplications of `x.powi(n)` by repeated squaring.
pub fn powi_muls(n: i32) -> u32 {
    let n = n.unsigned_abs();
    if n <= 1 {
        return 0;
    }
    (31 - n.leading_zeros()) + n.count_ones() - 1
}

/// Operations of Gaussian elimination with partial pivoting on an `n × n` system (one
/// reciprocal per pivot; comparisons not counted).
pub fn solve_block_ops(n: usize) -> OpCounts {
    let n = n as u32;
    // Elimination: for each pivot k, rows below get a factor (1 mul by the reciprocal) and
    // n-k-1 matrix updates plus one rhs update (a mul and an add each). Back substitution:
    // row k needs n-k-1 products and sums, then one multiplication by the reciprocal.
    let mut ops = OpCounts {
        div: n,
        ..OpCounts::default()
    };
    for k in 0..n {
        let below = n - k - 1;
        ops.mul += below * (1 + below + 1);
        ops.add += below * (below + 1);
        ops.mul += below + 1;
        ops.add += below;
    }
    ops
}

impl Program {
    /// Operation counts of the program (a `SinCos` counts once, a `SolveBlock` as its
    /// elimination).
    pub fn ops(&self) -> OpCounts {
        let mut ops = OpCounts::default();
        for s in &self.stmts {
            match s {
                Stmt::Let { node, .. } => match node {
                    Node::Copy(_) => {}
                    Node::Neg(_) | Node::Add(..) | Node::Sub(..) => ops.add += 1,
                    Node::Mul(..) => ops.mul += 1,
                    Node::Div(..) => ops.div += 1,
                    Node::Powi(_, n) => {
                        ops.mul += powi_muls(*n);
                        if *n < 0 {
                            ops.div += 1;
                        }
                    }
                    Node::Powf(..) => ops.transcendental += 1,
                    Node::Call(f, _) => count_call(&mut ops, *f),
                    Node::Call2(f, ..) => count_call(&mut ops, *f),
                    Node::Select(..) => ops.add += 1,
                },
                Stmt::SinCos { .. } => ops.trig += 1,
                Stmt::SolveBlock { n, .. } => ops += solve_block_ops(*n),
                // One multiplication per cancellation test (`|sum| <= tolerance * magnitude`).
                Stmt::CheckPivot { sums, .. } => ops.mul += sums.len() as u32,
                Stmt::Store { .. } => {}
            }
        }
        ops
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn powi_multiplications() {
        let table = [
            (0, 0),
            (1, 0),
            (2, 1),
            (3, 2),
            (4, 2),
            (5, 3),
            (8, 3),
            (-2, 1),
        ];
        for (n, m) in table {
            assert_eq!(powi_muls(n), m, "powi({n})");
        }
    }

    #[test]
    fn solve_block_counts() {
        let one = solve_block_ops(1);
        assert_eq!((one.add, one.mul, one.div), (0, 1, 1));
        let two = solve_block_ops(2);
        // factor 1, update a11 and b1: 2 mul 2 add; back: x1 = b1*r1 (1 mul),
        // x0 = (b0 - a01 x1)*r0 (1 mul, 1 add, 1 mul).
        assert_eq!((two.add, two.mul, two.div), (3, 6, 2));
    }

    #[test]
    fn comparisons_count_as_additions() {
        use crate::program::Operand;
        let let_ = |tmp, node| Stmt::Let { tmp, node };
        let program = Program {
            stmts: vec![
                let_(0, Node::Call(Func::Sign, Operand::State(0))),
                let_(1, Node::Call(Func::Abs, Operand::State(0))),
                let_(
                    2,
                    Node::Select(
                        Operand::State(0),
                        Operand::Const(0.0),
                        Operand::Tmp(0),
                        Operand::Tmp(1),
                    ),
                ),
            ],
        };
        assert_eq!(
            program.ops(),
            OpCounts {
                add: 2,
                ..OpCounts::default()
            }
        );
    }

    #[test]
    fn two_argument_calls_count_as_their_functions() {
        use crate::program::Operand;
        let call2 = |tmp, f| Stmt::Let {
            tmp,
            node: Node::Call2(f, Operand::State(0), Operand::State(1)),
        };
        let program = Program {
            stmts: vec![call2(0, Func::Hypot), call2(1, Func::Atan2)],
        };
        assert_eq!(
            program.ops(),
            OpCounts {
                sqrt: 1,
                trig: 1,
                ..OpCounts::default()
            }
        );
    }
}
