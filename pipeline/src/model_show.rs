//! `eulerdisk model show`: the disk's equations as the compiler solved them, so that a
//! physicist can set them beside the paper's (13)–(16).
//!
//! The text is produced while the models compile (the macro's `SOLVED_MARKDOWN` and
//! `SOLVED_LATEX`): explicit equations block by block in solve order, the pivots each block
//! divides by, and the outputs. For the rolling model the Markdown ends with a check a reader
//! can repeat by hand: `N/mg` at the paper's start from the generated model beside the paper's
//! formula (13).

use equations::formulas::{rolling_normal_force_ratio, BodyRates, FormulaError};
use equations::layout;
use equations::models::{rolling, sliding, sliding_cartesian};
use equations::DiskParams;
use equations::InitialState;
use model_runtime::{EvalError, WithOutputs as _};
use std::fmt::Write as _;

/// A model of the disk, by the name `model show` takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelName {
    /// Box 1: rolling without slipping.
    Rolling,
    /// Box 3 in the paper's polar slip variables.
    Sliding,
    /// Box 3 in Cartesian slip components.
    SlidingCartesian,
}

impl ModelName {
    /// Every model of the disk.
    pub const ALL: [ModelName; 3] = [
        ModelName::Rolling,
        ModelName::Sliding,
        ModelName::SlidingCartesian,
    ];

    /// The name as `model show` takes it.
    pub fn name(self) -> &'static str {
        match self {
            ModelName::Rolling => "rolling",
            ModelName::Sliding => "sliding",
            ModelName::SlidingCartesian => "sliding-cartesian",
        }
    }

    /// The model named `name`, in any case (`Rolling`, `SLIDING-CARTESIAN`).
    pub fn from_name(name: &str) -> Option<ModelName> {
        (ModelName::ALL.into_iter()).find(|model| model.name().eq_ignore_ascii_case(name))
    }
}

/// How the equations are printed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Markdown, the equations in DSL syntax.
    Markdown,
    /// A LaTeX `align*` environment.
    Latex,
}

/// `N/mg` at the paper's start, from the generated rolling model and from eq. (13).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalForceCheck {
    /// The generated model's output `N`, divided by `m g`.
    pub model: f64,
    /// The paper's closed form (13).
    pub formula: f64,
}

/// Why the check could not be made.
#[derive(Debug, thiserror::Error)]
pub enum CheckError {
    /// The model could not be evaluated at the paper's start.
    #[error("the rolling model at the paper's start: {0}")]
    Model(#[from] EvalError),
    /// The closed form has no value there.
    #[error("formula (13) at the paper's start: {0}")]
    Formula(#[from] FormulaError),
}

/// `N/mg` at the paper's start (paper parameters, still air) both ways.
pub fn paper_start_normal_force() -> Result<NormalForceCheck, CheckError> {
    let p = DiskParams::paper();
    let start = InitialState::paper(&p);
    let model = rolling::Model::new(p.to_array());
    let ev = model.evaluate(start.t, &start.state.y)?;
    let rates = BodyRates {
        omega_x: start.state.y[layout::OMEGA_X],
        omega_y: start.state.y[layout::OMEGA_Y],
        omega_z: start.state.y[layout::OMEGA_Z],
    };
    Ok(NormalForceCheck {
        model: ev.outputs[rolling::output::N] / p.weight(),
        formula: rolling_normal_force_ratio(&p, start.state.y[layout::THETA], &rates)?,
    })
}

/// The text `model show` prints.
pub fn show(model: ModelName, format: Format) -> Result<String, CheckError> {
    let (markdown, latex) = match model {
        ModelName::Rolling => (rolling::SOLVED_MARKDOWN, rolling::SOLVED_LATEX),
        ModelName::Sliding => (sliding::SOLVED_MARKDOWN, sliding::SOLVED_LATEX),
        ModelName::SlidingCartesian => (
            sliding_cartesian::SOLVED_MARKDOWN,
            sliding_cartesian::SOLVED_LATEX,
        ),
    };
    if format == Format::Latex {
        return Ok(latex.to_string());
    }
    let mut text = markdown.to_string();
    if model == ModelName::Rolling {
        let check = paper_start_normal_force()?;
        // Writing into a String cannot fail.
        let _ = write!(
            text,
            "\n## At the paper's start\n\n\
             theta0 = pi/2 - 1, Omega = (1, 0, 0) rad/s, at rest, paper parameters:\n\n\
             | N/mg | value |\n|---|---:|\n\
             | the model above (output `N`) | {} |\n\
             | the paper's formula (13), alpha1 + alpha2/sin(theta) | {} |\n\
             | difference | {:e} |\n",
            check.model,
            check.formula,
            check.model - check.formula
        );
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rolling_normal_force_at_the_paper_start_agrees_with_formula_13() {
        let check = paper_start_normal_force().unwrap();
        assert!(
            (check.model - check.formula).abs() <= 1e-13 * check.formula.abs(),
            "{check:?}"
        );
        // Not a trivial agreement: the start is tilted and turning, N differs from mg.
        assert!((check.model - 1.0).abs() > 1e-3, "{check:?}");
    }

    #[test]
    fn markdown_names_every_derivative_and_pivot() {
        let text = show(ModelName::Rolling, Format::Markdown).unwrap();
        for state in rolling::STATE_NAMES {
            assert!(
                text.contains(&format!("    der({state}) = ")),
                "der({state})"
            );
        }
        for pivot in rolling::INFO.pivots.iter() {
            assert!(text.contains(&format!("`{pivot}`")), "{pivot}");
        }
        assert!(text.contains("der(theta) = Omega_y"));
        assert!(text.contains("## At the paper's start"));
        let sliding = show(ModelName::SlidingCartesian, Format::Markdown).unwrap();
        for state in sliding_cartesian::STATE_NAMES {
            assert!(sliding.contains(&format!("der({state})")), "der({state})");
        }
    }

    #[test]
    fn disk_models_are_found_by_name_in_any_case() {
        for model in ModelName::ALL {
            assert_eq!(ModelName::from_name(model.name()), Some(model));
        }
        assert_eq!(
            ModelName::from_name("Sliding-Cartesian"),
            Some(ModelName::SlidingCartesian)
        );
        assert_eq!(ModelName::from_name("drop.dsl"), None);
    }

    #[test]
    fn latex_is_one_align_environment() {
        let text = show(ModelName::Sliding, Format::Latex).unwrap();
        assert!(text.starts_with("\\begin{align*}\n"));
        assert!(text.ends_with("\\end{align*}\n"));
        assert!(text.contains("\\dot{\\theta} &= \\Omega_{y} \\\\"));
        assert_eq!(text.matches("\\begin{").count(), 1);
    }
}
