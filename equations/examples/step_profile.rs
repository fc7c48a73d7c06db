//! Where the steps of the paper's run go, and what the guard checks find.
//!
//! The cost of the 100 s run is set by the number of steps, and those are not spread evenly:
//! late in the run θ dips to ~5e-5 rad once per period and the steps shrink to below a
//! microsecond there. This example counts accepted steps by simulated time, mode and
//! inclination band, and the transitions by kind, so the effect of a formulation, a tolerance
//! or a guard-check setting can be seen where it matters. With a sample rate it also reports the
//! largest friction ratio seen on rolling samples: above `μ_st`, an excursion was missed
//! between guard checks.
//!
//! It also counts the steps by slip speed and, for each state component, the accepted steps
//! whose size it limited (the largest scaled error), which shows what a different error norm
//! (`components` or `vectors`, `equations::ErrorNorm`) would change.
//!
//! ```text
//! cargo run --release -p equations --features measure --example step_profile -- \
//!     [t_end] [rtol] [atol] [none|exact:N|screened:N] [sample_hz] [components|vectors] [pi-gustafsson|pi-hairer|integral] [dopri5|dop853] [physical|regularised]
//! ```

use equations::models::{rolling, sliding_cartesian};
use equations::DiskParams;
use equations::{layout::THETA, Mode, SlipChart};
use equations::{simulate, DiskObserver, DiskSample, GeneratedModels, TransitionRecord};
use equations::{DiskConfig, InitialState, LimitingComponent};
use std::time::Instant;

/// Upper edges of the inclination bands (rad).
const BANDS: [f64; 5] = [1e-4, 3e-4, 1e-3, 1e-2, f64::INFINITY];

/// Upper edges of the slip-speed bands of sliding steps (m/s); rolling steps are counted apart.
const SLIP_BANDS: [f64; 4] = [1e-9, 1e-7, 3e-5, f64::INFINITY];

/// Accepted steps and simulated time in one band.
#[derive(Clone, Copy, Default)]
struct Band {
    steps: u64,
    time: f64,
}

/// Transitions by kind.
#[derive(Default)]
struct Kinds {
    rolling_to_sliding: u64,
    sliding_to_rolling: u64,
    sliding_restarts: u64,
}

#[derive(Default)]
struct Profile {
    /// Steps per 10 s window: rolling, sliding.
    windows: Vec<[u64; 2]>,
    bands: [Band; 5],
    /// Sliding steps by slip speed, then rolling steps.
    slip_bands: [Band; 5],
    last_t: f64,
    kinds: Kinds,
    /// Largest friction ratio on rolling samples.
    nu_rolling_max: f64,
}

impl Band {
    fn add(&mut self, dt: f64) {
        self.steps += 1;
        self.time += dt;
    }
}

/// The band of `value` among bands with upper `edges` (the last one open).
fn band(edges: &[f64], value: f64) -> usize {
    edges
        .iter()
        .position(|&e| value < e)
        .unwrap_or(edges.len() - 1)
}

/// The name of state component `i` in both modes of the Cartesian chart ("V_X/u_X" where
/// they differ).
fn component_name(i: usize) -> String {
    // One past the states: the clock of a run in regularised time.
    let (Some(r), Some(s)) = (
        rolling::STATE_NAMES.get(i),
        sliding_cartesian::STATE_NAMES.get(i),
    ) else {
        return "clock".to_string();
    };
    if r == s {
        r.to_string()
    } else {
        format!("{r}/{s}")
    }
}

impl DiskObserver for Profile {
    fn wants_steps(&self) -> bool {
        true
    }

    fn on_step(&mut self, s: &DiskSample) {
        // Window k holds the steps ending in (10k, 10k + 10] s.
        let w = ((s.t / 10.0).ceil() as usize).saturating_sub(1);
        if self.windows.len() <= w {
            self.windows.resize(w + 1, [0; 2]);
        }
        self.windows[w][usize::from(s.mode == Mode::Sliding)] += 1;
        let dt = s.t - self.last_t;
        self.last_t = s.t;
        let theta = s.state.y[THETA];
        self.bands[band(&BANDS, theta)].add(dt);
        let slip = match s.mode {
            Mode::Rolling => SLIP_BANDS.len(),
            Mode::Sliding => band(&SLIP_BANDS, s.state.slip.speed.abs()),
        };
        self.slip_bands[slip].add(dt);
    }

