//! An interpreter for [`Program`]s, so that emitted code can be checked without compiling it.
//!
//! It follows the semantics the front end must emit, statement by statement (including the
//! pivot checks and the numeric block solve), which makes it the reference the generated Rust
//! is tested against.

use crate::hash::HashMap;

use crate::expr::{call2_value, call_value, pow_value, select_value};
use crate::program::{Node, Operand, Program, Stmt, SumCheck, Target};

/// The values a program reads.
#[derive(Clone, Copy, Debug)]
pub struct Inputs<'a> {
    /// The time.
    pub t: f64,
    /// `y`.
    pub states: &'a [f64],
    /// `p`.
    pub params: &'a [f64],
    /// `dy` (read by the outputs program only).
    pub ders: &'a [f64],
}

/// Why a program stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum EvalFailure {
    /// A checked pivot is zero, not finite or cancelled (a pivot of a numeric block: zero or
    /// not finite).
    SingularPivot {
        /// The pivot's text.
        text: String,
        /// Its value.
        value: f64,
    },
    /// An operand reads an input slot or temporary that does not exist.
    BadOperand(Operand),
}

/// What a program stored, in order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stores(pub Vec<(Target, f64)>);

impl Stores {
    /// The derivatives stored, as a dense vector of length `n`.
    pub fn ders(&self, n: usize) -> Vec<f64> {
        let mut out = vec![0.0; n];
        for &(t, v) in &self.0 {
            if let Target::Der(i) = t {
                if i < n {
                    out[i] = v;
                }
            }
        }
        out
    }

    /// The outputs stored, as a dense vector of length `n`.
    pub fn outputs(&self, n: usize) -> Vec<f64> {
        let mut out = vec![0.0; n];
        for &(t, v) in &self.0 {
            if let Target::Output(i) = t {
                if i < n {
                    out[i] = v;
                }
            }
        }
        out
    }

    /// The Jacobian stored, as a dense `n × n` matrix (unstored entries are zero).
    pub fn jacobian(&self, n: usize) -> Vec<Vec<f64>> {
        let mut out = vec![vec![0.0; n]; n];
        for &(t, v) in &self.0 {
            if let Target::Jac(i, j) = t {
                if i < n && j < n {
                    out[i][j] = v;
                }
            }
        }
        out
    }
}

impl Program {
    /// Runs the program.
    pub fn eval(&self, inputs: &Inputs) -> Result<Stores, EvalFailure> {
        let mut tmps: HashMap<u32, f64> = HashMap::default();
        let mut stores = Stores::default();
        let read = |tmps: &HashMap<u32, f64>, o: Operand| -> Result<f64, EvalFailure> {
            let bad = EvalFailure::BadOperand(o);
            match o {
                Operand::Const(v) => Ok(v),
                Operand::State(i) => inputs.states.get(i).copied().ok_or(bad),
                Operand::Param(i) => inputs.params.get(i).copied().ok_or(bad),
                Operand::Der(i) => inputs.ders.get(i).copied().ok_or(bad),
                Operand::Time => Ok(inputs.t),
                Operand::Tmp(k) => tmps.get(&k).copied().ok_or(bad),
            }
        };
        for s in &self.stmts {
            match s {
                Stmt::Let { tmp, node } => {
                    let r = |o| read(&tmps, o);
                    let v = match *node {
                        Node::Copy(a) => r(a)?,
                        Node::Neg(a) => -r(a)?,
                        Node::Add(a, b) => r(a)? + r(b)?,
                        Node::Sub(a, b) => r(a)? - r(b)?,
                        Node::Mul(a, b) => r(a)? * r(b)?,
                        Node::Div(a, b) => r(a)? / r(b)?,
                        Node::Powi(a, n) => r(a)?.powi(n),
                        Node::Powf(a, b) => pow_value(r(a)?, r(b)?),
                        Node::Call(f, a) => call_value(f, r(a)?),
                        Node::Call2(f, a, b) => call2_value(f, r(a)?, r(b)?),
                        Node::Select(a, b, c, d) => select_value(r(a)?, r(b)?, r(c)?, r(d)?),
                    };
                    tmps.insert(*tmp, v);
                }
                Stmt::SinCos { sin, cos, arg } => {
                    let (s, c) = read(&tmps, *arg)?.sin_cos();
                    tmps.insert(*sin, s);
                    tmps.insert(*cos, c);
                }
                Stmt::CheckPivot {
                    value,
                    text,
                    sums,
                    tolerance,
                } => {
                    let v = read(&tmps, *value)?;
                    let mut cancelled = false;
                    for c in sums {
                        let (s, m) = (read(&tmps, c.sum)?, read(&tmps, c.magnitude)?);
                        cancelled |= SumCheck::cancelled(s, m, *tolerance);
                    }
                    if v == 0.0 || !v.is_finite() || cancelled {
                        return Err(EvalFailure::SingularPivot {
                            text: text.clone(),
                            value: v,
                        });
                    }
                }
                Stmt::SolveBlock {
                    n,
                    matrix,
                    rhs,
                    result,
                    text,
                } => {
                    let mut a = matrix
                        .iter()
                        .map(|&o| read(&tmps, o))
                        .collect::<Result<Vec<f64>, _>>()?;
                    let mut b = rhs
                        .iter()
                        .map(|&o| read(&tmps, o))
                        .collect::<Result<Vec<f64>, _>>()?;
                    let x = solve_dense(*n, &mut a, &mut b).map_err(|value| {
                        EvalFailure::SingularPivot {
                            text: text.clone(),
                            value,
                        }
                    })?;
                    for (&t, v) in result.iter().zip(x) {
                        tmps.insert(t, v);
                    }
                }
                Stmt::Store { target, value } => {
                    stores.0.push((*target, read(&tmps, *value)?));
                }
            }
        }
        Ok(stores)
    }
}

