//! How a run was produced, recorded in `summary.json` beside its results.
//!
//! A summary is only worth keeping if it can be reproduced: which program (version and git
//! revision), which scene (name and where it was read from), which overrides were given, and
//! every setting after defaults and overrides were applied, including the ones the simulation
//! derives from them. The paper's column of the printed comparison also depends on the scene:
//! it is shown only when the disk, friction, air and start are the paper's.

use std::path::Path;

use serde::Serialize;

use super::plan::SamplePlan;
use crate::scene::{self, Override, Scene, DEFAULT_SCENE};

/// The program's version (`Cargo.toml`).
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
/// The git revision the program was built from (`build.rs`), or `unknown (built without git)`.
pub const GIT_REVISION: &str = env!("EULERDISK_GIT_REVISION");

/// Everything needed to say how a run was produced.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Provenance {
    /// `eulerdisk <version>`.
    pub program: String,
    /// The git revision of the build.
    pub git_revision: String,
    /// The simulation engine that ran ([`equations::Engine::name`]: the hand-written system
    /// until a run says which ran, in its `summary.json`).
    pub engine: String,
    /// The scene's name.
    pub scene: String,
    /// Where the scene was read from: the file given, or `built-in scenes/<name>.toml`.
    pub scene_file: String,
    /// The overrides given on the command line, in the order applied, as `table.key=value`
    /// (`--rtol 1e-9` is `solver.rtol=1e-9`).
    pub overrides: Vec<String>,
    /// Every scene setting after defaults and overrides, table by table.
    pub settings: serde_json::Value,
    /// Settings the simulation derives from the scene's.
    pub derived: DerivedSettings,
}

/// Simulation settings that no scene key sets directly.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DerivedSettings {
    /// Slip speed at which the end of sliding is detected (m/s): `max(10 atol, 1e-9)`.
    pub stick_threshold: f64,
    /// The run stops when the disk comes this close to flat (rad).
    pub min_inclination: f64,
    /// Whether the state is projected onto the constraints after every step.
    pub project_each_step: bool,
    /// Mode decisions allowed within `chatter_window_s` before the run stops as chattering.
    pub chatter_max_transitions: usize,
    /// The chattering window (s).
    pub chatter_window_s: f64,
    /// Budget of step attempts.
    pub max_steps: u64,
    /// Samples per second delivered while the first and last second are recorded finely.
    pub fine_sample_rate: f64,
}

impl Provenance {
    /// The provenance of a run of `scene`, loaded from `name_or_path` with `overrides`.
    pub fn new(scene: &Scene, name_or_path: &str, overrides: &[Override]) -> Provenance {
        let fine_rate = SamplePlan::new(
            0.0,
            scene.file.settings.run.t_end,
            scene.file.settings.run.sample_rate,
        )
        .with_windows(&scene.file.cli.output.windows)
        .figure_rate();
        let c = &scene.config;
        Provenance {
            program: format!("eulerdisk {VERSION}"),
            git_revision: GIT_REVISION.to_string(),
            engine: equations::ENGINE.to_string(),
            scene: scene.name.clone(),
            scene_file: source_of(name_or_path, &scene.name),
            overrides: overrides
                .iter()
                .map(|o| format!("{}.{}={}", o.table, o.key, o.value))
                .collect(),
            settings: serde_json::to_value(&scene.file).unwrap_or_else(|e| {
                serde_json::Value::String(format!("the settings could not be recorded: {e}"))
            }),
            derived: DerivedSettings {
                stick_threshold: c.stick_threshold,
                min_inclination: c.min_inclination,
                project_each_step: c.project_each_step,
                chatter_max_transitions: c.chatter.max_transitions,
                chatter_window_s: c.chatter.window,
                max_steps: c.max_steps,
                fine_sample_rate: fine_rate,
            },
        }
    }
}

/// Where a scene named `name_or_path` is read from (the rule of [`scene::resolve`]).
fn source_of(name_or_path: &str, name: &str) -> String {
    if Path::new(name_or_path).is_file() {
        name_or_path.to_string()
    } else {
        format!("built-in scenes/{name}.toml")
    }
}

/// Whether `scene` is the paper's: the disk parameters (mass, radius, gravity, friction, air)
/// and the completed initial state of the built-in paper scene, however written (duration,
/// solver, sampling and outputs may differ). Only then does the printed comparison show the
/// paper's values.
pub fn is_papers_scene(scene: &Scene) -> bool {
    let Some((_, text)) = scene::BUILTIN.iter().find(|(n, _)| *n == DEFAULT_SCENE) else {
        return false;
    };
    let Ok(paper) = scene::parse(DEFAULT_SCENE, text, &[]) else {
        return false;
    };
    scene.params == paper.params && scene.initial == paper.initial
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(name: &str, overrides: &[Override]) -> Scene {
        scene::load(name, overrides).unwrap()
    }

    #[test]
    fn the_papers_scene_is_recognised_by_its_physics_not_its_name() {
        assert!(is_papers_scene(&load("tangent-toy", &[])));
        assert!(is_papers_scene(&load("tangent-toy-pruned", &[])));
        // Duration and solver are not physics.
        let shorter = [
            Override::new("run", "t_end", 2.0),
            Override::new("solver", "rtol", 1e-9),
        ];
        assert!(is_papers_scene(&load("tangent-toy", &shorter)));
        // Another disk or another start is not the paper's.
        assert!(!is_papers_scene(&load(
            "tangent-toy",
            &[Override::new("friction", "mu_st", 0.3)]
        )));
        assert!(!is_papers_scene(&load("pure-rolling", &[])));
        assert!(!is_papers_scene(&load("spinning-in-place", &[])));
    }

    #[test]
    fn provenance_names_the_scene_every_setting_and_the_overrides() {
        let overrides = [
            Override::new("solver", "rtol", 1e-9),
            Override::parse("solver.guard_checks=exact:4").unwrap(),
        ];
        let scene = load("tangent-toy", &overrides);
        let p = Provenance::new(&scene, "tangent-toy", &overrides);
        assert_eq!(
            p.program,
            format!("eulerdisk {}", env!("CARGO_PKG_VERSION"))
        );
        assert!(!p.git_revision.is_empty());
        assert_eq!(p.scene, "tangent-toy");
        assert_eq!(p.scene_file, "built-in scenes/tangent-toy.toml");
        assert_eq!(p.overrides.len(), 2);
        assert!(
            p.overrides[1].starts_with("solver.guard_checks="),
            "{:?}",
            p.overrides
        );
        let solver = &p.settings["solver"];
        assert_eq!(solver["rtol"], 1e-9);
        assert_eq!(solver["atol"], 1e-10);
        assert_eq!(solver["guard_checks"], "exact:4");
        for key in ["integrator", "error_norm", "step_control"] {
            assert!(solver[key].is_string(), "solver.{key} recorded: {solver}");
        }
        assert_eq!(p.settings["run"]["t_end"], 100.0);
        assert_eq!(p.derived.stick_threshold, 1e-9);
        assert!(p.derived.fine_sample_rate >= scene.file.settings.run.sample_rate);
    }

    #[test]
    fn a_scene_file_is_recorded_by_its_path() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("mine.toml");
        let (_, text) = scene::resolve("steady-circle").unwrap();
        std::fs::write(&path, text).unwrap();
        let given = path.to_string_lossy().into_owned();
        let scene = load(&given, &[]);
        assert_eq!(Provenance::new(&scene, &given, &[]).scene_file, given);
    }
}
