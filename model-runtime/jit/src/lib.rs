//! A model's flat programs ([`FlatProgram`]) compiled to machine code with Cranelift when the
//! model is read, so that a model read at run time evaluates about as fast as one compiled by
//! `model!`.
//!
//! The flat evaluator dispatches on every operation and keeps every value in memory; here each
//! program becomes one function whose values live in registers. The results are the flat
//! evaluator's to the bit: additions, subtractions, multiplications, divisions, negations,
//! square roots, absolute values and comparisons are single IEEE operations in both (Cranelift
//! never fuses a multiplication into an addition), an integer power is the runtime's `powi`'s
//! own multiplications, written out, and every other function (`sin`, `cos`,
//! `tan`, `exp`, `ln`, `sign`, `pow`, `atan2`, `hypot`, `sin_cos`, the numeric blocks' solve) is
//! called in the very Rust function the flat evaluator calls ([`Unary::apply`],
//! [`Binary::apply`], [`Block::run`]), passed to the generated code by address. The pivot checks
//! compute `SumCheck::cancelled` and the finiteness test with the same operations.
//!
//! Only the compiler's own programs are compiled, never anything read from disk as code: the
//! input is a [`FlatProgram`] built in this process. [`JitProgram::new`] fails (and the caller
//! keeps the flat evaluator) where Cranelift has no backend for the host.

use std::fmt;

use cranelift_codegen::ir::condcodes::FloatCC;
use cranelift_codegen::ir::{types, AbiParam, InstBuilder, MemFlagsData, Signature, Value};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{FuncId, Linkage, Module};
use model_algebra::{
    Binary, Block, EvalFailure, FlatProgram, Func, Inputs, Layout, Op, Scratch, Slot, Unary,
};

mod calls;

use calls::Callee;

/// Why a program was not compiled (the caller evaluates it with the flat evaluator instead).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum JitError {
    /// Cranelift has no backend for this machine.
    Unsupported(String),
    /// Cranelift refused the function (a bug here, reported rather than run).
    Codegen(String),
}

impl fmt::Display for JitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            JitError::Unsupported(why) => write!(f, "no code generator for this machine: {why}"),
            JitError::Codegen(why) => write!(f, "code generation failed: {why}"),
        }
    }
}

impl std::error::Error for JitError {}

/// The generated function: `(t, states, params, ders, out, work) -> status`, where status 0 is
/// success, `1 + k` a failed pivot check `k` and `1 + checks + k` a singular block `k`, the
/// failing pivot's value left in `work[0]`.
type Compiled =
    unsafe extern "C" fn(f64, *const f64, *const f64, *const f64, *mut f64, *mut f64) -> u32;

/// A program compiled to machine code, with the flat program it came from (its checks' and
/// blocks' texts, its shape).
pub struct JitProgram {
    flat: FlatProgram,
    function: Compiled,
    /// Owns the code `function` points into; dropped with it, never freed before.
    _module: JITModule,
}

impl fmt::Debug for JitProgram {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("JitProgram")
            .field("flat", &self.flat)
            .finish_non_exhaustive()
    }
}

/// Everything the generated code calls back into, by address: the blocks' solve reads the
/// block from here.
#[repr(C)]
struct BlockCall {
    block: *const Block,
}

impl JitProgram {
    /// Compiles `flat` for this machine.
    pub fn new(flat: FlatProgram) -> Result<Self, JitError> {
        let isa_builder =
            cranelift_native::builder().map_err(|e| JitError::Unsupported(e.to_string()))?;
        let mut flags = settings::builder();
        let set = |flags: &mut settings::Builder, name, value| {
            flags
                .set(name, value)
                .map_err(|e| JitError::Codegen(e.to_string()))
        };
        set(&mut flags, "opt_level", "speed")?;
        set(&mut flags, "use_colocated_libcalls", "false")?;
        set(&mut flags, "is_pic", "false")?;
        let isa = isa_builder
            .finish(settings::Flags::new(flags))
            .map_err(|e| JitError::Codegen(e.to_string()))?;
        let mut builder = JITBuilder::with_isa(isa, cranelift_module::default_libcall_names());
        for callee in Callee::ALL {
            builder.symbol(callee.name(), callee.address());
        }
        let mut module = JITModule::new(builder);
        let id = define(&mut module, &flat)?;
        module
            .finalize_definitions()
            .map_err(|e| JitError::Codegen(e.to_string()))?;
        let code = module.get_finalized_function(id);
        // SAFETY: `code` is the function just defined with the signature `Compiled` describes
        // (`signature` below), kept alive by `module`, which lives as long as `self`.
        let function = unsafe { std::mem::transmute::<*const u8, Compiled>(code) };
        Ok(JitProgram {
            flat,
            function,
            _module: module,
        })
    }

