//! A [`Program`] laid out for fast repeated evaluation: every value it reads or defines in one
//! slot of a `Vec<f64>`, the slot numbers fixed when the program is built.
//!
//! [`Program::eval`] is the reference: it follows the statements literally, keeps its
//! temporaries in a map and returns what was stored as a list, which costs a hash per
//! temporary and allocations on every call. A model read at run time calls its right-hand side
//! hundreds of thousands of times, so the slot numbers, the constants and the shape of every
//! store are worked out once here ([`FlatProgram::new`]) and a call ([`FlatProgram::run`]) is
//! a loop over plain array reads and writes, allocating nothing. Every operation is computed by
//! the same functions, in the same order, as [`Program::eval`] computes it, so the two agree to
//! the bit. The operations are public so that a code generator can translate the same list.
//!
//! The slots are `t`, the states, the parameters, the derivatives (outputs only), then the
//! constants and the temporaries ([`Layout`]). Where a program's stores leave part of the
//! destination unwritten (a Jacobian's structural zeros), [`FlatProgram::run`] zeroes the
//! destination first, as [`Stores`](crate::Stores) does.

use crate::hash::HashMap;

use crate::eval::{solve_dense_in, EvalFailure, Inputs};
use crate::expr::{call2_value, call_value, pow_value, select_value};
use crate::program::{Node, Operand, Program, Stmt, SumCheck, Target};
use crate::spec::Func;

/// An index into a flat program's slots.
pub type Slot = u32;

/// How many inputs of each kind a program is given (the slices of [`Inputs`] may be longer).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Shape {
    /// The number of states.
    pub states: usize,
    /// The number of parameters (a switched model's discrete values included).
    pub params: usize,
    /// The number of derivatives read (zero except in an outputs program).
    pub ders: usize,
}

/// Which stores a program's destination holds, and how it is indexed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sink {
    /// `dy`: `Target::Der(i)` at `i < n`.
    Ders(usize),
    /// `out`: `Target::Output(k)` at `k < n`.
    Outputs(usize),
    /// The Jacobian, row-major: `Target::Jac(i, j)` at `i * n + j` for `i, j < n`.
    Jacobian(usize),
}

impl Sink {
    /// The destination's length.
    pub fn len(self) -> usize {
        match self {
            Sink::Ders(n) | Sink::Outputs(n) => n,
            Sink::Jacobian(n) => n * n,
        }
    }

    /// Whether the destination is empty.
    pub fn is_empty(self) -> bool {
        self.len() == 0
    }

    /// Where `target` lands, if it belongs to this destination (others are not kept, as
    /// [`Stores::ders`](crate::Stores::ders) keeps only derivatives).
    fn index(self, target: Target) -> Option<usize> {
        match (self, target) {
            (Sink::Ders(n), Target::Der(i)) | (Sink::Outputs(n), Target::Output(i)) => {
                (i < n).then_some(i)
            }
            (Sink::Jacobian(n), Target::Jac(i, j)) => (i < n && j < n).then_some(i * n + j),
            _ => None,
        }
    }
}

/// Where the inputs sit among the slots: `t` at 0, then the states, the parameters and the
/// derivatives, each contiguous.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    /// The input counts.
    pub shape: Shape,
    /// The total number of slots (inputs, constants, temporaries).
    pub slots: usize,
}

impl Layout {
    /// The slot of `t`.
    pub const TIME: Slot = 0;

    /// The first state's slot.
    pub fn states(&self) -> Slot {
        1
    }

    /// The first parameter's slot.
    pub fn params(&self) -> Slot {
        1 + self.shape.states as Slot
    }

    /// The first derivative's slot.
    pub fn ders(&self) -> Slot {
        self.params() + self.shape.params as Slot
    }

    /// The first slot after the inputs.
    pub fn end_of_inputs(&self) -> Slot {
        self.ders() + self.shape.ders as Slot
    }
}

/// A one-argument operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unary {
    /// A copy.
    Copy,
    /// `-a`
    Neg,
    /// `a.powi(n)`
    Powi(i32),
    /// A one-argument function, by [`call_value`](crate::expr::call_value).
    Call(Func),
}

/// A two-argument operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Binary {
    /// `a + b`
    Add,
    /// `a - b`
    Sub,
    /// `a * b`
    Mul,
    /// `a / b`
    Div,
    /// `pow(a, b)` by [`pow_value`](crate::expr::pow_value).
    Powf,
    /// A two-argument function (`atan2`, `hypot`), by
    /// [`call2_value`](crate::expr::call2_value).
    Call(Func),
}

