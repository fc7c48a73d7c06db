//! `chart NAME { .. }`: the same model in other coordinates, written once.
//!
//! A chart replaces some states by new ones and defines each replaced state as a `let` of the
//! new states; everything else — parameters, the other lets, the equations, the outputs, the
//! variants, the options — is the model's own. The compiler's chain rule turns `der(v_C)` into
//! derivatives of the new states, so a fix to a row of the model is a fix to every chart of it.
//! The chart is emitted as a second module beside the model's, named after the chart.
//!
//! ```text
//! chart sliding_cartesian {
//!     states { u_X, u_Y } replace { v_C, alpha }
//!     let v_C = sqrt(u_X^2 + u_Y^2);
//!     let alpha = atan2(-u_Y, -u_X);
//!     outputs after V_Y { slip_speed = v_C; slip_direction = alpha; }
//! }
//! ```
//!
//! The new states take the place of the first replaced state, in order; a variant that keeps a
//! replaced state keeps all the new ones; the chart's outputs (optional) go after the model's
//! output named by `after`, or last.

use crate::ast::{Chart, ModelAst};
use crate::names::{Kind, Names};
use crate::span::Errors;
use model_algebra::Named;
use std::collections::BTreeSet;

impl Chart {
    /// The model in this chart: a model of its own, with the chart's name, docs and states.
    ///
    /// It never fails: names that do not fit are reported by [`validate`](crate::validate) on
    /// the model, and the chart's model is only validated once the model is valid.
    pub fn apply(&self, model: &ModelAst) -> ModelAst {
        let replaced: BTreeSet<&str> = self.replace.iter().map(|s| s.name.as_str()).collect();
        let first = model
            .states
            .iter()
            .position(|s| replaced.contains(s.name.as_str()))
            .unwrap_or(model.states.len());
        let mut states: Vec<Named<()>> = model.states[..first].to_vec();
        states.extend(self.states.iter().cloned());
        states.extend(
            (model.states[first..].iter())
                .filter(|s| !replaced.contains(s.name.as_str()))
                .cloned(),
        );
        let mut outputs = model.outputs.clone();
        let at = match &self.after {
            Some(after) => {
                (outputs.iter().position(|o| o.name == after.name)).map_or(outputs.len(), |k| k + 1)
            }
            None => outputs.len(),
        };
        outputs.splice(at..at, self.outputs.iter().cloned());
        let mut variants = model.variants.clone();
        for variant in &mut variants {
            let mut keep: Vec<Named<()>> = Vec::new();
            for kept in &variant.keep {
                let entries = if replaced.contains(kept.name.as_str()) {
                    self.states.clone()
                } else {
                    vec![kept.clone()]
                };
                for entry in entries {
                    if !keep.iter().any(|k| k.name == entry.name) {
                        keep.push(entry);
                    }
                }
            }
            variant.keep = keep;
        }
        ModelAst {
            attrs: self.attrs.clone(),
            vis: model.vis.clone(),
            name: self.name.clone(),
            params: model.params.clone(),
            states,
            lets: self.lets.iter().chain(&model.lets).cloned().collect(),
            equations: model.equations.clone(),
            outputs,
            variants,
            charts: Vec::new(),
            options: model.options.clone(),
            initial: Vec::new(),
            modes: Vec::new(),
            events: Vec::new(),
            accumulations: Vec::new(),
            time_scale: None,
            first_step: None,
            discrete: Vec::new(),
            docs: model.docs.clone(),
            spans: model.spans.clone(),
        }
    }
}

/// The checks that need the model: every replaced name is a state of the model, replaced once
/// and defined by a `let` of the chart; as many states come in as go out; `after` names an
/// output; the chart's name is new.
pub fn check(model: &ModelAst, names: &Names, errors: &mut Errors) {
    let mut seen = BTreeSet::from([model.name.to_string()]);
    for chart in &model.charts {
        let name = chart.name.to_string();
        if !seen.insert(name.clone()) {
            errors.at(
                model.spans.range(chart.id),
                format!("a model or chart called `{name}` is already declared: a chart is emitted as a module of that name"),
            );
        }
        let mut replaced = BTreeSet::new();
        for state in &chart.replace {
            let at = model.spans.range(state.id);
            if names.get(&state.name).map(|d| d.kind) != Some(Kind::State) {
                errors.at(
                    at,
                    format!(
                        "chart `{name}` replaces `{}`, which is not a state of the model",
                        state.name
                    ),
                );
            } else if !replaced.insert(state.name.as_str()) {
                errors.at(at, format!("`{}` is replaced twice", state.name));
            } else if !chart.lets.iter().any(|l| l.name == state.name) {
                errors.at(
                    at,
                    format!(
                        "chart `{name}` replaces `{0}` but does not define it: add `let {0} = ..;` in terms of the new states",
                        state.name
                    ),
                );
            }
        }
        if chart.states.len() != chart.replace.len() {
            errors.at(
                model.spans.range(chart.id),
                format!(
                    "chart `{name}` replaces {} states by {}: a change of variables keeps their number",
                    chart.replace.len(),
                    chart.states.len()
                ),
            );
        }
        if let Some(after) = &chart.after {
            if !model.outputs.iter().any(|o| o.name == after.name) {
                errors.at(
                    model.spans.range(after.id),
                    format!(
                        "chart `{name}` puts its outputs after `{}`, which is not an output of the model",
                        after.name
                    ),
                );
            }
        }
    }
}
