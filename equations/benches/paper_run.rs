//! The paper's 100 s scene end to end, the number a user waits for.
//!
//! DP5 at the paper's `rtol = 1e-8`, `atol = 1e-10`, Cartesian slip chart, physical slip sign,
//! single thread; the median of five runs (`--quick`: 10 s, three runs). The Python figures it
//! is compared with come from an independent implementation (scipy's DOP853 with events, same
//! tolerances): about 120 s and 8.9 M right-hand-side evaluations for the 100 s.
//!
//! ```text
//! cargo bench -p equations --bench paper_run [-- --quick] [--out DIR]
//! ```

use common::{Args, Clock};
use equations::hybrid::{simulate, DiskConfig, DiskModels, GeneratedModels, InitialState};
use equations::modes::SlipChart;
use equations::DiskParams;

mod common;

/// scipy DOP853 with events on the same scene and tolerances (s of CPU, RHS evaluations).
const PYTHON_SECONDS: f64 = 120.0;
const PYTHON_RHS_EVALS: f64 = 8.9e6;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let (t_end, repeats) = if args.quick { (10.0, 3) } else { (100.0, 5) };
    let params = DiskParams::paper();
    let models: GeneratedModels = DiskModels::generated(params, SlipChart::Cartesian)?;
    let config = DiskConfig {
        t_end,
        ..DiskConfig::paper()
    };
    let initial = InitialState::paper(&params);
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..repeats {
        let clock = Clock::start();
        let out = simulate(&models, &config, &initial, &mut ())?;
        times.push(clock.seconds());
        last = Some(out);
    }
    let out = last.ok_or("no run")?;
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    let st = out.stats;
    let scale = t_end / 100.0;
    let mut table = String::new();
    table.push_str(&format!(
        "paper scene {t_end} s, DP5 rtol 1e-8 atol 1e-10 ({}; median of {repeats}: {:.3} s; all: {:?})\n",
        Clock::kind(),
        median,
        times.iter().map(|t| format!("{t:.3}")).collect::<Vec<_>>()
    ));
    table.push_str("| quantity | value |\n|---|---:|\n");
    let rows = [
        ("time (s)", format!("{median:.3}")),
        ("steps", st.steps.to_string()),
        ("rejected", st.rejected.to_string()),
        ("RHS evaluations", st.rhs_evals.to_string()),
        (
            "RHS evaluations per simulated second",
            format!("{:.0}", st.rhs_evals as f64 / t_end),
        ),
        ("guard evaluations", st.guard_evals.to_string()),
        ("transitions", out.transitions.to_string()),
        (
            "ns per RHS evaluation, all included",
            format!("{:.0}", median / st.rhs_evals as f64 * 1e9),
        ),
        (
            "speed-up over Python (time, scaled to this span)",
            format!("{:.0}x", PYTHON_SECONDS * scale / median),
        ),
        (
            "RHS evaluations, Python / this",
            format!("{:.2}", PYTHON_RHS_EVALS * scale / st.rhs_evals as f64),
        ),
        ("stop", out.stop.name().to_string()),
    ];
    for (k, v) in rows {
        table.push_str(&format!("| {k} | {v} |\n"));
    }
    print!("{table}");
    std::fs::create_dir_all(&args.out)?;
    std::fs::write(args.out.join("paper_run.md"), table)?;
    Ok(())
}
