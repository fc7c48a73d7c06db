//! One namespace for everything a model declares.
//!
//! Parameters, states, lets and outputs share a single namespace with the built-ins (`t`, `pi`)
//! and the function names, so that a name in an expression always means one thing, and the
//! diagnostics can say what a name is ("`m` is a parameter") rather than just that it is wrong.

use model_algebra::{Func, NodeId};
use std::collections::BTreeMap;
use std::fmt;

/// What a declared name stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A parameter.
    Param,
    /// A state.
    State,
    /// A `let`.
    Let,
    /// An output, with its position in `outputs`.
    Output(usize),
    /// The time `t`.
    Time,
    /// The constant `pi`.
    Pi,
    /// A function of the DSL (`der` included).
    Function,
}

impl fmt::Display for Kind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Kind::Param => "a parameter",
            Kind::State => "a state",
            Kind::Let => "a `let`",
            Kind::Output(_) => "an output",
            Kind::Time => "the time (built in)",
            Kind::Pi => "the constant π (built in)",
            Kind::Function => "a function (built in)",
        })
    }
}

/// A declaration: what the name is, and where it was declared (`None` for built-ins).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Decl {
    /// What the name stands for.
    pub kind: Kind,
    /// The declaring token.
    pub id: Option<NodeId>,
}

/// The name of the `der(..)` operator.
pub const DER: &str = "der";

/// The model's namespace.
#[derive(Clone, Debug)]
pub struct Names {
    table: BTreeMap<String, Decl>,
    /// Declared names in declaration order, per kind (for "the declared ones are ..." lists).
    params: Vec<String>,
    states: Vec<String>,
    lets: Vec<String>,
    outputs: Vec<String>,
    /// Names declared more than once (already reported; their uses are not checked again).
    clashed: Vec<String>,
}

impl Names {
    /// A namespace holding only the built-ins.
    pub fn new() -> Self {
        let mut table = BTreeMap::new();
        table.insert("t".to_string(), builtin(Kind::Time));
        table.insert("pi".to_string(), builtin(Kind::Pi));
        table.insert(DER.to_string(), builtin(Kind::Function));
        for func in ALL_FUNCS {
            table.insert(func.name().to_string(), builtin(Kind::Function));
        }
        Names {
            table,
            params: Vec::new(),
            states: Vec::new(),
            lets: Vec::new(),
            outputs: Vec::new(),
            clashed: Vec::new(),
        }
    }

    /// Declares `name`; on a clash returns the earlier declaration and declares nothing.
    pub fn declare(&mut self, name: &str, kind: Kind, id: NodeId) -> Result<(), Decl> {
        if let Some(earlier) = self.table.get(name) {
            self.clashed.push(name.to_string());
            return Err(*earlier);
        }
        self.table
            .insert(name.to_string(), Decl { kind, id: Some(id) });
        let list = match kind {
            Kind::Param => &mut self.params,
            Kind::State => &mut self.states,
            Kind::Let => &mut self.lets,
            Kind::Output(_) => &mut self.outputs,
            Kind::Time | Kind::Pi | Kind::Function => return Ok(()),
        };
        list.push(name.to_string());
        Ok(())
    }

    /// Whether `name` was declared more than once.
    pub fn is_clashed(&self, name: &str) -> bool {
        self.clashed.iter().any(|clashed| clashed == name)
    }

    /// Looks a name up.
    pub fn get(&self, name: &str) -> Option<Decl> {
        self.table.get(name).copied()
    }

    /// The names usable in an expression, for an "unknown name" message: the outputs usable
    /// are the first `outputs_before` (none outside the `outputs` section).
    pub fn describe_usable(&self, outputs_before: usize) -> String {
        let mut parts = Vec::new();
        push_list(&mut parts, "parameters", &self.params);
        push_list(&mut parts, "states", &self.states);
        push_list(&mut parts, "lets", &self.lets);
        let outputs = &self.outputs[..outputs_before.min(self.outputs.len())];
        push_list(&mut parts, "outputs", outputs);
        parts.push("`t` and `pi`".to_string());
        parts.join("; ")
    }

