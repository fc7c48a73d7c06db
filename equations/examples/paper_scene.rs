//! Runs the paper's scene (docs/physics.md §11) on the hybrid driver and prints what it cost.
//!
//! ```text
//! cargo run --release -p equations --features measure --example paper_scene -- [t_end] [dopri5|dop853]
//! [cartesian|polar] [physical|paper] [rtol] [atol] [generated|graph|reference] [none|exact:N|screened:N]
//! [components|vectors] [pi-gustafsson|pi-hairer|integral] [physical|regularised]
//! ```
//!
//! `generated` runs the hand-written hybrid system over the generated models (`simulate`),
//! `graph` the DSL's mode graph (`simulate_graph`, the main job's default engine), `reference`
//! the hand-written system over the hand-written models.

use equations::DiskParams;
use equations::{
    simulate, simulate_graph, DiskModels, DiskObserver, GeneratedModels, ReferenceModels,
    RunOutcome, TransitionRecord,
};
use equations::{DiskConfig, InitialState, Integrator, SlipSign};
use equations::{Mode, SlipChart};
use std::time::Instant;

/// Counts the mode decisions in the first 1 s, 10 s and 100 s.
#[derive(Default)]
struct Counter {
    within: [u64; 3],
    /// Onsets of sliding within the last second before the end time.
    last_second_onsets: u64,
    t_end: f64,
    to_rolling: u64,
    restarts: u64,
    shortest_sliding: f64,
    /// Largest |α0 − α_r| (wrapped to [0, π]) at the onsets of sliding from rolling.
    largest_turn: f64,
    sliding_since: Option<f64>,
}

