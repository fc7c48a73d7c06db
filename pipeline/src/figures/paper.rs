//! The paper's Figures 1–10, recomputed from a run.
//!
//! Each figure is built as a [`Chart`] from the recorded samples: two time windows (the first
//! and the last simulated second, sampled finely) and the whole run (per-oscillation
//! envelopes, so 100 s of a 150 s⁻¹ oscillation stay readable). Heights and envelopes come
//! from the extrema the run located on the dense output ([`Located`]), not from samples, so
//! they do not change with the sampling rate; curves of θ, N and the slip speed are drawn
//! through the samples with the located extrema merged in by time (a force peak lasts
//! milliseconds: at any sampling rate the samples alone fall short of it, and a curve would
//! not reach the dots that mark it), and the force peaks are marked at their located heights. A run without located extrema (a
//! synthetic one) draws its envelopes from the samples. Every time axis spans the
//! time its figure covers, and a figure that has nothing to show on a scene (no nutation, no
//! sliding, a run shorter than a second) says why in the picture.

use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use equations::DiskParams;

use super::axes::time_range_label;
use super::chart::{colors, render, Chart};
use super::line::Line;
use crate::analysis::extrema::Located;
use crate::analysis::oscillation::{cycle_extremes, upward_crossings, CycleExtremes, Series};
use crate::output::atomic::WriteError;
use crate::record::RunData;
use equations::record::Sample;
use equations::{ExtremumKind, Watched};

/// The file stems of the figures, in the order [`paper_charts`] builds them: the files a run
/// writes (and owns: a rerun clears them first).
pub const FIGURE_STEMS: [&str; 15] = [
    "fig01a_theta",
    "fig03a_theta_dot",
    "fig05a_nu",
    "fig06a_slip_speed",
    "fig08a_normal_force",
    "fig01b_theta",
    "fig03b_theta_dot",
    "fig05b_nu",
    "fig06b_slip_speed",
    "fig08b_normal_force",
    "fig02_theta_envelope",
    "fig04_theta_dot_over_psi_dot",
    "fig07_slip_speed_envelope",
    "fig09_normal_force_vs_theta",
    "fig10_normal_force_last_second",
];

/// A time window of the run with its samples.
struct Window<'a> {
    /// `a` (first second) or `b` (last second), as in the paper's panels.
    panel: &'static str,
    /// Human description for titles.
    label: String,
    samples: &'a [Sample],
}

impl Window<'_> {
    /// The time the window covers, from its first to its last sample.
    fn span(&self) -> Option<std::ops::Range<f64>> {
        Some(self.samples.first()?.t..self.samples.last()?.t)
    }
}

fn windows(data: &RunData) -> [Window<'_>; 2] {
    let span = |s: &[Sample]| match (s.first(), s.last()) {
        (Some(a), Some(b)) => time_range_label(a.t, b.t),
        _ => "(no samples)".to_string(),
    };
    let first: &[Sample] = if data.first_second.is_empty() {
        let t0 = data.samples.first().map_or(0.0, |s| s.t);
        let n = data.samples.partition_point(|s| s.t <= t0 + 1.0);
        &data.samples[..n]
    } else {
        &data.first_second
    };
    let last: &[Sample] = if data.last_second.is_empty() {
        let t1 = data.samples.last().map_or(0.0, |s| s.t);
        let n = data.samples.partition_point(|s| s.t < t1 - 1.0);
        &data.samples[n..]
    } else {
        &data.last_second
    };
    [
        Window {
            panel: "a",
            label: format!("first second {}", span(first)),
            samples: first,
        },
        Window {
            panel: "b",
            label: format!("last second {}", span(last)),
            samples: last,
        },
    ]
}

fn points(samples: &[Sample], f: impl Fn(&Sample) -> f64) -> Vec<(f64, f64)> {
    samples.iter().map(|s| (s.t, f(s))).collect()
}

