//! The compiler's output: straight-line programs that the front end turns into Rust.
//!
//! Each emitted function (`rhs`, `jacobian`, `outputs`) is one [`Program`]: a list of
//! statements over numbered temporaries, in the order they must run, with every common
//! subexpression computed once. The front end translates it statement by statement; it does
//! no algebra of its own.

/// A value a statement reads.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Operand {
    /// A constant.
    Const(f64),
    /// `y[i]`: a state of the model being emitted (indices of the emitted model).
    State(usize),
    /// `p[i]`: a parameter of the model being emitted.
    Param(usize),
    /// `dy[i]`: a derivative; only in the `outputs` program, which is given `dy`.
    Der(usize),
    /// The time `t`.
    Time,
    /// A temporary defined by an earlier [`Stmt::Let`], [`Stmt::SinCos`] or [`Stmt::SolveBlock`].
    Tmp(u32),
}

/// A one-operation expression.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Node {
    /// A copy.
    Copy(Operand),
    /// `-a`
    Neg(Operand),
    /// `a + b`
    Add(Operand, Operand),
    /// `a - b`
    Sub(Operand, Operand),
    /// `a * b`
    Mul(Operand, Operand),
    /// `a / b`
    Div(Operand, Operand),
    /// `a.powi(n)`
    Powi(Operand, i32),
    /// `a.powf(b)`
    Powf(Operand, Operand),
    /// A one-argument function (never `Atan2`, `Hypot`, `Min` or `Max`).
    Call(crate::spec::Func, Operand),
    /// A two-argument function, `Atan2` or `Hypot`: `a.atan2(b)`, `a.hypot(b)` (that is,
    /// `atan2(a, b)`, `hypot(a, b)` in the DSL), by [`crate::expr::call2_value`].
    Call2(crate::spec::Func, Operand, Operand),
    /// `if a > b { c } else if a <= b { d } else { NaN }`: a condition, `min` or `max`, NaN when
    /// `a` or `b` is NaN (`crate::expr::select_value`).
    Select(Operand, Operand, Operand, Operand),
}

/// A sum inside a pivot (the pivot itself, or one factor of it) with the scale of its
/// rounding error: the sum of its terms' magnitudes as the program adds them.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SumCheck {
    /// The sum's value.
    pub sum: Operand,
    /// `Σ |term|` over the terms the sum adds.
    pub magnitude: Operand,
}

impl SumCheck {
    /// Whether the sum has lost all but `tolerance` of its magnitude to cancellation.
    pub fn cancelled(sum: f64, magnitude: f64, tolerance: f64) -> bool {
        sum.abs() <= tolerance * magnitude
    }
}

/// Where a result is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Target {
    /// `dy[i]`
    Der(usize),
    /// `out[k]`
    Output(usize),
    /// `jac[i][j]`
    Jac(usize, usize),
}

/// One statement.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Stmt {
    /// `let tK = node;`
    Let {
        /// The temporary defined.
        tmp: u32,
        /// Its value.
        node: Node,
    },
    /// `let (tS, tC) = arg.sin_cos();` — sine and cosine of one argument, computed together.
    SinCos {
        /// The temporary receiving the sine.
        sin: u32,
        /// The temporary receiving the cosine.
        cos: u32,
        /// The argument.
        arg: Operand,
    },
    /// Return `EvalError::SingularPivot` if the operand is zero or not finite, or if one of its
    /// sums has cancelled: `|sum| <= tolerance * magnitude`.
    CheckPivot {
        /// The pivot's value.
        value: Operand,
        /// The pivot as the user would write it (e.g. `sin(theta)`).
        text: String,
        /// The sums of the pivot tested for cancellation (empty when the tolerance is zero or
        /// the pivot has none).
        sums: Vec<SumCheck>,
        /// The fraction of its magnitude below which a sum counts as cancelled.
        tolerance: f64,
    },
    /// Solve the `n × n` system `A x = b` at run time by Gaussian elimination with partial
    /// pivoting (used where a symbolic solution would swell); a zero or non-finite pivot
    /// returns `EvalError::SingularPivot` with `text`.
    SolveBlock {
        /// The block's size.
        n: usize,
        /// `A`, row-major, `n * n` entries.
        matrix: Vec<Operand>,
        /// `b`, `n` entries.
        rhs: Vec<Operand>,
        /// The temporaries receiving `x`, `n` entries.
        result: Vec<u32>,
        /// The block named by its derivatives, e.g. `der(V_X), der(V_Y)`.
        text: String,
    },
    /// `target = value;` — after all stores to `dy`, the front end checks they are finite.
    Store {
        /// Where.
        target: Target,
        /// What.
        value: Operand,
    },
}

/// One emitted function's body.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Program {
    /// The statements, in execution order.
    pub stmts: Vec<Stmt>,
}

/// A compiled model: names and the three programs.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CompiledModel {
    /// The module name.
    pub name: String,
    /// State names, in index order.
    pub states: Vec<String>,
    /// Parameter names (fixed parameters of a variant are gone), with defaults.
    pub params: Vec<(String, Option<f64>)>,
    /// Output names, in order.
    pub outputs: Vec<String>,
    /// `dy = f(t, y, p)`.
    pub rhs: Program,
    /// `jac[i][j] = ∂f_i/∂y_j` (only nonzero entries are stored; the front end zeroes the rest).
    pub jacobian: Program,
    /// `out = g(t, y, dy, p)`.
    pub outputs_program: Program,
    /// Texts of the pivots checked at run time.
    pub pivots: Vec<String>,
    /// Texts of the blocks solved numerically.
    pub numeric_blocks: Vec<String>,
    /// The reduced variants, compiled.
    pub variants: Vec<CompiledModel>,
    /// The solved equations, printed (Markdown and LaTeX).
    pub explanation: Explanation,
    /// Each state's initial value as the model's text writes it (`states { x = 2 }`), `None`
    /// where none is written. The compiler leaves every one unwritten: initial values are no
    /// part of the equations, and the front end that read the text fills them in.
    pub initial: Vec<Option<f64>>,
}

/// The solved model, printed.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Explanation {
    /// Markdown: one section per block (its derivatives, the pivots, the solved equations in
    /// DSL syntax), then the outputs.
    pub markdown: String,
    /// A LaTeX `align*` environment of the same equations.
    pub latex: String,
    /// Every output's expression as solved, in the DSL's syntax and in LaTeX (the front end's
    /// internal outputs included, which the two texts above leave out).
    pub outputs: Vec<(String, String)>,
}
