//! Work against precision for every integrator the disk can run on (issue 6).
//!
//! A simulator is only "fast" at a stated accuracy, so each run here is timed *and* scored
//! against a reference solution: the error of the final state, of the first 20 transition times,
//! of the energy, and the constraint drift. The reference is DOP853 at `rtol = 1e-13`, and it is
//! only trusted after a second method (DP5 at `rtol = 1e-12`) agrees with it; the agreement is
//! printed, so a reader can see how far down the error axis the figure means anything.
//!
//! ```text
//! cargo bench -p equations --bench work_precision [-- --quick] [--out DIR] [--methods LIST]
//! ```
//!
//! `--methods "DP5,DP5 vectors"` runs only the named lines. `DP5 vectors` is DP5 with the
//! vector error norm ([`ErrorNorm::Vectors`]), `DP5 pi-hairer` and `DP5 integral` DP5 with
//! other step controls ([`StepControl`]): whether their fewer steps are a good trade shows
//! only at equal accuracy, which is what this table measures. `DOP853 regularised` and
//! `DP5 regularised` step in regularised time ([`TimeVariable::Regularised`]); the first is the
//! scenes' default.
//!
//! Tolerances: `atol = rtol·1e-2` (the paper's 1e-8/1e-10 pair is one point of the sweep), stick
//! threshold `max(1e-9, 10·atol)` m/s. RK4 runs at fixed steps `h` with the stick threshold
//! `max(1e-9, 2 μ_d g h)`, the slip's change over one step. Writes `work_precision.csv` and `work_precision_<scene>.svg` to
//! `target/bench/` (or `--out`).

use common::{Args, Clock};
use equations::DiskParams;
use equations::{layout, SlipChart, DIM};
use equations::{simulate, DiskModels, DiskRecorder, GeneratedModels, RunOutcome, SimError};
use equations::{DiskConfig, ErrorNorm, InitialState, Integrator, StepControl, TimeVariable};
use plotters::prelude::*;
use std::path::{Path, PathBuf};

mod common;

/// Transition times compared against the reference.
const FIRST_TRANSITIONS: usize = 20;

/// One simulated situation.
#[derive(Clone, Copy)]
struct Scene {
    name: &'static str,
    params: DiskParams,
    initial: InitialState,
    t_end: f64,
}

/// The paper's scene (slides, sticks, thousands of switches in 100 s).
fn paper_scene(t_end: f64, name: &'static str) -> Scene {
    let params = DiskParams::paper();
    Scene {
        name,
        params,
        initial: InitialState::paper(&params),
        t_end,
    }
}

/// A disk rolling fast and upright enough never to slip (static friction raised to 5): the
/// smooth, switch-free baseline where energy is conserved exactly.
fn rolling_scene(t_end: f64) -> Scene {
    let params = DiskParams {
        mu_st: 5.0,
        ..DiskParams::paper()
    };
    let theta: f64 = 1.2;
    let mut y = [0.0; DIM];
    y[layout::THETA] = theta;
    y[layout::Z] = params.a * theta.sin();
    y[layout::OMEGA_X] = 0.5;
    y[layout::OMEGA_Z] = 30.0;
    // On the rolling constraints: V = a (Ω_y cos ψ sin θ + Ω_z sin ψ, ...) with ψ = 0, Ω_y = 0.
    y[layout::V_Y] = -params.a * y[layout::OMEGA_Z];
    Scene {
        name: "rolling",
        params,
        initial: InitialState::from_velocity(&params, 0.0, y),
        t_end,
    }
}

/// The lines of the table and figure, in order.
const METHOD_NAMES: [&str; 9] = [
    "DP5",
    "DOP853 regularised",
    "DP5 regularised",
    "DP5 vectors",
    "DP5 pi-hairer",
    "DP5 integral",
    "DOP853",
    "Rodas4",
    "RK4",
];

/// The integrator, its error norm, its step control and the accuracy knob it was given.
#[derive(Clone, Copy)]
struct Method {
    choice: Integrator,
    norm: ErrorNorm,
    control: StepControl,
    time: TimeVariable,
    /// `rtol` for adaptive methods, the step for RK4.
    knob: f64,
}