/// A pivot check: its value and the sums tested for cancellation.
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    /// The pivot's slot.
    pub value: Slot,
    /// `(sum, magnitude)` slots of each sum tested.
    pub sums: Vec<(Slot, Slot)>,
    /// The cancellation tolerance ([`SumCheck::cancelled`]).
    pub tolerance: f64,
    /// The pivot's text.
    pub text: String,
}

/// A numeric block solved by Gaussian elimination.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// The block's size `n`.
    pub n: usize,
    /// `A`, row-major.
    pub matrix: Vec<Slot>,
    /// `b`.
    pub rhs: Vec<Slot>,
    /// The slots receiving `x`.
    pub result: Vec<Slot>,
    /// The block's text.
    pub text: String,
}

/// One operation of a flat program.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Op {
    /// `slots[dst] = op(slots[a])`
    Unary {
        /// The operation.
        op: Unary,
        /// The destination slot.
        dst: Slot,
        /// The argument.
        a: Slot,
    },
    /// `slots[dst] = op(slots[a], slots[b])`
    Binary {
        /// The operation.
        op: Binary,
        /// The destination slot.
        dst: Slot,
        /// The first argument.
        a: Slot,
        /// The second argument.
        b: Slot,
    },
    /// `slots[dst] = select_value(a, b, then, otherwise)`
    Select {
        /// The destination slot.
        dst: Slot,
        /// `[lhs, rhs, then, otherwise]`.
        args: [Slot; 4],
    },
    /// `(slots[sin], slots[cos]) = slots[arg].sin_cos()`
    SinCos {
        /// The sine's slot.
        sin: Slot,
        /// The cosine's slot.
        cos: Slot,
        /// The argument.
        arg: Slot,
    },
    /// Fail if [`FlatProgram::checks`]`[k]` finds a singular pivot.
    Check(u32),
    /// Solve [`FlatProgram::blocks`]`[k]`.
    Solve(u32),
    /// `out[index] = slots[value]`
    Store {
        /// The destination index ([`Sink`]).
        index: u32,
        /// The value.
        value: Slot,
    },
}

/// Why a program cannot be laid out: it reads something that does not exist (a compiler bug,
/// reported instead of evaluated).
#[derive(Clone, Debug, PartialEq)]
pub enum FlatError {
    /// An operand names a state, parameter, derivative or temporary the program does not have.
    BadOperand(Operand),
}

/// A program laid out in slots (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct FlatProgram {
    /// The slots' layout.
    pub layout: Layout,
    /// `(slot, value)` of every constant.
    pub constants: Vec<(Slot, f64)>,
    /// The operations, in order.
    pub ops: Vec<Op>,
    /// The pivot checks [`Op::Check`] refers to.
    pub checks: Vec<Check>,
    /// The blocks [`Op::Solve`] refers to.
    pub blocks: Vec<Block>,
    /// The destination.
    pub sink: Sink,
    /// Whether some entry of the destination is never stored (then it is zeroed first).
    pub zero_first: bool,
}

/// The memory one evaluation works in: the slots (constants already in place) and room for a
/// numeric block. Made once by [`FlatProgram::scratch`] and reused by every call.
#[derive(Clone, Debug)]
pub struct Scratch {
    slots: Vec<f64>,
    block: Vec<f64>,
}

impl Scratch {
    /// Memory for code generated from the program: at least two values, and `2 + n² + 2n`
    /// for its largest numeric block of size `n`.
    pub fn work(&mut self) -> &mut [f64] {
        &mut self.block
    }
}

/// Temporaries to slots, while a program is laid out.
struct Builder {
    layout: Layout,
    tmps: HashMap<u32, Slot>,
    constants: Vec<(Slot, f64)>,
    /// Constants by bit pattern, so that each is one slot.
    constant_slots: HashMap<u64, Slot>,
    next: Slot,
}

