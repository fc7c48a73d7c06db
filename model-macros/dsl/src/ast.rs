//! The model as written: a typed view of the DSL before any name is resolved.
//!
//! Names are plain strings here and calls keep the function's spelling, so that the validator can
//! say "unknown function `sine`" or "`m` is a parameter" with the user's own words; every node
//! carries a [`NodeId`] whose source range lives in [`Spans`].

use crate::span::Spans;
use model_algebra::{BinOp, CmpOp, Named, NodeId};
use std::collections::BTreeMap;

/// An expression before name resolution.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    /// A numeric literal.
    Num(NodeId, f64),
    /// A name, not yet resolved.
    Name(NodeId, String),
    /// `-x`
    Neg(NodeId, Box<Expr>),
    /// `x op y`
    Bin(NodeId, BinOp, Box<Expr>, Box<Expr>),
    /// `f(args..)`, including `der(..)`.
    Call(Call),
    /// `if(cond, then, otherwise)`: `then` where the comparison holds, else `otherwise`.
    If {
        /// The whole `if(..)`.
        id: NodeId,
        /// The comparison (never `==`: the parser refuses it).
        cond: Box<Relation>,
        /// The value where `cond` holds.
        then: Box<Expr>,
        /// The value where it does not.
        otherwise: Box<Expr>,
    },
}

/// A call `f(args..)` as written.
#[derive(Clone, Debug, PartialEq)]
pub struct Call {
    /// The whole call.
    pub id: NodeId,
    /// The function's name as written.
    pub func: String,
    /// The function name's token.
    pub func_id: NodeId,
    /// The arguments.
    pub args: Vec<Expr>,
}

impl Expr {
    /// The node this expression came from.
    pub fn id(&self) -> NodeId {
        match self {
            Expr::Num(id, _) | Expr::Name(id, _) | Expr::Neg(id, _) | Expr::Bin(id, ..) => *id,
            Expr::Call(call) => call.id,
            Expr::If { id, .. } => *id,
        }
    }

    /// Calls `visit` on this expression and every sub-expression, parents first.
    pub fn walk<'a>(&'a self, visit: &mut impl FnMut(&'a Expr)) {
        visit(self);
        match self {
            Expr::Num(..) | Expr::Name(..) => {}
            Expr::Neg(_, arg) => arg.walk(visit),
            Expr::Bin(_, _, lhs, rhs) => {
                lhs.walk(visit);
                rhs.walk(visit);
            }
            Expr::Call(call) => call.args.iter().for_each(|arg| arg.walk(visit)),
            Expr::If {
                cond,
                then,
                otherwise,
                ..
            } => {
                cond.lhs.walk(visit);
                cond.rhs.walk(visit);
                then.walk(visit);
                otherwise.walk(visit);
            }
        }
    }
}

/// A comparison, `lhs < rhs` and the like: the condition of a `when` guard or of an `if`.
#[derive(Clone, Debug, PartialEq)]
pub struct Relation {
    /// The whole comparison.
    pub id: NodeId,
    /// Left-hand side.
    pub lhs: Expr,
    /// The comparison operator.
    pub op: RelOp,
    /// Right-hand side.
    pub rhs: Expr,
}

/// A comparison operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RelOp {
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `==`
    Eq,
}

impl RelOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            RelOp::Lt => "<",
            RelOp::Le => "<=",
            RelOp::Gt => ">",
            RelOp::Ge => ">=",
            RelOp::Eq => "==",
        }
    }

    /// The algebra's comparison, for the orderings (`None` for `==`).
    pub fn ordering(self) -> Option<CmpOp> {
        match self {
            RelOp::Lt => Some(CmpOp::Lt),
            RelOp::Le => Some(CmpOp::Le),
            RelOp::Gt => Some(CmpOp::Gt),
            RelOp::Ge => Some(CmpOp::Ge),
            RelOp::Eq => None,
        }
    }
}

