//! Operation counts of the code the equation compiler emits.
//!
//! The compiler (`model-algebra`) counts the operations of every program it emits, and the
//! runtime (`model-runtime`) reports them in a model's `ModelInfo`; the interpreter hands the
//! one to the other. The two crates do not depend on each other (the compiler runs in the
//! build, the runtime in the simulation), so the type they share lives here, in a crate of its
//! own with no dependencies, instead of twice with a conversion between the copies.

/// Operation counts of one emitted function, after common-subexpression elimination.
///
/// Counted on the straight-line code the compiler emits: every `+`/`-` (and negation) is an
/// add, every `*` a mul, every `/` a div; `sqrt`, the trigonometric functions and the
/// transcendental ones are counted apart because they cost far more.
///
/// ```
/// use model_ops::OpCounts;
/// let ops = OpCounts { add: 3, mul: 2, trig: 1, ..OpCounts::default() };
/// assert_eq!(ops.total(), 6);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCounts {
    /// Additions and subtractions (including negations); also the comparisons of `sign`,
    /// `min`, `max` and `if` (one each: a comparison costs what a subtraction does).
    pub add: u32,
    /// Multiplications (integer powers count as the multiplications they expand to).
    pub mul: u32,
    /// Divisions.
    pub div: u32,
    /// Square roots (`hypot`, a square root of a sum of squares, counts as one).
    pub sqrt: u32,
    /// Trigonometric calls (`sin`, `cos`, `tan`, `atan2`); a shared `sin_cos` counts once.
    pub trig: u32,
    /// Other transcendental calls (`exp`, `ln`, `powf`; `abs` is not counted).
    pub transcendental: u32,
}

impl OpCounts {
    /// No operations: a hand-written model has no emitted code to count.
    pub const NONE: OpCounts = OpCounts {
        add: 0,
        mul: 0,
        div: 0,
        sqrt: 0,
        trig: 0,
        transcendental: 0,
    };

    /// All operations, weighted equally.
    pub fn total(&self) -> u32 {
        self.add + self.mul + self.div + self.sqrt + self.trig + self.transcendental
    }
}

impl std::ops::AddAssign for OpCounts {
    fn add_assign(&mut self, other: OpCounts) {
        self.add += other.add;
        self.mul += other.mul;
        self.div += other.div;
        self.sqrt += other.sqrt;
        self.trig += other.trig;
        self.transcendental += other.transcendental;
    }
}
