//! The numbers of a run that the paper also gives, side by side.
//!
//! The heights, periods and amplitudes come from the extrema the run located on the
//! integrator's dense output ([`super::extrema`]), so they do not depend on the sampling rate;
//! a run without located extrema (a synthetic run in the tests) falls back to its samples.
//! docs/summary-keys.md defines every key, its unit, its source and its accuracy.

use std::collections::BTreeMap;
use std::f64::consts::PI;

use equations::{paper, DiskParams};
use serde::Serialize;

use super::extrema::Located;
use super::oscillation::{mean_period, Series};
use crate::record::{RunData, SampleCounts, Timings};
use equations::record::Quantity;
use equations::record::{Sample, StopKind, TriggerKind};
use equations::Mode;
use equations::{ExtremumKind, Watched};

/// Time after which the paper reports the settled amplitudes (s).
pub const SETTLED_AFTER: f64 = paper::SETTLED_AFTER_S;

/// The shortest rolling phase counted as long (s).
pub const LONG_PHASE_S: f64 = 1e-3;

/// The summary of a run (`summary.json`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    /// The scene's name.
    pub scene: String,
    /// The models that ran, e.g. `pruned (8 states)`.
    pub model: String,
    /// Why those models.
    pub model_reason: String,
    /// Mode at the start (after the initial decision).
    pub start_mode: Option<Mode>,
    /// Why the run ended, as a word (`end_time`, `contact_lost`, `error`, ...); `null` for
    /// data without a stop.
    pub stop_reason: Option<StopKind>,
    /// Why the run ended, in full: the error, the event and its numbers (empty at the end
    /// time).
    pub stop_detail: String,
    /// Time the run ended (s).
    pub t_end: f64,
    /// Mode decisions during the run (the initial one not counted).
    pub transitions: usize,
    /// Accepted integrator steps, also of a run that failed (`null` when the simulation
    /// reported none, see `not_computed`).
    pub steps: Option<u64>,
    /// Right-hand-side evaluations (`null` as for `steps`).
    pub rhs_evals: Option<u64>,
    /// A failed run's last accepted state: time, mode, the states by name, slip, forces and
    /// energy (the library's record). Written only for a failed run that took a step.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub last_state: Option<Sample>,
    /// Wall-clock time (s).
    pub wall_s: f64,
    /// Period of θ in the first simulated second (s).
    pub theta_period_first_s: Option<f64>,
    /// Period of θ in the last simulated second (s).
    pub theta_period_last_s: Option<f64>,
    /// 2π / first period (1/s).
    pub theta_omega_first: Option<f64>,
    /// 2π / last period (1/s).
    pub theta_omega_last: Option<f64>,
    /// Largest θ after 50 s (rad).
    pub theta_max_after_50s: Option<f64>,
    /// Largest slip speed after 50 s (m/s).
    pub slip_speed_max_after_50s: Option<f64>,
    /// Mean ν while sliding (equals μ_d).
    pub nu_sliding: Option<f64>,
    /// Largest ν.
    pub nu_max: Option<f64>,
    /// Rolling phases per second in the last simulated second: every phase that is rolling
    /// at some time of that second (a disk that rolls throughout has one).
    pub rolling_phases_per_s_last: Option<f64>,
    /// As `rolling_phases_per_s_last`, counting only phases that last at least
    /// 1 ms (`LONG_PHASE_S`; the paper's "about 24 per second").
    pub rolling_phases_long_per_s_last: Option<f64>,
    /// Fraction of the last simulated second spent rolling.
    pub rolling_fraction_last: Option<f64>,
    /// Smallest N/(m g).
    pub n_over_mg_min: Option<f64>,
    /// Largest N/(m g).
    pub n_over_mg_max: Option<f64>,
    /// Largest N/(m g) in the last simulated second.
    pub n_over_mg_max_last_s: Option<f64>,
    /// Largest relative energy change within one rolling phase (energy is conserved in rolling
    /// without air drag, so this measures the integration error).
    pub energy_drift_rel: Option<f64>,
    /// Largest constraint drift before projection (SI units).
    pub constraint_drift_max: Option<f64>,
    /// Keys written as `null` because the models that ran do not compute them or the run was
    /// abandoned before they were reported, with the reason.
    pub not_computed: BTreeMap<&'static str, String>,
    /// How many samples were kept, and where.
    pub samples: SampleCounts,
    /// Where the wall time went: simulation (with the trajectory streamed meanwhile),
    /// outputs, analysis, figures.
    pub timings: Timings,
    /// Whether the scene is the paper's (its disk, friction, air and start), so that the
    /// printed comparison shows the paper's values beside ours. Set by the caller, who knows
    /// the scene; `false` from [`Summary::of`].
    pub compared_with_paper: bool,
    /// Stems of the paper's figures an interrupt left undrawn (empty when every figure asked
    /// for was drawn, or none was asked for). Set by the caller, who draws them.
    pub figures_not_drawn: Vec<String>,
}

