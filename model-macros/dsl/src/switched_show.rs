//! A switched model printed for a reader: the modes, what fires each event and what it does,
//! in Markdown (DSL syntax) and in LaTeX.

use crate::switched::{Action, Crossing};
use crate::switched_compile::{CompiledEvent, CompiledSwitched, Jump};
use model_algebra::latex_name;
use std::fmt::Write;

/// The modes and their events as Markdown: one table per mode.
pub fn switching_markdown(model: &CompiledSwitched) -> String {
    let states = model.states();
    let mut md = format!("# `{}`: modes and events\n\n", model.name);
    let modes: Vec<String> = model
        .modes
        .iter()
        .map(|m| format!("`{}`", m.model.name))
        .collect();
    let _ = writeln!(
        md,
        "Modes: {} (a run starts in the first).",
        modes.join(", ")
    );
    let initial: Vec<String> = (states.iter().zip(&model.initial))
        .filter_map(|(s, v)| v.map(|v| format!("{s} = {v}")))
        .collect();
    if !initial.is_empty() {
        let _ = writeln!(md, "Initial state: {}.", initial.join(", "));
    }
    if !model.discrete.is_empty() {
        let values: Vec<String> = (model.discrete.iter())
            .map(|(name, value)| format!("{name} = {value}"))
            .collect();
        let _ = writeln!(
            md,
            "Discrete values (held between events, set by resets): {}.",
            values.join(", ")
        );
    }
    for (k, mode) in model.modes.iter().enumerate() {
        let _ = writeln!(md, "\n## Mode `{}`\n", mode.model.name);
        let own: Vec<(&String, &String)> = (mode.model.states.iter().zip(states))
            .filter(|(a, b)| a != b)
            .collect();
        if !own.is_empty() {
            let news: Vec<String> = own.iter().map(|(a, _)| format!("`{a}`")).collect();
            let olds: Vec<String> = own.iter().map(|(_, b)| format!("`{b}`")).collect();
            let _ = writeln!(
                md,
                "States: {} in the slots of {}.\n",
                news.join(", "),
                olds.join(", ")
            );
        }
        if let Some(clock) = &mode.time_scale {
            let _ = writeln!(
                md,
                "Time scale (regularised time, `dt = s dτ`): `s = {}`.\n",
                clock.text
            );
        }
        if let Some(step) = &mode.first_step {
            let _ = writeln!(md, "First step when the mode starts: `{}`.\n", step.text);
        }
        if mode.events.is_empty() {
            md.push_str("No event: the run stays in this mode.\n");
            continue;
        }
        md.push_str("| event | fires when | then |\n|---|---|---|\n");
        for event in &mode.events {
            let then = match &event.action {
                Action::Record => "recorded; nothing changes".to_string(),
                Action::Stop => "the run stops".to_string(),
                Action::Jump(jump) => jump_text(model, k, jump),
            };
            let shared = if event.shared { " (every mode)" } else { "" };
            let _ = writeln!(
                md,
                "| `{}`{shared} | `{}` crosses 0 {} | {then} |",
                event.name,
                event.guard,
                crossing_words(event.crossing)
            );
            if let Some(jump) = &event.accumulation {
                let _ = writeln!(
                    md,
                    "| `{}` accumulates | its firings converge (a Zeno point) | {} |",
                    event.name,
                    jump_text(model, k, jump)
                );
            }
        }
    }
    md
}

/// The same as LaTeX: per mode, one line per event, `guard \downarrow 0 \Rightarrow resets`.
pub fn switching_latex(model: &CompiledSwitched) -> String {
    let mut tex = String::from("\\begin{align*}\n");
    for (k, mode) in model.modes.iter().enumerate() {
        let _ = writeln!(
            tex,
            "&\\textbf{{{}}} \\\\",
            mode.model.name.replace('_', "\\_")
        );
        for event in &mode.events {
            let _ = writeln!(
                tex,
                "&\\quad \\text{{{}}}: & {} &{} 0 \\;\\Rightarrow\\; {} \\\\",
                event.name.replace('_', "\\_"),
                event.guard_latex,
                match event.crossing {
                    Crossing::Up => "\\uparrow",
                    Crossing::Down => "\\downarrow",
                    Crossing::Both => "\\updownarrow",
                },
                action_latex(model, k, event)
            );
        }
    }
    tex.push_str("\\end{align*}\n");
    tex
}

fn action_latex(model: &CompiledSwitched, mode: usize, event: &CompiledEvent) -> String {
    let jump = |jump: &Jump| {
        let into = jump.to.unwrap_or(mode);
        let mut parts: Vec<String> = (jump.states.iter().zip(&jump.latex))
            .map(|(&s, v)| format!("{}^{{+}} = {v}", latex_name(model.value_name(into, s))))
            .collect();
        if let Some(function) = &jump.by {
            parts.push(format!(
                "y^{{+}} = \\texttt{{{}}}(t, y, \\dot y)",
                function.replace('_', "\\_")
            ));
        }
        if let Some(to) = jump.to {
            parts.push(format!(
                "\\to \\text{{{}}}",
                model.modes[to].model.name.replace('_', "\\_")
            ));
        }
        if let Some(choice) = &jump.choice {
            let mut next: Vec<String> = (choice.modes.iter())
                .map(|&k| {
                    format!(
                        "\\text{{{}}}",
                        model.modes[k].model.name.replace('_', "\\_")
                    )
                })
                .collect();
            if choice.stop {
                next.push("\\text{stop}".to_string());
            }
            parts.push(format!("\\to {}", next.join(" \\mid ")));
        }
        parts.join(",\\ ")
    };
    let mut text = match &event.action {
        Action::Record => "\\text{record}".to_string(),
        Action::Stop => "\\text{stop}".to_string(),
        Action::Jump(j) => jump(j),
    };
    if let Some(acc) = &event.accumulation {
        let _ = write!(text, ";\\ \\text{{accumulating}}: {}", jump(acc));
    }
    text
}

fn crossing_words(crossing: Crossing) -> &'static str {
    match crossing {
        Crossing::Up => "upwards",
        Crossing::Down => "downwards",
        Crossing::Both => "either way",
    }
}

fn jump_text(model: &CompiledSwitched, from: usize, jump: &Jump) -> String {
    let into = jump.to.unwrap_or(from);
    let mut parts: Vec<String> = (jump.states.iter().zip(&jump.texts))
        .map(|(&s, v)| format!("`{} := {v}`", model.value_name(into, s)))
        .collect();
    if let Some(function) = &jump.by {
        parts.push(format!("the state `by {function}` (Rust)"));
    }
    if let Some(choice) = &jump.choice {
        let mut next: Vec<String> = (choice.modes.iter())
            .map(|&k| format!("`{}`", model.modes[k].model.name))
            .collect();
        if choice.stop {
            next.push("stop".to_string());
        }
        parts.push(format!("go to one of {}, as it decides", next.join(", ")));
        return parts.join(", ");
    }
    parts.push(match jump.to {
        Some(to) => format!("go to `{}`", model.modes[to].model.name),
        None => format!("restart `{}`", model.modes[from].model.name),
    });
    parts.join(", ")
}
