//! Exact operation counts of compiled models: a change that makes emitted code bigger (or an
//! elimination that starts to swell) fails here first.

use crate::common::model;
use model_algebra::Inputs;
use model_algebra::ModelSpec;
use model_algebra::{compile, CompileOptions};
use model_algebra::{OpCounts, Program};

/// `(add, mul, div, sqrt, trig, transcendental)`.
fn counts(p: &Program) -> [u32; 6] {
    let OpCounts {
        add,
        mul,
        div,
        sqrt,
        trig,
        transcendental,
    } = p.ops();
    [add, mul, div, sqrt, trig, transcendental]
}

#[test]
fn pendulum_counts() {
    let spec = model(crate::end_to_end::PENDULUM);
    let m = compile(&spec, &CompileOptions::default()).unwrap();
    assert_eq!(counts(&m.rhs), PENDULUM_RHS, "{}", m.rhs);
    assert_eq!(counts(&m.jacobian), PENDULUM_JACOBIAN);
    assert_eq!(
        counts(&m.outputs_program),
        PENDULUM_OUTPUTS,
        "{}",
        m.outputs_program
    );
}

const PENDULUM_RHS: [u32; 6] = [7, 11, 2, 0, 0, 0];
const PENDULUM_JACOBIAN: [u32; 6] = [14, 34, 3, 0, 0, 0];
const PENDULUM_OUTPUTS: [u32; 6] = [2, 5, 0, 0, 0, 0];

/// The pinned counts of a disk model: its right-hand side, its Jacobian, and the right-hand
/// side of its first variant.
struct DiskCounts {
    /// The variant whose right-hand side is counted.
    variant: &'static str,
    rhs: [u32; 6],
    jacobian: [u32; 6],
    variant_rhs: [u32; 6],
}

/// Compiles the model `text` and compares its counts with `expected` (printing the program
/// whose counts differ).
fn assert_counts(spec: &ModelSpec, expected: DiskCounts) {
    let m = compile(spec, &CompileOptions::default()).unwrap();
    assert_eq!(counts(&m.rhs), expected.rhs, "{}", m.rhs);
    assert_eq!(counts(&m.jacobian), expected.jacobian);
    let variant = m.variants.iter().find(|v| v.name == expected.variant);
    let variant = &variant.expect("the variant exists").rhs;
    assert_eq!(counts(variant), expected.variant_rhs, "{variant}");
}

#[test]
fn rolling_counts() {
    // The variant: the spin-only rolling model.
    assert_counts(
        &model(&crate::rolling_disk::rolling_with_spin()),
        DiskCounts {
            variant: "spin",
            rhs: [20, 51, 3, 0, 2, 0],
            jacobian: [53, 148, 4, 0, 2, 0],
            variant_rhs: [4, 19, 2, 0, 1, 0],
        },
    );
}

#[test]
fn sliding_counts() {
    // The variant: the pruned sliding model.
    assert_counts(
        &model(&crate::common::sliding()),
        DiskCounts {
            variant: "pruned",
            rhs: [41, 102, 5, 0, 3, 0],
            jacobian: [170, 429, 9, 0, 3, 0],
            variant_rhs: [25, 42, 4, 0, 2, 0],
        },
    );
}

#[test]
fn cartesian_sliding_counts() {
    // Before the trigonometric identities: rhs [42, 101, 6, 1, 5, 0], pruned [27, 53, 6, 1, 3, 0].
    assert_counts(
        &crate::cartesian_disk::cartesian(),
        DiskCounts {
            variant: "pruned",
            rhs: [46, 114, 5, 1, 2, 0],
            jacobian: [232, 558, 9, 1, 2, 0],
            variant_rhs: [31, 71, 5, 1, 2, 0],
        },
    );
}

