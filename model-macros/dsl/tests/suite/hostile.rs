//! Hostile models: whatever the text, the front end and the compiler answer (a model or located
//! errors) without a panic, a hang or a stack overflow, and within the limits they state.

use model_algebra::CompiledModel;
use model_dsl::{Located, Source};

/// Compiles `text` on a thread with a 2 MiB stack (the test harness's default, smaller than
/// rustc's or a program's main thread), so that a recursion the limits do not bound fails here.
fn compile(text: &str) -> Result<Vec<CompiledModel>, Vec<Located>> {
    let text = text.to_string();
    std::thread::Builder::new()
        .stack_size(2 << 20)
        .spawn(move || {
            Source::new("hostile.dsl", text)
                .compile()
                .map(|models| models.into_iter().map(|m| m.compiled).collect())
                .map_err(|errors| errors.0)
        })
        .unwrap()
        .join()
        .expect("no panic")
}

/// Held by the tests that allocate tens of megabytes, and by the one that measures this
/// process's memory, so that it measures only its own (the tests of a binary run in parallel).
static LARGE: std::sync::Mutex<()> = std::sync::Mutex::new(());

pub(crate) fn large() -> std::sync::MutexGuard<'static, ()> {
    LARGE
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

fn errors(text: &str) -> Vec<Located> {
    match compile(text) {
        Ok(_) => panic!("must be rejected: {text}"),
        Err(errors) => errors,
    }
}

#[test]
fn constants_that_fold_to_infinity_are_errors_at_their_tokens() {
    for (text, at, message) in [
        (
            "mod m { states { x, y } equations { der(x) = 1e308*10*x + 1e308*10*y; der(y) = x; } }",
            "1e308*10",
            "this constant expression is not finite",
        ),
        (
            "mod m { states { x, y } equations { der(x) = 2^1e16*x + 2^1e16*y; der(y) = x; } }",
            "2^1e16",
            "this constant expression is not finite",
        ),
        (
            "mod m { states { x, y } equations { der(x) = x*1e308*10 - y*1e308*10; der(y) = x; } }",
            "x*1e308*10",
            "a constant factor or term of this expression is not finite",
        ),
        (
            "mod m { params { a = 1 } states { x, y } equations { der(x) = a*10*x + a*10*y; der(y) = x; }
                 variant v { keep { x } fix { a = 1e308 } } }",
            "a*10",
            "this constant expression is not finite",
        ),
    ] {
        let found = errors(text);
        let column = text.find(at).unwrap() + 1;
        assert_eq!((found[0].column, found[0].width), (column, at.len()), "{text}: {found:#?}");
        assert!(found[0].message.contains(message), "{found:#?}");
    }
}

/// `der(x) = EXPR;` in a one-state model.
fn with_rhs(rhs: &str) -> String {
    format!("mod m {{ states {{ x }} equations {{ der(x) = {rhs}; }} }}")
}

#[test]
fn deep_nesting_is_an_error_naming_the_limit() {
    let n = 10_000;
    let tower: Vec<&str> = vec!["x"; n];
    let sum: Vec<&str> = vec!["x"; 100_000];
    for text in [
        with_rhs(&format!("{}x{}", "(".repeat(n), ")".repeat(n))),
        with_rhs(&format!("{}x{}", "sin(".repeat(n), ")".repeat(n))),
        with_rhs(&format!("{}x", "-".repeat(n))),
        with_rhs(&tower.join("^")),
        with_rhs(&sum.join(" + ")),
        with_rhs(&format!("{}x{}", "der(".repeat(n), ")".repeat(n))),
        with_rhs(&format!("{}x{}", "if(x > 0, ".repeat(n), ", 1)".repeat(n))),
        with_rhs(&format!("{}x{}", "if(".repeat(n), " > 0, 1, 2)".repeat(n))),
    ] {
        let found = errors(&text);
        assert_eq!(found.len(), 1, "{found:#?}");
        assert!(
            found[0].message.contains("limit MAX_DEPTH is 256"),
            "{}",
            found[0]
        );
    }
}

#[test]
fn a_long_chain_of_lets_is_an_error_naming_the_limit() {
    let lets: String = (1..10_000)
        .map(|k| format!("let a{k} = sin(a{});\n", k - 1))
        .collect();
    let text =
        format!("mod m {{ states {{ x }} let a0 = x;\n{lets} equations {{ der(x) = a9999; }} }}");
    let found = errors(&text);
    assert_eq!(found.len(), 1, "{found:#?}");
    assert!(found[0].message.starts_with("let `a"), "{}", found[0]);
    assert!(
        found[0].message.contains("limit MAX_DEPTH is 256"),
        "{}",
        found[0]
    );
}