impl Method {
    fn name(&self) -> &'static str {
        if self.time == TimeVariable::Regularised {
            return match self.choice {
                Integrator::Dop853 => "DOP853 regularised",
                _ => "DP5 regularised",
            };
        }
        match (self.choice, self.norm, self.control) {
            (Integrator::Dopri5, ErrorNorm::Vectors, _) => "DP5 vectors",
            (Integrator::Dopri5, _, StepControl::PiHairer) => "DP5 pi-hairer",
            (Integrator::Dopri5, _, StepControl::Integral) => "DP5 integral",
            (Integrator::Dopri5, ..) => "DP5",
            (Integrator::Dop853, ..) => "DOP853",
            (Integrator::Rodas4, ..) => "Rodas4",
            (Integrator::Rk4 { .. }, ..) => "RK4",
        }
    }

    fn adaptive(choice: Integrator, rtol: f64) -> Self {
        Method {
            choice,
            norm: ErrorNorm::Components,
            control: StepControl::default(),
            time: TimeVariable::Physical,
            knob: rtol,
        }
    }

    fn rk4(h: f64) -> Self {
        Method {
            choice: Integrator::Rk4 { h },
            norm: ErrorNorm::Components,
            control: StepControl::default(),
            time: TimeVariable::Physical,
            knob: h,
        }
    }

    fn config(&self, t_end: f64, params: &DiskParams) -> DiskConfig {
        match self.choice {
            Integrator::Rk4 { h } => {
                let config = sweep_config(self.choice, 1e-8, t_end);
                // A fixed step moves the slip by about μ_d g h whatever happens, so a stick
                // threshold below that is stepped over and every stick is missed (measured:
                // none of the 14 in the first second at h = 1e-4 with δ = 1e-9).
                DiskConfig {
                    stick_threshold: config.stick_threshold.max(2.0 * params.mu_d * params.g * h),
                    ..config
                }
            }
            _ => DiskConfig {
                error_norm: self.norm,
                step_control: self.control,
                time: self.time,
                ..sweep_config(self.choice, self.knob, t_end)
            },
        }
    }
}

/// What one run produced.
struct Run {
    outcome: RunOutcome,
    transitions: Vec<equations::TransitionRecord>,
    seconds: f64,
}

fn run_once(models: &GeneratedModels, scene: &Scene, config: &DiskConfig) -> Result<Run, SimError> {
    let mut record = DiskRecorder::default();
    let clock = Clock::start();
    let outcome = simulate(models, config, &scene.initial, &mut record)?;
    let seconds = clock.seconds();
    Ok(Run {
        outcome,
        transitions: record.transitions,
        seconds,
    })
}

/// Runs `repeats` times and keeps the run with the median time.
fn timed(
    models: &GeneratedModels,
    scene: &Scene,
    config: &DiskConfig,
    repeats: usize,
) -> Result<Run, SimError> {
    let mut runs = (0..repeats)
        .map(|_| run_once(models, scene, config))
        .collect::<Result<Vec<_>, _>>()?;
    runs.sort_by(|a, b| a.seconds.total_cmp(&b.seconds));
    Ok(runs.swap_remove(runs.len() / 2))
}

/// How far a run is from the reference.
#[derive(Clone, Copy)]
struct Score {
    /// Max over components of `|Δy| / (|y_ref| + 1e-2)` of the final state (rolling variables).
    state: f64,
    /// |Δθ| at the end (rad).
    theta: f64,
    /// Largest |Δt| over the first transitions both runs share (s); NaN if none.
    transition_times: f64,
    /// Index of the first transition whose kind (from → to) differs, if any within the first 20.
    kind_mismatch: Option<usize>,
    /// |E − E_ref| at the end (J).
    energy: f64,
}

fn score(run: &Run, reference: &Run) -> Score {
    let (y, r) = (&run.outcome.last.state.y, &reference.outcome.last.state.y);
    let state = y
        .iter()
        .zip(r)
        .map(|(a, b)| (a - b).abs() / (b.abs() + 1e-2))
        .fold(0.0, f64::max);
    let shared = run
        .transitions
        .iter()
        .zip(&reference.transitions)
        .take(FIRST_TRANSITIONS);
    let mut transition_times = f64::NAN;
    let mut kind_mismatch = None;
    for (k, (a, b)) in shared.enumerate() {
        if (a.from, a.to) != (b.from, b.to) {
            kind_mismatch = Some(k);
            break;
        }
        let d = (a.t - b.t).abs();
        transition_times = if transition_times.is_nan() {
            d
        } else {
            transition_times.max(d)
        };
    }
    Score {
        state: if run.outcome.last.t == reference.outcome.last.t {
            state
        } else {
            f64::INFINITY
        },
        theta: (y[layout::THETA] - r[layout::THETA]).abs(),
        transition_times,
        kind_mismatch,
        energy: (run.outcome.last.energy - reference.outcome.last.energy).abs(),
    }
}

/// One line of the table.
struct Row {
    scene: &'static str,
    method: &'static str,
    knob: f64,
    result: Result<(Run, Score), String>,
}

struct Settings {
    quick: bool,
    repeats: usize,
    out: PathBuf,
    /// The method names to run (all if `None`).
    only: Option<Vec<String>>,
}