    /// The declared or built-in name closest to a misspelt `name`, if one is close enough to be
    /// a likely typo; only names usable in the same place are proposed (the first
    /// `outputs_before` outputs; functions when `function` is set).
    pub fn suggest(&self, name: &str, outputs_before: usize, function: bool) -> Option<&str> {
        let outputs = &self.outputs[..outputs_before.min(self.outputs.len())];
        let values = (self
            .params
            .iter()
            .chain(&self.states)
            .chain(&self.lets)
            .chain(outputs))
        .map(String::as_str)
        .chain(["t", "pi"]);
        let functions = ALL_FUNCS.iter().map(|func| func.name()).chain([DER]);
        let candidates: Vec<&str> = if function {
            functions.collect()
        } else {
            values.collect()
        };
        closest(name, candidates)
    }

    /// The states and outputs, for a variant's `keep`.
    pub fn describe_keepable(&self) -> String {
        let mut parts = Vec::new();
        push_list(&mut parts, "states", &self.states);
        push_list(&mut parts, "outputs", &self.outputs);
        if parts.is_empty() {
            "there are none".to_string()
        } else {
            parts.join("; ")
        }
    }

    /// The parameters, for a variant's `fix`.
    pub fn describe_params(&self) -> String {
        let mut parts = Vec::new();
        push_list(&mut parts, "parameters", &self.params);
        if parts.is_empty() {
            "the model has no parameters".to_string()
        } else {
            parts.join("; ")
        }
    }
}

impl Default for Names {
    fn default() -> Self {
        Names::new()
    }
}

/// Every function of the DSL except `der`.
pub const ALL_FUNCS: [Func; 12] = [
    Func::Sin,
    Func::Cos,
    Func::Tan,
    Func::Sqrt,
    Func::Exp,
    Func::Ln,
    Func::Abs,
    Func::Atan2,
    Func::Hypot,
    Func::Sign,
    Func::Min,
    Func::Max,
];

/// `sin, cos, ..., max, der and if(x > y, a, b)`, for messages.
pub fn function_list() -> String {
    let names: Vec<&str> = ALL_FUNCS.iter().map(|func| func.name()).collect();
    format!("{}, `{DER}` and `if(x > y, a, b)`", quoted(&names))
}

fn builtin(kind: Kind) -> Decl {
    Decl { kind, id: None }
}

fn push_list(parts: &mut Vec<String>, label: &str, names: &[String]) {
    if !names.is_empty() {
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        parts.push(format!("{label} {}", quoted(&names)));
    }
}

/// Levenshtein distance between two names, in characters.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut previous: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut current = vec![i + 1; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            let substitution = previous[j] + usize::from(ca != cb);
            current[j + 1] = substitution.min(previous[j + 1] + 1).min(current[j] + 1);
        }
        previous = current;
    }
    previous[b.len()]
}

/// `` `a`, `b`, `c` ``
pub fn quoted(names: &[&str]) -> String {
    names
        .iter()
        .map(|name| format!("`{name}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The candidate `name` is most likely a typo of, if one is close: the same name in other
/// case (`Resting` for `resting`), else roughly one edit per three characters, and never a
/// whole replacement (`z` is not a typo of `x`).
pub(crate) fn closest<'c>(
    name: &str,
    candidates: impl IntoIterator<Item = &'c str>,
) -> Option<&'c str> {
    let length = name.chars().count();
    let limit = ((length + 1) / 3).max(1);
    let lower = name.to_lowercase();
    candidates
        .into_iter()
        .map(|candidate| {
            let distance = match candidate.to_lowercase() == lower {
                true => 0,
                false => edit_distance(name, candidate),
            };
            (distance, candidate)
        })
        .filter(|&(distance, _)| distance <= limit && distance < length)
        .min_by_key(|&(distance, _)| distance)
        .map(|(_, candidate)| candidate)
}