/// One equation `label: lhs = rhs;`.
#[derive(Clone, Debug, PartialEq)]
pub struct Equation {
    /// The label and its token, when one was written.
    pub label: Option<Named<()>>,
    /// The whole equation, label included (diagnostics about the equation as a whole point
    /// here).
    pub id: NodeId,
    /// Left-hand side.
    pub lhs: Expr,
    /// Right-hand side.
    pub rhs: Expr,
}

/// `variant NAME { keep { .. } fix { .. } }`.
#[derive(Clone, Debug)]
pub struct Variant {
    /// Doc comments written before `variant`.
    pub attrs: Vec<syn::Attribute>,
    /// The variant's module name.
    pub name: syn::Ident,
    /// The name's node.
    pub id: NodeId,
    /// States and outputs to keep.
    pub keep: Vec<Named<()>>,
    /// Parameters fixed at compile time.
    pub fix: Vec<Named<f64>>,
}

/// `chart NAME { states { .. } replace { .. } let ..; outputs [after NAME] { .. } }`.
#[derive(Clone, Debug)]
pub struct Chart {
    /// Doc comments written before `chart`.
    pub attrs: Vec<syn::Attribute>,
    /// The chart's module name.
    pub name: syn::Ident,
    /// The name's node.
    pub id: NodeId,
    /// The new states.
    pub states: Vec<Named<()>>,
    /// The model's states they replace.
    pub replace: Vec<Named<()>>,
    /// Lets placed before the model's, defining every replaced state.
    pub lets: Vec<Named<Expr>>,
    /// Outputs added to the model's.
    pub outputs: Vec<Named<Expr>>,
    /// The model's output after which `outputs` go (`None`: last).
    pub after: Option<Named<()>>,
}

/// `mode NAME { let ..; equations { .. } when .. }`: one mode of a switched model, with the
/// equations it adds to the model's shared ones.
#[derive(Clone, Debug)]
pub struct Mode {
    /// Doc comments written before `mode`.
    pub attrs: Vec<syn::Attribute>,
    /// The mode's name (and module name).
    pub name: syn::Ident,
    /// The name's node.
    pub id: NodeId,
    /// `mode NAME like OTHER`: the mode whose lets, equations, states, clock and first step
    /// this one takes (its events are its own).
    pub like: Option<Named<()>>,
    /// Lets of this mode, after the model's.
    pub lets: Vec<Named<Expr>>,
    /// Equations of this mode, after the model's shared ones.
    pub equations: Vec<Equation>,
    /// Events of this mode, before the model's shared ones.
    pub events: Vec<When>,
    /// Accumulation rules of this mode's events.
    pub accumulations: Vec<Accumulates>,
    /// `time_scale = EXPR;`: this mode's clock in regularised time, instead of the model's.
    pub time_scale: Option<Named<Expr>>,
    /// `first_step = EXPR;`: the step the integrator tries first when the mode starts.
    pub first_step: Option<Named<Expr>>,
    /// `states { NEW, .. } replace { OLD, .. }`: the mode carries other coordinates in some of
    /// the model's state slots.
    pub states: Option<ModeStates>,
}

/// `states { u_X, u_Y } replace { V_X, V_Y }` in a mode: the new states take the slots of the
/// replaced ones, in order (as in a chart), while the run is in the mode.
#[derive(Clone, Debug)]
pub struct ModeStates {
    /// The keyword's node.
    pub id: NodeId,
    /// The mode's own states.
    pub new: Vec<Named<()>>,
    /// The model's states whose slots they take.
    pub replace: Vec<Named<()>>,
}

/// `when NAME: GUARD [-> TARGET] [{ RESETS } | by FUNCTION]`: an event, located where the guard's relation
/// starts to hold.
#[derive(Clone, Debug)]
pub struct When {
    /// Doc comments written before `when`.
    pub attrs: Vec<syn::Attribute>,
    /// The event's name.
    pub name: Named<()>,
    /// The guard.
    pub guard: Relation,
    /// Where the run goes: `None` stays in the mode (a restart after a reset, or only a record
    /// when there is no reset either).
    pub target: Option<Target>,
    /// `{ state = EXPR; .. }`; `None` when no braces were written.
    pub resets: Option<Vec<Named<Expr>>>,
    /// `by FUNCTION`: the new state is computed by a Rust function instead of written resets.
    pub by: Option<Named<()>>,
}

