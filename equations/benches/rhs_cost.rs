//! Cost of one right-hand-side evaluation, per mode and per implementation.
//!
//! The run time of a simulation is, to first order, RHS evaluations × cost per evaluation, so
//! this bench answers two questions: is the code the equation compiler emits at least as fast
//! as evaluating the same implicit system numerically (the hand-written reference assembles
//! `M(y)·ẏ = f(y)` from vector Newton–Euler and solves it by LU with one refinement step, which
//! *is* the "assemble and LU" baseline), and what do the pruned variants buy.
//!
//! ```text
//! cargo bench -p equations --bench rhs_cost [-- --quick] [--out DIR]
//! ```
//!
//! Prints a table and writes `rhs_cost.csv` to `target/bench/` (or `--out`).

use common::{Args, Clock};
use equations::models::{rolling, sliding, sliding_cartesian};
use equations::DiskParams;
use equations::{layout, PhysicalState, Slip, SlipChart, DIM};
use equations::{DiskModels, GeneratedModels, ReferenceModels};
use model_runtime::{Model, ModelInfo, OpCounts};
use std::hint::black_box;
use std::path::PathBuf;

mod common;

/// A handful of states along the paper's scene (tilted, spinning, slipping), so the timing does
/// not hinge on one lucky operand.
fn probe_states(p: &DiskParams) -> Vec<PhysicalState> {
    let mut states = Vec::new();
    for (k, theta) in [1.0_f64 - 0.43, 0.3, 0.05, 1e-3].iter().enumerate() {
        let mut y = [0.0; DIM];
        y[layout::THETA] = *theta;
        y[layout::Z] = p.a * theta.sin();
        y[layout::PSI] = 0.3 + k as f64;
        y[layout::PHI] = 0.1 * k as f64;
        y[layout::OMEGA_X] = 1.0 + k as f64;
        y[layout::OMEGA_Y] = 0.2;
        y[layout::OMEGA_Z] = 5.0 * (k + 1) as f64;
        let state = PhysicalState::from_rolling(&y, 0.4);
        states.push(state);
    }
    states
}

/// One row of the table: a model, its mode, and what one evaluation costs.
struct Row {
    mode: &'static str,
    implementation: String,
    ns_per_eval: f64,
    ops: Option<OpCounts>,
}

/// Median over `repeats` of the mean time per evaluation of `f` cycled over `inputs`.
fn time_per_eval<const N: usize>(
    inputs: &[[f64; N]],
    repeats: usize,
    evals: usize,
    f: impl Fn(&[f64; N], &mut [f64; N]) -> bool,
) -> f64 {
    let mut dy = [0.0; N];
    // Warm-up, and a check that every input evaluates (a failing model would time its error path).
    for y in inputs {
        assert!(f(y, &mut dy), "model refused a probe state {y:?}");
    }
    let mut samples: Vec<f64> = (0..repeats)
        .map(|_| {
            let clock = Clock::start();
            for i in 0..evals {
                let y = black_box(&inputs[i % inputs.len()]);
                f(y, black_box(&mut dy));
            }
            clock.seconds() / evals as f64 * 1e9
        })
        .collect();
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}

/// Picks a variant's states out of full-model states, by name.
fn restrict<const N: usize>(full: &ModelInfo, variant: &ModelInfo, y: &[f64; DIM]) -> [f64; N] {
    std::array::from_fn(|i| {
        let name = &variant.state_names[i];
        let j = (full.state_names.position(name))
            .unwrap_or_else(|| panic!("variant state {name} not in the full model"));
        y[j]
    })
}

struct Settings {
    repeats: usize,
    evals: usize,
    out: PathBuf,
}

