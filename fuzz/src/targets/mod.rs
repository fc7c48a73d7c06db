//! The fuzz targets, one file each; [`ALL`] lists them in the order `all` runs them.

pub mod dsl;
pub mod models;
pub mod scene;
pub mod sweep;
pub mod text;
pub mod toml;

use crate::supervisor::Target;
use text::TextTarget;

const DSL_SEEDS: &[&str] = &["fuzz/corpus/dsl"];
static DSL_FRONT: TextTarget = TextTarget::new(
    "dsl-front",
    "dsl",
    DSL_SEEDS,
    &dsl::VOCABULARY,
    dsl::check_front,
);
static DSL_COMPILE: TextTarget = TextTarget::new(
    "dsl-compile",
    "dsl",
    DSL_SEEDS,
    &dsl::VOCABULARY,
    dsl::check_compile,
);
static DSL_EVAL: TextTarget = TextTarget::new(
    "dsl-eval",
    "dsl",
    DSL_SEEDS,
    &dsl::VOCABULARY,
    dsl::check_eval,
);
static SCENE: TextTarget = TextTarget::new(
    "scene",
    "toml",
    &["scenes", "fuzz/corpus/scene"],
    &toml::VOCABULARY,
    scene::check,
);
static SWEEP: TextTarget = TextTarget::new(
    "sweep",
    "toml",
    &["sweeps", "fuzz/corpus/sweep"],
    &toml::VOCABULARY,
    sweep::check,
);
static MODELS: models::Models = models::Models::new();

/// Every target.
pub static ALL: [&dyn Target; 6] = [&DSL_FRONT, &DSL_COMPILE, &DSL_EVAL, &SCENE, &SWEEP, &MODELS];

/// The target called `name`.
pub fn named(name: &str) -> Option<&'static dyn Target> {
    ALL.iter().copied().find(|t| t.name() == name)
}