/// Gaussian elimination with partial pivoting; `Err(pivot)` when a pivot is zero or not finite.
pub fn solve_dense(n: usize, a: &mut [f64], b: &mut [f64]) -> Result<Vec<f64>, f64> {
    let mut x = vec![0.0; n];
    solve_dense_in(n, a, b, &mut x)?;
    Ok(x)
}

/// [`solve_dense`] writing the solution into `x` (of length `n`), allocating nothing.
pub fn solve_dense_in(n: usize, a: &mut [f64], b: &mut [f64], x: &mut [f64]) -> Result<(), f64> {
    for k in 0..n {
        let p = (k..n)
            .max_by(|&i, &j| a[i * n + k].abs().total_cmp(&a[j * n + k].abs()))
            .unwrap_or(k);
        let pivot = a[p * n + k];
        if pivot == 0.0 || !pivot.is_finite() {
            return Err(pivot);
        }
        if p != k {
            for j in 0..n {
                a.swap(k * n + j, p * n + j);
            }
            b.swap(k, p);
        }
        let r = 1.0 / a[k * n + k];
        // Row by row as slices (no index checked per entry, so the update vectorizes); each
        // entry is the same `a - f * p` as written out, so the result is the same to the bit.
        let (above, below) = a[..n * n].split_at_mut((k + 1) * n);
        let pivot_row = &above[k * n + k + 1..(k + 1) * n];
        let (b_above, b_below) = b[..n].split_at_mut(k + 1);
        let bk = b_above[k];
        for (row, bi) in below.chunks_exact_mut(n).zip(b_below.iter_mut()) {
            let f = row[k] * r;
            for (entry, &p) in row[k + 1..].iter_mut().zip(pivot_row) {
                *entry -= f * p;
            }
            *bi -= f * bk;
        }
    }
    for k in (0..n).rev() {
        let mut s = b[k];
        for j in k + 1..n {
            s -= a[k * n + j] * x[j];
        }
        x[k] = s / a[k * n + k];
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dense_solve_with_pivoting() {
        // [[0, 1], [2, 1]] x = [1, 4] -> x = [1.5, 1]
        let mut a = vec![0.0, 1.0, 2.0, 1.0];
        let mut b = vec![1.0, 4.0];
        assert_eq!(solve_dense(2, &mut a, &mut b), Ok(vec![1.5, 1.0]));
        let mut a = vec![1.0, 2.0, 2.0, 4.0];
        let mut b = vec![1.0, 2.0];
        assert!(solve_dense(2, &mut a, &mut b).is_err());
    }

    #[test]
    fn interpreter_runs_every_statement_kind() {
        let p = Program {
            stmts: vec![
                Stmt::SinCos {
                    sin: 0,
                    cos: 1,
                    arg: Operand::State(0),
                },
                Stmt::CheckPivot {
                    value: Operand::Tmp(0),
                    text: "sin(x)".into(),
                    sums: vec![],
                    tolerance: 0.0,
                },
                Stmt::Let {
                    tmp: 2,
                    node: Node::Div(Operand::Tmp(1), Operand::Tmp(0)),
                },
                Stmt::Store {
                    target: Target::Der(0),
                    value: Operand::Tmp(2),
                },
            ],
        };
        let ok = p
            .eval(&Inputs {
                t: 0.0,
                states: &[0.5],
                params: &[],
                ders: &[],
            })
            .unwrap();
        assert!((ok.ders(1)[0] - 1.0 / 0.5f64.tan()).abs() < 1e-15);
        let err = p.eval(&Inputs {
            t: 0.0,
            states: &[0.0],
            params: &[],
            ders: &[],
        });
        assert_eq!(
            err,
            Err(EvalFailure::SingularPivot {
                text: "sin(x)".into(),
                value: 0.0
            })
        );
    }
}