/// One line of the printed comparison.
#[derive(Clone, Debug, PartialEq)]
pub struct ComparisonRow {
    /// The summary key.
    pub key: &'static str,
    /// Our value, formatted.
    pub ours: String,
    /// The paper's value, if it gives one.
    pub paper: Option<&'static str>,
}

fn fold<I: Iterator<Item = f64>>(it: I, f: fn(f64, f64) -> f64) -> Option<f64> {
    it.filter(|v| v.is_finite()).reduce(f)
}

/// The θ period in `[t0, t1]`, from the fine window if it covers the interval, else from the
/// regular samples.
fn theta_period(fine: &[Sample], coarse: &[Sample], t0: f64, t1: f64) -> Option<f64> {
    let period_of = |s: &[Sample]| {
        let t: Vec<f64> = s.iter().map(|s| s.t).collect();
        let v: Vec<f64> = s.iter().map(|s| s.state.omega_y).collect();
        mean_period(Series { t: &t, v: &v }, t0, t1)
    };
    period_of(fine).or_else(|| period_of(coarse))
}

impl Summary {
    /// Summarises `data` of scene `scene` for a disk with parameters `p`.
    pub fn of(scene: &str, data: &RunData, p: &DiskParams) -> Summary {
        let s = &data.samples;
        let t_start = s.first().map_or(0.0, |x| x.t);
        let t_stop = data
            .stop
            .as_ref()
            .map(|x| x.t)
            .or_else(|| s.last().map(|x| x.t))
            .unwrap_or(0.0);
        let mg = p.weight();
        let all = || s.iter().chain(&data.first_second).chain(&data.last_second);
        let located = Located::new(&data.extrema, mg);
        let exact = !located.is_empty();
        let period = |t0: f64, t1: f64, fine: &[Sample]| {
            if exact {
                located.theta_period(t0, t1)
            } else {
                theta_period(fine, s, t0, t1)
            }
        };
        let first = period(t_start, t_start + 1.0, &data.first_second);
        let last = if t_stop - 1.0 >= t_start {
            period(t_stop - 1.0, t_stop, &data.last_second)
        } else {
            None
        };
        let largest = |q: Watched, t0: f64, sampled: Option<f64>| {
            if exact {
                located.extreme(q, ExtremumKind::Max, t0, t_stop)
            } else {
                sampled
            }
        };
        let settled = || s.iter().filter(|x| x.t >= SETTLED_AFTER);
        let has_settled = t_stop >= SETTLED_AFTER;
        let sliding: Vec<f64> = s
            .iter()
            .filter(|x| x.mode == Mode::Sliding)
            .map(|x| x.forces.nu)
            .filter(|v| v.is_finite())
            .collect();
        let last_window = t_stop - 1.0;
        let has_last = t_stop - t_start >= 1.0;
        let phases = if has_last {
            rolling_phases(data, t_start, t_stop, last_window)
        } else {
            Vec::new()
        };
        let count =
            |min: f64| has_last.then(|| phases.iter().filter(|(a, b)| b - a >= min).count() as f64);
        let rolling_fraction = has_last.then(|| {
            phases
                .iter()
                .map(|(a, b)| b.min(t_stop) - a.max(last_window))
                .sum::<f64>()
                / (t_stop - last_window)
        });
        let mut not_computed = BTreeMap::new();
        // Keys that need a state the models may leave frozen: (key, the quantity it is of).
        for (key, q) in [
            ("energy_drift_rel", Quantity::Energy),
            ("constraint_drift_max", Quantity::ResidualZ),
        ] {
            if let Some(reason) = data.model.missing(q) {
                not_computed.insert(key, reason);
            }
        }
        // A simulation that reported no counters (its thread died): say so rather than write
        // zeros. A failed run reports the work it did until it failed.
        let abandoned = |what: &str| {
            let how = data.stop.as_ref().map_or("unknown", |s| s.kind.name());
            format!("the simulation was abandoned at its stop ({how}) before it reported {what}")
        };
        if data.work.steps.is_none() {
            not_computed.insert("steps", abandoned("its step count"));
        }
        if data.work.rhs_evals.is_none() {
            not_computed.insert("rhs_evals", abandoned("its evaluation count"));
        }
        if data.constraint_drift_max.is_none() && !not_computed.contains_key("constraint_drift_max")
        {
            not_computed.insert("constraint_drift_max", abandoned("the drift"));
        }
        let computes = |key| !not_computed.contains_key(key);
        Summary {
            scene: scene.to_string(),
            model: data.model.model.label(),
            model_reason: data.model.reason.clone(),
            start_mode: start_mode(data),
            stop_reason: data.stop.as_ref().map(|x| x.kind),
            last_state: data.last_state,
            stop_detail: data
                .stop
                .as_ref()
                .map_or(String::new(), |x| x.detail.clone()),
            t_end: t_stop,
            transitions: data
                .events
                .iter()
                .filter(|e| e.trigger.kind() != TriggerKind::InitialFriction)
                .count(),
            steps: data.work.steps,
            rhs_evals: data.work.rhs_evals,
            wall_s: data.work.wall_s,
            theta_period_first_s: first,
            theta_period_last_s: last,
            theta_omega_first: first.map(|p| 2.0 * PI / p),
            theta_omega_last: last.map(|p| 2.0 * PI / p),
            theta_max_after_50s: has_settled
                .then(|| {
                    let sampled = fold(settled().map(|x| x.state.theta), f64::max);
                    largest(Watched::Theta, SETTLED_AFTER, sampled)
                })
                .flatten(),
            slip_speed_max_after_50s: has_settled
                .then(|| {
                    let sampled = fold(settled().map(|x| x.slip.speed), f64::max);
                    largest(Watched::SlipSpeed, SETTLED_AFTER, sampled)
                })
                .flatten(),
            nu_sliding: (!sliding.is_empty())
                .then(|| sliding.iter().sum::<f64>() / sliding.len() as f64),
            nu_max: fold(all().map(|x| x.forces.nu), f64::max),
            rolling_phases_per_s_last: count(0.0),
            rolling_phases_long_per_s_last: count(LONG_PHASE_S),
            rolling_fraction_last: rolling_fraction,
            n_over_mg_min: if exact {
                located.extreme(Watched::NormalForce, ExtremumKind::Min, t_start, t_stop)
            } else {
                fold(all().map(|x| x.forces.normal / mg), f64::min)
            },
            n_over_mg_max: largest(
                Watched::NormalForce,
                t_start,
                fold(all().map(|x| x.forces.normal / mg), f64::max),
            ),
            n_over_mg_max_last_s: largest(
                Watched::NormalForce,
                last_window,
                fold(
                    data.last_second
                        .iter()
                        .chain(s.iter())
                        .filter(|x| x.t >= last_window)
                        .map(|x| x.forces.normal / mg),
                    f64::max,
                ),
            ),
            energy_drift_rel: rolling_energy_drift(s).filter(|_| computes("energy_drift_rel")),
            constraint_drift_max: data
                .constraint_drift_max
                .filter(|_| computes("constraint_drift_max")),
            not_computed,
            samples: SampleCounts {
                trajectory: s.len(),
                first_second: data.first_second.len(),
                last_second: data.last_second.len(),
            },
            timings: Timings::default(),
            compared_with_paper: false,
            figures_not_drawn: Vec::new(),
        }
    }

