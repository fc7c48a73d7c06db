//! How a solve evaluates a model's programs: each laid out once in slots
//! ([`model_algebra::FlatProgram`]) with its working memory, so a right-hand side allocates
//! nothing and hashes nothing, and compiled to machine code ([`model_jit`]) once it has been
//! evaluated often enough for the compile to pay off. The flat evaluator runs until then, where
//! there is no code generator for the machine, and when [`set_evaluator`] chooses it
//! (`--no-jit`); both give the same values to the bit, so when (and whether) a program is
//! compiled never changes a result.
//!
//! Why tiers: compiling costs about as much per operation as some three to nine thousand flat
//! evaluations save per operation (BENCHMARKS.md, "Models read at run time"), so a short run
//! (the 20-link chain for 5 s, a few thousand right-hand sides; a Jacobian an explicit method
//! never asks for) is faster without compiling, and a long one much faster with it. Compiling
//! a program once its evaluations reach that break-even count ([`Evaluator::COMPILE_AFTER`])
//! never costs more than twice the better of the two choices made in hindsight (the
//! ski-rental bound), with no setting for the user to get wrong; each program (right-hand
//! side, Jacobian, outputs, a switched model's guards) counts its own evaluations.
//!
//! The reference interpreter ([`model_algebra::Program::eval`]) stays what one-off evaluations
//! and the tests use; an [`Engine`] computes the same values to the bit, only faster. The
//! working memory sits in a `RefCell` because the runtime evaluates a model through `&self`;
//! one engine serves one solve on one thread.

use std::cell::{Cell, OnceCell, RefCell};
use std::sync::atomic::{AtomicU64, Ordering};

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

/// How models read at run time are evaluated, for the whole process. Every choice gives the
/// same results to the bit; they differ in speed only.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Evaluator {
    /// The flat evaluator first, each program compiled to machine code once it has been
    /// evaluated `after` times (the default: [`Evaluator::COMPILE_AFTER`]).
    Tiered {
        /// The evaluations of a program before it is compiled.
        after: u64,
    },
    /// Every program compiled to machine code at its first evaluation.
    Compiled,
    /// The flat evaluator, operation by operation, never compiled.
    Flat,
}

impl Evaluator {
    /// The default count of evaluations after which a program is compiled: about the
    /// break-even count of compiling (its cost against what machine code saves per
    /// evaluation) measured on the heavy top, the 20-link chain and the disk (BENCHMARKS.md,
    /// "Models read at run time").
    pub const COMPILE_AFTER: u64 = 5_000;

    /// Evaluations before compiling; `None`: never.
    fn countdown(self) -> Option<u64> {
        match self {
            Evaluator::Tiered { after } => Some(after.min(u64::MAX - 1)),
            Evaluator::Compiled => Some(0),
            Evaluator::Flat => None,
        }
    }
}

impl Default for Evaluator {
    fn default() -> Self {
        Evaluator::Tiered {
            after: Evaluator::COMPILE_AFTER,
        }
    }
}

/// The evaluations before a program is compiled, for the whole process (`u64::MAX`: never).
static COMPILE_AFTER: AtomicU64 = AtomicU64::new(Evaluator::COMPILE_AFTER);

/// Chooses how the models of later solves are evaluated (the results are the same).
pub fn set_evaluator(evaluator: Evaluator) {
    let after = evaluator.countdown().unwrap_or(u64::MAX);
    COMPILE_AFTER.store(after, Ordering::Relaxed);
}

/// A program with its working memory: laid out in slots, and compiled once its evaluations
/// reach the countdown.
pub(crate) struct Runner {
    program: FlatProgram,
    /// Set once compiling was tried: the machine code, or `None` where the machine has no
    /// code generator (the flat evaluator then, with the same results).
    compiled: OnceCell<Option<Box<JitProgram>>>,
    /// The evaluations left before compiling; `None`: never.
    countdown: Cell<Option<u64>>,
    scratch: RefCell<Scratch>,
}

impl Runner {
    /// `program`, compiled as [`set_evaluator`] chose.
    fn new(program: FlatProgram) -> Self {
        let after = COMPILE_AFTER.load(Ordering::Relaxed);
        Runner::compiled_after(program, (after != u64::MAX).then_some(after))
    }