impl DiskObserver for Counter {
    fn on_transition(&mut self, r: &TransitionRecord) {
        if std::env::var_os("PAPER_SCENE_TRACE").is_some() {
            println!("{r:?}");
        }
        for (n, limit) in self.within.iter_mut().zip([1.0, 10.0, 100.0]) {
            if r.t <= limit {
                *n += 1;
            }
        }
        if r.t > self.t_end - 1.0 && r.to == Mode::Sliding {
            self.last_second_onsets += 1;
        }
        match (r.from, r.to) {
            (Mode::Sliding, Mode::Rolling) => {
                self.to_rolling += 1;
                if let Some(t0) = self.sliding_since.take() {
                    let d = r.t - t0;
                    if self.shortest_sliding == 0.0 || d < self.shortest_sliding {
                        self.shortest_sliding = d;
                    }
                }
            }
            (Mode::Sliding, Mode::Sliding) => self.restarts += 1,
            (Mode::Rolling, Mode::Sliding) => {
                self.sliding_since = Some(r.t);
                if let (Some(a0), Some(ar)) = (r.slip_direction, r.rolling_direction) {
                    let turn = (a0 - ar).sin().atan2((a0 - ar).cos()).abs();
                    self.largest_turn = self.largest_turn.max(turn);
                }
            }
            _ => {}
        }
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize| args.get(i).map(String::as_str);
    let params = DiskParams::paper();
    let mut config = DiskConfig::paper();
    config.t_end = arg(0).map(str::parse).transpose()?.unwrap_or(1.0);
    config.integrator = match arg(1).unwrap_or("dopri5") {
        "dop853" => Integrator::Dop853,
        _ => Integrator::Dopri5,
    };
    let chart = match arg(2).unwrap_or("cartesian") {
        "polar" => SlipChart::Polar,
        _ => SlipChart::Cartesian,
    };
    if arg(3) == Some("paper") {
        config.slip_sign = SlipSign::Paper;
    }
    if let Some(r) = arg(4) {
        config.rtol = r.parse()?;
    }
    if let Some(a) = arg(5) {
        config.atol = a.parse()?;
    }
    let which = arg(6).unwrap_or("generated");
    if let Some(c) = arg(7) {
        config.guard_checks = c.parse()?;
    }
    if let Some(n) = arg(8) {
        config.error_norm = n.parse()?;
    }
    if let Some(c) = arg(9) {
        config.step_control = c.parse()?;
    }
    if let Some(t) = arg(10) {
        config.time = t.parse()?;
    }
    let mut counter = Counter {
        t_end: config.t_end,
        ..Counter::default()
    };
    let start = Instant::now();
    let initial = InitialState::paper(&params);
    let out: RunOutcome = if which == "reference" {
        let models = ReferenceModels::reference(params, chart)?;
        simulate(&models, &config, &initial, &mut counter)?
    } else if which == "graph" {
        let models: GeneratedModels = DiskModels::generated(params, chart)?;
        simulate_graph(&models, &config, &initial, &mut counter)?
    } else {
        let models: GeneratedModels = DiskModels::generated(params, chart)?;
        simulate(&models, &config, &initial, &mut counter)?
    };
    let elapsed = start.elapsed();
    println!(
        "paper scene, {which} models, {:?}, {chart:?} chart, {:?} slip, rtol {:e}, atol {:e}, guard checks {}, error norm {:?}, time {}",
        config.integrator, config.slip_sign, config.rtol, config.atol, config.guard_checks, config.error_norm, config.time
    );
    println!("stop: {} at t = {}", out.stop.name(), out.last.t);
    println!(
        "time {:.3} s; steps {} (rejected {}); rhs evals {}; guard evals {}; guard estimates {}",
        elapsed.as_secs_f64(),
        out.stats.steps,
        out.stats.rejected,
        out.stats.rhs_evals,
        out.stats.guard_evals,
        out.stats.guard_estimates
    );
    println!(
        "transitions {} (t<=1 s: {}, t<=10 s: {}, t<=100 s: {}); to rolling {}, sliding restarts {}",
        out.transitions,
        counter.within[0],
        counter.within[1],
        counter.within[2],
        counter.to_rolling,
        counter.restarts
    );
    println!(
        "shortest sliding phase ending in rolling: {:e} s; sliding onsets in the last second: {}",
        counter.shortest_sliding, counter.last_second_onsets
    );
    println!(
        "largest |alpha0 - alpha_r| at an onset from rolling: {:.4} rad",
        counter.largest_turn
    );
    println!(
        "max drift: |Z - a sin th| {:e} m, |V_Z - a Om_y cos th| {:e} m/s, no-slip {:e} m/s",
        out.max_drift.height, out.max_drift.vertical_speed, out.max_drift.no_slip
    );
    println!(
        "final: theta {:.10}, energy {:.12} J, mode {}",
        out.last.state.y[equations::layout::THETA],
        out.last.energy,
        out.last.mode
    );
    if which != "reference" {
        let models: GeneratedModels = DiskModels::generated(params, chart)?;
        print_costs(&models, &out, elapsed.as_secs_f64());
    }
    Ok(())
}

/// Times the models alone, to split the run's time between the models and the driver.
fn print_costs(models: &GeneratedModels, out: &RunOutcome, run_seconds: f64) {
    use model_runtime::Model;
    let rolling = out.last.state.rolling_vector();
    let sliding = out.last.state.sliding_vector(
        models.chart,
        equations::Slip {
            speed: 1e-3,
            direction: 0.7,
        },
    );
    let mut dy = [0.0; 12];
    let reps = 200_000;
    let mut per_eval = |f: &dyn Fn(&mut [f64; 12])| {
        let start = Instant::now();
        for _ in 0..reps {
            f(std::hint::black_box(&mut dy));
        }
        start.elapsed().as_secs_f64() / reps as f64
    };
    let roll = per_eval(&|dy| models.rolling.rhs(0.0, &rolling, dy).unwrap_or(()));
    let slide = per_eval(&|dy| models.sliding.rhs(0.0, &sliding, dy).unwrap_or(()));
    let mean = 0.5 * (roll + slide);
    let model_seconds = mean * out.stats.rhs_evals as f64;
    println!(
        "model cost: rolling rhs {:.0} ns, sliding rhs {:.0} ns; ~{:.2} s of the run in the models ({:.0}%), the rest in the driver (steps, dense output, guards, root finding, samples)",
        roll * 1e9,
        slide * 1e9,
        model_seconds,
        100.0 * model_seconds / run_seconds
    );
}