impl Builder {
    fn read(&mut self, o: Operand) -> Result<Slot, FlatError> {
        let shape = self.layout.shape;
        let within = |i: usize, n: usize, first: Slot| {
            (i < n)
                .then_some(first + i as Slot)
                .ok_or(FlatError::BadOperand(o))
        };
        match o {
            Operand::Time => Ok(Layout::TIME),
            Operand::State(i) => within(i, shape.states, self.layout.states()),
            Operand::Param(i) => within(i, shape.params, self.layout.params()),
            Operand::Der(i) => within(i, shape.ders, self.layout.ders()),
            Operand::Tmp(k) => self.tmps.get(&k).copied().ok_or(FlatError::BadOperand(o)),
            Operand::Const(v) => Ok(match self.constant_slots.get(&v.to_bits()) {
                Some(&slot) => slot,
                None => {
                    let slot = self.fresh();
                    self.constant_slots.insert(v.to_bits(), slot);
                    self.constants.push((slot, v));
                    slot
                }
            }),
        }
    }

    fn fresh(&mut self) -> Slot {
        let slot = self.next;
        self.next += 1;
        slot
    }

    /// A new slot for temporary `tmp` (a redefinition gets its own slot, so an earlier
    /// reader keeps the value it read).
    fn define(&mut self, tmp: u32) -> Slot {
        let slot = self.fresh();
        self.tmps.insert(tmp, slot);
        slot
    }
}

impl FlatProgram {
    /// Lays out `program`, given inputs of `shape`, storing into `sink`.
    pub fn new(program: &Program, shape: Shape, sink: Sink) -> Result<Self, FlatError> {
        let inputs = Layout { shape, slots: 0 }.end_of_inputs();
        let mut b = Builder {
            layout: Layout { shape, slots: 0 },
            tmps: HashMap::default(),
            constants: Vec::new(),
            constant_slots: HashMap::default(),
            next: inputs,
        };
        let (mut ops, mut checks, mut blocks) = (Vec::new(), Vec::new(), Vec::new());
        let mut stored = vec![false; sink.len()];
        for s in &program.stmts {
            match s {
                Stmt::Let { tmp, node } => {
                    let op = match *node {
                        Node::Copy(a) => unary(Unary::Copy, b.read(a)?),
                        Node::Neg(a) => unary(Unary::Neg, b.read(a)?),
                        Node::Powi(a, n) => unary(Unary::Powi(n), b.read(a)?),
                        Node::Call(f, a) => unary(Unary::Call(f), b.read(a)?),
                        Node::Add(x, y) => binary(Binary::Add, b.read(x)?, b.read(y)?),
                        Node::Sub(x, y) => binary(Binary::Sub, b.read(x)?, b.read(y)?),
                        Node::Mul(x, y) => binary(Binary::Mul, b.read(x)?, b.read(y)?),
                        Node::Div(x, y) => binary(Binary::Div, b.read(x)?, b.read(y)?),
                        Node::Powf(x, y) => binary(Binary::Powf, b.read(x)?, b.read(y)?),
                        Node::Call2(f, x, y) => binary(Binary::Call(f), b.read(x)?, b.read(y)?),
                        Node::Select(w, x, y, z) => {
                            let args = [b.read(w)?, b.read(x)?, b.read(y)?, b.read(z)?];
                            Box::new(move |dst| Op::Select { dst, args })
                        }
                    };
                    ops.push(op(b.define(*tmp)));
                }
                Stmt::SinCos { sin, cos, arg } => {
                    let arg = b.read(*arg)?;
                    let (sin, cos) = (b.define(*sin), b.define(*cos));
                    ops.push(Op::SinCos { sin, cos, arg });
                }
                Stmt::CheckPivot {
                    value,
                    text,
                    sums,
                    tolerance,
                } => {
                    let value = b.read(*value)?;
                    let sums = (sums.iter())
                        .map(|c: &SumCheck| Ok((b.read(c.sum)?, b.read(c.magnitude)?)))
                        .collect::<Result<Vec<_>, FlatError>>()?;
                    ops.push(Op::Check(checks.len() as u32));
                    checks.push(Check {
                        value,
                        sums,
                        tolerance: *tolerance,
                        text: text.clone(),
                    });
                }
                Stmt::SolveBlock {
                    n,
                    matrix,
                    rhs,
                    result,
                    text,
                } => {
                    let matrix = (matrix.iter().map(|&o| b.read(o))).collect::<Result<_, _>>()?;
                    let rhs = (rhs.iter().map(|&o| b.read(o))).collect::<Result<_, _>>()?;
                    let result = result.iter().map(|&t| b.define(t)).collect();
                    ops.push(Op::Solve(blocks.len() as u32));
                    blocks.push(Block {
                        n: *n,
                        matrix,
                        rhs,
                        result,
                        text: text.clone(),
                    });
                }
                Stmt::Store { target, value } => {
                    let value = b.read(*value)?;
                    if let Some(index) = sink.index(*target) {
                        stored[index] = true;
                        ops.push(Op::Store {
                            index: index as u32,
                            value,
                        });
                    }
                }
            }
        }
        let layout = Layout {
            shape,
            slots: b.next as usize,
        };
        Ok(FlatProgram {
            layout,
            constants: b.constants,
            ops,
            checks,
            blocks,
            sink,
            zero_first: stored.iter().any(|s| !s),
        })
    }

