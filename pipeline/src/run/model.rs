//! Which models a run integrates: the scene's `[output] quantities` decide.
//!
//! The pruned variants (`variant pruned` in the model files) integrate 8 of the 12 states and
//! compile the air out, so they are cheaper per step; but the states they drop (`X`, `Y`, `Z`,
//! `phi`) stay frozen at their initial values, and so does everything computed from them (the
//! energy, the height residual). A run therefore takes them only when nothing it writes needs
//! a dropped state — every quantity of `trajectory.csv`, and every quantity the figures plot —
//! and the air is still; otherwise the full models run. Summary keys that a pruned run cannot
//! compute are written as `null` with the reason, never as a number from a frozen state.
//! `eulerdisk sound` asks the same question for the one quantity it keeps, `N`.
//!
//! The three model sets are three types; [`with_models`] builds the chosen one and hands it to
//! a [`ModelsTask`] as a `&dyn DiskRunner`, so a caller states once what it does with models,
//! whichever they are, and the engine is compiled once per set of models, not per task.

use equations::{DiskParams, Engine, ParamError};
use equations::{
    DiskRunner, GeneratedModels, PruneError, PrunedModels, ReferenceModels, PRUNED_STATES,
};
use equations::{SlipChart, DIM};

use crate::eval::Backend;
use crate::figures::FIGURE_QUANTITIES;
use crate::scene::Scene;
use equations::record::Quantity;

/// The models a run integrates.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RunModel {
    /// The generated models, all 12 states.
    #[default]
    Full,
    /// The generated pruned variants: 8 states, still air.
    Pruned,
    /// The hand-written reference models, all 12 states.
    Reference,
}

impl RunModel {
    /// The short name: `full`, `pruned` or `reference`.
    pub fn name(self) -> &'static str {
        match self {
            RunModel::Full => "full",
            RunModel::Pruned => "pruned",
            RunModel::Reference => "reference",
        }
    }

    /// How `summary.json` and the printed table name it, e.g. `pruned (8 states)`.
    pub fn label(self) -> String {
        match self {
            RunModel::Full => format!("full ({DIM} states)"),
            RunModel::Pruned => format!("pruned ({PRUNED_STATES} states)"),
            RunModel::Reference => format!("reference ({DIM} states)"),
        }
    }
}

/// The models chosen for a run, why, and what they leave unintegrated.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ModelChoice {
    /// The models.
    pub model: RunModel,
    /// States (rolling-layout names) the models leave frozen; empty for the full models.
    pub frozen: Vec<&'static str>,
    /// Why these models (one line, for the user).
    pub reason: String,
    /// The engine that runs them ([`ModelChoice::on_engine`]; the hand-written system unless
    /// asked otherwise).
    pub engine: Engine,
}

/// Which engine a front end asks for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EngineChoice {
    /// The DSL's mode graph (`equations::simulate_graph`) where it models the run: the full
    /// models in still air, the Cartesian slip chart, DOP853 or DP5, no projection after steps
    /// ([`Engine::for_run`]); the hand-written system elsewhere.
    #[default]
    ModeGraph,
    /// The hand-written hybrid system (`equations::simulate`), the graph's reference.
    HandWritten,
}

/// The engine the front ends ask for unless told otherwise (`eulerdisk run --engine`): the
/// one line to switch. The mode graph, which runs the scenes it models as the hand-written
/// system does, to the byte (ARCHITECTURE.md, "The engines").
pub const DEFAULT_ENGINE: EngineChoice = EngineChoice::ModeGraph;

impl ModelChoice {
    /// These models on the engine `asked` for `scene`: the mode graph only for the full
    /// models and where it models the scene.
    pub fn on_engine(self, asked: EngineChoice, scene: &Scene) -> ModelChoice {
        let graph = asked == EngineChoice::ModeGraph
            && self.model == RunModel::Full
            && Engine::for_run(&scene.params, &scene.config) == Engine::ModeGraph;
        let engine = if graph {
            Engine::ModeGraph
        } else {
            Engine::HandWritten
        };
        ModelChoice { engine, ..self }
    }

    /// Whether the run computes `q`.
    pub fn computes(&self, q: Quantity) -> bool {
        q.computed_without(&self.frozen)
    }

    /// Why the run does not compute `q`, if it does not.
    pub fn missing(&self, q: Quantity) -> Option<String> {
        let frozen = q.reads_among(&self.frozen);
        (!frozen.is_empty()).then(|| {
            format!(
                "{} models: {} not integrated",
                self.model.name(),
                frozen.join(", ")
            )
        })
    }
}

fn full(model: RunModel, reason: String) -> ModelChoice {
    ModelChoice {
        model,
        frozen: Vec::new(),
        reason,
        engine: Engine::HandWritten,
    }
}

