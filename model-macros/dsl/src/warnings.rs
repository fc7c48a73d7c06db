//! What a switched model says that is legal but almost surely not meant: warnings, not
//! errors, each at its token.
//!
//! Why: a guard that can never change sign, a mode that nothing enters or nothing leaves,
//! are accepted by every rule of the language and then do nothing, silently: a run of such
//! a model ends "at the end time" with an answer its author did not mean. These checks need
//! only the model's text (the sign of an expression from its form, the graph of the modes);
//! what needs the numbers of a run (a guard that starts on its threshold) is the library's
//! that runs it.

use crate::ast::{Call, Expr, Relation};
use crate::span::SpanRange;
use crate::switched::{Action, Crossing, JumpPlan, SwitchedPlan};
use model_algebra::BinOp;

/// One warning: where, and what.
#[derive(Clone, Debug)]
pub struct Warning {
    /// The tokens it is about.
    pub range: SpanRange,
    /// What is likely wrong, in the user's words.
    pub message: String,
}

/// The signs an expression can take, as far as its form says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Signs {
    neg: bool,
    zero: bool,
    pos: bool,
}

const ANY: Signs = Signs {
    neg: true,
    zero: true,
    pos: true,
};

impl Signs {
    fn of_number(v: f64) -> Signs {
        Signs {
            neg: v < 0.0,
            zero: v == 0.0,
            pos: v > 0.0,
        }
    }

    fn negated(self) -> Signs {
        Signs {
            neg: self.pos,
            zero: self.zero,
            pos: self.neg,
        }
    }

    fn union(self, other: Signs) -> Signs {
        Signs {
            neg: self.neg || other.neg,
            zero: self.zero || other.zero,
            pos: self.pos || other.pos,
        }
    }

    fn sum(self, other: Signs) -> Signs {
        if !self.neg && !other.neg {
            Signs {
                neg: false,
                zero: self.zero && other.zero,
                pos: self.pos || other.pos,
            }
        } else if !self.pos && !other.pos {
            self.negated().sum(other.negated()).negated()
        } else {
            ANY
        }
    }

    fn product(self, other: Signs) -> Signs {
        Signs {
            neg: (self.neg && other.pos) || (self.pos && other.neg),
            zero: self.zero || other.zero,
            pos: (self.pos && other.pos) || (self.neg && other.neg),
        }
    }
}

/// The signs `expr` can take, from its form alone (a name may take any).
fn signs(expr: &Expr) -> Signs {
    match expr {
        Expr::Num(_, v) => Signs::of_number(*v),
        Expr::Name(_, name) if name == "pi" => Signs::of_number(1.0),
        Expr::Name(..) => ANY,
        Expr::Neg(_, e) => signs(e).negated(),
        Expr::Bin(_, op, a, b) => {
            let (sa, sb) = (signs(a), signs(b));
            match op {
                BinOp::Add => sa.sum(sb),
                BinOp::Sub => sa.sum(sb.negated()),
                BinOp::Mul | BinOp::Div => sa.product(sb),
                BinOp::Pow => match **b {
                    Expr::Num(_, n) if n.fract() == 0.0 && n % 2.0 == 0.0 && n > 0.0 => Signs {
                        neg: false,
                        zero: sa.zero,
                        pos: sa.neg || sa.pos,
                    },
                    _ if !sa.neg && !sa.zero => Signs::of_number(1.0),
                    _ => ANY,
                },
            }
        }
        Expr::Call(Call { func, args, .. }) => match (func.as_str(), args.as_slice()) {
            ("abs", [a]) => {
                let s = signs(a);
                Signs {
                    neg: false,
                    zero: s.zero,
                    pos: s.neg || s.pos,
                }
            }
            ("exp" | "cosh", [_]) => Signs::of_number(1.0),
            ("sqrt", [_]) => Signs {
                neg: false,
                zero: true,
                pos: true,
            },
            _ => ANY,
        },
        Expr::If {
            then, otherwise, ..
        } => signs(then).union(signs(otherwise)),
    }
}

/// Why `guard` can never fire, crossing as `crossing`, if its form says so.
fn never_crosses(guard: &Relation, crossing: Crossing) -> Option<&'static str> {
    let value = signs(&guard.lhs).sum(signs(&guard.rhs).negated());
    match crossing {
        Crossing::Down if !value.neg => Some("its left side never falls below its right side"),
        Crossing::Up if !value.pos => Some("its left side never rises above its right side"),
        Crossing::Both if !value.neg || !value.pos => Some("its two sides never pass each other"),
        _ => None,
    }
}