/// `when NAME accumulates -> TARGET [{ RESETS }]`: what an accumulation of an event's resets
/// (a ball's ever shorter bounces) turns into.
#[derive(Clone, Debug)]
pub struct Accumulates {
    /// The event that accumulates.
    pub event: Named<()>,
    /// Where the run goes.
    pub target: Target,
    /// The states set there.
    pub resets: Vec<Named<Expr>>,
    /// `by FUNCTION`: the new state is computed by a Rust function instead.
    pub by: Option<Named<()>>,
}

/// The target of a transition.
#[derive(Clone, Debug)]
pub enum Target {
    /// `-> NAME`: a mode.
    Mode(Named<()>),
    /// `-> stop`: end the run, with the event's name as the reason.
    Stop(NodeId),
    /// `-> a | b | stop`: one of these, decided by the event's Rust function (`by FUNCTION`).
    Choice {
        /// The modes, in the order written.
        modes: Vec<Named<()>>,
        /// Whether `stop` is among them.
        stop: bool,
        /// The first name's node.
        id: NodeId,
    },
}

/// A whole `model!` invocation as written.
#[derive(Clone, Debug)]
pub struct ModelAst {
    /// Doc comments on the module.
    pub attrs: Vec<syn::Attribute>,
    /// The module's visibility.
    pub vis: syn::Visibility,
    /// The module's name.
    pub name: syn::Ident,
    /// Parameters with optional defaults.
    pub params: Vec<Named<Option<f64>>>,
    /// States, in index order.
    pub states: Vec<Named<()>>,
    /// Named intermediate expressions.
    pub lets: Vec<Named<Expr>>,
    /// The equations.
    pub equations: Vec<Equation>,
    /// Outputs, in order.
    pub outputs: Vec<Named<Expr>>,
    /// Reduced variants.
    pub variants: Vec<Variant>,
    /// The model in other coordinates.
    pub charts: Vec<Chart>,
    /// Compiler options (`options { name = value }`).
    pub options: Vec<Named<f64>>,
    /// Initial values written on states (`states { h = 1.0 }`).
    pub initial: Vec<Named<f64>>,
    /// The modes of a switched model (empty for a smooth one).
    pub modes: Vec<Mode>,
    /// Events of every mode (of the model itself when it has no modes).
    pub events: Vec<When>,
    /// Accumulation rules of the shared events (or of the model's events without modes).
    pub accumulations: Vec<Accumulates>,
    /// `time_scale = EXPR;` outside every mode: the clock, in regularised time, of every mode
    /// that declares none (`dt = time_scale dτ`).
    pub time_scale: Option<Named<Expr>>,
    /// `first_step = EXPR;` outside every mode: the first step of every mode that declares
    /// none.
    pub first_step: Option<Named<Expr>>,
    /// `discrete { NAME = VALUE, .. }`: values that hold between events, set only by events'
    /// resets, read like parameters.
    pub discrete: Vec<Named<f64>>,
    /// Doc comments written on parameters, states and outputs, by name (they document the
    /// emitted index constants).
    pub docs: BTreeMap<String, Vec<syn::Attribute>>,
    /// Source ranges of every node.
    pub spans: Spans,
}

impl ModelAst {
    /// A model with this header and nothing declared yet.
    pub fn empty(attrs: Vec<syn::Attribute>, vis: syn::Visibility, name: syn::Ident) -> Self {
        ModelAst {
            attrs,
            vis,
            name,
            params: Vec::new(),
            states: Vec::new(),
            lets: Vec::new(),
            equations: Vec::new(),
            outputs: Vec::new(),
            variants: Vec::new(),
            charts: Vec::new(),
            options: Vec::new(),
            initial: Vec::new(),
            modes: Vec::new(),
            events: Vec::new(),
            accumulations: Vec::new(),
            time_scale: None,
            first_step: None,
            discrete: Vec::new(),
            docs: BTreeMap::new(),
            spans: Spans::default(),
        }
    }
}
