//! Cost of one right-hand side of a model read at run time, per evaluator: the reference
//! interpreter (`Program::eval`), the flat evaluator (`FlatProgram::run`), the same program
//! compiled to machine code (`model_jit::JitProgram`, with the time that compiling takes) and,
//! where the same model is compiled by `model!`, the compiled model. The evaluators are timed alternately,
//! repeat by repeat, so the machine's load weighs on all of them alike; the median is printed.
//!
//! ```text
//! cargo bench -p model-interpreted --bench engine_cost [-- --quick]
//! ```

use common::{Args, Clock};
use equations::models::sliding;
use equations::{DiskParams, InitialState, PhysicalState, Slip, SlipChart};
use model_algebra::{CompiledModel, FlatModel, Inputs};
use model_interpreted::ModelFile;
use model_runtime::Model;
use std::hint::black_box;

#[path = "../../../equations/benches/common/mod.rs"]
#[allow(dead_code)]
mod common;

#[path = "../../../model-macros/examples/heavy_top.rs"]
#[allow(dead_code, unused)]
mod heavy_top_example;

/// A right-hand side of a compiled model, on slices.
type Rhs = dyn Fn(&[f64], &mut [f64]);

/// One model: its text compiled, the points to evaluate it at, and the same model compiled by
/// `model!` where there is one.
struct Case {
    name: &'static str,
    model: CompiledModel,
    params: Vec<f64>,
    points: Vec<Vec<f64>>,
    compiled: Option<Box<Rhs>>,
}

fn read(path: &str) -> CompiledModel {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let file = ModelFile::read(std::path::Path::new(&format!("{root}/{path}"))).unwrap();
    file.smooth(None).unwrap().clone()
}

fn defaults(model: &CompiledModel) -> Vec<f64> {
    model.params.iter().map(|(_, v)| v.unwrap_or(1.0)).collect()
}

/// States spread around `centre`, deterministic.
fn around(centre: &[f64], count: usize) -> Vec<Vec<f64>> {
    (0..count)
        .map(|k| {
            (centre.iter().enumerate())
                .map(|(i, c)| c + 0.01 * ((k * 7 + i * 3) % 11) as f64)
                .collect()
        })
        .collect()
}

fn cases() -> Vec<Case> {
    let top = read("model-macros/examples/heavy_top.dsl");
    let top_model = heavy_top_example::heavy_top::Model::default();
    let chain = read("model-macros/examples/pendulum_chain.dsl");
    let n_chain = chain.states.len();
    let chain_centre: Vec<f64> = (0..n_chain)
        .map(|i| {
            if i < n_chain / 2 {
                0.1 + 0.02 * i as f64
            } else {
                0.05
            }
        })
        .collect();
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let path = format!("{root}/equations/src/models/box3_sliding.rs");
    let models = (model_dsl::Source::read(path.as_ref()).unwrap())
        .compile()
        .unwrap();
    let disk = models[0].compiled.clone();
    let p = DiskParams::paper();
    let start = InitialState::paper(&p).state.y;
    let slip = Slip {
        speed: 1e-3,
        direction: 0.7,
    };
    let y = PhysicalState::from_rolling(&start, 0.4).sliding_vector(SlipChart::Polar, slip);
    let disk_model = sliding::Model::new(p.to_array());
    vec![
        Case {
            name: "heavy top (6 states)",
            params: defaults(&top),
            points: around(&[0.1, 0.5, 0.2, 1.0, 0.3, 150.0], 8),
            model: top,
            compiled: Some(Box::new(move |y, dy| {
                let (y, dy) = (y.try_into().unwrap(), dy.try_into().unwrap());
                top_model.rhs(0.0, y, dy).unwrap();
            })),
        },
        Case {
            name: "20-link chain (40 states)",
            params: defaults(&chain),
            points: around(&chain_centre, 8),
            model: chain,
            compiled: None,
        },
        Case {
            name: "disk, sliding (12 states)",
            params: p.to_array().to_vec(),
            points: around(&y, 8),
            model: disk,
            compiled: Some(Box::new(move |y, dy| {
                let (y, dy) = (y.try_into().unwrap(), dy.try_into().unwrap());
                disk_model.rhs(0.0, y, dy).unwrap();
            })),
        },
    ]
}

/// Mean ns per evaluation of `f` over `evals` calls cycling through `points`.
fn time(points: &[Vec<f64>], evals: usize, mut f: impl FnMut(&[f64], &mut [f64])) -> f64 {
    let mut dy = vec![0.0; points[0].len()];
    let clock = Clock::start();
    for i in 0..evals {
        f(black_box(&points[i % points.len()]), black_box(&mut dy));
    }
    clock.seconds() / evals as f64 * 1e9
}