    /// The memory [`run`](Self::run) works in, constants in place.
    pub fn scratch(&self) -> Scratch {
        let mut slots = vec![0.0; self.layout.slots];
        for &(slot, v) in &self.constants {
            slots[slot as usize] = v;
        }
        let n = self.blocks.iter().map(|b| b.n).max().unwrap_or(0);
        Scratch {
            slots,
            // Two more than a block needs: generated code keeps a failing pivot and a
            // `sin_cos` there (`Scratch::work`).
            block: vec![0.0; 2 + n * n + 2 * n],
        }
    }

    /// Runs the program on `inputs`, writing its stores into `out` (of the sink's length; a
    /// shorter `out` is a caller's bug and panics). `scratch` must come from this program's
    /// [`scratch`](Self::scratch). Inputs shorter than the program's [`Shape`] fail as the
    /// reference does, naming the first operand missing.
    pub fn run(
        &self,
        inputs: &Inputs,
        scratch: &mut Scratch,
        out: &mut [f64],
    ) -> Result<(), EvalFailure> {
        let shape = self.layout.shape;
        let missing = |len: usize, n: usize, operand: fn(usize) -> Operand| {
            (len < n).then(|| EvalFailure::BadOperand(operand(len)))
        };
        if let Some(failure) = (missing(inputs.states.len(), shape.states, Operand::State))
            .or_else(|| missing(inputs.params.len(), shape.params, Operand::Param))
            .or_else(|| missing(inputs.ders.len(), shape.ders, Operand::Der))
        {
            return Err(failure);
        }
        let out = &mut out[..self.sink.len()];
        if self.zero_first {
            out.fill(0.0);
        }
        let s = &mut scratch.slots[..];
        s[0] = inputs.t;
        let l = &self.layout;
        let copy = |s: &mut [f64], first: Slot, from: &[f64], n: usize| {
            s[first as usize..first as usize + n].copy_from_slice(&from[..n]);
        };
        copy(s, l.states(), inputs.states, shape.states);
        copy(s, l.params(), inputs.params, shape.params);
        copy(s, l.ders(), inputs.ders, shape.ders);
        for op in &self.ops {
            match *op {
                Op::Unary { op, dst, a } => s[dst as usize] = op.apply(s[a as usize]),
                Op::Binary { op, dst, a, b } => {
                    s[dst as usize] = op.apply(s[a as usize], s[b as usize])
                }
                Op::Select {
                    dst,
                    args: [w, x, y, z],
                } => {
                    let r = |k: Slot| s[k as usize];
                    s[dst as usize] = select_value(r(w), r(x), r(y), r(z));
                }
                Op::SinCos { sin, cos, arg } => {
                    let (a, b) = s[arg as usize].sin_cos();
                    s[sin as usize] = a;
                    s[cos as usize] = b;
                }
                Op::Check(k) => self.checks[k as usize].run(s)?,
                Op::Solve(k) => self.blocks[k as usize].run(s, &mut scratch.block)?,
                Op::Store { index, value } => out[index as usize] = s[value as usize],
            }
        }
        Ok(())
    }
}

fn unary(op: Unary, a: Slot) -> Box<dyn Fn(Slot) -> Op> {
    Box::new(move |dst| Op::Unary { op, dst, a })
}

fn binary(op: Binary, a: Slot, b: Slot) -> Box<dyn Fn(Slot) -> Op> {
    Box::new(move |dst| Op::Binary { op, dst, a, b })
}

impl Unary {
    /// The operation's value, as [`Program::eval`] computes it.
    #[inline]
    pub fn apply(self, a: f64) -> f64 {
        match self {
            Unary::Copy => a,
            Unary::Neg => -a,
            Unary::Powi(n) => a.powi(n),
            Unary::Call(f) => call_value(f, a),
        }
    }
}

