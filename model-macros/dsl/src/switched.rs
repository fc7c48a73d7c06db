//! A switched model checked: each mode becomes a model of its own, and its events a plan the
//! compiler can follow.
//!
//! A mode's model is the model's shared rows (parameters, states, lets, equations, outputs)
//! with the mode's lets and equations added, so the validator and the compiler of smooth models
//! check and solve it unchanged. Every guard and every reset right-hand side is evaluated in the
//! mode the event fires in, just before the event, and may read the mode's derivatives and
//! outputs (a contact force, an acceleration): so each becomes an extra output of that mode's
//! model, with a name no user can write (`when:impact`), and the compiler splits the outputs
//! program into the user's outputs, the guards and each event's resets.
//!
//! A mistake in a shared row is found in every mode: it is reported once, and a mistake found
//! in some modes only names them.

use crate::ast::{Accumulates, Expr, ModelAst, RelOp, Target, When};
use crate::span::Errors;
use crate::validate::{validate_one, Validated, RESERVED_MODULES};
use model_algebra::{BinOp, Named, NodeId};
use std::collections::BTreeMap;

/// Which crossings of a guard fire its event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Crossing {
    /// `a > b`, `a >= b`: `a - b` crosses zero upwards.
    Up,
    /// `a < b`, `a <= b`: `a - b` crosses zero downwards.
    Down,
    /// `a == b`: either way.
    Both,
}

impl Crossing {
    fn of(op: RelOp) -> Crossing {
        match op {
            RelOp::Gt | RelOp::Ge => Crossing::Up,
            RelOp::Lt | RelOp::Le => Crossing::Down,
            RelOp::Eq => Crossing::Both,
        }
    }
}

/// What an event does once located.
#[derive(Clone, Debug, PartialEq)]
pub enum Action<J> {
    /// Nothing: it is recorded, and the run goes on untouched.
    Record,
    /// The run ends, with the event's name as the reason.
    Stop,
    /// Reset states and go on (in another mode, or restart this one).
    Jump(J),
}

/// A jump as planned: the target mode and the states reset, each by the output of the mode's
/// model that computes its new value.
#[derive(Clone, Debug, PartialEq)]
pub struct JumpPlan {
    /// The mode the run continues in (`None`: the same mode, restarted).
    pub to: Option<usize>,
    /// `(state index, output index)` per reset, in the order written.
    pub resets: Vec<(usize, usize)>,
    /// The Rust function that computes the new state instead (`by FUNCTION`; then `resets` is
    /// empty).
    pub by: Option<String>,
    /// When the function also decides where the run goes (`-> a | b | stop by FUNCTION`):
    /// the modes it may name (`to` is then `None`).
    pub choice: Option<Choice>,
}

/// The modes a decided event may continue in, and whether it may stop the run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Choice {
    /// The mode indices, in the order written.
    pub modes: Vec<usize>,
    /// Whether the function may stop the run.
    pub stop: bool,
}

/// One event of a mode as planned.
#[derive(Clone, Debug)]
pub struct EventPlan {
    /// The event's name.
    pub name: String,
    /// The name's node.
    pub id: NodeId,
    /// The guard relation's node.
    pub guard_id: NodeId,
    /// Which crossings fire it.
    pub crossing: Crossing,
    /// The output of the mode's model holding the guard's value, `lhs - rhs`.
    pub guard_output: usize,
    /// What it does.
    pub action: Action<JumpPlan>,
    /// What an accumulation of its resets turns into.
    pub accumulation: Option<JumpPlan>,
    /// Whether the event is the model's (shared by every mode) rather than the mode's own.
    pub shared: bool,
}

/// One mode ready for the compiler.
#[derive(Clone, Debug)]
pub struct ModePlan {
    /// The mode's model: shared rows, the mode's rows, and the guards and resets as outputs
    /// after the user's.
    pub model: Validated,
    /// How many outputs are the user's (the rest are guards and resets).
    pub user_outputs: usize,
    /// Its events: its own first, then the shared ones.
    pub events: Vec<EventPlan>,
    /// The output of the mode's model holding its time scale (its own, or the model's), if
    /// either is declared.
    pub time_scale: Option<(NodeId, usize)>,
}

/// A switched model ready for the compiler.
#[derive(Clone, Debug)]
pub struct SwitchedPlan {
    /// The model as written.
    pub ast: ModelAst,
    /// The modes, the first being where a run starts.
    pub modes: Vec<ModePlan>,
    /// Each state's initial value, where one is written.
    pub initial: Vec<Option<f64>>,
}

