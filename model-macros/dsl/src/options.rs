//! `options { .. }`: the compiler's knobs, settable per model.
//!
//! The defaults suit most models; `swell_bound` lets a model force (or forbid) the numeric
//! solve of its coupled blocks, e.g. to compare both or to keep a huge symbolic pivot out, and
//! `pivot_tolerance` sets how much cancellation a pivot may suffer before it counts as zero
//! (`0` restores the exact-zero test, e.g. for a model whose pivots cancel by design).

use crate::span::{Errors, Spans};
use model_algebra::CompileOptions;
use model_algebra::Named;

/// The options a model may set, with what each means (for the "unknown option" message).
const KNOWN: [(&str, &str); 2] = [
    (
        "swell_bound",
        "the most operations a block's symbolic solution may cost before it is solved numerically",
    ),
    (
        "pivot_tolerance",
        "the fraction of its terms' magnitudes below which a pivot's sum counts as zero",
    ),
];

/// The compiler options of a model: the defaults, overridden by its `options` section.
pub fn compile_options(
    options: &[Named<f64>],
    spans: &Spans,
    errors: &mut Errors,
) -> CompileOptions {
    let mut compile = CompileOptions::default();
    let mut seen = Vec::new();
    for option in options {
        let at = spans.range(option.id);
        if seen.contains(&option.name.as_str()) {
            errors.at(at, format!("option `{}` is set twice", option.name));
            continue;
        }
        seen.push(option.name.as_str());
        match option.name.as_str() {
            "swell_bound" => match whole_number(option.value) {
                Some(bound) => compile.swell_bound = bound,
                None => errors.at(
                    at,
                    format!(
                        "`swell_bound` must be a whole number of operations, not {}",
                        option.value
                    ),
                ),
            },
            "pivot_tolerance" => {
                if (0.0..1.0).contains(&option.value) {
                    compile.pivot_tolerance = option.value;
                } else {
                    errors.at(
                        at,
                        format!(
                            "`pivot_tolerance` must be at least 0 and below 1, not {}",
                            option.value
                        ),
                    );
                }
            }
            other => {
                let known: Vec<String> = KNOWN
                    .iter()
                    .map(|(name, what)| format!("`{name}` ({what})"))
                    .collect();
                errors.at(
                    at,
                    format!(
                        "unknown option `{other}`; the options are {}",
                        known.join(", ")
                    ),
                );
            }
        }
    }
    compile
}

fn whole_number(value: f64) -> Option<usize> {
    (value >= 0.0 && value.fract() == 0.0 && value <= u32::MAX as f64).then_some(value as usize)
}
