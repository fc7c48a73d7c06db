//! The paper's 100 s scene end to end, the number a user waits for, with the full generated
//! models and with their pruned variants (what a scene asking only for θ and N runs).
//!
//! DP5 at the paper's `rtol = 1e-8`, `atol = 1e-10`, Cartesian slip chart, physical slip sign,
//! single thread; the median of nine runs of each model set, alternating so that both see the
//! same machine (`--quick`: 10 s, five runs). The pruned/full ratio is measured in this one
//! run, per pair of neighbouring runs (the median of those ratios is the robust number on a
//! busy machine, where single runs move by ±10%). The Python figures it is compared with come from an independent implementation
//! (scipy's DOP853 with events, same tolerances): about 120 s and 8.9 M right-hand-side
//! evaluations for the 100 s.
//!
//! ```text
//! cargo bench -p equations --bench paper_run [-- --quick] [--out DIR]
//! ```

use common::{Args, Clock};
use equations::hybrid::{
    simulate, DiskConfig, DiskModels, GeneratedModels, InitialState, PrunedModels, RunOutcome,
    SimError,
};
use equations::modes::SlipChart;
use equations::DiskParams;
use model_runtime::Model;

mod common;

/// scipy DOP853 with events on the same scene and tolerances (s of CPU, RHS evaluations).
const PYTHON_SECONDS: f64 = 120.0;
const PYTHON_RHS_EVALS: f64 = 8.9e6;

/// One model set's runs: the CPU times and the last outcome (every run is identical).
struct Measured {
    label: &'static str,
    times: Vec<f64>,
    outcome: Option<RunOutcome>,
}

impl Measured {
    fn new(label: &'static str) -> Self {
        Measured {
            label,
            times: Vec::new(),
            outcome: None,
        }
    }

    fn run<R: Model<12>, S: Model<12>>(
        &mut self,
        models: &DiskModels<R, S>,
        config: &DiskConfig,
        initial: &InitialState,
    ) -> Result<(), SimError> {
        let clock = Clock::start();
        let out = simulate(models, config, initial, &mut ())?;
        self.times.push(clock.seconds());
        self.outcome = Some(out);
        Ok(())
    }

    fn median(&self) -> f64 {
        let mut t = self.times.clone();
        t.sort_by(f64::total_cmp);
        t[t.len() / 2]
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let (t_end, repeats) = if args.quick { (10.0, 5) } else { (100.0, 9) };
    let params = DiskParams::paper();
    let full: GeneratedModels = DiskModels::generated(params, SlipChart::Cartesian)?;
    let pruned = PrunedModels::pruned(params, SlipChart::Cartesian)?;
    let config = DiskConfig {
        t_end,
        ..DiskConfig::paper()
    };
    let initial = InitialState::paper(&params);
    let mut runs = [
        Measured::new("full (12 states)"),
        Measured::new("pruned (8 states)"),
    ];
    for _ in 0..repeats {
        runs[0].run(&full, &config, &initial)?;
        runs[1].run(&pruned, &config, &initial)?;
    }
    let scale = t_end / 100.0;
    let mut table = format!(
        "paper scene {t_end} s, DP5 rtol 1e-8 atol 1e-10 ({}; median of {repeats}, runs alternating)\n",
        Clock::kind(),
    );
    table.push_str(&format!(
        "| quantity | {} | {} |\n|---|---:|---:|\n",
        runs[0].label, runs[1].label
    ));
    let outs: Vec<&RunOutcome> = runs
        .iter()
        .map(|r| r.outcome.as_ref().ok_or("no run"))
        .collect::<Result<_, _>>()?;
    let medians: Vec<f64> = runs.iter().map(Measured::median).collect();
    let row = |f: &dyn Fn(usize) -> String| [f(0), f(1)];
    let rows: Vec<(&str, [String; 2])> = vec![
        ("time (s)", row(&|i| format!("{:.3}", medians[i]))),
        (
            "all times (s)",
            row(&|i| {
                runs[i]
                    .times
                    .iter()
                    .map(|t| format!("{t:.3}"))
                    .collect::<Vec<_>>()
                    .join(" ")
            }),
        ),
        ("steps", row(&|i| outs[i].stats.steps.to_string())),
        ("rejected", row(&|i| outs[i].stats.rejected.to_string())),
        (
            "RHS evaluations",
            row(&|i| outs[i].stats.rhs_evals.to_string()),
        ),
        (
            "RHS evaluations per simulated second",
            row(&|i| format!("{:.0}", outs[i].stats.rhs_evals as f64 / t_end)),
        ),
        (
            "guard evaluations",
            row(&|i| outs[i].stats.guard_evals.to_string()),
        ),
        ("transitions", row(&|i| outs[i].transitions.to_string())),
        (
            "ns per RHS evaluation, all included",
            row(&|i| format!("{:.0}", medians[i] / outs[i].stats.rhs_evals as f64 * 1e9)),
        ),
        (
            "speed-up over Python (time, scaled to this span)",
            row(&|i| format!("{:.0}x", PYTHON_SECONDS * scale / medians[i])),
        ),
        (
            "RHS evaluations, Python / this",
            row(&|i| {
                format!(
                    "{:.2}",
                    PYTHON_RHS_EVALS * scale / outs[i].stats.rhs_evals as f64
                )
            }),
        ),
        ("stop", row(&|i| outs[i].stop.name().to_string())),
    ];
    for (k, [a, b]) in rows {
        table.push_str(&format!("| {k} | {a} | {b} |\n"));
    }
    let pairs: Vec<f64> = runs[1]
        .times
        .iter()
        .zip(&runs[0].times)
        .map(|(p, f)| p / f)
        .collect();
    let mut sorted = pairs.clone();
    sorted.sort_by(f64::total_cmp);
    table.push_str(&format!(
        "\npruned / full: time {:.3} (ratio of the medians {:.3}; per pair {}), \
         RHS evaluations {:.3}, steps {:.3}\n",
        sorted[sorted.len() / 2],
        medians[1] / medians[0],
        pairs
            .iter()
            .map(|r| format!("{r:.3}"))
            .collect::<Vec<_>>()
            .join(" "),
        outs[1].stats.rhs_evals as f64 / outs[0].stats.rhs_evals as f64,
        outs[1].stats.steps as f64 / outs[0].stats.steps as f64,
    ));
    print!("{table}");
    std::fs::create_dir_all(&args.out)?;
    std::fs::write(args.out.join("paper_run.md"), table)?;
    Ok(())
}
