//! How a solve evaluates a model's programs: each laid out once in slots
//! ([`model_algebra::FlatProgram`]) with its working memory, so a right-hand side allocates
//! nothing and hashes nothing, and by default compiled to machine code ([`model_jit`]) when
//! the solve starts. The flat evaluator runs where there is no code generator for the machine
//! and when [`set_evaluator`] chooses it (`--no-jit`); both give the same values to the bit.
//!
//! The reference interpreter ([`model_algebra::Program::eval`]) stays what one-off evaluations
//! and the tests use; an [`Engine`] computes the same values to the bit, only faster. The
//! working memory sits in a `RefCell` because the runtime evaluates a model through `&self`;
//! one engine serves one solve on one thread.

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};

use model_jit::JitProgram;

use model_algebra::{
    CompiledModel, EvalFailure, FlatError, FlatModel, FlatProgram, Inputs, Program, Scratch, Shape,
    Sink,
};

/// A program that cannot be laid out reads what does not exist: the reference interpreter's
/// failure for it.
fn bad_operand(error: FlatError) -> EvalFailure {
    match error {
        FlatError::BadOperand(operand) => EvalFailure::BadOperand(operand),
    }
}

/// How models read at run time are evaluated, for the whole process.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Evaluator {
    /// Compiled to machine code when the solve starts (the flat evaluator where the machine
    /// has no code generator).
    #[default]
    Compiled,
    /// The flat evaluator, operation by operation.
    Flat,
}

/// Whether the flat evaluator was chosen.
static FLAT: AtomicBool = AtomicBool::new(false);

/// Chooses how the models of later solves are evaluated (the results are the same).
pub fn set_evaluator(evaluator: Evaluator) {
    FLAT.store(evaluator == Evaluator::Flat, Ordering::Relaxed);
}

/// A program as it runs: machine code, or laid out in slots.
enum Code {
    Compiled(Box<JitProgram>),
    Flat(FlatProgram),
}

/// A program with its working memory.
pub(crate) struct Runner {
    code: Code,
    scratch: RefCell<Scratch>,
}

impl Runner {
    fn new(program: FlatProgram) -> Self {
        let scratch = RefCell::new(program.scratch());
        let code = match FLAT.load(Ordering::Relaxed) {
            true => Code::Flat(program),
            // No code generator for this machine: the flat evaluator, with the same results.
            false => match JitProgram::new(program.clone()) {
                Ok(compiled) => Code::Compiled(Box::new(compiled)),
                Err(_) => Code::Flat(program),
            },
        };
        Runner { code, scratch }
    }

    fn program(&self) -> &FlatProgram {
        match &self.code {
            Code::Compiled(compiled) => compiled.flat(),
            Code::Flat(program) => program,
        }
    }

    /// `program` (reading `dy`) storing `Output` targets into `n` values, reading `params`
    /// parameters: a switched model's guards, resets and first steps.
    pub(crate) fn outputs(
        program: &Program,
        model: &CompiledModel,
        params: usize,
        n: usize,
    ) -> Result<Self, EvalFailure> {
        let states = model.states.len();
        let shape = Shape {
            states,
            params,
            ders: states,
        };
        let flat = FlatProgram::new(program, shape, Sink::Outputs(n)).map_err(bad_operand)?;
        Ok(Runner::new(flat))
    }

    /// Runs the program, its stores into `out`.
    pub(crate) fn run(&self, inputs: &Inputs, out: &mut [f64]) -> Result<(), EvalFailure> {
        let scratch = &mut self.scratch.borrow_mut();
        match &self.code {
            Code::Compiled(compiled) => compiled.run(inputs, scratch, out),
            Code::Flat(program) => program.run(inputs, scratch, out),
        }
    }
}

/// A model's right-hand side, Jacobian and outputs, ready to be evaluated many times.
pub(crate) struct Engine {
    rhs: Runner,
    jacobian: Runner,
    outputs: Runner,
    /// The Jacobian, row-major, before it is copied into the runtime's rows.
    jacobian_values: RefCell<Vec<f64>>,
}

impl Engine {
    /// `model`'s programs, reading `params` parameters (a switched model's discrete values
    /// included). A program reading what does not exist is a compiler bug, reported as the
    /// reference interpreter would report it.
    pub(crate) fn new(model: &CompiledModel, params: usize) -> Result<Self, EvalFailure> {
        let flat = FlatModel::new(model, params).map_err(bad_operand)?;
        let n = model.states.len();
        Ok(Engine {
            rhs: Runner::new(flat.rhs),
            jacobian: Runner::new(flat.jacobian),
            outputs: Runner::new(flat.outputs),
            jacobian_values: RefCell::new(vec![0.0; n * n]),
        })
    }

    /// `dy = f(t, y, p)`.
    pub(crate) fn rhs(
        &self,
        t: f64,
        y: &[f64],
        params: &[f64],
        dy: &mut [f64],
    ) -> Result<(), EvalFailure> {
        let inputs = Inputs {
            t,
            states: y,
            params,
            ders: &[],
        };
        self.rhs.run(&inputs, dy)
    }

    /// `jac[i][j] = ∂f_i/∂y_j`.
    pub(crate) fn jacobian(
        &self,
        t: f64,
        y: &[f64],
        params: &[f64],
        jac: &mut [Vec<f64>],
    ) -> Result<(), EvalFailure> {
        let inputs = Inputs {
            t,
            states: y,
            params,
            ders: &[],
        };
        let mut values = self.jacobian_values.borrow_mut();
        self.jacobian.run(&inputs, &mut values)?;
        let n = y.len();
        for (row, values) in jac.iter_mut().zip(values.chunks_exact(n.max(1))) {
            row.copy_from_slice(values);
        }
        Ok(())
    }

    /// The outputs at `(t, y)` with derivatives `dy`.
    pub(crate) fn outputs(
        &self,
        t: f64,
        y: &[f64],
        dy: &[f64],
        params: &[f64],
        out: &mut [f64],
    ) -> Result<(), EvalFailure> {
        let inputs = Inputs {
            t,
            states: y,
            params,
            ders: dy,
        };
        self.outputs.run(&inputs, out)
    }

    /// The number of outputs.
    pub(crate) fn n_outputs(&self) -> usize {
        self.outputs.program().sink.len()
    }
}
