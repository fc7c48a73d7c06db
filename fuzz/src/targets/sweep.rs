//! The sweep loader and its expansion, as `eulerdisk sweep --dry-run` calls them: a sweep
//! file with `--set` arguments (`#set` lines, see [`super::toml`]), parsed, planned (axes,
//! rules, every point's scene validated), and its points listed as `run` commands.
//!
//! Seeds: the repository's `sweeps/` and the edge cases of `fuzz/corpus/sweep/`. What the
//! listing says must be true: each listed point's `--set` arguments, read as `eulerdisk run`
//! reads them, load to exactly the scene the plan validated for that point (a point listed as
//! runnable that the loader refuses, or loads to another scene, is a finding), and each such
//! scene can start (the scene target's [`startable`]).

use eulerdisk::{parse_scene, parse_sweep, plan, run_arguments, LoadedSweep, Override, Plan};

use super::scene::{proportionate, startable};
use super::toml::sets;

/// The most points of one plan whose listing is checked (the first and the last half).
const CHECKED_POINTS: usize = 64;

/// Checks one sweep input (a sweep file's text with `#set` lines), with the command line's
/// Parquet writer installed, as `eulerdisk sweep` has it.
pub fn check(text: &str) -> Result<(), String> {
    eulerdisk_parquet::install();
    let file = match parse_sweep("fuzz", text) {
        Ok(file) => file,
        Err(e) => return proportionate(&e.to_string(), text),
    };
    let loaded = LoadedSweep {
        name: "fuzz".into(),
        folder: None,
        file,
    };
    let cli_sets: Vec<String> = sets(text).into_iter().map(str::to_string).collect();
    match plan(&loaded, &cli_sets) {
        Ok(plan) => listing_is_true(&plan),
        Err(e) => proportionate(&e.to_string(), text),
    }
}

/// `Err` naming the first listed point that `eulerdisk run` would not load as planned.
fn listing_is_true(plan: &Plan) -> Result<(), String> {
    let d = &plan.definition;
    if d.points.len() != plan.scenes.len() {
        return Err(format!(
            "{} points but {} scenes",
            d.points.len(),
            plan.scenes.len()
        ));
    }
    let n = d.points.len();
    let half = CHECKED_POINTS / 2;
    let checked = (0..n).filter(|&i| i < half || i + half >= n);
    for i in checked {
        let arguments = run_arguments(d, &d.points[i]);
        let overrides: Result<Vec<Override>, _> =
            arguments.iter().map(|a| Override::parse(a)).collect();
        let said = || format!("point {i} listed as `--set {}`", arguments.join(" --set "));
        let overrides = overrides.map_err(|e| format!("{}: {e}", said()))?;
        let scene = parse_scene(&d.scene_name, &d.scene_text, &overrides)
            .map_err(|e| format!("{}, which `run` refuses: {e}", said()))?;
        if scene != plan.scenes[i] {
            return Err(format!("{} loads to another scene than planned", said()));
        }
        startable(&scene)?;
    }
    Ok(())
}