fn settings() -> Settings {
    let Args { quick, out } = Args::parse();
    Settings {
        repeats: if quick { 3 } else { 7 },
        evals: if quick { 100_000 } else { 400_000 },
        out,
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let s = settings();
    let p = DiskParams::paper();
    let states = probe_states(&p);
    let slip = Slip {
        speed: 1e-3,
        direction: 0.7,
    };
    let mut rows = Vec::new();
    let rolling_in: Vec<[f64; DIM]> = states.iter().map(|st| st.rolling_vector()).collect();

    for chart in [SlipChart::Cartesian, SlipChart::Polar] {
        let generated: GeneratedModels = DiskModels::generated(p, chart)?;
        let reference = ReferenceModels::reference(p, chart)?;
        let sliding_in: Vec<[f64; DIM]> = states
            .iter()
            .map(|st| st.sliding_vector(chart, slip))
            .collect();
        let mode: &'static str = match chart {
            SlipChart::Cartesian => "sliding (Cartesian)",
            SlipChart::Polar => "sliding (polar)",
        };
        rows.push(Row {
            mode,
            implementation: "generated".into(),
            ns_per_eval: time_per_eval(&sliding_in, s.repeats, s.evals, |y, dy| {
                generated.sliding.rhs(0.0, y, dy).is_ok()
            }),
            ops: Some(generated.sliding.info().rhs_ops),
        });
        rows.push(Row {
            mode,
            implementation: "reference (assembly + LU)".into(),
            ns_per_eval: time_per_eval(&sliding_in, s.repeats, s.evals, |y, dy| {
                reference.sliding.rhs(0.0, y, dy).is_ok()
            }),
            ops: None,
        });
        if chart == SlipChart::Cartesian {
            let generated_rolling = generated.rolling;
            rows.push(Row {
                mode: "rolling",
                implementation: "generated".into(),
                ns_per_eval: time_per_eval(&rolling_in, s.repeats, s.evals, |y, dy| {
                    generated_rolling.rhs(0.0, y, dy).is_ok()
                }),
                ops: Some(generated_rolling.info().rhs_ops),
            });
            let reference_rolling = reference.rolling;
            rows.push(Row {
                mode: "rolling",
                implementation: "reference (assembly + LU)".into(),
                ns_per_eval: time_per_eval(&rolling_in, s.repeats, s.evals, |y, dy| {
                    reference_rolling.rhs(0.0, y, dy).is_ok()
                }),
                ops: None,
            });
        }
    }

    // Pruned variants: still air, only what the mode switching needs.
    let v = [p.m, p.a, p.g, p.mu_d, p.mu_st];
    {
        let m = rolling::pruned::Model::new(v);
        let inputs: Vec<[f64; rolling::pruned::N_STATES]> = rolling_in
            .iter()
            .map(|y| restrict(&rolling::INFO, &rolling::pruned::INFO, y))
            .collect();
        rows.push(Row {
            mode: "rolling",
            implementation: format!("generated, pruned ({} states)", rolling::pruned::N_STATES),
            ns_per_eval: time_per_eval(&inputs, s.repeats, s.evals, |y, dy| {
                m.rhs(0.0, y, dy).is_ok()
            }),
            ops: Some(rolling::pruned::INFO.rhs_ops),
        });
    }
    {
        let m = sliding_cartesian::pruned::Model::new(v);
        let full: Vec<[f64; DIM]> = states
            .iter()
            .map(|st| st.sliding_vector(SlipChart::Cartesian, slip))
            .collect();
        let inputs: Vec<[f64; sliding_cartesian::pruned::N_STATES]> = full
            .iter()
            .map(|y| {
                restrict(
                    &sliding_cartesian::INFO,
                    &sliding_cartesian::pruned::INFO,
                    y,
                )
            })
            .collect();
        rows.push(Row {
            mode: "sliding (Cartesian)",
            implementation: format!(
                "generated, pruned ({} states)",
                sliding_cartesian::pruned::N_STATES
            ),
            ns_per_eval: time_per_eval(&inputs, s.repeats, s.evals, |y, dy| {
                m.rhs(0.0, y, dy).is_ok()
            }),
            ops: Some(sliding_cartesian::pruned::INFO.rhs_ops),
        });
    }
    {
        let m = sliding::pruned::Model::new(v);
        let full: Vec<[f64; DIM]> = states
            .iter()
            .map(|st| st.sliding_vector(SlipChart::Polar, slip))
            .collect();
        let inputs: Vec<[f64; sliding::pruned::N_STATES]> = full
            .iter()
            .map(|y| restrict(&sliding::INFO, &sliding::pruned::INFO, y))
            .collect();
        rows.push(Row {
            mode: "sliding (polar)",
            implementation: format!("generated, pruned ({} states)", sliding::pruned::N_STATES),
            ns_per_eval: time_per_eval(&inputs, s.repeats, s.evals, |y, dy| {
                m.rhs(0.0, y, dy).is_ok()
            }),
            ops: Some(sliding::pruned::INFO.rhs_ops),
        });
    }

    print_and_save(&rows, &s)
}

fn print_and_save(rows: &[Row], s: &Settings) -> Result<(), Box<dyn std::error::Error>> {
    println!(
        "RHS cost, median of {} repeats of {} evaluations over 4 states (ns per evaluation, {})",
        s.repeats,
        s.evals,
        Clock::kind()
    );
    println!("| mode | implementation | ns/eval | add | mul | div | sqrt | trig | total ops |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|");
    let mut csv = String::from("mode,implementation,ns_per_eval,add,mul,div,sqrt,trig,total_ops\n");
    for r in rows {
        let ops = match r.ops {
            Some(o) => format!(
                "{} | {} | {} | {} | {} | {}",
                o.add,
                o.mul,
                o.div,
                o.sqrt,
                o.trig,
                o.total()
            ),
            None => "– | – | – | – | – | –".into(),
        };
        println!(
            "| {} | {} | {:.0} | {ops} |",
            r.mode, r.implementation, r.ns_per_eval
        );
        let ops_csv = match r.ops {
            Some(o) => format!(
                "{},{},{},{},{},{}",
                o.add,
                o.mul,
                o.div,
                o.sqrt,
                o.trig,
                o.total()
            ),
            None => ",,,,,".into(),
        };
        csv.push_str(&format!(
            "{},{},{:.1},{ops_csv}\n",
            r.mode, r.implementation, r.ns_per_eval
        ));
    }
    std::fs::create_dir_all(&s.out)?;
    let path = s.out.join("rhs_cost.csv");
    std::fs::write(&path, csv)?;
    println!("wrote {}", path.display());
    Ok(())
}
