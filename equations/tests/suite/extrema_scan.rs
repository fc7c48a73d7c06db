//! The extrema scan (`equations::hybrid::extrema`) against a brute-force scan of the same
//! steps: the paper's scene's first 10 s (sticks and slides, 170 decisions), every step kept
//! ([`Trailing`]) and N and the slip speed read at 64 points of each step placed in physical
//! time, as a sample is placed (the scan reads its points at fractions of the step in the run's
//! variable, `τ`: another path to the same state). Checked:
//!
//! * sound: each extremum the scan lists (not a one-sided value at a mode switch) is one of
//!   the brute-force curve: its value at least as high (a maximum) as the curve a little way
//!   to either side;
//! * complete where it promises to be: each turning point of the brute-force curve with no
//!   other within two of its step's lengths is listed, of the same kind, within the brute-force
//!   spacing and at least as extreme as the brute-force point. Steps within 1e-6 s of a mode
//!   decision are left out: the bridges there are not scanned, and the chatter before a stick
//!   is where pairs closer than the scan resolves crowd.

use equations::{
    simulate, DiskConfig, DiskObserver, DiskParams, Extremum, ExtremumKind, GeneratedModels,
    InitialState, Mode, SlipChart, Trailing, TransitionRecord, Watched,
};

/// Brute-force points per step.
const POINTS: usize = 64;

/// A turning point of a brute-force curve.
#[derive(Clone, Copy, Debug)]
struct Turn {
    quantity: Watched,
    kind: ExtremumKind,
    t: f64,
    value: f64,
    /// The step it lies in.
    step: (f64, f64),
}

#[derive(Default)]
struct Scan {
    listed: Vec<Extremum>,
    turns: Vec<Turn>,
    /// Listed extrema each with the values a little way to either side: (extremum, before,
    /// after).
    sides: Vec<(Extremum, f64, f64)>,
    steps: usize,
    decisions: Vec<f64>,
}

/// N or the slip speed (NaN while rolling) of a sample.
fn read(q: Watched, s: &equations::DiskSample) -> f64 {
    match q {
        Watched::NormalForce => s.force.normal,
        Watched::SlipSpeed if s.mode == Mode::Sliding => s.state.slip.speed,
        _ => f64::NAN,
    }
}

impl DiskObserver for Scan {
    fn wants_sample(&self, _t: f64) -> bool {
        false
    }
    fn wants_extrema(&self) -> bool {
        true
    }
    fn on_extremum(&mut self, e: &Extremum) {
        if e.quantity != Watched::Theta && !e.at_switch {
            self.listed.push(*e);
        }
    }
    fn on_transition(&mut self, record: &TransitionRecord) {
        self.decisions.push(record.t);
    }
    fn keeps_trailing(&self) -> Option<f64> {
        Some(f64::INFINITY)
    }
    fn on_trailing(&mut self, trailing: &Trailing<'_>) {
        let spans: Vec<(f64, f64)> = trailing.step_spans().collect();
        self.steps = spans.len();
        for &(t0, t1) in &spans {
            // Inside the step: at its ends the kept step before may answer, in its own mode.
            let samples: Vec<_> = (0..=POINTS)
                .map(|i| t0 + (t1 - t0) * (i as f64 + 0.5) / (POINTS + 1) as f64)
                .map(|t| trailing.sample(t).unwrap().unwrap())
                .collect();
            for q in [Watched::NormalForce, Watched::SlipSpeed] {
                let v: Vec<f64> = samples.iter().map(|s| read(q, s)).collect();
                for i in 1..POINTS {
                    let kind = if v[i] > v[i - 1] && v[i] > v[i + 1] {
                        ExtremumKind::Max
                    } else if v[i] < v[i - 1] && v[i] < v[i + 1] {
                        ExtremumKind::Min
                    } else {
                        continue;
                    };
                    self.turns.push(Turn {
                        quantity: q,
                        kind,
                        t: samples[i].t,
                        value: v[i],
                        step: (t0, t1),
                    });
                }
            }
        }
        // A thousandth of the step to either side of each listed extremum (Brent leaves it
        // within 1e-7 of its bracket of the true one), within the same step.
        for e in &self.listed {
            let Some(&(t0, t1)) = spans.iter().find(|s| s.0 <= e.t && e.t <= s.1) else {
                continue;
            };
            let d = 1e-3 * (t1 - t0);
            if e.t - d < t0 || e.t + d > t1 {
                continue;
            }
            let at = |t: f64| read(e.quantity, &trailing.sample(t).unwrap().unwrap());
            self.sides.push((*e, at(e.t - d), at(e.t + d)));
        }
    }
}

#[test]
fn the_scan_lists_the_brute_force_curves_turning_points() {
    let p = DiskParams::paper();
    let models = GeneratedModels::generated(p, SlipChart::Cartesian).unwrap();
    let config = DiskConfig {
        t_end: 10.0,
        sample_rate: None,
        ..DiskConfig::default()
    };
    let mut scan = Scan::default();
    let out = simulate(&models, &config, &InitialState::paper(&p), &mut scan).unwrap();
    assert_eq!(out.transitions, 170);
    assert!(scan.steps > 5000, "{} steps kept", scan.steps);

    // Sound: every listed extremum is a turning point of the curve (to round-off).
    let mut checked = 0;
    for (e, before, after) in &scan.sides {
        let slack = 1e-12 * e.value.abs();
        let ok = match e.kind {
            ExtremumKind::Max => e.value + slack >= before.max(*after),
            ExtremumKind::Min => e.value - slack <= before.min(*after),
        };
        assert!(ok, "{e:?}: {before} before, {after} after");
        checked += 1;
    }
    eprintln!(
        "listed {}, checked {checked}, turns {}",
        scan.listed.len(),
        scan.turns.len()
    );
    assert!(checked > 800, "{checked} listed extrema checked");

    // Complete: every isolated turning point is listed.
    let mut isolated = 0;
    for (i, turn) in scan.turns.iter().enumerate() {
        let reach = 2.0 * (turn.step.1 - turn.step.0);
        let crowded = scan.turns.iter().enumerate().any(|(j, other)| {
            j != i && other.quantity == turn.quantity && (other.t - turn.t).abs() < reach
        });
        let near_decision =
            (scan.decisions.iter()).any(|&t| t > turn.step.0 - 1e-6 && t < turn.step.1 + 1e-6);
        if crowded || near_decision {
            continue;
        }
        isolated += 1;
        let spacing = (turn.step.1 - turn.step.0) / (POINTS + 1) as f64;
        let found = scan.listed.iter().any(|e| {
            e.quantity == turn.quantity
                && e.kind == turn.kind
                && (e.t - turn.t).abs() <= spacing
                && match e.kind {
                    ExtremumKind::Max => e.value >= turn.value - 1e-12 * turn.value.abs(),
                    ExtremumKind::Min => e.value <= turn.value + 1e-12 * turn.value.abs(),
                }
        });
        assert!(found, "not listed: {turn:?}");
    }
    eprintln!("isolated {isolated}");
    assert!(isolated > 600, "{isolated} isolated turning points");
}