/// Chooses the models for `scene`: the pruned ones if the generated backend is asked for, the
/// air is still, and every quantity of `trajectory.csv` (and of the figures, when `figures`)
/// is computed by them; the full ones otherwise.
pub fn choose(scene: &Scene, backend: Backend, figures: bool) -> ModelChoice {
    let needed = scene
        .quantities
        .iter()
        .chain(if figures { &FIGURE_QUANTITIES[..] } else { &[] });
    choose_for(scene, backend, needed, "output.quantities")
}

/// Chooses the models for a run of `scene` that needs the quantities `needed` (`asked_by`
/// names where they come from, for the reason shown to the user).
pub fn choose_for<'q>(
    scene: &Scene,
    backend: Backend,
    needed: impl IntoIterator<Item = &'q Quantity>,
    asked_by: &str,
) -> ModelChoice {
    if backend == Backend::Reference {
        return full(RunModel::Reference, "--reference".into());
    }
    let pruned = match PrunedModels::pruned(scene.params, scene.config.chart()) {
        Ok(m) => m,
        Err(PruneError::AirNotStill { name, value }) => {
            return full(
                RunModel::Full,
                format!("air.{name} = {value}: the pruned models assume still air"),
            )
        }
        Err(e) => return full(RunModel::Full, format!("the pruned models cannot run: {e}")),
    };
    let frozen = pruned.frozen_states();
    let lost: Vec<String> = needed
        .into_iter()
        .filter_map(|q| {
            let dropped = q.reads_among(&frozen);
            (!dropped.is_empty()).then(|| format!("{} (needs {})", q.name(), dropped.join(", ")))
        })
        .collect();
    if !lost.is_empty() {
        return full(
            RunModel::Full,
            format!(
                "{asked_by} asks for {}; the pruned models do not integrate {}",
                lost.join(", "),
                frozen.join(", ")
            ),
        );
    }
    ModelChoice {
        model: RunModel::Pruned,
        reason: format!(
            "every requested quantity follows from the {PRUNED_STATES} states of the pruned \
             model (frozen: {}), in still air",
            frozen.join(", ")
        ),
        frozen,
        engine: Engine::HandWritten,
    }
}

/// Work to do with a set of disk models, whichever of the three it is.
pub trait ModelsTask {
    /// What the work returns.
    type Output;
    /// Does the work with `models`.
    fn run(self, models: &dyn DiskRunner) -> Self::Output;
}

/// Why the chosen models could not be built.
#[derive(Debug, thiserror::Error)]
pub enum BuildError {
    /// The parameters are not valid for the full or reference models.
    #[error("invalid parameters: {0}")]
    Params(#[from] ParamError),
    /// The pruned models refuse these parameters.
    #[error(transparent)]
    Pruned(#[from] PruneError),
}

/// Builds the models `model` for `params` and `chart` and runs `task` with them.
pub fn with_models<T: ModelsTask>(
    model: RunModel,
    params: DiskParams,
    chart: SlipChart,
    task: T,
) -> Result<T::Output, BuildError> {
    Ok(match model {
        RunModel::Reference => task.run(&ReferenceModels::reference(params, chart)?),
        RunModel::Full => task.run(&GeneratedModels::generated(params, chart)?),
        RunModel::Pruned => task.run(&PrunedModels::pruned(params, chart)?),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{self, Override};

    fn load(name: &str, overrides: &[Override]) -> Scene {
        scene::load(name, overrides).unwrap()
    }

    /// The mode graph runs by default, only the full models, and only where it models the
    /// scene; the hand-written system where asked and everywhere else.
    #[test]
    fn the_mode_graph_runs_by_default_where_it_models_the_scene() {
        let paper = load("tangent-toy", &[]);
        let engine = |scene: &Scene, backend, asked| {
            choose(scene, backend, false).on_engine(asked, scene).engine
        };
        let graph = EngineChoice::ModeGraph;
        assert_eq!(DEFAULT_ENGINE, graph);
        let full = choose(&paper, Backend::Generated, false);
        assert_eq!(full.model, RunModel::Full);
        assert_eq!(
            engine(&paper, Backend::Generated, DEFAULT_ENGINE),
            Engine::ModeGraph
        );
        assert_eq!(
            engine(&paper, Backend::Generated, EngineChoice::HandWritten),
            Engine::HandWritten
        );
        // The reference models and the pruned ones keep the hand-written system.
        assert_eq!(
            engine(&paper, Backend::Reference, graph),
            Engine::HandWritten
        );
        let pruned = load("tangent-toy-pruned", &[]);
        assert_eq!(
            choose(&pruned, Backend::Generated, false).model,
            RunModel::Pruned
        );
        assert_eq!(
            engine(&pruned, Backend::Generated, graph),
            Engine::HandWritten
        );
        // Air, the paper's slip sign, an implicit integrator: the graph does not model them.
        for o in [
            "air.mu_a=0.001",
            "run.slip_sign=paper",
            "solver.integrator=rodas4",
        ] {
            let other = load("tangent-toy", &[Override::parse(o).unwrap()]);
            assert_eq!(
                engine(&other, Backend::Generated, graph),
                Engine::HandWritten,
                "{o}"
            );
        }
    }
}