    /// Our values beside the paper's (Saje & Zupan, section 4), in summary order. The paper's
    /// values are given only when [`Summary::compared_with_paper`]: another scene is not the
    /// paper's run.
    pub fn comparison(&self) -> Vec<ComparisonRow> {
        let num = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4e}"));
        let paper_scene = self.compared_with_paper;
        let with_paper = |key, ours: String, paper: Option<&'static str>| ComparisonRow {
            key,
            ours,
            paper: paper.filter(|_| paper_scene),
        };
        let row = |key, ours: String| with_paper(key, ours, paper::reported(key));
        let unless_missing = |key: &'static str, ours: String| match self.not_computed.get(key) {
            Some(reason) => with_paper(key, format!("null ({reason})"), None),
            None => row(key, ours),
        };
        let maybe = |key: &'static str, v: Option<f64>| unless_missing(key, num(v));
        let count = |key: &'static str, v: Option<u64>| {
            unless_missing(key, v.map_or("-".to_string(), |v| v.to_string()))
        };
        vec![
            row("model", self.model.clone()),
            row(
                "start_mode",
                self.start_mode.map_or("-".into(), |m| m.to_string()),
            ),
            row(
                "stop_reason",
                self.stop_reason.map_or("-".into(), |k| k.to_string()),
            ),
            row("t_end", format!("{}", self.t_end)),
            row("transitions", self.transitions.to_string()),
            count("steps", self.steps),
            count("rhs_evals", self.rhs_evals),
            row("wall_s", format!("{:.3}", self.wall_s)),
            row("theta_period_first_s", num(self.theta_period_first_s)),
            row("theta_period_last_s", num(self.theta_period_last_s)),
            row("theta_omega_first", num(self.theta_omega_first)),
            row("theta_omega_last", num(self.theta_omega_last)),
            row("theta_max_after_50s", num(self.theta_max_after_50s)),
            row(
                "slip_speed_max_after_50s",
                num(self.slip_speed_max_after_50s),
            ),
            row("nu_sliding", num(self.nu_sliding)),
            row("nu_max", num(self.nu_max)),
            row(
                "rolling_phases_per_s_last",
                num(self.rolling_phases_per_s_last),
            ),
            row(
                "rolling_phases_long_per_s_last",
                num(self.rolling_phases_long_per_s_last),
            ),
            row("rolling_fraction_last", num(self.rolling_fraction_last)),
            row("n_over_mg_min", num(self.n_over_mg_min)),
            row("n_over_mg_max", num(self.n_over_mg_max)),
            row("n_over_mg_max_last_s", num(self.n_over_mg_max_last_s)),
            maybe("energy_drift_rel", self.energy_drift_rel),
            maybe("constraint_drift_max", self.constraint_drift_max),
        ]
    }

    /// The comparison as an aligned text table; the paper's column only for the paper's scene.
    pub fn table(&self) -> String {
        let rows = self.comparison();
        let w = rows.iter().map(|r| r.key.len()).max().unwrap_or(0);
        let wo = rows.iter().map(|r| r.ours.len()).max().unwrap_or(0).max(4);
        let line = |key: &str, ours: &str, paper: Option<&str>| match paper {
            Some(paper) if self.compared_with_paper => format!("{key:<w$}  {ours:>wo$}  {paper}\n"),
            _ => format!("{key:<w$}  {ours:>wo$}\n"),
        };
        let mut out = line("quantity", "ours", Some("paper"));
        for r in &rows {
            out.push_str(&line(r.key, &r.ours, Some(r.paper.unwrap_or(""))));
        }
        out
    }
}

