//! The fuzz targets, one file each; [`ALL`] lists them in the order `all` runs them.

pub mod dsl;
pub mod models;
pub mod scene;
pub mod sweep;
pub mod toml;

use crate::supervisor::Target;

static DSL_FRONT: dsl::Dsl = dsl::Dsl::new(dsl::Stage::Front);
static DSL_COMPILE: dsl::Dsl = dsl::Dsl::new(dsl::Stage::Compile);
static DSL_EVAL: dsl::Dsl = dsl::Dsl::new(dsl::Stage::Eval);
static SCENE: scene::SceneLoader = scene::SceneLoader::new();
static SWEEP: sweep::SweepLoader = sweep::SweepLoader::new();
static MODELS: models::Models = models::Models::new();

/// Every target.
pub static ALL: [&dyn Target; 6] = [&DSL_FRONT, &DSL_COMPILE, &DSL_EVAL, &SCENE, &SWEEP, &MODELS];

/// The target called `name`.
pub fn named(name: &str) -> Option<&'static dyn Target> {
    ALL.iter().copied().find(|t| t.name() == name)
}