    /// `program`, compiled after `countdown` evaluations (`None`: never).
    fn compiled_after(program: FlatProgram, countdown: Option<u64>) -> Self {
        Runner {
            scratch: RefCell::new(program.scratch()),
            program,
            compiled: OnceCell::new(),
            countdown: Cell::new(countdown),
        }
    }

    fn program(&self) -> &FlatProgram {
        &self.program
    }

    /// The machine code, once compiled; compiles it when this evaluation ends the countdown.
    fn machine_code(&self) -> Option<&JitProgram> {
        if let Some(compiled) = self.compiled.get() {
            return compiled.as_deref();
        }
        match self.countdown.get()? {
            0 => {
                let compiled = JitProgram::new(self.program.clone()).ok().map(Box::new);
                self.compiled.get_or_init(|| compiled).as_deref()
            }
            left => {
                self.countdown.set(Some(left - 1));
                None
            }
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
        match self.machine_code() {
            Some(compiled) => compiled.run(inputs, scratch, out),
            None => self.program.run(inputs, scratch, out),
        }
    }

    /// Whether the program runs as machine code now.
    #[cfg(test)]
    fn is_compiled(&self) -> bool {
        matches!(self.compiled.get(), Some(Some(_)))
    }
}

/// A model's right-hand side, Jacobian and outputs, ready to be evaluated many times.
pub(crate) struct Engine {
    rhs: Runner,
    jacobian: Runner,
    outputs: Runner,
    /// The Jacobian, row-major, before it is copied into the runtime's rows.
    jacobian_values: RefCell<Vec<f64>>,
    /// Whether the outputs read the derivatives (else a recorded point's outputs need no
    /// right-hand side).
    outputs_read_ders: bool,
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
            outputs_read_ders: !model.outputs_program.reads().ders.is_empty(),
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

    /// The outputs at `(t, y)`, the derivatives evaluated into `dy` first only where the
    /// outputs read them (`dy` is left as it was otherwise): a recorded point costs one
    /// evaluation of the outputs, not a right-hand side more.
    pub(crate) fn outputs_at(
        &self,
        t: f64,
        y: &[f64],
        params: &[f64],
        dy: &mut [f64],
        out: &mut [f64],
    ) -> Result<(), EvalFailure> {
        if self.outputs_read_ders {
            self.rhs(t, y, params, dy)?;
        }
        self.outputs(t, y, dy, params, out)
    }

    /// The number of outputs.
    pub(crate) fn n_outputs(&self) -> usize {
        self.outputs.program().sink.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ModelFile;

    const TOP: &str = include_str!("../../../model-macros/examples/heavy_top.dsl");

    /// A runner counts its own evaluations, compiles at the count it was given, and gives the
    /// flat evaluator's values to the bit before and after.
    #[test]
    fn a_program_is_compiled_after_its_countdown_with_the_same_values() {
        let file = ModelFile::from_text("top.dsl", TOP).unwrap();
        let model = file.smooth(None).unwrap();
        let params: Vec<f64> = model.params.iter().map(|(_, v)| v.unwrap()).collect();
        let flat = FlatModel::new(model, params.len()).unwrap();
        let runner = Runner::compiled_after(flat.rhs.clone(), Some(3));
        let never = Runner::compiled_after(flat.rhs.clone(), None);
        let mut scratch = flat.rhs.scratch();
        let supported = cfg!(any(target_arch = "x86_64", target_arch = "aarch64"));
        for k in 0..8 {
            let y: Vec<f64> = (0..6).map(|i| 0.1 + 0.37 * (k * 6 + i) as f64).collect();
            let inputs = Inputs {
                t: 0.0,
                states: &y,
                params: &params,
                ders: &[],
            };
            let (mut want, mut got, mut flat_got) = ([0.0; 6], [0.0; 6], [0.0; 6]);
            flat.rhs.run(&inputs, &mut scratch, &mut want).unwrap();
            runner.run(&inputs, &mut got).unwrap();
            never.run(&inputs, &mut flat_got).unwrap();
            assert_eq!(
                got.map(f64::to_bits),
                want.map(f64::to_bits),
                "evaluation {k}"
            );
            assert_eq!(flat_got.map(f64::to_bits), want.map(f64::to_bits));
            // Three evaluations by the flat evaluator, the fourth compiles.
            assert_eq!(runner.is_compiled(), supported && k >= 3, "evaluation {k}");
            assert!(!never.is_compiled());
        }
    }
}
