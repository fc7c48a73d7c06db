//! A switched model compiled: each mode's model by the algebra, and its outputs program split
//! into the user's outputs, the guards and each event's resets.

use crate::compile::compile;
use crate::span::Errors;
use crate::switched::{Action, Choice, Crossing, JumpPlan, SwitchedPlan};
use model_algebra::{CompiledModel, Program};

/// A switched model after the compiler.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CompiledSwitched {
    /// The model's name.
    pub name: String,
    /// Each state's initial value, where one is written.
    pub initial: Vec<Option<f64>>,
    /// The discrete values and their initial values: each mode's model takes them as
    /// parameters after the model's own (their defaults there).
    pub discrete: Vec<(String, f64)>,
    /// The modes, the first being where a run starts.
    pub modes: Vec<CompiledMode>,
    /// What the model says that is legal but likely not meant (a guard that can never fire,
    /// a mode never entered or never left), each at its place in the text when the model
    /// was read from one ([`crate::Source::compile_switched`]); empty otherwise.
    pub warnings: Vec<crate::located::Located>,
}

/// One mode compiled.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CompiledMode {
    /// The mode's model (named after the mode), with the user's outputs only.
    pub model: CompiledModel,
    /// `out[k]` = the guard value of event `k`, `lhs - rhs` (reads `t`, `y`, `dy`, `p`).
    pub guards: Program,
    /// The mode's events, in priority order.
    pub events: Vec<CompiledEvent>,
    /// The mode's time scale, if one is declared.
    pub time_scale: Option<Clock>,
    /// The step to try first when the mode starts, if one is declared (`out[0]`; reads `t`,
    /// `y`, `dy`, `p`: the derivatives are evaluated first). A value that is not finite and
    /// positive leaves the choice to the integrator.
    pub first_step: Option<Clock>,
}

/// One number a mode declares besides its equations (its clock in regularised time,
/// `dt = s dτ`, or its first step), compiled.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Clock {
    /// `out[0]` = the number (a clock reads `y` and `p` only).
    pub program: Program,
    /// The number as the compiler simplified it, in the DSL's syntax.
    pub text: String,
}

/// One event compiled.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CompiledEvent {
    /// The event's name.
    pub name: String,
    /// Which crossings fire it.
    pub crossing: Crossing,
    /// The guard as the compiler simplified it, `lhs - rhs` in the DSL's syntax.
    pub guard: String,
    /// The same in LaTeX.
    pub guard_latex: String,
    /// What it does.
    pub action: Action<Jump>,
    /// What an accumulation of its resets turns into.
    pub accumulation: Option<Jump>,
    /// Whether every mode has it.
    pub shared: bool,
}

/// A compiled jump: the target and the program of the new values.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Jump {
    /// The mode the run continues in (`None`: the same mode, restarted).
    pub to: Option<usize>,
    /// The states reset, in the order written.
    pub states: Vec<usize>,
    /// `out[k]` = the new value of `states[k]`, from the state just before the event.
    pub program: Program,
    /// Each new value as the compiler simplified it, in the DSL's syntax.
    pub texts: Vec<String>,
    /// The same in LaTeX.
    pub latex: Vec<String>,
    /// The Rust function that computes the new state instead (`by FUNCTION`): the compiled
    /// model calls it; a model that has one can run only compiled.
    pub by: Option<String>,
    /// The modes the function chooses among, when it also decides where the run goes.
    pub choice: Option<Choice>,
}

impl CompiledSwitched {
    /// The state names of the first mode (every mode has as many; a mode may name some of
    /// its slots its own way: [`CompiledSwitched::slot_names`]).
    pub fn states(&self) -> &[String] {
        &self.modes[0].model.states
    }

    /// Each state slot's name, or its names joined by `/` where modes name it differently
    /// (`V_X/u_X`), in the order the modes first use them.
    pub fn slot_names(&self) -> Vec<String> {
        (0..self.states().len())
            .map(|k| {
                let mut names: Vec<&str> = Vec::new();
                for mode in &self.modes {
                    let name = mode.model.states[k].as_str();
                    if !names.contains(&name) {
                        names.push(name);
                    }
                }
                names.join("/")
            })
            .collect()
    }

    /// The name a reset into mode `mode` assigns at `slot`: the mode's state there, or after
    /// the states a discrete value.
    pub fn value_name(&self, mode: usize, slot: usize) -> &str {
        let states = &self.modes[mode].model.states;
        match states.get(slot) {
            Some(state) => state,
            None => &self.discrete[slot - states.len()].0,
        }
    }

    /// The number of the model's own parameters (each mode's model takes the discrete values
    /// after them).
    pub fn n_params(&self) -> usize {
        self.modes[0].model.params.len() - self.discrete.len()
    }