fn start_mode(data: &RunData) -> Option<Mode> {
    let t0 = data.samples.first().map(|s| s.t);
    match data.events.first() {
        Some(e) if e.trigger.kind() == TriggerKind::InitialFriction => Some(e.to),
        Some(e) if Some(e.t) == t0 => Some(e.to),
        _ => data.samples.first().map(|s| s.mode),
    }
}

/// The rolling phases, `(start, end)`, of a run over `[t_start, t_stop]` that are rolling at
/// some time after `from`: from the start mode and the mode decisions (a sliding restart is
/// no boundary). A phase keeps its whole extent, also where it began before `from`.
fn rolling_phases(data: &RunData, t_start: f64, t_stop: f64, from: f64) -> Vec<(f64, f64)> {
    let mut phases = Vec::new();
    let mut rolling_since = (start_mode(data) == Some(Mode::Rolling)).then_some(t_start);
    for e in &data.events {
        match (rolling_since, e.to) {
            (None, Mode::Rolling) => rolling_since = Some(e.t),
            (Some(a), Mode::Sliding) => {
                phases.push((a, e.t));
                rolling_since = None;
            }
            _ => {}
        }
    }
    if let Some(a) = rolling_since {
        phases.push((a, t_stop));
    }
    phases.retain(|&(_, b)| b > from);
    phases
}

/// Largest `|E − E_phase_start| / |E_phase_start|` over the rolling phases of `samples`.
pub fn rolling_energy_drift(samples: &[Sample]) -> Option<f64> {
    let mut worst: Option<f64> = None;
    let mut phase_start: Option<f64> = None;
    for s in samples {
        if s.mode != Mode::Rolling {
            phase_start = None;
            continue;
        }
        let e0 = *phase_start.get_or_insert(s.energy);
        if e0 != 0.0 && e0.is_finite() && s.energy.is_finite() {
            let rel = ((s.energy - e0) / e0).abs();
            worst = Some(worst.map_or(rel, |w: f64| w.max(rel)));
        }
    }
    worst
}