#[test]
fn nesting_up_to_the_limit_compiles() {
    // The deepest expression allowed, through every stage, on a 2 MiB stack.
    let depth = model_dsl::MAX_DEPTH as usize - 3;
    let text = with_rhs(&format!("{}x{}", "sin(".repeat(depth), ")".repeat(depth)));
    assert!(compile(&text).is_ok());
    let terms: Vec<&str> = vec!["x"; 200];
    assert!(compile(&with_rhs(&terms.join(" - "))).is_ok());
    // Lets of lets, up to the limit.
    let lets: String = (1..120)
        .map(|k| format!("let a{k} = 2*a{};\n", k - 1))
        .collect();
    let text =
        format!("mod m {{ states {{ x }} let a0 = x;\n{lets} equations {{ der(x) = a119; }} }}");
    assert!(compile(&text).is_ok());
}

#[test]
fn lexical_errors_name_the_problem_at_its_character() {
    let cases = [
        (
            "mod m { states { x }\n  equations { der(x = -x; }\n}\n",
            (2, 18),
            "this `(` is never closed: the `}` at line 2, column 27 comes before its `)`",
        ),
        (
            "mod m { states { x } equations { der(x) = -x; }\n",
            (1, 7),
            "this `{` is never closed: the text ends before its `}`",
        ),
        (
            "mod m { states { x } equations { der(x) = x²; } }",
            (1, 44),
            "`²` is not a character of the DSL: write a power as `x^2`",
        ),
        (
            "mod m { states { x } equations { x' = -x; } }",
            (1, 35),
            "`'` is not part of the DSL: a derivative is written `der(x)`",
        ),
        (
            "mod m { states { x } /* the state\n equations { der(x) = -x; } }",
            (1, 22),
            "unterminated comment: this `/*` is never closed by `*/`",
        ),
        (
            "mod m { states { x } # the pendulum's angle\n equations { der(x) = -x; } }",
            (1, 22),
            "`#` does not start a comment in the DSL",
        ),
        (
            "mod m { states { x } # the angle\n equations { der(x) = -x; } }",
            (1, 22),
            "`#` does not start a comment in the DSL",
        ),
        (
            "mod m { states { x } equations { der(x) = -x; } ) }",
            (1, 7),
            "this `{` is never closed: the `)` at line 1, column 49 comes before its `}`",
        ),
        (
            "mod m { states { x } equations { der(x) = -x; } } )",
            (1, 51),
            "`)` closes nothing",
        ),
    ];
    for (text, place, message) in cases {
        let found = errors(text);
        assert_eq!(found.len(), 1, "{found:#?}");
        assert_eq!((found[0].line, found[0].column), place, "{}", found[0]);
        assert!(found[0].message.starts_with(message), "{}", found[0]);
    }
}

#[test]
fn a_rust_keyword_as_a_name_is_one_error_at_its_token() {
    let text = "mod m { params { in = 1.0 } states { x, type } let loop = in*x;
        equations { der(x) = -loop; der(type) = x + type; } outputs { final = loop; } }";
    let found = errors(text);
    let words: Vec<&str> = found
        .iter()
        .map(|e| &e.source_line[e.column - 1..e.column - 1 + e.width])
        .collect();
    assert_eq!(words, ["in", "type", "loop", "final"], "{found:#?}");
    for error in &found {
        assert!(error.message.contains("is a Rust keyword"), "{error}");
    }
    assert!(model_dsl::is_rust_keyword("box") && !model_dsl::is_rust_keyword("x"));
}

#[test]
fn a_missing_states_block_is_the_one_error() {
    let text = "mod m {\n    params { k = 1 }\n    equations { der(x) = -k*x; der(y) = x; }\n    outputs { e = x^2; }\n}\n";
    let found = errors(text);
    assert_eq!(found.len(), 1, "{found:#?}");
    assert_eq!((found[0].line, found[0].column), (1, 5));
    assert_eq!(
        found[0].message,
        "the model has no states: declare them in `states { .. }` (the equations differentiate \
         `x`, `y`)"
    );
}