fn at<'a>(y: &'a [f64], params: &'a [f64]) -> Inputs<'a> {
    Inputs {
        t: 0.0,
        states: y,
        params,
        ders: &[],
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let Args { quick, .. } = Args::parse();
    let (repeats, budget) = if quick { (3, 2e-2) } else { (7, 2e-1) };
    println!(
        "RHS cost, median of {repeats} alternating repeats (ns per evaluation, {})",
        Clock::kind()
    );
    println!(
        "| model | reference interpreter | flat evaluator | JIT | `model!` | JIT / `model!` | JIT compile (rhs + Jacobian) |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let mut compile_rows = Vec::new();
    for case in cases() {
        let flat = FlatModel::new(&case.model, case.params.len()).unwrap();
        let mut scratch = flat.rhs.scratch();
        let compile = |program: &model_algebra::FlatProgram| {
            let clock = std::time::Instant::now();
            let jit = model_jit::JitProgram::new(program.clone()).unwrap();
            (jit, clock.elapsed().as_secs_f64() * 1e3)
        };
        let (jit, rhs_ms) = compile(&flat.rhs);
        let jacobian_ms = compile(&flat.jacobian).1;
        let outputs_ms = compile(&flat.outputs).1;
        let compile_ms = rhs_ms + jacobian_ms;
        let params = case.params.clone();
        // The evaluators agree before they are timed (and the points evaluate).
        for y in &case.points {
            let want = case.model.rhs.eval(&at(y, &params)).unwrap().ders(y.len());
            let mut got = vec![0.0; y.len()];
            flat.rhs
                .run(&at(y, &params), &mut scratch, &mut got)
                .unwrap();
            assert_eq!(got, want, "{}", case.name);
            jit.run(&at(y, &params), &mut scratch, &mut got).unwrap();
            assert_eq!(got, want, "{}", case.name);
            if let Some(compiled) = &case.compiled {
                compiled(y, &mut got);
                for (g, w) in got.iter().zip(&want) {
                    assert!(
                        (g - w).abs() <= 1e-9 * w.abs().max(1.0),
                        "{}: {g} vs {w}",
                        case.name
                    );
                }
            }
        }
        // Calls per repeat: about `budget` seconds of the reference.
        let probe = time(&case.points, 200, |y, dy| {
            dy.copy_from_slice(&case.model.rhs.eval(&at(y, &params)).unwrap().ders(y.len()));
        });
        let evals = ((budget / (probe * 1e-9)) as usize).max(1000);
        let (mut reference, mut flat_ns, mut compiled_ns) = (Vec::new(), Vec::new(), Vec::new());
        let mut jit_ns = Vec::new();
        for _ in 0..repeats {
            reference.push(time(&case.points, evals, |y, dy| {
                dy.copy_from_slice(&case.model.rhs.eval(&at(y, &params)).unwrap().ders(y.len()));
            }));
            flat_ns.push(time(&case.points, evals * 4, |y, dy| {
                flat.rhs.run(&at(y, &params), &mut scratch, dy).unwrap();
            }));
            jit_ns.push(time(&case.points, evals * 4, |y, dy| {
                jit.run(&at(y, &params), &mut scratch, dy).unwrap();
            }));
            if let Some(compiled) = &case.compiled {
                compiled_ns.push(time(&case.points, evals * 4, |y, dy| compiled(y, dy)));
            }
        }
        let (reference, flat_ns, jit_ns) = (median(reference), median(flat_ns), median(jit_ns));
        let (compiled, ratio) = match compiled_ns.is_empty() {
            true => ("–".to_string(), "–".to_string()),
            false => {
                let c = median(compiled_ns);
                (format!("{c:.0}"), format!("{:.2}×", jit_ns / c))
            }
        };
        println!(
            "| {} | {reference:.0} | {flat_ns:.0} | {jit_ns:.0} | {compiled} | {ratio} | {compile_ms:.1} ms |",
            case.name
        );
        // The right-hand side's break-even: evaluations whose savings pay for its compile.
        let break_even = rhs_ms * 1e6 / (flat_ns - jit_ns);
        let per_op = |ms: f64, program: &model_algebra::FlatProgram| {
            format!(
                "{} ops, {ms:.2} ms ({:.1} µs/op)",
                program.ops.len(),
                ms * 1e3 / program.ops.len().max(1) as f64
            )
        };
        compile_rows.push(format!(
            "| {} | {} | {} | {} | {break_even:.0} |",
            case.name,
            per_op(rhs_ms, &flat.rhs),
            per_op(jacobian_ms, &flat.jacobian),
            per_op(outputs_ms, &flat.outputs),
        ));
    }
    println!();
    println!("JIT compile per program, and the right-hand side's break-even (its compile time over flat − JIT per evaluation)");
    println!("| model | right-hand side | Jacobian | outputs | break-even evaluations |");
    println!("|---|---:|---:|---:|---:|");
    for row in compile_rows {
        println!("{row}");
    }
}