/// A dense `n × n` mass matrix of unrelated entries: its symbolic inverse swells.
fn dense_model(n: usize) -> String {
    let params: Vec<String> = (0..n * n)
        .map(|k| format!("p{k} = {:?}", 1.0 + k as f64 / 7.0))
        .collect();
    let states: Vec<String> = (0..n).map(|i| format!("y{i}")).collect();
    let mut equations = String::new();
    for i in 0..n {
        let lhs: Vec<String> = (0..n)
            .map(|j| {
                let diag = if i == j {
                    format!("{} + ", 3 * n)
                } else {
                    String::new()
                };
                format!("({diag}p{}*sin(y{j}))*der(y{j})", i * n + j)
            })
            .collect();
        equations += &format!("e{i}: {} = cos(y{i});\n", lhs.join(" + "));
    }
    format!(
        "mod dense {{ params {{ {} }} states {{ {} }} equations {{ {equations} }} }}",
        params.join(", "),
        states.join(", ")
    )
}

#[test]
fn swelling_block_falls_back_to_a_numeric_solve() {
    let spec = model(&dense_model(8));
    let m = compile(&spec, &CompileOptions::default()).unwrap();
    assert_eq!(
        m.numeric_blocks,
        vec!["der(y0), der(y1), der(y2), der(y3), der(y4), der(y5), der(y6), der(y7)"]
    );
    assert!(m.pivots.is_empty());
    assert_eq!(counts(&m.rhs), DENSE8_RHS, "{}", m.rhs);
    // The same block solved symbolically gives the same derivatives.
    let symbolic = compile(
        &spec,
        &CompileOptions {
            swell_bound: usize::MAX,
            ..CompileOptions::default()
        },
    )
    .unwrap();
    assert!(symbolic.numeric_blocks.is_empty());
    let p: Vec<f64> = (0..64).map(|k| 1.0 + k as f64 / 7.0).collect();
    let y = [0.3, 0.5, 0.7, 0.9, 1.1, 1.3, 1.5, 1.7];
    let inputs = Inputs {
        t: 0.0,
        states: &y,
        params: &p,
        ders: &[],
    };
    let a = m.rhs.eval(&inputs).unwrap().ders(8);
    let b = symbolic.rhs.eval(&inputs).unwrap().ders(8);
    for k in 0..8 {
        assert!(
            (a[k] - b[k]).abs() <= 1e-12 * (1.0 + b[k].abs()),
            "{a:?} vs {b:?}"
        );
    }
    crate::end_to_end::assert_jacobian_matches(&m, &y, &p);
}

const DENSE8_RHS: [u32; 6] = [204, 296, 8, 0, 8, 0];

#[test]
fn small_dense_block_stays_symbolic() {
    let spec = model(&dense_model(2));
    let m = compile(&spec, &CompileOptions::default()).unwrap();
    assert!(m.numeric_blocks.is_empty());
    assert_eq!(m.pivots.len(), 2);
}

/// Forty states in coupled pairs, each pair reading the one before: the work must grow
/// linearly, not explode (a generous bound, to catch exponential behaviour only).
#[test]
fn a_long_chain_of_blocks_compiles_quickly() {
    let states: Vec<String> = (0..40).map(|i| format!("s{i}")).collect();
    let mut equations = String::new();
    for i in (0..40).step_by(2) {
        let prev = if i == 0 {
            "k".to_string()
        } else {
            format!("der(s{})", i - 1)
        };
        let (a, b) = (format!("s{i}"), format!("s{}", i + 1));
        equations += &format!(
            "e{i}: cos({a})*der({a}) + sin({b})*der({b}) = {prev}*{b};\n\
             e{}: -sin({a})*der({a}) + (2 + cos({b}))*der({b}) = {prev} + {a};\n",
            i + 1
        );
    }
    let text = format!(
        "mod chain {{ params {{ k = 2 }} states {{ {} }} equations {{ {equations} }} }}",
        states.join(", ")
    );
    let spec = model(&text);
    let start = std::time::Instant::now();
    let m = compile(&spec, &CompileOptions::default()).unwrap();
    let elapsed = start.elapsed();
    assert!(elapsed.as_secs_f64() < 10.0, "{elapsed:?}");
    assert_eq!(m.states.len(), 40);
    let y: Vec<f64> = (0..40).map(|i| 0.1 + 0.02 * i as f64).collect();
    crate::end_to_end::assert_jacobian_matches(&m, &y, &[2.0]);
}