    fn on_sample(&mut self, s: &DiskSample) {
        if s.mode == Mode::Rolling {
            self.nu_rolling_max = self.nu_rolling_max.max(s.force.ratio());
        }
    }

    fn on_transition(&mut self, r: &TransitionRecord) {
        let k = &mut self.kinds;
        match (r.from, r.to) {
            (Mode::Rolling, _) => k.rolling_to_sliding += 1,
            (Mode::Sliding, Mode::Rolling) => k.sliding_to_rolling += 1,
            (Mode::Sliding, Mode::Sliding) => k.sliding_restarts += 1,
        }
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let number = |i: usize| args.get(i).map(|a| a.parse::<f64>()).transpose();
    let params = DiskParams::paper();
    let mut config = DiskConfig::paper();
    config.t_end = number(0)?.unwrap_or(100.0);
    config.rtol = number(1)?.unwrap_or(config.rtol);
    config.atol = number(2)?.unwrap_or(config.atol);
    if let Some(c) = args.get(3) {
        config.guard_checks = c.parse()?;
    }
    config.sample_rate = number(4)?.filter(|&r| r > 0.0);
    if let Some(n) = args.get(5) {
        config.error_norm = n.parse()?;
    }
    if let Some(c) = args.get(6) {
        config.step_control = c.parse()?;
    }
    if args.get(7).map(String::as_str) == Some("dop853") {
        config.integrator = equations::Integrator::Dop853;
    }
    if let Some(t) = args.get(8) {
        config.time = t.parse()?;
    }
    config.limiting_component = LimitingComponent::Tracked;
    let models = GeneratedModels::generated(params, SlipChart::Cartesian)?;
    let mut p = Profile::default();
    let start = Instant::now();
    let out = simulate(&models, &config, &InitialState::paper(&params), &mut p)?;
    let wall = start.elapsed().as_secs_f64();
    let s = &out.stats;
    println!(
        "t_end {} rtol {:e} atol {:e} guard checks {:?} error norm {:?}: stop {} at t = {}",
        config.t_end,
        config.rtol,
        config.atol,
        config.guard_checks,
        config.error_norm,
        out.stop.name(),
        out.last.t
    );
    println!(
        "steps {} (rejected {}), rhs evals {}, guard evals {}, guard estimates {}, wall {wall:.3} s (with per-step callbacks)",
        s.steps, s.rejected, s.rhs_evals, s.guard_evals, s.guard_estimates
    );
    let k = &p.kinds;
    println!(
        "transitions {}: rolling -> sliding {}, sliding -> rolling {}, sliding restarts {}",
        out.transitions, k.rolling_to_sliding, k.sliding_to_rolling, k.sliding_restarts
    );
    if config.sample_rate.is_some() {
        println!("largest nu on rolling samples: {}", p.nu_rolling_max);
    }
    for (i, [r, s]) in p.windows.iter().enumerate() {
        println!(
            "{:>4}-{:<4} s: rolling {r:>8} sliding {s:>8} steps",
            i * 10,
            i * 10 + 10
        );
    }
    for (edge, b) in BANDS.iter().zip(&p.bands) {
        println!(
            "theta < {edge:e}: {:>8} steps over {:.4} s",
            b.steps, b.time
        );
    }
    for (i, b) in p.slip_bands.iter().enumerate() {
        let label = match (i.checked_sub(1).map(|j| SLIP_BANDS[j]), SLIP_BANDS.get(i)) {
            (_, None) => "rolling".to_string(),
            (None, Some(hi)) => format!("slip < {hi:e} m/s"),
            (Some(lo), Some(hi)) if hi.is_infinite() => format!("slip >= {lo:e} m/s"),
            (Some(lo), Some(hi)) => format!("slip {lo:e}..{hi:e} m/s"),
        };
        println!("{label:>24}: {:>8} steps over {:.4} s", b.steps, b.time);
    }
    println!("steps limited by (largest scaled error):");
    for (i, n) in s.limiting.nonzero() {
        let share = 100.0 * n as f64 / s.steps.max(1) as f64;
        println!("{:>16}: {n:>8} ({share:.1}%)", component_name(i));
    }
    Ok(())
}
