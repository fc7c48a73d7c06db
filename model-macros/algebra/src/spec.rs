//! The compiler's input: a model as the parser read it, before any algebra.
//!
//! The proc-macro front end (which owns the spans) builds a [`ModelSpec`]; every node of every
//! expression carries a [`NodeId`] so that a diagnostic found here can be pointed back at the
//! user's token. Names are resolved by the front end: a [`Ast::Name`] here is known to be a
//! parameter, a state, a let, an earlier output, `t` or `pi`.

/// Identifies one node of the user's source (the front end maps it to a span).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct NodeId(pub u32);

/// The built-in functions of the DSL.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Func {
    /// `sin(x)`
    Sin,
    /// `cos(x)`
    Cos,
    /// `tan(x)`
    Tan,
    /// `sqrt(x)`
    Sqrt,
    /// `exp(x)`
    Exp,
    /// `ln(x)`
    Ln,
    /// `abs(x)`
    Abs,
    /// `atan2(y, x)` (two arguments)
    Atan2,
    /// `hypot(x, y)`: `sqrt(x^2 + y^2)` without overflow or underflow, as `f64::hypot` rounds
    /// it (two arguments)
    Hypot,
    /// `sign(x)`: `-1`, `0` or `1` (`0` at zero, NaN stays NaN)
    Sign,
    /// `min(a, b)` (two arguments; NaN if either is NaN)
    Min,
    /// `max(a, b)` (two arguments; NaN if either is NaN)
    Max,
}

impl Func {
    /// The function's name as written in the DSL.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Sqrt => "sqrt",
            Func::Exp => "exp",
            Func::Ln => "ln",
            Func::Abs => "abs",
            Func::Atan2 => "atan2",
            Func::Hypot => "hypot",
            Func::Sign => "sign",
            Func::Min => "min",
            Func::Max => "max",
        }
    }

    /// Looks a function up by its DSL name.
    pub fn from_name(name: &str) -> Option<Func> {
        Some(match name {
            "sin" => Func::Sin,
            "cos" => Func::Cos,
            "tan" => Func::Tan,
            "sqrt" => Func::Sqrt,
            "exp" => Func::Exp,
            "ln" => Func::Ln,
            "abs" => Func::Abs,
            "atan2" => Func::Atan2,
            "hypot" => Func::Hypot,
            "sign" => Func::Sign,
            "min" => Func::Min,
            "max" => Func::Max,
            _ => return None,
        })
    }

    /// How many arguments the function takes.
    pub fn arity(self) -> usize {
        match self {
            Func::Atan2 | Func::Hypot | Func::Min | Func::Max => 2,
            _ => 1,
        }
    }
}

/// Binary operators of the DSL.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^`
    Pow,
}

/// The comparison of a condition (`==` has no place in one: two computed values are
/// practically never equal).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CmpOp {
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
}

impl CmpOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            CmpOp::Lt => "<",
            CmpOp::Le => "<=",
            CmpOp::Gt => ">",
            CmpOp::Ge => ">=",
        }
    }
}

/// A condition `lhs op rhs`, as in `if(v > vb, a, b)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Condition {
    /// The node of the whole comparison.
    pub id: NodeId,
    /// Left-hand side.
    pub lhs: Ast,
    /// The comparison.
    pub op: CmpOp,
    /// Right-hand side.
    pub rhs: Ast,
}

/// An expression as written, with the source node of every part.
#[derive(Clone, Debug, PartialEq)]
pub enum Ast {
    /// A numeric literal.
    Num(NodeId, f64),
    /// A resolved name: parameter, state, let, output, `t` or `pi`.
    Name(NodeId, String),
    /// `-x`
    Neg(NodeId, Box<Ast>),
    /// `x op y`
    Bin(NodeId, BinOp, Box<Ast>, Box<Ast>),
    /// `f(args..)`
    Call(NodeId, Func, Vec<Ast>),
    /// `der(x)`
    Der(NodeId, Box<Ast>),
    /// `if(condition, then, otherwise)`: `then` where the condition holds, else `otherwise`.
    If(NodeId, Box<Condition>, Box<Ast>, Box<Ast>),
}

impl Ast {
    /// The node this expression came from.
    pub fn id(&self) -> NodeId {
        match self {
            Ast::Num(id, _)
            | Ast::Name(id, _)
            | Ast::Neg(id, _)
            | Ast::Bin(id, ..)
            | Ast::Call(id, ..)
            | Ast::Der(id, _)
            | Ast::If(id, ..) => *id,
        }
    }

    /// The direct subexpressions, in source order (an `if`'s comparison sides first).
    pub fn children(&self) -> Vec<&Ast> {
        match self {
            Ast::Num(..) | Ast::Name(..) => vec![],
            Ast::Neg(_, a) | Ast::Der(_, a) => vec![a],
            Ast::Bin(_, _, a, b) => vec![a, b],
            Ast::Call(_, _, args) => args.iter().collect(),
            Ast::If(_, c, a, b) => vec![&c.lhs, &c.rhs, a, b],
        }
    }
}

/// A named item with its source node.
#[derive(Clone, Debug, PartialEq)]
pub struct Named<T> {
    /// The name as written.
    pub name: String,
    /// The node of the name token.
    pub id: NodeId,
    /// The payload.
    pub value: T,
}

/// One implicit equation `lhs = rhs`.
#[derive(Clone, Debug, PartialEq)]
pub struct EquationSpec {
    /// The label (`R4`), or `equation K` when none was written.
    pub label: String,
    /// The node of the label (or of the `=` when unlabelled).
    pub id: NodeId,
    /// Left-hand side.
    pub lhs: Ast,
    /// Right-hand side.
    pub rhs: Ast,
}

/// A reduced variant: keep only what some quantities need, fix some parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct VariantSpec {
    /// The variant's module name.
    pub name: String,
    /// The node of the name.
    pub id: NodeId,
    /// States and outputs to keep, by name, with their nodes.
    pub keep: Vec<Named<()>>,
    /// Parameters fixed at compile time.
    pub fix: Vec<Named<f64>>,
}

/// A whole model as the front end read it.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelSpec {
    /// The module name.
    pub name: String,
    /// Parameters with optional defaults.
    pub params: Vec<Named<Option<f64>>>,
    /// States, in index order.
    pub states: Vec<Named<()>>,
    /// Named intermediate expressions (any order; the compiler sorts them).
    pub lets: Vec<Named<Ast>>,
    /// Equations, one per state.
    pub equations: Vec<EquationSpec>,
    /// Outputs, in order (each may use the ones above it).
    pub outputs: Vec<Named<Ast>>,
    /// Reduced variants.
    pub variants: Vec<VariantSpec>,
}

/// What went wrong, pointed at a node.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    /// The node the message is about.
    pub id: NodeId,
    /// The message, lowercase, in the user's terms.
    pub message: String,
}