    /// The flat program compiled.
    pub fn flat(&self) -> &FlatProgram {
        &self.flat
    }

    /// Runs the program on `inputs`, writing its stores into `out` (of the sink's length), as
    /// [`FlatProgram::run`] does, with the same results and failures. `scratch` comes from
    /// the flat program's [`FlatProgram::scratch`].
    pub fn run(
        &self,
        inputs: &Inputs,
        scratch: &mut Scratch,
        out: &mut [f64],
    ) -> Result<(), EvalFailure> {
        let shape = self.flat.layout.shape;
        let short = |len: usize, n: usize| len < n;
        if short(inputs.states.len(), shape.states)
            || short(inputs.params.len(), shape.params)
            || short(inputs.ders.len(), shape.ders)
        {
            // The flat evaluator names the missing operand.
            return self.flat.run(inputs, scratch, out);
        }
        let out = &mut out[..self.flat.sink.len()];
        if self.flat.zero_first {
            out.fill(0.0);
        }
        let work = scratch.work();
        // SAFETY: the function reads `shape.states`, `shape.params` and `shape.ders` values
        // (checked above), writes below `sink.len()` into `out` (sliced above) and uses `work`
        // as `Scratch::work` sizes it (at least one value and every block's `n² + 2n`).
        let status = unsafe {
            (self.function)(
                inputs.t,
                inputs.states.as_ptr(),
                inputs.params.as_ptr(),
                inputs.ders.as_ptr(),
                out.as_mut_ptr(),
                work.as_mut_ptr(),
            )
        };
        if status == 0 {
            return Ok(());
        }
        let k = status as usize - 1;
        let value = work[0];
        match self.flat.checks.get(k) {
            Some(check) => Err(check.failure(value)),
            None => Err(EvalFailure::SingularPivot {
                text: self.flat.blocks[k - self.flat.checks.len()].text.clone(),
                value,
            }),
        }
    }
}

/// Every load and store: aligned, and never trapping (the pointers are the caller's slices).
const MEM: MemFlagsData = MemFlagsData::trusted();

/// The generated function's signature.
fn signature(module: &JITModule) -> Signature {
    let pointer = module.target_config().pointer_type();
    let mut sig = module.make_signature();
    sig.params.push(AbiParam::new(types::F64));
    for _ in 0..5 {
        sig.params.push(AbiParam::new(pointer));
    }
    sig.returns.push(AbiParam::new(types::I32));
    sig
}

/// Defines the program's function in `module`.
fn define(module: &mut JITModule, flat: &FlatProgram) -> Result<FuncId, JitError> {
    let codegen = |e: cranelift_module::ModuleError| JitError::Codegen(e.to_string());
    let sig = signature(module);
    let id = module
        .declare_function("program", Linkage::Export, &sig)
        .map_err(codegen)?;
    let mut ctx = module.make_context();
    ctx.func.signature = sig;
    let mut fctx = FunctionBuilderContext::new();
    let frontend = module.isa().frontend_config();
    {
        let mut b = FunctionBuilder::new(&mut ctx.func, &mut fctx);
        let entry = b.create_block();
        b.append_block_params_for_function_params(entry);
        b.switch_to_block(entry);
        b.seal_block(entry);
        let params = b.block_params(entry).to_vec();
        let mut g = Generator {
            flat,
            module,
            values: vec![None; flat.layout.slots],
            t: params[0],
            inputs: [params[1], params[2], params[3]],
            out: params[4],
            work: params[5],
        };
        for &(slot, v) in &flat.constants {
            g.values[slot as usize] = Some(b.ins().f64const(v));
        }
        for (k, op) in flat.ops.iter().enumerate() {
            g.op(&mut b, k, op)?;
        }
        let ok = b.ins().iconst(types::I32, 0);
        b.ins().return_(&[ok]);
        b.finalize(frontend);
    }
    module.define_function(id, &mut ctx).map_err(codegen)?;
    module.clear_context(&mut ctx);
    Ok(id)
}