/// The curve of `q` (its value read off a sample by `f`) over `samples`, with the located
/// extrema of `q` inside their span merged in by time: it passes through every located peak
/// and trough, so its own maxima are the located ones whatever the sampling rate.
fn through_located(
    located: &Located,
    q: Watched,
    samples: &[Sample],
    f: impl Fn(&Sample) -> f64,
) -> Vec<(f64, f64)> {
    let sampled = points(samples, f);
    match (samples.first(), samples.last()) {
        (Some(a), Some(b)) => {
            merge_by_time(sampled, located.all_of(q, a.t, b.t).map(|e| (e.t, e.value)))
        }
        _ => sampled,
    }
}

/// The points of `a` and `b` (each in time order) in time order; a point of `b` at the time
/// of one of `a` follows it.
fn merge_by_time(a: Vec<(f64, f64)>, b: impl Iterator<Item = (f64, f64)>) -> Vec<(f64, f64)> {
    let mut b = b.peekable();
    let mut out = Vec::with_capacity(a.len() + b.size_hint().0);
    for p in a {
        while let Some(e) = b.next_if(|e| e.0 < p.0) {
            out.push(e);
        }
        out.push(p);
    }
    out.extend(b);
    out
}

/// Per-oscillation extremes of `f` over the whole run: cycles bounded by the minima of θ
/// (upward zero crossings of θ̇).
fn per_cycle(samples: &[Sample], f: impl Fn(&Sample) -> f64) -> Vec<CycleExtremes> {
    let t: Vec<f64> = samples.iter().map(|s| s.t).collect();
    let theta_dot: Vec<f64> = samples.iter().map(|s| s.state.omega_y).collect();
    let peak = theta_dot.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let bounds = upward_crossings(
        Series {
            t: &t,
            v: &theta_dot,
        },
        1e-3 * peak,
    );
    let values: Vec<f64> = samples.iter().map(f).collect();
    cycle_extremes(&t, &values, &bounds)
}

/// Per-oscillation extremes of `q` from the located extrema, cycles bounded by θ's minima
/// (`bounds_at` = min) or maxima;
/// `None` when the run located none (the caller then reads the samples).
fn located_cycles(
    located: &Located,
    q: Watched,
    bounds_at: ExtremumKind,
    t0: f64,
    t1: f64,
) -> Option<Vec<CycleExtremes>> {
    if located.is_empty() {
        return None;
    }
    let bounds = located.theta_cycles(bounds_at, t0, t1);
    let cycles = bounds
        .windows(2)
        .filter_map(|w| {
            let pick = |kind| {
                let it = located.of(q, kind, w[0], w[1]);
                match kind {
                    ExtremumKind::Max => it.max_by(|a, b| a.value.total_cmp(&b.value)),
                    ExtremumKind::Min => it.min_by(|a, b| a.value.total_cmp(&b.value)),
                }
                .copied()
            };
            let (hi, lo) = (pick(ExtremumKind::Max)?, pick(ExtremumKind::Min));
            let lo = lo.unwrap_or(hi);
            Some(CycleExtremes {
                t_max: hi.t,
                max: hi.value,
                t_min: lo.t,
                min: lo.value,
            })
        })
        .collect();
    Some(cycles)
}

/// The located peaks of N/mg within a window: the largest per θ cycle (bounded by θ's maxima,
/// so that each force peak at a minimum of θ is inside one), as dots.
fn peak_marks(located: &Located, span: Option<std::ops::Range<f64>>) -> Option<Line> {
    let span = span?;
    let bounds: Vec<f64> = std::iter::once(span.start)
        .chain(located.theta_cycles(ExtremumKind::Max, span.start, span.end))
        .chain(std::iter::once(span.end))
        .collect();
    let peaks = located.per_cycle_max(Watched::NormalForce, &bounds);
    (!peaks.is_empty()).then(|| {
        Line::new(
            "peak N/mg (located)",
            peaks.iter().map(|e| (e.t, e.value)).collect(),
            colors::BLACK,
        )
        .dots()
    })
}

