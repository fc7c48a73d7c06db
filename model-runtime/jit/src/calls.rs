//! The Rust functions generated code calls, by address: each evaluates exactly as the flat
//! evaluator does, by calling the same function ([`Unary::apply`], [`Binary::apply`],
//! `f64::sin_cos`, [`solve_dense_in`]).

use cranelift_codegen::ir::{types, AbiParam, Signature, Type};
use model_algebra::{solve_dense_in, Binary, Block, Func, Unary};

/// A function generated code may call.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Callee {
    /// A one-argument function (`sqrt` and `abs` are instructions instead).
    Unary(Func),
    /// `pow`, `atan2` or `hypot`.
    Binary(Binary),
    /// `sin_cos(x)` into `work[0]`, `work[1]`.
    SinCos,
    /// A numeric block's solve on `work`.
    Solve,
}

impl Callee {
    /// Every callee, for the module's symbol table.
    pub(crate) const ALL: [Callee; 12] = [
        Callee::Unary(Func::Sin),
        Callee::Unary(Func::Cos),
        Callee::Unary(Func::Tan),
        Callee::Unary(Func::Exp),
        Callee::Unary(Func::Ln),
        Callee::Unary(Func::Sign),
        Callee::Unary(Func::Sqrt),
        Callee::Binary(Binary::Powf),
        Callee::Binary(Binary::Call(Func::Atan2)),
        Callee::Binary(Binary::Call(Func::Hypot)),
        Callee::SinCos,
        Callee::Solve,
    ];

    /// The symbol's name.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Callee::Unary(Func::Sin) => "model_sin",
            Callee::Unary(Func::Cos) => "model_cos",
            Callee::Unary(Func::Tan) => "model_tan",
            Callee::Unary(Func::Exp) => "model_exp",
            Callee::Unary(Func::Ln) => "model_ln",
            Callee::Unary(Func::Sign) => "model_sign",
            // Only `sqrt` is left: the generator calls no other one-argument function here.
            Callee::Unary(_) => "model_sqrt",
            Callee::Binary(Binary::Powf) => "model_pow",
            Callee::Binary(Binary::Call(Func::Hypot)) => "model_hypot",
            // Only `atan2` is left: the generator calls no other two-argument function here.
            Callee::Binary(_) => "model_atan2",
            Callee::SinCos => "model_sin_cos",
            Callee::Solve => "model_solve",
        }
    }

    /// The function's address.
    pub(crate) fn address(self) -> *const u8 {
        match self {
            Callee::Unary(Func::Sin) => sin as *const u8,
            Callee::Unary(Func::Cos) => cos as *const u8,
            Callee::Unary(Func::Tan) => tan as *const u8,
            Callee::Unary(Func::Exp) => exp as *const u8,
            Callee::Unary(Func::Ln) => ln as *const u8,
            Callee::Unary(Func::Sign) => sign as *const u8,
            Callee::Unary(_) => sqrt as *const u8,
            Callee::Binary(Binary::Powf) => pow as *const u8,
            Callee::Binary(Binary::Call(Func::Hypot)) => hypot as *const u8,
            Callee::Binary(_) => atan2 as *const u8,
            Callee::SinCos => sin_cos as *const u8,
            Callee::Solve => solve as *const u8,
        }
    }

    /// Its signature.
    pub(crate) fn signature(self, sig: &mut Signature, pointer: Type) {
        let f = AbiParam::new(types::F64);
        let (params, returns): (Vec<AbiParam>, Vec<AbiParam>) = match self {
            Callee::Unary(_) => (vec![f], vec![f]),
            Callee::Binary(_) => (vec![f, f], vec![f]),
            Callee::SinCos => (vec![f, AbiParam::new(pointer)], vec![]),
            Callee::Solve => (
                vec![AbiParam::new(pointer), AbiParam::new(pointer)],
                vec![AbiParam::new(types::I32)],
            ),
        };
        sig.params = params;
        sig.returns = returns;
    }
}

extern "C" fn sin(x: f64) -> f64 {
    Unary::Call(Func::Sin).apply(x)
}

extern "C" fn cos(x: f64) -> f64 {
    Unary::Call(Func::Cos).apply(x)
}

extern "C" fn tan(x: f64) -> f64 {
    Unary::Call(Func::Tan).apply(x)
}

extern "C" fn exp(x: f64) -> f64 {
    Unary::Call(Func::Exp).apply(x)
}

extern "C" fn ln(x: f64) -> f64 {
    Unary::Call(Func::Ln).apply(x)
}

extern "C" fn sign(x: f64) -> f64 {
    Unary::Call(Func::Sign).apply(x)
}

/// `sqrt` (generated as an instruction; in the table so that every entry has a symbol).
extern "C" fn sqrt(x: f64) -> f64 {
    Unary::Call(Func::Sqrt).apply(x)
}

extern "C" fn pow(x: f64, y: f64) -> f64 {
    Binary::Powf.apply(x, y)
}

extern "C" fn atan2(x: f64, y: f64) -> f64 {
    Binary::Call(Func::Atan2).apply(x, y)
}

extern "C" fn hypot(x: f64, y: f64) -> f64 {
    Binary::Call(Func::Hypot).apply(x, y)
}

/// # Safety
/// `work` points to at least two values.
unsafe extern "C" fn sin_cos(x: f64, work: *mut f64) {
    let (s, c) = x.sin_cos();
    // SAFETY: the caller's contract.
    unsafe {
        *work = s;
        *work.add(1) = c;
    }
}

/// Solves the block whose `A` and `b` the generated code stored at `work[2..]` (row-major `A`,
/// then `b`), its solution after them; a singular pivot's value goes to `work[0]` and the
/// result is 1.
///
/// # Safety
/// `block` points to a live [`Block`] and `work` to at least `2 + n² + 2n` values.
unsafe extern "C" fn solve(block: *const Block, work: *mut f64) -> u32 {
    // SAFETY: the caller's contract.
    let (n, work) = unsafe {
        let n = (*block).n;
        (n, std::slice::from_raw_parts_mut(work, 2 + n * n + 2 * n))
    };
    let (head, rest) = work.split_at_mut(2);
    let (a, rest) = rest.split_at_mut(n * n);
    let (b, x) = rest.split_at_mut(n);
    match solve_dense_in(n, a, b, x) {
        Ok(()) => 0,
        Err(pivot) => {
            head[0] = pivot;
            1
        }
    }
}