/// The state of code generation: each slot's value where it is defined.
struct Generator<'a> {
    flat: &'a FlatProgram,
    module: &'a mut JITModule,
    values: Vec<Option<Value>>,
    t: Value,
    /// The states', parameters' and derivatives' pointers.
    inputs: [Value; 3],
    out: Value,
    work: Value,
}

impl Generator<'_> {
    /// The value of `slot`: an input is loaded where it is first read (that block dominates
    /// every later one: the code is straight-line with side exits).
    fn get(&mut self, b: &mut FunctionBuilder, slot: Slot) -> Value {
        if let Some(v) = self.values[slot as usize] {
            return v;
        }
        let l: &Layout = &self.flat.layout;
        let v = if slot == Layout::TIME {
            self.t
        } else {
            let (base, first) = if slot < l.params() {
                (self.inputs[0], l.states())
            } else if slot < l.ders() {
                (self.inputs[1], l.params())
            } else {
                (self.inputs[2], l.ders())
            };
            let offset = 8 * (slot - first) as i32;
            b.ins().load(types::F64, MEM, base, offset)
        };
        self.values[slot as usize] = Some(v);
        v
    }

    fn set(&mut self, slot: Slot, v: Value) {
        self.values[slot as usize] = Some(v);
    }

    /// A call of `callee` with `args`; its one result, if it has one.
    fn call(
        &mut self,
        b: &mut FunctionBuilder,
        callee: Callee,
        args: &[Value],
    ) -> Result<Option<Value>, JitError> {
        let pointer = self.module.target_config().pointer_type();
        let mut sig = self.module.make_signature();
        callee.signature(&mut sig, pointer);
        let id = self
            .module
            .declare_function(callee.name(), Linkage::Import, &sig)
            .map_err(|e| JitError::Codegen(e.to_string()))?;
        let f = self.module.declare_func_in_func(id, b.func);
        let call = b.ins().call(f, args);
        Ok(b.inst_results(call).first().copied())
    }

    /// Returns `status` with `value` in `work[0]` when `failed`; goes on otherwise.
    fn exit_if(&mut self, b: &mut FunctionBuilder, failed: Value, status: u32, value: Value) {
        let fail = b.create_block();
        let next = b.create_block();
        b.ins().brif(failed, fail, &[], next, &[]);
        b.switch_to_block(fail);
        b.seal_block(fail);
        b.ins().store(MEM, value, self.work, 0);
        let code = b.ins().iconst(types::I32, status as i64);
        b.ins().return_(&[code]);
        b.switch_to_block(next);
        b.seal_block(next);
    }

    fn op(&mut self, b: &mut FunctionBuilder, _k: usize, op: &Op) -> Result<(), JitError> {
        match *op {
            Op::Unary { op, dst, a } => {
                let a = self.get(b, a);
                let v = match op {
                    Unary::Copy => a,
                    Unary::Neg => b.ins().fneg(a),
                    Unary::Call(Func::Sqrt) => b.ins().sqrt(a),
                    Unary::Call(Func::Abs) => b.ins().fabs(a),
                    Unary::Powi(n) => powi(b, a, n),
                    Unary::Call(
                        f @ (Func::Sin | Func::Cos | Func::Tan | Func::Exp | Func::Ln | Func::Sign),
                    ) => self.call(b, Callee::Unary(f), &[a])?.expect("a result"),
                    // A two-argument function as a unary operation is a compiler bug: refused
                    // here (the flat evaluator then runs the program and reports it), never
                    // sent to a function of another name.
                    Unary::Call(f) => {
                        return Err(JitError::Codegen(format!("`{f:?}` as a one-argument call")))
                    }
                };
                self.set(dst, v);
            }
            Op::Binary { op, dst, a, b: c } => {
                let (x, y) = (self.get(b, a), self.get(b, c));
                let v = match op {
                    Binary::Add => b.ins().fadd(x, y),
                    Binary::Sub => b.ins().fsub(x, y),
                    Binary::Mul => b.ins().fmul(x, y),
                    Binary::Div => b.ins().fdiv(x, y),
                    Binary::Powf | Binary::Call(Func::Atan2 | Func::Hypot) => self
                        .call(b, Callee::Binary(op), &[x, y])?
                        .expect("a result"),
                    // A one-argument function as a binary operation is a compiler bug: refused
                    // here, as above.
                    Binary::Call(f) => {
                        return Err(JitError::Codegen(format!("`{f:?}` as a two-argument call")))
                    }
                };
                self.set(dst, v);
            }
            Op::Select { dst, args } => {
                let [lhs, rhs, then, otherwise] = args.map(|s| self.get(b, s));
                // `select_value`: `then` where lhs > rhs, `otherwise` where lhs <= rhs, NaN
                // where neither (an operand is NaN).
                let gt = b.ins().fcmp(FloatCC::GreaterThan, lhs, rhs);
                let le = b.ins().fcmp(FloatCC::LessThanOrEqual, lhs, rhs);
                let nan = b.ins().f64const(f64::NAN);
                let other = b.ins().select(le, otherwise, nan);
                let v = b.ins().select(gt, then, other);
                self.set(dst, v);
            }
            Op::SinCos { sin, cos, arg } => {
                let x = self.get(b, arg);
                self.call(b, Callee::SinCos, &[x, self.work])?;
                let s = b.ins().load(types::F64, MEM, self.work, 0);
                let c = b.ins().load(types::F64, MEM, self.work, 8);
                self.set(sin, s);
                self.set(cos, c);
            }
            Op::Check(k) => {
                let check = &self.flat.checks[k as usize];
                let v = self.get(b, check.value);
                // `v == 0 || !v.is_finite() || cancelled`, as `Check::run` computes it.
                let zero = b.ins().f64const(0.0);
                let is_zero = b.ins().fcmp(FloatCC::Equal, v, zero);
                let magnitude = b.ins().fabs(v);
                let infinity = b.ins().f64const(f64::INFINITY);
                let finite = b.ins().fcmp(FloatCC::LessThan, magnitude, infinity);
                let mut failed = b.ins().bnot(finite);
                failed = b.ins().bor(failed, is_zero);
                let tolerance = b.ins().f64const(check.tolerance);
                for &(sum, scale) in &check.sums.clone() {
                    let (s, m) = (self.get(b, sum), self.get(b, scale));
                    let s = b.ins().fabs(s);
                    let bound = b.ins().fmul(tolerance, m);
                    let cancelled = b.ins().fcmp(FloatCC::LessThanOrEqual, s, bound);
                    failed = b.ins().bor(failed, cancelled);
                }
                // `bnot` of a comparison's 0/1 sets the upper bits: keep the lowest one.
                let failed = b.ins().band_imm_u(failed, 1);
                self.exit_if(b, failed, 1 + k, v);
            }
            Op::Solve(k) => {
                let block = &self.flat.blocks[k as usize];
                // The block's entries go to `work[1..]`, which `jit_solve` hands to
                // `Block::run` as the slots it reads and writes.
                let slots: Vec<Slot> = block.matrix.iter().chain(&block.rhs).copied().collect();
                let base = solve_base(block);
                for (i, &s) in slots.iter().enumerate() {
                    let v = self.get(b, s);
                    b.ins().store(MEM, v, self.work, 8 * (base + i) as i32);
                }
                let pointer = self.module.target_config().pointer_type();
                let call = BlockCall { block };
                // The block outlives the code: `self.flat` is moved into the `JitProgram`
                // that owns both, and a `Vec`'s elements stay where they are.
                let address = b.ins().iconst(pointer, call.block as i64);
                let status = self
                    .call(b, Callee::Solve, &[address, self.work])?
                    .expect("a result");
                let failed = b.ins().icmp_imm_u(
                    cranelift_codegen::ir::condcodes::IntCC::NotEqual,
                    status,
                    0,
                );
                let pivot = b.ins().load(types::F64, MEM, self.work, 0);
                self.exit_if(b, failed, 1 + self.flat.checks.len() as u32 + k, pivot);
                for (i, &r) in block.result.iter().enumerate() {
                    let offset = 8 * (base + slots.len() + i) as i32;
                    let v = b.ins().load(types::F64, MEM, self.work, offset);
                    self.set(r, v);
                }
            }
            Op::Store { index, value } => {
                let v = self.get(b, value);
                b.ins().store(MEM, v, self.out, 8 * index as i32);
            }
        }
        Ok(())
    }
}

