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

use crate::ast::{Accumulates, Expr, ModeStates, ModelAst, RelOp, Target, When};
use crate::span::Errors;
use crate::validate::{validate_one, Validated, RESERVED_MODULES};
use model_algebra::{BinOp, Named, NodeId};
use std::collections::BTreeMap;

/// Which crossings of a guard fire its event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
    /// The output holding its first step (its own, or the model's), if either is declared.
    pub first_step: Option<(NodeId, usize)>,
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
    /// The discrete values and their initial values, in the order written: each mode's model
    /// takes them as parameters after the model's own.
    pub discrete: Vec<(String, f64)>,
}

impl ModelAst {
    /// Whether the model switches: it has modes or events.
    pub fn is_switched(&self) -> bool {
        !self.modes.is_empty()
            || !self.events.is_empty()
            || !self.accumulations.is_empty()
            || self.time_scale.is_some()
            || self.first_step.is_some()
            || !self.discrete.is_empty()
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
    /// The mode's own first step, or the model's.
    first_step: Option<&'a Named<Expr>>,
    /// The mode's own states in some of the model's slots.
    states: Option<&'a ModeStates>,
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
    check_likes(ast, &mut errors);
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
            || view.name == "discrete"
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
    // Each mode's states (the model's, with the mode's own in the slots they replace), and the
    // names a reset into the mode may assign: its states, then the discrete values.
    let mode_states: Vec<Vec<Named<()>>> = views
        .iter()
        .map(|view| match view.states {
            Some(own) => mode_state_list(ast, view, own, &mut errors),
            None => ast.states.clone(),
        })
        .collect();
    let assignable: Vec<BTreeMap<&str, usize>> = (mode_states.iter())
        .map(|states| {
            (states.iter().map(|s| s.name.as_str()))
                .chain(ast.discrete.iter().map(|d| d.name.as_str()))
                .enumerate()
                .map(|(k, name)| (name, k))
                .collect()
        })
        .collect();
    let mode_list = || {
        let names: Vec<String> = views.iter().map(|v| format!("`{}`", v.name)).collect();
        format!("the modes are {}", names.join(", "))
    };
    let state_list = |mode: usize| {
        let names: Vec<String> = (mode_states[mode].iter().map(|s| s.name.as_str()))
            .chain(ast.discrete.iter().map(|d| d.name.as_str()))
            .map(|name| format!("`{name}`"))
            .collect();
        let what = if ast.discrete.is_empty() {
            "the states are"
        } else {
            "the states and discrete values are"
        };
        format!("{what} {}", names.join(", "))
    };

    let mut plans_ast = Vec::new();
    for (this, view) in views.iter().enumerate() {
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
                        format!(
                            "unknown mode `{}`{}: {}",
                            name.name,
                            did_you_mean(&name.name, views.iter().map(|v| v.name.as_str())),
                            mode_list()
                        ),
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
            // A reset assigns the states of the mode it goes on in (read in this one).
            let into = to.unwrap_or(this);
            let mut planned = Vec::new();
            for reset in resets {
                let Some(&state) = assignable[into].get(reset.name.as_str()) else {
                    let what = if ast.discrete.is_empty() {
                        "a state"
                    } else {
                        "a state or a discrete value"
                    };
                    errors.at(
                        range(reset.id),
                        format!(
                            "event `{event}` resets `{}`, which is not {what} of mode `{}`; {}",
                            reset.name,
                            views[into].name,
                            state_list(into)
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
                // Internal names, unique even where the user declared an event twice (that
                // is reported once, naming the event): never in a message.
                outputs.push(Named {
                    name: format!("{kind}:{}:{event}:{}", outputs.len(), reset.name),
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
        for (k, &(when, _)) in view.events.iter().enumerate() {
            let guard = &when.guard;
            outputs.push(Named {
                name: format!("when:{k}:{}", when.name.name),
                id: when.name.id,
                value: Expr::Bin(
                    guard.id,
                    BinOp::Sub,
                    Box::new(guard.lhs.clone()),
                    Box::new(guard.rhs.clone()),
                ),
            });
        }
        // The clock next (read by the integrator at every evaluation in regularised time),
        // then the first step: each an output of its own, under a name no user can write.
        let mut declared = |number: Option<&Named<Expr>>| {
            number.map(|number| {
                outputs.push(Named {
                    name: format!("{}:", number.name),
                    id: number.id,
                    value: number.value.clone(),
                });
                (number.id, outputs.len() - 1)
            })
        };
        let time_scale = declared(view.time_scale);
        let first_step = declared(view.first_step);
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
        model.states = mode_states[this].clone();
        model.params.extend((ast.discrete.iter()).map(|d| Named {
            name: d.name.clone(),
            id: d.id,
            value: Some(d.value),
        }));
        model.discrete = Vec::new();
        model.first_step = None;
        model.equations = view.equations.clone();
        model.outputs = outputs;
        model.variants = Vec::new();
        model.charts = Vec::new();
        model.modes = Vec::new();
        model.events = Vec::new();
        model.accumulations = Vec::new();
        model.time_scale = None;
        plans_ast.push((view, model, user_outputs, events, time_scale, first_step));
    }

    // Each mode's model through the smooth validator; a problem found in every mode is the
    // shared rows' and is reported once.
    let mut found: Vec<(String, String, syn::Error, Vec<String>)> = Vec::new();
    let mut modes = Vec::new();
    for (view, model, user_outputs, events, time_scale, first_step) in plans_ast {
        match validate_one(&model) {
            Ok(validated) => modes.push(ModePlan {
                model: validated,
                user_outputs,
                events,
                time_scale,
                first_step,
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
        discrete: (ast.discrete.iter())
            .map(|d| (d.name.clone(), d.value))
            .collect(),
    })
}

/// Every `like OTHER` names another mode of the model that writes its own rows.
fn check_likes(ast: &ModelAst, errors: &mut Errors) {
    for mode in &ast.modes {
        let Some(like) = &mode.like else { continue };
        let range = ast.spans.range(like.id);
        match ast.modes.iter().find(|m| m.name == like.name.as_str()) {
            None => {
                let names: Vec<String> =
                    ast.modes.iter().map(|m| format!("`{}`", m.name)).collect();
                errors.at(
                    range,
                    format!(
                        "mode `{}` is like `{}`, which is not a mode; the modes are {}",
                        mode.name,
                        like.name,
                        names.join(", ")
                    ),
                );
            }
            Some(base) if base.like.is_some() || base.name == mode.name => errors.at(
                range,
                format!(
                    "mode `{}` is like `{}`, which does not write its own equations: name the \
                     mode that does",
                    mode.name, like.name
                ),
            ),
            Some(_) => {}
        }
    }
}

/// The states of a mode that carries its own coordinates in some slots: the model's, with the
/// new states in the place of the first replaced one, in order (as a chart places them). Every
/// replaced name must be a state of the model, once, and as many states must come in as go
/// out; a mistake is reported here and the model's states are used.
fn mode_state_list(
    ast: &ModelAst,
    view: &ModeView,
    own: &ModeStates,
    errors: &mut Errors,
) -> Vec<Named<()>> {
    let range = |id: NodeId| ast.spans.range(id);
    let mut ok = true;
    let mut slots = Vec::new();
    for old in &own.replace {
        match ast.states.iter().position(|s| s.name == old.name) {
            Some(k) if slots.contains(&k) => {
                errors.at(
                    range(old.id),
                    format!("mode `{}` replaces `{}` twice", view.name, old.name),
                );
                ok = false;
            }
            Some(k) => slots.push(k),
            None => {
                let names: Vec<String> =
                    ast.states.iter().map(|s| format!("`{}`", s.name)).collect();
                errors.at(
                    range(old.id),
                    format!(
                        "mode `{}` replaces `{}`, which is not a state of the model; the states are {}",
                        view.name,
                        old.name,
                        names.join(", ")
                    ),
                );
                ok = false;
            }
        }
    }
    if own.new.len() != own.replace.len() {
        errors.at(
            range(own.id),
            format!(
                "mode `{}` brings {} states in for {} replaced: the modes share the model's {} state slots",
                view.name,
                own.new.len(),
                own.replace.len(),
                ast.states.len()
            ),
        );
        ok = false;
    }
    if !ok {
        return ast.states.clone();
    }
    let first = slots.iter().copied().min().unwrap_or(ast.states.len());
    let mut states: Vec<Named<()>> = ast.states[..first].to_vec();
    states.extend(own.new.iter().cloned());
    states.extend(
        (ast.states[first..].iter().enumerate())
            .filter(|(k, _)| !slots.contains(&(first + k)))
            .map(|(_, s)| s.clone()),
    );
    states
}

/// The modes as written, or the model itself as its only mode when it has events but no
/// modes; each with the model's shared equations and events added.
fn mode_views<'a>(ast: &'a ModelAst) -> Vec<ModeView<'a>> {
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
            first_step: ast.first_step.as_ref(),
            states: None,
        }];
    }
    ast.modes
        .iter()
        .map(|mode| {
            // `like OTHER`: the other mode's rows first, then this one's own; its states,
            // clock and first step unless this one writes its own. (An unknown or chained
            // `like` is reported by `check_likes`.)
            let base = (mode.like.as_ref())
                .and_then(|like| ast.modes.iter().find(|m| m.name == like.name.as_str()))
                .filter(|base| base.like.is_none());
            let lets: Vec<Named<Expr>> = (base.iter().flat_map(|b| &b.lets))
                .chain(&mode.lets)
                .cloned()
                .collect();
            let own_equations: Vec<crate::ast::Equation> = (base.iter().flat_map(|b| &b.equations))
                .chain(&mode.equations)
                .cloned()
                .collect();
            let pick =
                |own: &'a Option<Named<Expr>>,
                 theirs: fn(&'a crate::ast::Mode) -> &'a Option<Named<Expr>>| {
                    own.as_ref()
                        .or_else(|| base.and_then(|b| theirs(b).as_ref()))
                };
            let time_scale = pick(&mode.time_scale, |m| &m.time_scale);
            let first_step = pick(&mode.first_step, |m| &m.first_step);
            let states = mode
                .states
                .as_ref()
                .or_else(|| base.and_then(|b| b.states.as_ref()));
            let mut events: Vec<(&When, bool)> = mode.events.iter().map(|w| (w, false)).collect();
            events.extend(ast.events.iter().map(|w| (w, true)));
            let mut accumulations: Vec<&Accumulates> = mode.accumulations.iter().collect();
            accumulations.extend(&ast.accumulations);
            ModeView {
                name: mode.name.to_string(),
                id: mode.id,
                attrs: mode.attrs.clone(),
                lets,
                equations: ast.equations.iter().cloned().chain(own_equations).collect(),
                events,
                accumulations,
                time_scale: time_scale.or(ast.time_scale.as_ref()),
                first_step: first_step.or(ast.first_step.as_ref()),
                states,
            }
        })
        .collect()
}

/// ` (did you mean `NAME`?)` for the closest of `candidates`, or nothing.
fn did_you_mean<'c>(name: &str, candidates: impl IntoIterator<Item = &'c str>) -> String {
    match crate::names::closest(name, candidates) {
        Some(close) => format!(" (did you mean `{close}`?)"),
        None => String::new(),
    }
}