impl ModelAst {
    /// Whether the model switches: it has modes or events.
    pub fn is_switched(&self) -> bool {
        !self.modes.is_empty()
            || !self.events.is_empty()
            || !self.accumulations.is_empty()
            || self.time_scale.is_some()
    }

    /// Every `by FUNCTION` of the model's events and accumulations, in the order written: the
    /// Rust functions a run calls, which only a model compiled by `model!` can call.
    pub fn rust_calls(&self) -> Vec<&Named<()>> {
        let events = (self.modes.iter().flat_map(|m| &m.events)).chain(&self.events);
        let accumulations =
            (self.modes.iter().flat_map(|m| &m.accumulations)).chain(&self.accumulations);
        (events.filter_map(|w| w.by.as_ref()))
            .chain(accumulations.filter_map(|a| a.by.as_ref()))
            .collect()
    }
}

/// One mode as the validator sees it, before its model is built.
struct ModeView<'a> {
    name: String,
    id: NodeId,
    attrs: Vec<syn::Attribute>,
    lets: Vec<Named<Expr>>,
    equations: Vec<crate::ast::Equation>,
    /// Own events, then shared ones (flag).
    events: Vec<(&'a When, bool)>,
    accumulations: Vec<&'a Accumulates>,
    /// The mode's own time scale, or the model's.
    time_scale: Option<&'a Named<Expr>>,
}