/// The modes a jump can go on in (`this` for a restart of the same mode).
fn targets(jump: &JumpPlan, this: usize) -> Vec<usize> {
    match &jump.choice {
        Some(choice) => choice.modes.clone(),
        None => vec![jump.to.unwrap_or(this)],
    }
}

/// The warnings of a validated switched model: guards that can never fire, modes no event
/// enters, modes with events none of which leaves (where the run would stay for good).
pub fn warnings(plan: &SwitchedPlan) -> Vec<Warning> {
    let ast = &plan.ast;
    let mut found = Vec::new();
    let range = |id| ast.spans.range(id);
    let when = |name: &str| {
        (ast.events.iter())
            .chain(ast.modes.iter().flat_map(|m| &m.events))
            .find(|w| w.name.name == name)
    };
    // A mode's name where it is declared (a model without modes is its only one).
    let mode_range = |m: usize| match ast.modes.get(m) {
        Some(mode) => range(mode.id),
        None => SpanRange::single(ast.name.span()),
    };
    let mut entered = vec![false; plan.modes.len()];
    entered[0] = true;
    for (m, mode) in plan.modes.iter().enumerate() {
        let mut leaves = false;
        for event in &mode.events {
            let jumps = match &event.action {
                Action::Jump(jump) => vec![jump],
                Action::Stop => {
                    leaves = true;
                    vec![]
                }
                Action::Record => vec![],
            };
            for jump in jumps.into_iter().chain(&event.accumulation) {
                for to in targets(jump, m) {
                    entered[to] = true;
                    leaves |= to != m;
                }
                leaves |= jump.choice.as_ref().is_some_and(|c| c.stop);
            }
            if event.shared && m > 0 {
                continue;
            }
            let written = when(&event.name).filter(|w| w.name.id == event.id);
            if let Some(reason) = written.and_then(|w| never_crosses(&w.guard, event.crossing)) {
                found.push(Warning {
                    range: range(event.guard_id),
                    message: format!(
                        "event `{}` can never fire: {reason}, so its guard never changes sign",
                        event.name
                    ),
                });
            }
        }
        let name = &mode.model.ast.name;
        if !leaves && plan.modes.len() > 1 && !mode.events.is_empty() {
            found.push(Warning {
                range: mode_range(m),
                message: format!(
                    "mode `{name}` has events but none leaves it: once the run enters \
                     `{name}` it stays there to the end"
                ),
            });
        }
    }
    for (m, mode) in plan.modes.iter().enumerate() {
        if !entered[m] {
            let name = &mode.model.ast.name;
            found.push(Warning {
                range: mode_range(m),
                message: format!(
                    "mode `{name}` is never entered: no event or accumulation goes on in it \
                     (a run starts in the first mode written)"
                ),
            });
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::text::Source;

    fn messages(text: &str) -> Vec<String> {
        let source = Source::new("m.dsl", text);
        let ast = source.parse().expect("parses");
        let plan = crate::validate_switched(&ast).expect("validates");
        warnings(&plan).into_iter().map(|w| w.message).collect()
    }

    #[test]
    fn a_guard_that_cannot_change_sign_is_named() {
        let found = messages(
            "mod m { states { h = 1, v } equations { der(h) = v; der(v) = -1; }
               when never: h^2 < 0 { v = 0; }
               when also: -(abs(v) + exp(h)) > 0 { v = 0; }
               when fine: h < 0 { v = -v; } }",
        );
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(
            found[0].starts_with("event `never` can never fire"),
            "{found:?}"
        );
        assert!(
            found[1].starts_with("event `also` can never fire"),
            "{found:?}"
        );
    }

    #[test]
    fn modes_without_a_way_in_or_out_are_named() {
        let found = messages(
            "mod m { states { x = 1 }
               mode a { equations { der(x) = -1; } when hit: x < 0 -> b { x = 1; } }
               mode b { equations { der(x) = 1; } when tick: x > 2 { x = 0; } }
               mode c { equations { der(x) = 0; } } }",
        );
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(
            found[0].starts_with("mode `b` has events but none leaves it"),
            "{found:?}"
        );
        assert!(
            found[1].starts_with("mode `c` is never entered"),
            "{found:?}"
        );
    }
}