/// `a.powi(n)` as the multiplications and the one division the runtime's `powi` makes
/// (`__powidf2`, by squaring: the odd bits' powers multiplied in from the lowest up, the
/// reciprocal last for a negative `n`), so the same IEEE operations in the same order and the
/// same result to the bit, without a call.
fn powi(b: &mut FunctionBuilder, a: Value, n: i32) -> Value {
    let mut bits = n.unsigned_abs();
    let mut power = a;
    let mut product: Option<Value> = None;
    loop {
        if bits & 1 != 0 {
            product = Some(match product {
                Some(p) => b.ins().fmul(p, power),
                None => power,
            });
        }
        bits >>= 1;
        if bits == 0 {
            break;
        }
        power = b.ins().fmul(power, power);
    }
    let product = product.unwrap_or_else(|| b.ins().f64const(1.0));
    match n < 0 {
        true => {
            let one = b.ins().f64const(1.0);
            b.ins().fdiv(one, product)
        }
        false => product,
    }
}

/// Where a block's values start in `work`: after the failing value at `work[0]` and the
/// sine and cosine at `work[0..2]`.
fn solve_base(_block: &Block) -> usize {
    2
}

#[cfg(test)]
mod tests {
    use super::*;
    use model_algebra::{Node, Operand, Program, Shape, Sink, Stmt, Target};