/// Every figure of the paper for `data`, as chart descriptions. The legends quote the
/// paper's numbers only when `compared_with_paper` (the scene is the paper's: another disk or
/// start has other numbers).
pub fn paper_charts(data: &RunData, p: &DiskParams, compared_with_paper: bool) -> Vec<Chart> {
    let mg = p.weight();
    let located = Located::new(&data.extrema, mg);
    let all = &data.samples;
    let t_start = all.first().map_or(0.0, |s| s.t);
    let t_end = all.last().map_or(0.0, |s| s.t);
    let whole = time_range_label(t_start, t_end);
    let after_one = time_range_label(t_start + 1.0, t_end);
    let chart = Chart::over_time;
    let theta_curve =
        |s: &[Sample]| through_located(&located, Watched::Theta, s, |x| x.state.theta);
    let normal_curve =
        |s: &[Sample]| through_located(&located, Watched::NormalForce, s, |x| x.forces.normal / mg);
    let mut charts = Vec::new();
    for w in windows(data) {
        let s = w.samples;
        let window = |mut c: Chart| {
            c.x_range = w.span();
            c
        };
        charts.push(window(chart(
            &format!("fig01{}_theta", w.panel),
            format!("Fig. 1{}: inclination θ, {}", w.panel, w.label),
            "θ (rad)",
            vec![Line::new("θ", theta_curve(s), colors::BLUE)],
        )));
        charts.push(window(chart(
            &format!("fig03{}_theta_dot", w.panel),
            format!("Fig. 3{}: nutation rate dθ/dt, {}", w.panel, w.label),
            "dθ/dt (rad/s)",
            vec![Line::new(
                "dθ/dt",
                points(s, |x| x.state.omega_y),
                colors::BLUE,
            )],
        )));
        charts.push(window(chart(
            &format!("fig05{}_nu", w.panel),
            format!("Fig. 5{}: friction ratio ν = T/N, {}", w.panel, w.label),
            "ν = T/N (1)",
            vec![
                Line::new("μ_d", points(s, |_| p.mu_d), colors::GREEN).thin(),
                Line::new("μ_st", points(s, |_| p.mu_st), colors::RED).thin(),
                Line::new("ν", points(s, |x| x.forces.nu), colors::BLUE),
            ],
        )));
        charts.push(window(chart(
            &format!("fig06{}_slip_speed", w.panel),
            format!("Fig. 6{}: slip speed v_C, {}", w.panel, w.label),
            "v_C (m/s)",
            vec![Line::new(
                "v_C",
                through_located(&located, Watched::SlipSpeed, s, |x| x.slip.speed),
                colors::BLUE,
            )],
        )));
        // θ first, so that the force spikes are drawn over it.
        let mut lines = vec![
            Line::new("θ", theta_curve(s), colors::BLUE).right(),
            Line::new("N/mg", normal_curve(s), colors::RED),
        ];
        lines.extend(peak_marks(&located, w.span()));
        let mut fig8 = window(chart(
            &format!("fig08{}_normal_force", w.panel),
            format!("Fig. 8{}: N/mg and θ, {}", w.panel, w.label),
            "N/mg (1)",
            lines,
        ));
        fig8.y2_label = Some("θ (rad)".to_string());
        charts.push(fig8);
    }

    let whole_run = |mut c: Chart, empty: &str| {
        c.x_range = Some(t_start..t_end);
        c.empty_note = empty.to_string();
        c
    };
    let after_1s: Vec<Sample> = all
        .iter()
        .filter(|s| s.t >= t_start + 1.0)
        .copied()
        .collect();
    let from_one_second = |mut c: Chart, empty: &str| {
        c.x_range = Some(t_start + 1.0..t_end);
        c.empty_note = if after_1s.is_empty() {
            "the run ends before its first second is over".to_string()
        } else {
            empty.to_string()
        };
        c
    };

    // θ's envelopes: its located turning points (ripples aside), or per sampled cycle.
    let theta_envelopes = if located.is_empty() {
        let cycles = per_cycle(all, |x| x.state.theta);
        (
            cycles.iter().map(|c| (c.t_max, c.max)).collect(),
            cycles.iter().map(|c| (c.t_min, c.min)).collect(),
        )
    } else {
        let turns = |kind| {
            located
                .theta_turns(kind, t_start, t_end)
                .iter()
                .map(|e| (e.t, e.value))
                .collect::<Vec<_>>()
        };
        (turns(ExtremumKind::Max), turns(ExtremumKind::Min))
    };
    let (theta_max, theta_min) = theta_envelopes;
    charts.push(whole_run(
        chart(
            "fig02_theta_envelope",
            format!("Fig. 2: envelopes of θ per oscillation, {whole}"),
            "θ (rad)",
            vec![
                Line::new("max θ", theta_max, colors::RED),
                Line::new("min θ", theta_min, colors::BLUE),
            ],
        ),
        "θ completes no oscillation: no envelope to draw",
    ));

    let mut fig4 = from_one_second(
        chart(
            "fig04_theta_dot_over_psi_dot",
            format!("Fig. 4: |dθ/dt ÷ dψ/dt|, {after_one}"),
            "|dθ/dt ÷ dψ/dt| (1)",
            vec![Line::new(
                "|dθ/dt ÷ dψ/dt|",
                points(&after_1s, |x| (x.state.omega_y / x.state.psi_dot()).abs()),
                colors::BLUE,
            )],
        ),
        "dθ/dt is zero throughout (no nutation): nothing to show on a logarithmic axis",
    );
    fig4.log_y = true;
    charts.push(fig4);

    let slip_cycles = located_cycles(
        &located,
        Watched::SlipSpeed,
        ExtremumKind::Min,
        t_start,
        t_end,
    )
    .unwrap_or_else(|| per_cycle(all, |x| x.slip.speed));
    let mut fig7 = whole_run(
        chart(
            "fig07_slip_speed_envelope",
            format!("Fig. 7: largest slip speed per oscillation, {whole}"),
            "max v_C (m/s)",
            vec![Line::new(
                "max v_C per oscillation",
                slip_cycles
                    .iter()
                    .filter(|c| c.max > 0.0)
                    .map(|c| (c.t_max, c.max))
                    .collect(),
                colors::BLUE,
            )],
        ),
        if slip_cycles.is_empty() {
            "θ completes no oscillation: no per-oscillation maximum to draw"
        } else {
            "the disk does not slide in any full oscillation"
        },
    );
    fig7.log_y = true;
    charts.push(fig7);

    // The envelope at the located peaks, each at its own θ.
    let located_envelope = located_cycles(
        &located,
        Watched::NormalForce,
        ExtremumKind::Max,
        t_start + 1.0,
        t_end,
    )
    .map(|cycles| {
        cycles
            .iter()
            .filter_map(|c| {
                located
                    .of(Watched::NormalForce, ExtremumKind::Max, c.t_max, c.t_max)
                    .next()
                    .map(|e| (e.theta, e.value))
            })
            .collect::<Vec<_>>()
    });
    let normal_cycles = per_cycle(&after_1s, |x| x.forces.normal / mg);
    let theta_at = |t: f64| {
        let i = after_1s
            .partition_point(|s| s.t < t)
            .min(after_1s.len().saturating_sub(1));
        after_1s.get(i).map_or(f64::NAN, |s| s.state.theta)
    };
    let mut fig9 = from_one_second(
        chart(
            "fig09_normal_force_vs_theta",
            format!("Fig. 9: N/mg against θ and its envelope, {after_one}"),
            "N/mg (1)",
            vec![
                Line::new(
                    "N/mg against θ",
                    after_1s
                        .iter()
                        .map(|x| (x.state.theta, x.forces.normal / mg))
                        .chain(
                            located
                                .all_of(Watched::NormalForce, t_start + 1.0, t_end)
                                .map(|e| (e.theta, e.value)),
                        )
                        .collect(),
                    colors::BLUE,
                )
                .cloud(),
                Line::new(
                    "envelope: largest N/mg per oscillation",
                    located_envelope.unwrap_or_else(|| {
                        normal_cycles
                            .iter()
                            .map(|c| (theta_at(c.t_max), c.max))
                            .collect()
                    }),
                    colors::RED,
                )
                .dots(),
            ],
        ),
        "N/mg is nowhere positive: nothing to show on logarithmic axes",
    );
    // Its x axis is θ, not time.
    fig9.x_range = None;
    // θ spans three decades after the first second (0.5 down to ~1e-4 rad) and the peaks of N
    // all happen below 0.01 rad: on a linear axis they crowd into the first pixel column.
    fig9.log_y = true;
    fig9.log_x = true;
    fig9.x_label = "θ (rad)".to_string();
    charts.push(fig9);

    let [_, last] = windows(data);
    let located_period = last
        .span()
        .and_then(|span| located.theta_period(span.start, span.end));
    let period = located_period.or_else(|| {
        let t: Vec<f64> = last.samples.iter().map(|s| s.t).collect();
        let v: Vec<f64> = last.samples.iter().map(|s| s.state.omega_y).collect();
        let (t0, t1) = (
            t.first().copied().unwrap_or(0.0),
            t.last().copied().unwrap_or(0.0),
        );
        crate::analysis::oscillation::mean_period(Series { t: &t, v: &v }, t0, t1)
    });
    let (every, rate) = period.map_or(
        ("no full oscillation".to_string(), "N/mg".to_string()),
        |p| {
            let omega = format!("N/mg; 2π/T = {:.1} s⁻¹", 2.0 * std::f64::consts::PI / p);
            let paper = if compared_with_paper {
                format!(
                    " (paper {} s⁻¹, recorded sound {} s⁻¹)",
                    equations::paper::THETA_OMEGA_LAST,
                    equations::paper::RECORDED_OMEGA
                )
            } else {
                String::new()
            };
            (format!("peaks every {p:.4} s"), omega + &paper)
        },
    );
    let mut lines = vec![Line::new(rate, normal_curve(last.samples), colors::RED)];
    lines.extend(peak_marks(&located, last.span()));
    let mut fig10 = chart(
        "fig10_normal_force_last_second",
        format!("Fig. 10: N/mg in the last second, {every}"),
        "N/mg (1)",
        lines,
    );
    fig10.x_range = last.span();
    charts.push(fig10);
    charts
}

