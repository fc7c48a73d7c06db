//! The one way these tests run a scene in-process: quietly, into a fresh temporary folder,
//! with the generated models, no figures and no `trajectory.csv` unless a test asks.

use std::sync::atomic::AtomicBool;

use eulerdisk::{
    run_scene, Backend, Override, ProgressStyle, Provenance, RunOptions, RunReport, Scene,
};

/// What a test may change about a quiet run.
#[derive(Clone, Copy, Debug)]
pub struct Quiet {
    /// Which implementation runs.
    pub backend: Backend,
    /// Draw the figures.
    pub figures: bool,
    /// Write `trajectory.csv`.
    pub trajectory: bool,
}

impl Default for Quiet {
    fn default() -> Self {
        Quiet {
            backend: Backend::Generated,
            figures: false,
            trajectory: false,
        }
    }
}

/// Runs `scene` (loaded with `overrides`) into a temporary folder; `interrupt` as `run_scene`
/// takes it. The folder lives as long as the returned handle.
pub fn run_quietly(
    scene: &Scene,
    overrides: &[Override],
    how: Quiet,
    interrupt: &AtomicBool,
) -> (tempfile::TempDir, RunReport) {
    let dir = tempfile::tempdir().unwrap();
    let opts = RunOptions {
        out_dir: dir.path().to_path_buf(),
        progress: ProgressStyle::Quiet,
        backend: how.backend,
        engine: eulerdisk::DEFAULT_ENGINE,
        figures: how.figures,
        trajectory: how.trajectory,
        provenance: Provenance::new(scene, &scene.name, overrides),
    };
    let report = run_scene(scene, &opts, interrupt).unwrap();
    (dir, report)
}
