//! Throughput of `eulerdisk sweep` with 1 and 2 workers on the same 16 short runs.
//!
//! `cargo run --release --example sweep_scaling [-- RUNS T_END ROUNDS]` runs a sweep of RUNS
//! points (the paper's scene, μ_d spread over [0.10, 0.13], DP5, T_END simulated seconds each)
//! into a fresh folder for each measurement, alternating 1 and 2 workers ROUNDS times, and
//! prints runs per second of each, the ratio, and the load of the machine (`/proc/loadavg`)
//! before and after: on a shared machine the load says how much the numbers can be trusted.
//! The CPU time of each measurement (all threads) shows how many cores a run keeps busy.

use std::sync::atomic::AtomicBool;
use std::time::Instant;

use eulerdisk::{
    parse_sweep, plan, process_cpu_s, run_sweep, ExecOptions, LoadedSweep, ProgressStyle,
};

fn load() -> String {
    std::fs::read_to_string("/proc/loadavg").unwrap_or_else(|_| "unknown".into())
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: &str| args.get(i).cloned().unwrap_or_else(|| default.to_string());
    let runs: u32 = arg(0, "16").parse().expect("RUNS: a whole number");
    let t_end: f64 = arg(1, "20").parse().expect("T_END: seconds");
    let rounds: usize = arg(2, "3").parse().expect("ROUNDS: a whole number");
    let text = format!(
        "scene = \"tangent-toy-pruned\"\n[set]\nrun.t_end = {t_end}\nsolver.integrator = \"dopri5\"\n\
         [[axis]]\nkey = \"friction.mu_d\"\nlinspace = {{ from = 0.10, to = 0.13, num = {runs} }}\n"
    );
    let sweep = LoadedSweep {
        name: "scaling".into(),
        folder: None,
        file: parse_sweep("scaling", &text).expect("the benchmark's sweep parses"),
    };
    let plan = plan(&sweep, &[]).expect("the benchmark's sweep is valid");
    let root = std::env::temp_dir().join(format!("eulerdisk-sweep-scaling-{}", std::process::id()));
    println!(
        "{runs} runs of {t_end} s (DP5, paper's scene), {rounds} rounds; load before: {}",
        load().trim()
    );
    let mut best = [f64::INFINITY; 2];
    let mut all = [Vec::new(), Vec::new()];
    for round in 0..rounds {
        for (k, jobs) in [1usize, 2].into_iter().enumerate() {
            let out = root.join(format!("r{round}-j{jobs}"));
            let opts = ExecOptions {
                jobs,
                progress: ProgressStyle::Quiet,
                shard: None,
            };
            let started = Instant::now();
            let cpu0 = process_cpu_s();
            let report =
                run_sweep(&plan, &out, &opts, &AtomicBool::new(false)).expect("the sweep runs");
            let wall = started.elapsed().as_secs_f64();
            let cpu = process_cpu_s() - cpu0;
            assert_eq!(report.exec.ran, runs as usize);
            best[k] = best[k].min(wall);
            all[k].push(wall);
            println!(
                "round {round}, {jobs} worker(s): {wall:.3} s, {:.2} runs/s, CPU {cpu:.3} s ({:.2} cores busy)",
                runs as f64 / wall,
                cpu / wall
            );
        }
    }
    let _ = std::fs::remove_dir_all(&root);
    for (k, jobs) in [1, 2].into_iter().enumerate() {
        let mut v = all[k].clone();
        v.sort_by(f64::total_cmp);
        println!(
            "{jobs} worker(s): best {:.3} s ({:.2} runs/s), median {:.3} s",
            best[k],
            runs as f64 / best[k],
            v[v.len() / 2]
        );
    }
    println!(
        "throughput ratio 2 workers / 1 worker (best of each): {:.2}",
        best[0] / best[1]
    );
    println!("load after: {}", load().trim());
}