    /// The mode named `name`.
    pub fn mode(&self, name: &str) -> Option<usize> {
        self.modes.iter().position(|m| m.model.name == name)
    }
}

/// Compiles every mode of a checked switched model; all errors are reported together.
pub fn compile_switched(plan: &SwitchedPlan) -> syn::Result<CompiledSwitched> {
    let mut errors = Errors::default();
    let mut modes = Vec::new();
    for mode in &plan.modes {
        let mut model = match compile(&mode.model) {
            Ok(model) => model,
            Err(error) => {
                let name = &mode.model.spec.name;
                for error in error {
                    errors.push(syn::Error::new(
                        error.span(),
                        format!("in mode `{name}`: {error}"),
                    ));
                }
                continue;
            }
        };
        let all = model.outputs_program.clone();
        let texts: Vec<String> = (model.explanation.outputs.iter())
            .map(|(text, _)| text.clone())
            .collect();
        let latex: Vec<String> = (model.explanation.outputs.iter())
            .map(|(_, latex)| latex.clone())
            .collect();
        let n_user = mode.user_outputs;
        let spans = &mode.model.ast.spans;
        let guards = all.select_outputs(n_user..n_user + mode.events.len());
        let mut events = Vec::new();
        for event in &mode.events {
            let guard = all.select_outputs(event.guard_output..event.guard_output + 1);
            if guard.reads_only_parameters() && !event.shared {
                errors.at(
                    spans.range(event.guard_id),
                    format!(
                        "the guard of `{}` reads no state, derivative or time: it never changes sign during a run, so the event never fires",
                        event.name
                    ),
                );
            }
            let jump = |plan: &JumpPlan| {
                let outputs = plan.resets.iter().map(|&(_, o)| o);
                let range = match (outputs.clone().min(), outputs.clone().max()) {
                    (Some(lo), Some(hi)) => lo..hi + 1,
                    _ => 0..0,
                };
                Jump {
                    to: plan.to,
                    states: plan.resets.iter().map(|&(s, _)| s).collect(),
                    program: all.select_outputs(range),
                    texts: outputs.clone().map(|o| texts[o].clone()).collect(),
                    latex: outputs.map(|o| latex[o].clone()).collect(),
                    by: plan.by.clone(),
                    choice: plan.choice.clone(),
                }
            };
            events.push(CompiledEvent {
                name: event.name.clone(),
                crossing: event.crossing,
                guard: texts[event.guard_output].clone(),
                guard_latex: latex[event.guard_output].clone(),
                action: match &event.action {
                    Action::Record => Action::Record,
                    Action::Stop => Action::Stop,
                    Action::Jump(plan) => Action::Jump(jump(plan)),
                },
                accumulation: event.accumulation.as_ref().map(jump),
                shared: event.shared,
            });
        }
        let time_scale = mode.time_scale.map(|(id, output)| {
            let program = all.select_outputs(output..output + 1);
            let reads = program.reads();
            if reads.time || !reads.ders.is_empty() {
                errors.at(
                    spans.range(id),
                    "a time scale reads only states and parameters: the integrator evaluates it \
                     before it knows the derivatives, and in regularised time `t` is a state of \
                     the clock, not an input",
                );
            }
            Clock {
                program,
                text: texts[output].clone(),
            }
        });
        // Outputs are functions of the state (a trajectory's rows are computed from the states
        // alone): one that reads a discrete value is refused at its name.
        let n_params = model.params.len() - plan.discrete.len();
        for (k, output) in mode.model.ast.outputs.iter().take(n_user).enumerate() {
            let reads = all.select_outputs(k..k + 1).reads();
            if let Some(&d) = reads.params.iter().find(|&&i| i >= n_params) {
                errors.at(
                    spans.range(output.id),
                    format!(
                        "output `{}` reads the discrete value `{}`: outputs are functions of the \
                         state, parameters and time; a value held between events belongs in \
                         equations, guards and resets",
                        output.name,
                        plan.discrete[d - n_params].0
                    ),
                );
            }
        }
        let first_step = mode.first_step.map(|(_, output)| Clock {
            program: all.select_outputs(output..output + 1),
            text: texts[output].clone(),
        });
        model.outputs.truncate(n_user);
        model.outputs_program = all.select_outputs(0..n_user);
        model.explanation.outputs.truncate(n_user);
        modes.push(CompiledMode {
            model,
            guards,
            events,
            time_scale,
            first_step,
        });
    }
    errors.finish()?;
    Ok(CompiledSwitched {
        name: plan.ast.name.to_string(),
        initial: plan.initial.clone(),
        warnings: Vec::new(),
        discrete: plan.discrete.clone(),
        modes,
    })
}