/// Checks a switched model and builds each mode's model; `Err` carries every problem.
pub fn validate_switched(ast: &ModelAst) -> syn::Result<SwitchedPlan> {
    let mut errors = Errors::default();
    let range = |id: NodeId| ast.spans.range(id);
    for chart in &ast.charts {
        errors.at(
            range(chart.id),
            "a switched model cannot have charts yet: write the mode's equations in the chart's states",
        );
    }
    for variant in &ast.variants {
        errors.at(
            range(variant.id),
            "a switched model cannot have variants yet",
        );
    }
    let views = mode_views(ast);
    let mode_index: BTreeMap<&str, usize> = views
        .iter()
        .enumerate()
        .map(|(k, v)| (v.name.as_str(), k))
        .collect();
    let mut seen = BTreeMap::new();
    for view in &views {
        if RESERVED_MODULES.contains(&view.name.as_str())
            || view.name == "stop"
            || view.name == "mode"
        {
            errors.at(
                range(view.id),
                format!(
                    "a mode cannot be called `{}`: the name is taken by the model's own items",
                    view.name
                ),
            );
        } else if seen.insert(view.name.clone(), view.id).is_some() {
            errors.at(
                range(view.id),
                format!("mode `{}` is declared twice", view.name),
            );
        }
    }
    let state_index: BTreeMap<&str, usize> = (ast.states.iter().enumerate())
        .map(|(k, s)| (s.name.as_str(), k))
        .collect();
    let mode_list = || {
        let names: Vec<String> = views.iter().map(|v| format!("`{}`", v.name)).collect();
        format!("the modes are {}", names.join(", "))
    };
    let state_list = || {
        let names: Vec<String> = ast.states.iter().map(|s| format!("`{}`", s.name)).collect();
        format!("the states are {}", names.join(", "))
    };

    let mut plans_ast = Vec::new();
    for view in &views {
        let mut outputs = ast.outputs.clone();
        let user_outputs = outputs.len();
        let mut events = Vec::new();
        let mut names = BTreeMap::new();
        // Checks and plans a jump: its target and its resets, each a new output.
        let jump = |target: Option<&Target>,
                    resets: &[Named<Expr>],
                    by: Option<&Named<()>>,
                    event: &str,
                    kind: &str,
                    outputs: &mut Vec<Named<Expr>>,
                    errors: &mut Errors|
         -> Option<JumpPlan> {
            let index = |name: &Named<()>, errors: &mut Errors| {
                let found = mode_index.get(name.name.as_str()).copied();
                if found.is_none() {
                    errors.at(
                        range(name.id),
                        format!("unknown mode `{}`: {}", name.name, mode_list()),
                    );
                }
                found
            };
            let mut choice = None;
            let to = match target {
                Some(Target::Mode(name)) => Some(index(name, errors)?),
                Some(Target::Choice { modes, stop, id }) => {
                    if by.is_none() {
                        errors.at(
                            range(*id),
                            format!(
                                "event `{event}` goes on in one of several modes: a Rust function \
                                 decides which (`by FUNCTION`), and none is named"
                            ),
                        );
                        return None;
                    }
                    let indices: Vec<Option<usize>> =
                        modes.iter().map(|m| index(m, errors)).collect();
                    choice = Some(Choice {
                        modes: indices.into_iter().collect::<Option<Vec<usize>>>()?,
                        stop: *stop,
                    });
                    None
                }
                _ => None,
            };
            let mut planned = Vec::new();
            for reset in resets {
                let Some(&state) = state_index.get(reset.name.as_str()) else {
                    errors.at(
                        range(reset.id),
                        format!(
                            "event `{event}` resets `{}`, which is not a state; {}",
                            reset.name,
                            state_list()
                        ),
                    );
                    continue;
                };
                if planned.iter().any(|&(s, _)| s == state) {
                    errors.at(
                        range(reset.id),
                        format!("event `{event}` resets `{}` twice", reset.name),
                    );
                    continue;
                }
                planned.push((state, outputs.len()));
                outputs.push(Named {
                    name: format!("{kind}:{event}:{}", reset.name),
                    id: reset.id,
                    value: reset.value.clone(),
                });
            }
            Some(JumpPlan {
                to,
                resets: planned,
                by: by.map(|f| f.name.clone()),
                choice,
            })
        };
        // The guards first, together, then each jump's resets, together: the compiler then
        // splits the outputs program into contiguous parts.
        for &(when, _) in &view.events {
            let guard = &when.guard;
            outputs.push(Named {
                name: format!("when:{}", when.name.name),
                id: when.name.id,
                value: Expr::Bin(
                    guard.id,
                    BinOp::Sub,
                    Box::new(guard.lhs.clone()),
                    Box::new(guard.rhs.clone()),
                ),
            });
        }
        // The clock next, read by the integrator at every evaluation in regularised time.
        let time_scale = view.time_scale.map(|clock| {
            outputs.push(Named {
                name: "time_scale:".to_string(),
                id: clock.id,
                value: clock.value.clone(),
            });
            (clock.id, outputs.len() - 1)
        });
        for (k, &(when, shared)) in view.events.iter().enumerate() {
            let guard_output = user_outputs + k;
            if names.insert(when.name.name.clone(), when.name.id).is_some() {
                errors.at(
                    range(when.name.id),
                    format!(
                        "event `{}` is declared twice in mode `{}`",
                        when.name.name, view.name
                    ),
                );
            }
            let guard = &when.guard;
            let sets_state = when.resets.is_some() || when.by.is_some();
            let action = match (&when.target, sets_state) {
                (Some(Target::Stop(id)), true) => {
                    errors.at(
                        range(*id),
                        format!(
                            "event `{}` stops the run: it has no state to reset",
                            when.name.name
                        ),
                    );
                    Action::Stop
                }
                (Some(Target::Stop(_)), false) => Action::Stop,
                (None, false) => Action::Record,
                (target, _) => {
                    let resets = when.resets.as_deref().unwrap_or(&[]);
                    match jump(
                        target.as_ref(),
                        resets,
                        when.by.as_ref(),
                        &when.name.name,
                        "reset",
                        &mut outputs,
                        &mut errors,
                    ) {
                        Some(plan) => Action::Jump(plan),
                        None => Action::Record,
                    }
                }
            };
            events.push(EventPlan {
                name: when.name.name.clone(),
                id: when.name.id,
                guard_id: guard.id,
                crossing: Crossing::of(guard.op),
                guard_output,
                action,
                accumulation: None,
                shared,
            });
        }
        for acc in &view.accumulations {
            let Some(k) = events.iter().position(|e| e.name == acc.event.name) else {
                let known: Vec<String> = events.iter().map(|e| format!("`{}`", e.name)).collect();
                errors.at(
                    range(acc.event.id),
                    format!(
                        "no event `{}` in mode `{}` to accumulate; its events are {}",
                        acc.event.name,
                        view.name,
                        if known.is_empty() {
                            "none".to_string()
                        } else {
                            known.join(", ")
                        }
                    ),
                );
                continue;
            };
            if !matches!(events[k].action, Action::Jump(_)) {
                errors.at(
                    range(acc.event.id),
                    format!(
                        "event `{}` resets nothing, so it cannot accumulate: only an event that \
                         resets states and goes on can fire ever faster",
                        acc.event.name
                    ),
                );
                continue;
            }
            if events[k].accumulation.is_some() {
                errors.at(
                    range(acc.event.id),
                    format!("the accumulation of `{}` is declared twice", acc.event.name),
                );
                continue;
            }
            if let Target::Choice { id, .. } = acc.target {
                errors.at(
                    range(id),
                    "an accumulation goes on in one mode: a choice belongs to an event",
                );
                continue;
            }
            if let Target::Stop(id) = acc.target {
                errors.at(
                    range(id),
                    "an accumulation goes on in a mode: without this rule the run already stops there, with the accumulation as its reason",
                );
                continue;
            }
            let plan = jump(
                Some(&acc.target),
                &acc.resets,
                acc.by.as_ref(),
                &acc.event.name,
                "accumulation",
                &mut outputs,
                &mut errors,
            );
            events[k].accumulation = plan;
        }
        let mut model = ast.clone();
        model.attrs = view.attrs.clone();
        model.name = syn::Ident::new(&view.name, ast.name.span());
        model.lets = ast.lets.iter().chain(&view.lets).cloned().collect();
        model.equations = view.equations.clone();
        model.outputs = outputs;
        model.variants = Vec::new();
        model.charts = Vec::new();
        model.modes = Vec::new();
        model.events = Vec::new();
        model.accumulations = Vec::new();
        model.time_scale = None;
        plans_ast.push((view, model, user_outputs, events, time_scale));
    }

    // Each mode's model through the smooth validator; a problem found in every mode is the
    // shared rows' and is reported once.
    let mut found: Vec<(String, String, syn::Error, Vec<String>)> = Vec::new();
    let mut modes = Vec::new();
    for (view, model, user_outputs, events, time_scale) in plans_ast {
        match validate_one(&model) {
            Ok(validated) => modes.push(ModePlan {
                model: validated,
                user_outputs,
                events,
                time_scale,
            }),
            Err(error) => {
                for error in error {
                    let key = (error.to_string(), format!("{:?}", error.span()));
                    match found
                        .iter_mut()
                        .find(|(m, s, ..)| (m, s) == (&key.0, &key.1))
                    {
                        Some(entry) => entry.3.push(view.name.clone()),
                        None => found.push((key.0, key.1, error, vec![view.name.clone()])),
                    }
                }
            }
        }
    }
    for (message, _, error, in_modes) in found {
        if in_modes.len() == views.len() {
            errors.push(error);
        } else {
            let names: Vec<String> = in_modes.iter().map(|m| format!("`{m}`")).collect();
            let which = if names.len() == 1 { "mode" } else { "modes" };
            errors.push(syn::Error::new(
                error.span(),
                format!("in {which} {}: {message}", names.join(", ")),
            ));
        }
    }
    let initial = ast
        .states
        .iter()
        .map(|s| {
            ast.initial
                .iter()
                .find(|i| i.name == s.name)
                .map(|i| i.value)
        })
        .collect();
    errors.finish()?;
    Ok(SwitchedPlan {
        ast: ast.clone(),
        modes,
        initial,
    })
}