/// The figures of a run: the ones drawn, and the ones an interrupt left undrawn.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FiguresDrawn {
    /// Stems of the figures written (PNG and SVG), in the order they are numbered.
    pub drawn: Vec<String>,
    /// Stems of the figures not drawn because `stop` was set first, in order.
    pub not_drawn: Vec<String>,
}

/// Renders every figure into `dir` (PNG and SVG) on every core, until `stop` is set.
/// The figures are independent and each is written atomically, so they are drawn in
/// parallel, a few per thread, in the order they are numbered. Each thread looks at `stop`
/// before it starts a figure: an interrupt leaves the figures in progress to finish (a
/// fraction of a second each) and draws no more, so every file present is complete.
pub fn write_paper_figures(
    data: &RunData,
    p: &DiskParams,
    compared_with_paper: bool,
    dir: &Path,
    stop: &AtomicBool,
) -> Result<FiguresDrawn, WriteError> {
    let charts = paper_charts(data, p, compared_with_paper);
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let next = AtomicUsize::new(0);
    let done: Vec<AtomicBool> = charts.iter().map(|_| AtomicBool::new(false)).collect();
    let draw = || -> Result<(), WriteError> {
        while !stop.load(Ordering::SeqCst) {
            let i = next.fetch_add(1, Ordering::Relaxed);
            let Some(chart) = charts.get(i) else {
                return Ok(());
            };
            render(chart, dir)?;
            done[i].store(true, Ordering::SeqCst);
        }
        Ok(())
    };
    std::thread::scope(|scope| {
        let workers: Vec<_> = (1..threads.min(charts.len()))
            .map(|_| scope.spawn(draw))
            .collect();
        let mine = draw();
        workers
            .into_iter()
            .map(|w| w.join().expect("a figure thread panicked"))
            .chain(std::iter::once(mine))
            .collect::<Result<(), WriteError>>()
    })?;
    let mut figures = FiguresDrawn::default();
    for (chart, done) in charts.into_iter().zip(&done) {
        if done.load(Ordering::SeqCst) {
            figures.drawn.push(chart.stem);
        } else {
            figures.not_drawn.push(chart.stem);
        }
    }
    Ok(figures)
}