/// This process's resident memory in bytes (Linux).
#[cfg(target_os = "linux")]
fn resident() -> usize {
    let statm = std::fs::read_to_string("/proc/self/statm").unwrap();
    let pages: usize = statm.split_whitespace().nth(1).unwrap().parse().unwrap();
    pages * 4096
}

#[cfg(target_os = "linux")]
#[test]
fn reading_model_after_model_keeps_no_text() {
    // 3,000 reads of a 20 kB text would keep 60 MB if every text stayed recorded.
    let padding = "// a comment that makes the text long enough to notice\n".repeat(400);
    let text = format!("{padding}mod m {{ states {{ x }} equations {{ der(x) = -kk*x; }} }}");
    let _large = large();
    let read = move || {
        let before = resident();
        for _ in 0..3_000 {
            let errors = Source::new("long.dsl", text.as_str())
                .compile()
                .unwrap_err();
            assert_eq!(errors.0[0].line, 401, "{errors}");
        }
        resident().saturating_sub(before)
    };
    let grown = std::thread::spawn(read).join().unwrap();
    assert!(grown < 20 << 20, "grew by {grown} bytes");
}

#[test]
fn decoupled_states_compile_in_linear_time() {
    // Each Jacobian column, and each block's pivot sampling, costs what its state touches:
    // 10,000 decoupled states took minutes when every one of them went through the whole
    // system (now about a second).
    let _large = large();
    let n = 10_000;
    let states: Vec<String> = (0..n).map(|k| format!("x{k}")).collect();
    let equations: String = (0..n).map(|k| format!("der(x{k}) = -x{k}*x{k};")).collect();
    let text = format!(
        "mod m {{ states {{ {} }} equations {{ {equations} }} }}",
        states.join(", ")
    );
    let started = std::time::Instant::now();
    let models = compile(&text).unwrap();
    assert_eq!(models[0].states.len(), n);
    let seconds = started.elapsed().as_secs_f64();
    assert!(seconds < 30.0, "{seconds} s");
}

/// The derivatives of `der(s_n) = -y*x; der(y) = x` with `s_0 = x`, `s_{k+1} = sin(s_k)`, and
/// the first row of their Jacobian, by the chain rule: with `P = Π_{k<n} cos(s_k)`,
/// `der(x) = -x y / P`, `∂/∂x = -y/P · (1 + x Σ_k tan(s_k) Π_{j<k} cos(s_j))`, `∂/∂y = -x/P`.
fn chain_closed_form(n: usize, x: f64, y: f64) -> (f64, [f64; 2]) {
    let mut s = x;
    let (mut product, mut sum) = (1.0, 0.0);
    for _ in 0..n {
        sum += s.tan() * product;
        product *= s.cos();
        s = s.sin();
    }
    let der = -x * y / product;
    (der, [-y / product * (1.0 + x * sum), -x / product])
}

#[test]
fn a_deep_chain_under_der_compiles_to_its_chain_rule() {
    // `der(sin(sin(..(x)..)))` 200 deep: the product rule makes each Jacobian entry a
    // triangular sum of about n²/2 factors, which the factoring of common factors took n³ to
    // nest (seconds at this depth); its value is the chain rule's.
    let _large = large();
    let n = 200;
    let chain = format!("{}x{}", "sin(".repeat(n), ")".repeat(n));
    let text =
        format!("mod m {{ states {{ x, y }} equations {{ der({chain}) = -y*x; der(y) = x; }} }}");
    let model = compile(&text).unwrap().remove(0);
    // Linear code: a few operations per level of the chain.
    assert!(model.jacobian.ops().total() <= 12 * n as u32);
    for (x, y) in [(0.3, 0.5), (-0.7, 2.0), (1.2, -0.4)] {
        let (der, row) = chain_closed_form(n, x, y);
        let got = model.derivatives(0.0, &[x, y], &[]).unwrap();
        assert!(
            (got[0] - der).abs() <= 1e-12 * der.abs(),
            "{} vs {der}",
            got[0]
        );
        assert_eq!(got[1], x);
        let inputs = model_algebra::Inputs {
            t: 0.0,
            states: &[x, y],
            params: &[],
            ders: &[],
        };
        let jacobian = model.jacobian.eval(&inputs).unwrap().jacobian(2);
        for (got, want) in jacobian[0].iter().zip(row) {
            assert!((got - want).abs() <= 1e-12 * want.abs(), "{got} vs {want}");
        }
        assert_eq!(jacobian[1], [1.0, 0.0]);
    }
}