fn settings() -> Settings {
    let Args { quick, out } = Args::parse();
    let args: Vec<String> = std::env::args().collect();
    let only = args
        .iter()
        .position(|a| a == "--methods")
        .and_then(|i| args.get(i + 1))
        .map(|list| list.split(',').map(|m| m.trim().to_string()).collect());
    Settings {
        quick,
        repeats: if quick { 1 } else { 3 },
        out,
        only,
    }
}

fn methods(quick: bool) -> Vec<Method> {
    let rtols: Vec<f64> = if quick {
        vec![1e-4, 1e-6, 1e-8, 1e-10]
    } else {
        (3..=12).map(|k| 10f64.powi(-k)).collect()
    };
    let mut all = Vec::new();
    for choice in [Integrator::Dopri5, Integrator::Dop853] {
        all.extend(rtols.iter().map(|&r| Method::adaptive(choice, r)));
        all.extend(rtols.iter().map(|&r| Method {
            time: TimeVariable::Regularised,
            ..Method::adaptive(choice, r)
        }));
    }
    all.extend(rtols.iter().map(|&r| Method {
        norm: ErrorNorm::Vectors,
        ..Method::adaptive(Integrator::Dopri5, r)
    }));
    // The other step controls (BENCHMARKS.md §3: fewer steps, not less work at equal accuracy).
    for control in [StepControl::PiHairer, StepControl::Integral] {
        all.extend(rtols.iter().map(|&r| Method {
            control,
            ..Method::adaptive(Integrator::Dopri5, r)
        }));
    }
    // Rodas4 with its symbolic Jacobian: an order-4 method, so the sweep stops where its cost
    // runs away (documented in BENCHMARKS.md).
    all.extend(
        rtols
            .iter()
            .filter(|&&r| r >= 1e-9)
            .map(|&r| Method::adaptive(Integrator::Rodas4, r)),
    );
    let steps: &[f64] = if quick {
        &[1e-3, 1e-4]
    } else {
        &[1e-3, 3e-4, 1e-4, 3e-5, 1e-5]
    };
    all.extend(steps.iter().map(|&h| Method::rk4(h)));
    all
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let s = settings();
    let scenes = if s.quick {
        vec![paper_scene(1.0, "paper 1 s"), rolling_scene(2.0)]
    } else {
        vec![
            paper_scene(1.0, "paper 1 s"),
            paper_scene(10.0, "paper 10 s"),
            rolling_scene(10.0),
        ]
    };
    std::fs::create_dir_all(&s.out)?;
    println!(
        "times: {}, median of {} run(s); atol = rtol * 1e-2",
        Clock::kind(),
        s.repeats
    );
    let mut rows = Vec::new();
    for scene in &scenes {
        let models: GeneratedModels = DiskModels::generated(scene.params, SlipChart::Cartesian)?;
        let reference = run_once(
            &models,
            scene,
            &sweep_config(Integrator::Dop853, 1e-13, scene.t_end),
        )?;
        let check = run_once(
            &models,
            scene,
            &sweep_config(Integrator::Dopri5, 1e-12, scene.t_end),
        )?;
        let agreement = score(&check, &reference);
        println!(
            "\n## {} (t_end = {} s): reference DOP853 rtol 1e-13 ({} transitions, stop: {}); DP5 rtol 1e-12 agrees to state {:.1e}, transition times {:.1e} s{}",
            scene.name,
            scene.t_end,
            reference.outcome.transitions,
            reference.outcome.stop.name(),
            agreement.state,
            agreement.transition_times,
            match agreement.kind_mismatch {
                Some(k) => format!(", transition kinds differ from #{k}"),
                None => String::new(),
            }
        );
        print_header();
        let first = rows.len();
        let chosen = methods(s.quick).into_iter().filter(|m| {
            s.only
                .as_ref()
                .is_none_or(|names| names.iter().any(|n| n == m.name()))
        });
        for method in chosen {
            let config = method.config(scene.t_end, &scene.params);
            let result = timed(&models, scene, &config, s.repeats)
                .map(|run| {
                    let sc = score(&run, &reference);
                    (run, sc)
                })
                .map_err(|e| e.to_string());
            let row = Row {
                scene: scene.name,
                method: method.name(),
                knob: method.knob,
                result,
            };
            print_row(&row, reference.outcome.transitions);
            rows.push(row);
        }
        figure(&s.out, scene.name, &rows[first..])?;
    }
    write_csv(&s.out.join("work_precision.csv"), &rows)?;
    println!("\nwrote {}", s.out.display());
    Ok(())
}

/// `atol = rtol·1e-2`, and the stick threshold kept well above the slip's integration error
/// as [`DiskConfig::stick_threshold`] requires: `δ = max(1e-9, 10·atol)` m/s. With a fixed
/// `δ = 1e-9` the loose tolerances integrate the slip with errors far above `δ`; the slip then
/// hovers near zero in the stiff Cartesian chart and the step size collapses (DP5 at
/// `rtol = 1e-6` took 9 M steps for 1 s).
fn sweep_config(choice: Integrator, rtol: f64, t_end: f64) -> DiskConfig {
    let atol = rtol * 1e-2;
    let paper = DiskConfig::paper();
    DiskConfig {
        integrator: choice,
        rtol,
        atol,
        t_end,
        stick_threshold: paper.stick_threshold.max(10.0 * atol),
        ..paper
    }
}

