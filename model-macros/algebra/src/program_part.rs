//! A part of a program: the statements some of its stores need, and nothing else.
//!
//! One outputs program can compute values that are needed at different times: a switched
//! model's mode computes its user outputs (for a file), its guards (after every step) and each
//! event's resets (once, at the event) from one compiled model, so every subexpression they
//! share is derived once by the compiler. Each use then runs only the statements it needs.

use crate::hash::HashSet;
use crate::program::{Node, Operand, Program, Stmt, Target};
use std::ops::Range;

impl Program {
    /// The statements that the stores to `Output(k)`, `k` in `outputs`, need, with those
    /// stores renumbered from 0; every other store is dropped. A pivot check is kept when the
    /// value it checks is kept.
    pub fn select_outputs(&self, outputs: Range<usize>) -> Program {
        let mut live: HashSet<u32> = HashSet::default();
        let mut kept: Vec<Stmt> = Vec::new();
        let need = |operand: &Operand, live: &mut HashSet<u32>| {
            if let Operand::Tmp(t) = operand {
                live.insert(*t);
            }
        };
        for stmt in self.stmts.iter().rev() {
            let keep = match stmt {
                Stmt::Store {
                    target: Target::Output(k),
                    value,
                } if outputs.contains(k) => {
                    need(value, &mut live);
                    kept.push(Stmt::Store {
                        target: Target::Output(k - outputs.start),
                        value: *value,
                    });
                    continue;
                }
                Stmt::Store { .. } => false,
                Stmt::Let { tmp, .. } => live.contains(tmp),
                Stmt::SinCos { sin, cos, .. } => live.contains(sin) || live.contains(cos),
                Stmt::SolveBlock { result, .. } => result.iter().any(|t| live.contains(t)),
                Stmt::CheckPivot { value, .. } => match value {
                    Operand::Tmp(t) => live.contains(t),
                    _ => false,
                },
            };
            if !keep {
                continue;
            }
            for operand in operands(stmt) {
                need(&operand, &mut live);
            }
            kept.push(stmt.clone());
        }
        kept.reverse();
        Program { stmts: kept }
    }

    /// Whether the program reads no state, no derivative and not the time: its values are fixed
    /// for a whole run (a guard that can never change sign).
    pub fn reads_only_parameters(&self) -> bool {
        self.stmts
            .iter()
            .flat_map(operands)
            .all(|operand| !matches!(operand, Operand::State(_) | Operand::Der(_) | Operand::Time))
    }

    /// The states, derivatives and parameters the program reads, each in increasing index order and
    /// without repeats: what a caller must supply for its values (the rest may be anything).
    pub fn reads(&self) -> Reads {
        let mut reads = Reads::default();
        for operand in self.stmts.iter().flat_map(operands) {
            match operand {
                Operand::State(i) => reads.states.push(i),
                Operand::Der(i) => reads.ders.push(i),
                Operand::Time => reads.time = true,
                Operand::Param(i) => reads.params.push(i),
                _ => {}
            }
        }
        for list in [&mut reads.states, &mut reads.ders, &mut reads.params] {
            list.sort_unstable();
            list.dedup();
        }
        reads
    }
}

/// What a program reads of the state and its derivative ([`Program::reads`]).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Reads {
    /// The indices of the states read.
    pub states: Vec<usize>,
    /// The indices of the derivatives read.
    pub ders: Vec<usize>,
    /// Whether the time is read.
    pub time: bool,
    /// The indices of the parameters read.
    pub params: Vec<usize>,
}

/// The operands a statement reads.
fn operands(stmt: &Stmt) -> Vec<Operand> {
    match stmt {
        Stmt::Let { node, .. } => node_operands(node),
        Stmt::SinCos { arg, .. } => vec![*arg],
        Stmt::CheckPivot { value, sums, .. } => {
            let mut all = vec![*value];
            for sum in sums {
                all.push(sum.sum);
                all.push(sum.magnitude);
            }
            all
        }
        Stmt::SolveBlock { matrix, rhs, .. } => matrix.iter().chain(rhs).copied().collect(),
        Stmt::Store { value, .. } => vec![*value],
    }
}

fn node_operands(node: &Node) -> Vec<Operand> {
    match node {
        Node::Copy(a) | Node::Neg(a) | Node::Powi(a, _) | Node::Call(_, a) => vec![*a],
        Node::Add(a, b)
        | Node::Sub(a, b)
        | Node::Mul(a, b)
        | Node::Div(a, b)
        | Node::Powf(a, b)
        | Node::Call2(_, a, b) => vec![*a, *b],
        Node::Select(a, b, c, d) => vec![*a, *b, *c, *d],
    }
}

#[cfg(test)]
mod tests {
    use crate::program::{Node, Operand, Program, Stmt, Target};

    fn store(k: usize, value: Operand) -> Stmt {
        Stmt::Store {
            target: Target::Output(k),
            value,
        }
    }

    #[test]
    fn keeps_only_what_the_selected_stores_need() {
        // t0 = y0 * y1 (shared), t1 = t0 + 1 (output 0 only), t2 = t0 * 2 (output 1 only)
        let program = Program {
            stmts: vec![
                Stmt::Let {
                    tmp: 0,
                    node: Node::Mul(Operand::State(0), Operand::State(1)),
                },
                Stmt::Let {
                    tmp: 1,
                    node: Node::Add(Operand::Tmp(0), Operand::Const(1.0)),
                },
                Stmt::Let {
                    tmp: 2,
                    node: Node::Mul(Operand::Tmp(0), Operand::Const(2.0)),
                },
                store(0, Operand::Tmp(1)),
                store(1, Operand::Tmp(2)),
                store(2, Operand::Const(3.0)),
            ],
        };
        let second = program.select_outputs(1..2);
        assert_eq!(
            second.stmts,
            vec![
                program.stmts[0].clone(),
                program.stmts[2].clone(),
                store(0, Operand::Tmp(2))
            ]
        );
        let first = program.select_outputs(0..1);
        assert_eq!(first.stmts.len(), 3);
        assert!(!first.reads_only_parameters());
        let reads = first.reads();
        assert_eq!((reads.states, reads.ders), (vec![0, 1], vec![]));
        let third = program.select_outputs(2..3);
        assert_eq!(third.stmts, vec![store(0, Operand::Const(3.0))]);
        assert!(third.reads_only_parameters());
        assert_eq!(
            program.select_outputs(0..3).stmts.len(),
            program.stmts.len()
        );
    }

    #[test]
    fn reads_lists_each_state_and_derivative_once_in_order() {
        // out0 = dy2 * y3 + y3, out1 = t * y0 (only out0 selected)
        let program = Program {
            stmts: vec![
                Stmt::Let {
                    tmp: 0,
                    node: Node::Mul(Operand::Der(2), Operand::State(3)),
                },
                Stmt::Let {
                    tmp: 1,
                    node: Node::Add(Operand::Tmp(0), Operand::State(3)),
                },
                Stmt::Let {
                    tmp: 2,
                    node: Node::Mul(Operand::Time, Operand::State(0)),
                },
                store(0, Operand::Tmp(1)),
                store(1, Operand::Tmp(2)),
            ],
        };
        let reads = program.select_outputs(0..1).reads();
        assert_eq!(
            (reads.states, reads.ders, reads.time),
            (vec![3], vec![2], false)
        );
        let reads = program.reads();
        assert_eq!(
            (reads.states, reads.ders, reads.time),
            (vec![0, 3], vec![2], true)
        );
    }
}
