//! The DSL's targets: its front end, its compiler, and the compiled programs at extreme
//! values, fed mutations of the seed models in `fuzz/corpus/dsl/`.
//!
//! - `dsl-front`: parse and validate (the model and its switched form);
//! - `dsl-compile`: the whole pipeline, as `model!` and `eulerdisk model` run it;
//! - `dsl-eval`: the compiled programs (right-hand side, Jacobian, outputs) at extreme states
//!   and parameters (zeros, signed zeros, subnormals, ±1e308, infinities, NaN, multiples of
//!   π). A user's model may compute a NaN where it likes, so only crashes and hangs count here;
//!   the disk's own models are held to finite answers by the `models` target.

use model_algebra::{CompiledModel, Inputs};
use model_dsl::Source;

use crate::mutate::Vocabulary;

/// How far into the pipeline a DSL target goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Parse and validate.
    Front,
    /// The whole compiler.
    Compile,
    /// Compile, then evaluate at extreme values.
    Eval,
}

/// Runs `text` through the DSL up to `stage`.
pub fn check(stage: Stage, text: &str) -> Result<(), String> {
    match stage {
        Stage::Front => front(text),
        Stage::Compile => {
            compile(text);
        }
        Stage::Eval => {
            for model in compile(text) {
                evaluate(&model);
            }
        }
    }
    Ok(())
}

/// [`check`] of the front end.
pub fn check_front(text: &str) -> Result<(), String> {
    check(Stage::Front, text)
}

/// [`check`] of the compiler.
pub fn check_compile(text: &str) -> Result<(), String> {
    check(Stage::Compile, text)
}

/// [`check`] of the compiled programs' evaluation.
pub fn check_eval(text: &str) -> Result<(), String> {
    check(Stage::Eval, text)
}

fn switched(text: &str) -> bool {
    text.contains("mode") || text.contains("when")
}

fn front(text: &str) {
    let source = Source::new("fuzz.dsl", text);
    if let Ok(ast) = source.parse() {
        let _ = model_dsl::validate(&ast);
        if switched(text) {
            let _ = model_dsl::validate_switched(&ast);
        }
    }
}

fn compile(text: &str) -> Vec<CompiledModel> {
    let source = Source::new("fuzz.dsl", text);
    if switched(text) {
        let _ = source.compile_switched();
    }
    match source.compile() {
        Ok(models) => models.into_iter().map(|m| m.compiled).collect(),
        Err(_) => Vec::new(),
    }
}

/// Values that break careless arithmetic.
const EXTREMES: [f64; 14] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    5e-324,
    1e-308,
    1e308,
    -1e308,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NAN,
    std::f64::consts::PI,
    std::f64::consts::FRAC_PI_2,
    1e16,
];

fn evaluate(model: &CompiledModel) {
    let n = model.states.len();
    let defaults: Vec<f64> = model.params.iter().map(|(_, v)| v.unwrap_or(1.0)).collect();
    for (k, &x) in EXTREMES.iter().enumerate() {
        let states: Vec<f64> = (0..n)
            .map(|i| match i % 2 {
                0 => x,
                _ => EXTREMES[(k + i) % EXTREMES.len()],
            })
            .collect();
        for params in [defaults.clone(), vec![x; defaults.len()]] {
            let inputs = Inputs {
                t: x,
                states: &states,
                params: &params,
                ders: &[],
            };
            let ders = match model.rhs.eval(&inputs) {
                Ok(stores) => stores.ders(n),
                Err(_) => vec![x; n],
            };
            let _ = model.jacobian.eval(&inputs);
            let with_ders = Inputs {
                ders: &ders,
                ..inputs
            };
            let _ = model.outputs_program.eval(&with_ders);
        }
    }
}

/// The DSL's words and operators, Rust keywords, extreme numbers and strays.
pub const VOCABULARY: Vocabulary = Vocabulary {
    words: &[
        "mod",
        "pub",
        "params",
        "states",
        "let",
        "equations",
        "outputs",
        "variant",
        "keep",
        "fix",
        "chart",
        "replace",
        "after",
        "options",
        "mode",
        "when",
        "include",
        "\"rows.dsl\"",
        "\"fuzz.dsl\"",
        "\".\"",
        "\"/dev/zero\"",
        "accumulates",
        "stop",
        "der",
        "sin",
        "cos",
        "tan",
        "sqrt",
        "exp",
        "ln",
        "abs",
        "atan2",
        "hypot",
        "sign",
        "min",
        "max",
        "if",
        "t",
        "pi",
        "type",
        "in",
        "loop",
        "self",
        "_",
        "x",
        "y",
        "{",
        "}",
        "(",
        ")",
        "[",
        "]",
        ",",
        ";",
        ":",
        "=",
        "==",
        "<",
        "<=",
        ">",
        ">=",
        "+",
        "-",
        "*",
        "/",
        "^",
        "**",
        ".",
        "->",
        "#",
        "'",
        "\"",
        "/*",
        "//",
        "\n",
        "²",
        "1e308",
        "1e-308",
        "5e-324",
        "0",
        "-0.0",
        "1e16",
        "1e400",
        "0.5",
        "2",
        "swell_bound",
        "pivot_tolerance",
        "1u8",
        "0x10",
        "///",
        "!",
        "discrete",
        "first_step",
        "like",
        "by",
    ],
    numbers: &["1e308", "1e-308", "0", "1e16", "4.9e-324", "1e300", "0.0"],
    nests: &[
        ("(", ")"),
        ("sin(", ")"),
        ("der(", ")"),
        ("-", ""),
        ("x^", ""),
        ("x + ", ""),
        ("if(x > 0, ", ", 1)"),
    ],
    strays: &['²', '\'', '#', '"', '\u{0}', 'θ', '·', '\\', '@', '$', '`'],
    max_depth: 400,
};