fn print_header() {
    println!("| method | rtol / h | time (ms) | steps | rejected | RHS evals | transitions | state err | θ err (rad) | first-20 Δt (s) | energy err (J) | constraint drift | stop |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|");
}

fn print_row(row: &Row, reference_transitions: u64) {
    match &row.result {
        Ok((run, sc)) => {
            let st = &run.outcome.stats;
            let dt = match sc.kind_mismatch {
                Some(k) => format!("kinds differ at #{k}"),
                None => format!("{:.1e}", sc.transition_times),
            };
            println!(
                "| {} | {:.0e} | {:.2} | {} | {} | {} | {} ({:+}) | {:.1e} | {:.1e} | {dt} | {:.1e} | {:.1e} | {} |",
                row.method,
                row.knob,
                run.seconds * 1e3,
                st.steps,
                st.rejected,
                st.rhs_evals,
                run.outcome.transitions,
                run.outcome.transitions as i64 - reference_transitions as i64,
                sc.state,
                sc.theta,
                sc.energy,
                run.outcome.max_drift.max_abs(),
                run.outcome.stop.name(),
            );
        }
        Err(e) => println!("| {} | {:.0e} | failed: {e} |", row.method, row.knob),
    }
}

fn write_csv(path: &Path, rows: &[Row]) -> std::io::Result<()> {
    let mut csv = String::from("scene,method,rtol_or_h,seconds,steps,rejected,rhs_evals,transitions,state_err,theta_err,first20_dt,first20_kind_mismatch,energy_err,constraint_drift,stop,error\n");
    for row in rows {
        match &row.result {
            Ok((run, sc)) => {
                let st = &run.outcome.stats;
                csv.push_str(&format!(
                    "{},{},{:e},{:e},{},{},{},{},{:e},{:e},{:e},{},{:e},{:e},{},\n",
                    row.scene,
                    row.method,
                    row.knob,
                    run.seconds,
                    st.steps,
                    st.rejected,
                    st.rhs_evals,
                    run.outcome.transitions,
                    sc.state,
                    sc.theta,
                    sc.transition_times,
                    sc.kind_mismatch.map(|k| k.to_string()).unwrap_or_default(),
                    sc.energy,
                    run.outcome.max_drift.max_abs(),
                    run.outcome.stop.name()
                ));
            }
            Err(e) => csv.push_str(&format!(
                "{},{},{:e},,,,,,,,,,,,,\"{}\"\n",
                row.scene,
                row.method,
                row.knob,
                e.replace('"', "'")
            )),
        }
    }
    std::fs::write(path, csv)
}

/// The shipped font, so the figure's text renders without system fonts.
const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Error of the final state against CPU time, log-log, one line per integrator.
fn figure(out: &Path, scene: &str, rows: &[Row]) -> Result<(), Box<dyn std::error::Error>> {
    static FONT_ONCE: std::sync::Once = std::sync::Once::new();
    FONT_ONCE.call_once(|| {
        if plotters::style::register_font("sans-serif", FontStyle::Normal, FONT).is_err() {
            eprintln!("warning: the embedded font could not be loaded; the figure lacks text");
        }
    });
    let points = |method: &str| -> Vec<(f64, f64)> {
        rows.iter()
            .filter(|r| r.method == method)
            .filter_map(|r| r.result.as_ref().ok())
            .map(|(run, sc)| (run.seconds, sc.state.max(1e-16)))
            .filter(|(t, e)| t.is_finite() && e.is_finite() && *t > 0.0)
            .collect()
    };
    let all: Vec<(f64, f64)> = METHOD_NAMES.iter().flat_map(|m| points(m)).collect();
    if all.is_empty() {
        return Ok(());
    }
    let span = |v: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = v.fold((f64::INFINITY, 0.0_f64), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
        (lo / 2.0)..(hi * 2.0)
    };
    let x = span(&mut all.iter().map(|p| p.0));
    let y = span(&mut all.iter().map(|p| p.1));
    let file = out.join(format!("work_precision_{}.svg", scene.replace(' ', "_")));
    let root = SVGBackend::new(&file, (900, 600)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("Work-precision, {scene}"), ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x.log_scale(), y.log_scale())?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc("final-state error vs reference")
        .draw()?;
    for (k, m) in METHOD_NAMES.iter().enumerate() {
        let mut pts = points(m);
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let color = Palette99::pick(k).to_rgba();
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))?
            .label(*m)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
            });
        chart.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