    /// `x^n` for every `n` in `-12..=12` and the `n` of a few larger powers, as one program.
    fn powers(exponents: &[i32]) -> FlatProgram {
        let mut stmts = Vec::new();
        for (k, &n) in exponents.iter().enumerate() {
            stmts.push(Stmt::Let {
                tmp: k as u32,
                node: Node::Powi(Operand::State(0), n),
            });
            stmts.push(Stmt::Store {
                target: Target::Der(k),
                value: Operand::Tmp(k as u32),
            });
        }
        let shape = Shape {
            states: 1,
            ..Shape::default()
        };
        FlatProgram::new(&Program { stmts }, shape, Sink::Ders(exponents.len())).unwrap()
    }

    /// The integer powers written out are Rust's `powi`, to the bit, on ordinary, tiny,
    /// huge, signed-zero, infinite and NaN bases.
    #[test]
    fn integer_powers_are_the_runtimes_powi_to_the_bit() {
        let exponents: Vec<i32> = (-12..=12).chain([31, -31, 64, 1023, -1075]).collect();
        let flat = powers(&exponents);
        let Ok(jit) = JitProgram::new(flat.clone()) else {
            return; // No code generator for this machine: nothing compiled to compare.
        };
        let mut scratch = flat.scratch();
        let bases = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            -0.7,
            1.0000001,
            3.0,
            -2.5,
            1e-160,
            5e-324,
            1e154,
            -1e200,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            std::f64::consts::PI,
        ];
        let mut out = vec![0.0; exponents.len()];
        for x in bases {
            let inputs = Inputs {
                t: 0.0,
                states: &[x],
                params: &[],
                ders: &[],
            };
            jit.run(&inputs, &mut scratch, &mut out).unwrap();
            for (&n, got) in exponents.iter().zip(&out) {
                assert_eq!(got.to_bits(), x.powi(n).to_bits(), "{x}^{n}: {got}");
            }
        }
    }
}