impl Binary {
    /// The operation's value, as [`Program::eval`] computes it.
    #[inline]
    pub fn apply(self, a: f64, b: f64) -> f64 {
        match self {
            Binary::Add => a + b,
            Binary::Sub => a - b,
            Binary::Mul => a * b,
            Binary::Div => a / b,
            Binary::Powf => pow_value(a, b),
            Binary::Call(f) => call2_value(f, a, b),
        }
    }
}

impl Check {
    /// The check on the slots' values, as [`Program::eval`] makes it.
    pub fn run(&self, s: &[f64]) -> Result<(), EvalFailure> {
        let v = s[self.value as usize];
        let mut cancelled = false;
        for &(sum, magnitude) in &self.sums {
            cancelled |=
                SumCheck::cancelled(s[sum as usize], s[magnitude as usize], self.tolerance);
        }
        if v == 0.0 || !v.is_finite() || cancelled {
            return Err(self.failure(v));
        }
        Ok(())
    }

    /// The failure for pivot value `value`.
    pub fn failure(&self, value: f64) -> EvalFailure {
        EvalFailure::SingularPivot {
            text: self.text.clone(),
            value,
        }
    }
}

impl Block {
    /// Solves the block on the slots' values, `work` holding at least `n² + 2n` values.
    pub fn run(&self, s: &mut [f64], work: &mut [f64]) -> Result<(), EvalFailure> {
        let n = self.n;
        let (a, rest) = work.split_at_mut(n * n);
        let (b, x) = rest.split_at_mut(n);
        for (a, &k) in a.iter_mut().zip(&self.matrix) {
            *a = s[k as usize];
        }
        for (b, &k) in b.iter_mut().zip(&self.rhs) {
            *b = s[k as usize];
        }
        let x = &mut x[..n];
        solve_dense_in(n, a, b, x).map_err(|value| EvalFailure::SingularPivot {
            text: self.text.clone(),
            value,
        })?;
        for (&k, &v) in self.result.iter().zip(x.iter()) {
            s[k as usize] = v;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inputs<'a>(states: &'a [f64], params: &'a [f64]) -> Inputs<'a> {
        Inputs {
            t: 0.25,
            states,
            params,
            ders: &[],
        }
    }

    #[test]
    fn a_program_reading_a_missing_temporary_is_refused() {
        let p = Program {
            stmts: vec![Stmt::Store {
                target: Target::Der(0),
                value: Operand::Tmp(7),
            }],
        };
        let shape = Shape {
            states: 1,
            ..Shape::default()
        };
        assert_eq!(
            FlatProgram::new(&p, shape, Sink::Ders(1)),
            Err(FlatError::BadOperand(Operand::Tmp(7)))
        );
    }

    #[test]
    fn unstored_entries_are_zero_and_short_inputs_fail() {
        let p = Program {
            stmts: vec![
                Stmt::Let {
                    tmp: 0,
                    node: Node::Mul(Operand::State(1), Operand::Const(2.0)),
                },
                Stmt::Store {
                    target: Target::Jac(0, 1),
                    value: Operand::Tmp(0),
                },
            ],
        };
        let shape = Shape {
            states: 2,
            ..Shape::default()
        };
        let flat = FlatProgram::new(&p, shape, Sink::Jacobian(2)).unwrap();
        assert!(flat.zero_first);
        let mut scratch = flat.scratch();
        let mut out = [9.0; 4];
        flat.run(&inputs(&[1.0, 3.0], &[]), &mut scratch, &mut out)
            .unwrap();
        assert_eq!(out, [0.0, 6.0, 0.0, 0.0]);
        assert_eq!(
            flat.run(&inputs(&[1.0], &[]), &mut scratch, &mut out),
            Err(EvalFailure::BadOperand(Operand::State(1)))
        );
    }

    #[test]
    fn a_singular_block_names_itself() {
        let p = Program {
            stmts: vec![Stmt::SolveBlock {
                n: 2,
                matrix: vec![Operand::Param(0); 4],
                rhs: vec![Operand::Const(1.0); 2],
                result: vec![0, 1],
                text: "der(a), der(b)".into(),
            }],
        };
        let shape = Shape {
            params: 1,
            ..Shape::default()
        };
        let flat = FlatProgram::new(&p, shape, Sink::Ders(0)).unwrap();
        let got = flat.run(&inputs(&[], &[1.0]), &mut flat.scratch(), &mut []);
        assert_eq!(got, p.eval(&inputs(&[], &[1.0])).map(|_| ()));
        assert!(matches!(got, Err(EvalFailure::SingularPivot { .. })));
    }
}
