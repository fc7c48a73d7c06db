//! The scene loader, as `eulerdisk run` calls it: a scene's text with `--set` overrides
//! (`#set` lines, see [`super::toml`]), parsed, overridden, validated and completed.
//!
//! Seeds: the repository's `scenes/` and the edge cases of `fuzz/corpus/scene/`. A scene the
//! loader accepts must be one a run can start: parameters the models accept, a start and
//! settings whose every number is finite and within the run's own rules, and the models'
//! right-hand side at the start finite or a clear error. A rejected scene's message must stay
//! in proportion to its input (a key repeated a million times prints a bounded list).

use equations::{GeneratedModels, Mode};
use eulerdisk::{parse_scene, Override, Scene};
use model_runtime::Model;

use super::toml::sets;

/// Checks one scene input (a scene's text with `#set` lines), with the command line's Parquet
/// writer installed, as `eulerdisk run` has it.
pub fn check(text: &str) -> Result<(), String> {
    eulerdisk_parquet::install();
    let parsed: Result<Vec<Override>, _> = sets(text).into_iter().map(Override::parse).collect();
    let Ok(overrides) = parsed else {
        return Ok(()); // a malformed `--set`: a clear error
    };
    match parse_scene("fuzz", text, &overrides) {
        Ok(scene) => startable(&scene),
        Err(e) => proportionate(&e.to_string(), text),
    }
}

/// The longest message a rejected input of `len` bytes may give.
pub fn message_bound(len: usize) -> usize {
    (1 << 16) + 4 * len
}

/// `Err` when `message` is out of proportion to `input`.
pub fn proportionate(message: &str, input: &str) -> Result<(), String> {
    match message.len() <= message_bound(input.len()) {
        true => Ok(()),
        false => Err(format!(
            "a {} byte input gave a {} byte message",
            input.len(),
            message.len()
        )),
    }
}

/// `Err` saying how an accepted scene cannot start.
pub fn startable(scene: &Scene) -> Result<(), String> {
    let name = &scene.name;
    scene
        .params
        .validate()
        .map_err(|e| format!("scene `{name}` accepted with parameters a run refuses: {e}"))?;
    let chart = scene.config.chart();
    let mut issues = scene.config.issues(scene.initial.t, chart);
    issues.extend(scene.initial.issues());
    if let Some(issue) = issues.first() {
        return Err(format!(
            "scene `{name}` accepted, but a run refuses it: {issue}"
        ));
    }
    let models = GeneratedModels::generated(scene.params, chart)
        .map_err(|e| format!("scene `{name}`: the generated models refuse it: {e}"))?;
    let state = &scene.initial.state;
    let y = match scene.initial.mode {
        Mode::Rolling => state.y,
        Mode::Sliding => models.sliding_vector(state, state.slip),
    };
    let mut dy = [0.0; equations::DIM];
    let rhs = match scene.initial.mode {
        Mode::Rolling => models.rolling.rhs(scene.initial.t, &y, &mut dy),
        Mode::Sliding => models.sliding.rhs(scene.initial.t, &y, &mut dy),
    };
    match rhs.is_ok() && dy.iter().any(|v| !v.is_finite()) {
        true => Err(format!(
            "scene `{name}`: the start's derivative is Ok but not finite: {dy:?}"
        )),
        false => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_message_out_of_proportion_to_its_input_is_a_finding() {
        let input = "a = 1\n".repeat(1000);
        assert!(proportionate(&"x".repeat(message_bound(input.len())), &input).is_ok());
        let flood = "x".repeat(message_bound(input.len()) + 1);
        assert!(proportionate(&flood, &input).is_err());
    }

    #[test]
    fn a_scene_repeating_one_bad_entry_gives_a_bounded_message() {
        let lines: String = (0..20_000)
            .map(|k| format!("#set disk.m{k}=-1\n"))
            .collect();
        check(&format!("{lines}[disk]\nm = -1.0\n")).unwrap();
    }
}