/// The modes as written, or the model itself as its only mode when it has events but no
/// modes; each with the model's shared equations and events added.
fn mode_views(ast: &ModelAst) -> Vec<ModeView<'_>> {
    if ast.modes.is_empty() {
        return vec![ModeView {
            name: ast.name.to_string(),
            id: NodeId(u32::MAX),
            attrs: ast.attrs.clone(),
            lets: Vec::new(),
            equations: ast.equations.clone(),
            events: ast.events.iter().map(|w| (w, false)).collect(),
            accumulations: ast.accumulations.iter().collect(),
            time_scale: ast.time_scale.as_ref(),
        }];
    }
    ast.modes
        .iter()
        .map(|mode| {
            let mut events: Vec<(&When, bool)> = mode.events.iter().map(|w| (w, false)).collect();
            events.extend(ast.events.iter().map(|w| (w, true)));
            let mut accumulations: Vec<&Accumulates> = mode.accumulations.iter().collect();
            accumulations.extend(&ast.accumulations);
            ModeView {
                name: mode.name.to_string(),
                id: mode.id,
                attrs: mode.attrs.clone(),
                lets: mode.lets.clone(),
                equations: ast
                    .equations
                    .iter()
                    .chain(&mode.equations)
                    .cloned()
                    .collect(),
                events,
                accumulations,
                time_scale: mode.time_scale.as_ref().or(ast.time_scale.as_ref()),
            }
        })
        .collect()
}
