//! The paper's 100 s scene end to end, the number a user waits for: the paper's own settings
//! (DP5 in physical time), the recommended ones (DOP853 in regularised time, the scenes'
//! default) with the full models and with their pruned variants (what a scene asking only
//! for θ and N runs), and the recommended ones run by the disk's mode graph said in the DSL
//! (`equations::disk`, the switched model) instead of the hand-written system.
//!
//! The paper's `rtol = 1e-8`, `atol = 1e-10`, Cartesian slip chart, physical slip sign,
//! single thread; the median of nine runs of each setting, alternating so that all see the
//! same machine (`--quick`: 10 s, five runs). Ratios between settings are the medians of the
//! per-round ratios (robust on a busy machine, where single runs move by ±10%). No speed-up
//! against another implementation is printed: a time is comparable only with one measured in
//! the same run on the same machine, and no peer runs here. What is comparable across
//! machines is the work: the right-hand-side evaluations against an independent Python
//! implementation's (scipy's DOP853 with events, same tolerances: 8.9 M for the 100 s).
//!
//! ```text
//! cargo bench -p equations --bench paper_run [-- --quick] [--out DIR]
//! ```

use common::{Args, Clock};
use equations::DiskParams;
use equations::SlipChart;
use equations::{simulate, simulate_switched, DiskModels, GeneratedModels, PrunedModels};
use equations::{DiskConfig, InitialState, SimFailure};
use model_runtime::{Model, Stats};

mod common;

/// scipy DOP853 with events on the same scene and tolerances: its RHS evaluations.
const PYTHON_RHS_EVALS: f64 = 8.9e6;

/// Which system runs a setting.
#[derive(Clone, Copy, PartialEq)]
enum System {
    /// The hand-written system with the full generated models.
    Full,
    /// The hand-written system with the pruned variants.
    Pruned,
    /// The disk's switched model (the DSL's mode graph).
    Switched,
}

/// What a run did, whichever system ran it.
struct Outcome {
    stats: Stats,
    transitions: u64,
    stop: String,
}

/// One setting's runs: the CPU times and the last outcome (every run is identical).
struct Measured {
    label: &'static str,
    config: DiskConfig,
    system: System,
    times: Vec<f64>,
    outcome: Option<Outcome>,
}

impl Measured {
    fn new(label: &'static str, config: DiskConfig, system: System) -> Self {
        Measured {
            label,
            config,
            system,
            times: Vec::new(),
            outcome: None,
        }
    }

    fn run<R: Model<12>, S: Model<12>>(
        &mut self,
        models: &DiskModels<R, S>,
        initial: &InitialState,
    ) -> Result<(), SimFailure> {
        let clock = Clock::start();
        let out = simulate(models, &self.config, initial, &mut ())?;
        self.times.push(clock.seconds());
        self.outcome = Some(Outcome {
            stats: out.stats,
            transitions: out.transitions,
            stop: out.stop.name().to_string(),
        });
        Ok(())
    }

    fn run_switched(&mut self, initial: &InitialState) -> Result<(), SimFailure> {
        let params = DiskParams::paper();
        let clock = Clock::start();
        let out = simulate_switched(&params, &self.config, initial)?;
        self.times.push(clock.seconds());
        self.outcome = Some(Outcome {
            stats: out.stats,
            transitions: out.decisions().len() as u64,
            stop: out.stopped_by.unwrap_or_else(|| "end time".to_string()),
        });
        Ok(())
    }

    fn median(&self) -> f64 {
        median(&self.times)
    }
}

/// How a table row computes its cell for the setting with this index.
type Cell<'a> = Box<dyn Fn(usize) -> String + 'a>;

fn median(values: &[f64]) -> f64 {
    let mut t = values.to_vec();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let (t_end, repeats) = if args.quick { (10.0, 5) } else { (100.0, 9) };
    let params = DiskParams::paper();
    let full: GeneratedModels = DiskModels::generated(params, SlipChart::Cartesian)?;
    let pruned = PrunedModels::pruned(params, SlipChart::Cartesian)?;
    let paper = DiskConfig {
        t_end,
        ..DiskConfig::paper()
    };
    let recommended = DiskConfig {
        t_end,
        ..DiskConfig::default()
    };
    let initial = InitialState::paper(&params);
    let mut runs = [
        Measured::new("DP5, physical time (the paper's)", paper, System::Full),
        Measured::new("DOP853, regularised (default)", recommended, System::Full),
        Measured::new("DOP853, regularised, pruned", recommended, System::Pruned),
        Measured::new(
            "DOP853, regularised, DSL mode graph",
            recommended,
            System::Switched,
        ),
    ];
    for _ in 0..repeats {
        for m in runs.iter_mut() {
            match m.system {
                System::Full => m.run(&full, &initial)?,
                System::Pruned => m.run(&pruned, &initial)?,
                System::Switched => m.run_switched(&initial)?,
            }
        }
    }
    let scale = t_end / 100.0;
    let mut table = format!(
        "paper scene {t_end} s, rtol 1e-8 atol 1e-10, full models unless said ({}; median of {repeats}, runs alternating)\n",
        Clock::kind(),
    );
    table.push_str("| quantity |");
    for m in &runs {
        table.push_str(&format!(" {} |", m.label));
    }
    table.push_str("\n|---|");
    table.push_str(&"---:|".repeat(runs.len()));
    table.push('\n');
    let outs: Vec<&Outcome> = runs
        .iter()
        .map(|r| r.outcome.as_ref().ok_or("no run"))
        .collect::<Result<_, _>>()?;
    let medians: Vec<f64> = runs.iter().map(Measured::median).collect();
    let rows: Vec<(&str, Cell)> = vec![
        ("time (s)", Box::new(|i| format!("{:.3}", medians[i]))),
        (
            "all times (s)",
            Box::new(|i| {
                runs[i]
                    .times
                    .iter()
                    .map(|t| format!("{t:.3}"))
                    .collect::<Vec<_>>()
                    .join(" ")
            }),
        ),
        ("steps", Box::new(|i| outs[i].stats.steps.to_string())),
        ("rejected", Box::new(|i| outs[i].stats.rejected.to_string())),
        (
            "RHS evaluations",
            Box::new(|i| outs[i].stats.rhs_evals.to_string()),
        ),
        (
            "guard evaluations",
            Box::new(|i| outs[i].stats.guard_evals.to_string()),
        ),
        ("transitions", Box::new(|i| outs[i].transitions.to_string())),
        (
            "ns per RHS evaluation, all included",
            Box::new(|i| format!("{:.0}", medians[i] / outs[i].stats.rhs_evals as f64 * 1e9)),
        ),
        (
            "RHS evaluations, Python / this",
            Box::new(|i| {
                format!(
                    "{:.2}",
                    PYTHON_RHS_EVALS * scale / outs[i].stats.rhs_evals as f64
                )
            }),
        ),
        ("stop", Box::new(|i| outs[i].stop.clone())),
    ];
    for (k, f) in rows {
        table.push_str(&format!("| {k} |"));
        for i in 0..runs.len() {
            table.push_str(&format!(" {} |", f(i)));
        }
        table.push('\n');
    }
    table.push('\n');
    for i in 1..runs.len() {
        let pairs: Vec<f64> = runs[i]
            .times
            .iter()
            .zip(&runs[0].times)
            .map(|(a, b)| a / b)
            .collect();
        table.push_str(&format!(
            "{} / {}: time {:.3} (median of the per-round ratios), RHS evaluations {:.3}, steps {:.3}\n",
            runs[i].label,
            runs[0].label,
            median(&pairs),
            outs[i].stats.rhs_evals as f64 / outs[0].stats.rhs_evals as f64,
            outs[i].stats.steps as f64 / outs[0].stats.steps as f64,
        ));
    }
    // The mode graph in the DSL against the hand-written system, at the same settings.
    let (dsl, default) = (&runs[3], &runs[1]);
    let pairs: Vec<f64> = (dsl.times.iter().zip(&default.times))
        .map(|(a, b)| a / b)
        .collect();
    table.push_str(&format!(
        "{} / {}: time {:.3} (median of the per-round ratios), steps {:.3}, transitions {} / {}\n",
        dsl.label,
        default.label,
        median(&pairs),
        outs[3].stats.steps as f64 / outs[1].stats.steps as f64,
        outs[3].transitions,
        outs[1].transitions,
    ));
    print!("{table}");
    std::fs::create_dir_all(&args.out)?;
    std::fs::write(args.out.join("paper_run.md"), table)?;
    Ok(())
}
