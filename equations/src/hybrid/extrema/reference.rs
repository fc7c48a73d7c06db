//! The scan as it was before the ends' cubic screened the steps: every step interpolated and
//! evaluated at its hairs and interior points. Kept as the reference the screened scan is held
//! to: on the paper's scene both must locate the same extrema.
//!
//! One input is shared: N at a step's end comes from the integrator's rate there in both (the
//! reference scan evaluated the model; the two agree to round-off, checked here too). Where N
//! is flat to round-off across the end's hair, that last bit decides whether the old scan saw a
//! plateau as a minimum: on the paper's first 10 s it did once (t = 8.6e-8 s, N flat to 16
//! digits), a row the screened scan no longer lists.

use super::*;
use std::cell::Cell;

thread_local! {
    /// Whether scanners made on this thread scan every step inside (the reference).
    pub(super) static FULL_SCAN: Cell<bool> = const { Cell::new(false) };
    /// The largest relative difference, over the steps the reference scanned, between N at a
    /// step's end from the integrator's rate and from a model evaluation there.
    static END_MISMATCH: Cell<f64> = const { Cell::new(0.0) };
}

impl Scanner {
    /// The reference scan of one step: N at the ends, the hairs and the interior points, all
    /// from the interpolant and a model evaluation each.
    pub(super) fn full_step<R: Model<DIM>, S: Model<DIM>>(
        &mut self,
        models: &DiskModels<R, S>,
        phase: Phase,
        step: &StepView<'_, Const<DIM>, Phase>,
        out: &mut impl FnMut(Extremum),
    ) {
        let Some(dense) = step.dense else { return };
        let (t0, t1) = (step.t0, step.t1);
        if phase == Phase::Bridge || t1.partial_cmp(&t0) != Some(std::cmp::Ordering::Greater) {
            return;
        }
        let mode = phase.mode();
        let h = t1 - t0;
        let mut ts = [0.0; INTERIOR + 4];
        ts[0] = t0;
        ts[1] = t0 + EDGE * h;
        for (k, t) in ts[2..INTERIOR + 2].iter_mut().enumerate() {
            *t = t0 + h * (k + 1) as f64 / (INTERIOR + 1) as f64;
        }
        ts[INTERIOR + 2] = t1 - EDGE * h;
        ts[INTERIOR + 3] = t1;
        let eval = |t: f64| {
            let mut y = [0.0; DIM];
            dense.at(t, &mut y);
            (watched_at(models, phase, t, &y), y[OMEGA_Y])
        };
        let mut n = [0.0; INTERIOR + 4];
        let mut slip = [0.0; INTERIOR + 4];
        let mut w = [0.0; INTERIOR + 4];
        let continued = self.last.filter(|e| e.t == t0 && self.mode == Some(mode));
        for (i, &t) in ts.iter().enumerate() {
            let ((ni, si), wi) = match (i, continued) {
                (0, Some(e)) => ((e.n.0, e.slip.0), step.y0[OMEGA_Y]),
                (0, None) => (watched_at(models, phase, t, step.y0), step.y0[OMEGA_Y]),
                _ if i == INTERIOR + 3 => {
                    let from_rate =
                        watched_from(models, phase, step.y1, &end_rate(models, phase, step));
                    let evaluated = watched_at(models, phase, t, step.y1);
                    let off = (from_rate.0 - evaluated.0).abs() / evaluated.0.abs();
                    END_MISMATCH.with(|m| m.set(m.get().max(off)));
                    (from_rate, step.y1[OMEGA_Y])
                }
                _ => eval(t),
            };
            n[i] = ni;
            slip[i] = si;
            w[i] = wi;
        }
        self.scan(
            models,
            (phase, step, dense),
            &ts,
            (&n, &slip, &w),
            continued,
            out,
        );
        let last = INTERIOR + 3;
        self.last = Some(StepEnd {
            t: t1,
            theta: step.y1[THETA],
            n: (n[last], n[last - 1]),
            slip: (slip[last], slip[last - 1]),
        });
        self.mode = Some(mode);
    }
}

/// The paper's scene for `t_end` seconds at the default settings, its extrema located by the
/// screened scan or (`full`) the reference.
fn located(t_end: f64, full: bool) -> Vec<Extremum> {
    use crate::{
        simulate, DiskConfig, DiskObserver, DiskParams, GeneratedModels, InitialState, SlipChart,
    };

    #[derive(Default)]
    struct Seen(Vec<Extremum>);
    impl DiskObserver for Seen {
        fn wants_sample(&self, _t: f64) -> bool {
            false
        }
        fn wants_extrema(&self) -> bool {
            true
        }
        fn on_extremum(&mut self, e: &Extremum) {
            self.0.push(*e);
        }
    }
    let p = DiskParams::paper();
    let models = GeneratedModels::generated(p, SlipChart::Cartesian).unwrap();
    let config = DiskConfig {
        t_end,
        sample_rate: None,
        ..DiskConfig::default()
    };
    let mut seen = Seen::default();
    FULL_SCAN.with(|f| f.set(full));
    let outcome = simulate(&models, &config, &InitialState::paper(&p), &mut seen);
    FULL_SCAN.with(|f| f.set(false));
    outcome.unwrap();
    seen.0
}

/// The extrema of `a` that `b` does not list (same quantity, kind, mode and switch flag; time
/// and value to 1e-9, relative above 1: what `extrema.csv` holds).
fn unmatched<'a>(a: &'a [Extremum], b: &[Extremum]) -> Vec<&'a Extremum> {
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-9 * x.abs().max(1.0);
    let same = |x: &Extremum, y: &Extremum| {
        (x.quantity, x.kind, x.mode, x.at_switch) == (y.quantity, y.kind, y.mode, y.at_switch)
            && close(x.t, y.t)
            && close(x.value, y.value)
    };
    a.iter().filter(|x| !b.iter().any(|y| same(x, y))).collect()
}

#[test]
fn the_screened_scan_locates_what_the_full_scan_does() {
    let screened = located(10.0, false);
    let full = located(10.0, true);
    let missed = unmatched(&full, &screened);
    let added = unmatched(&screened, &full);
    let show = |list: &[&Extremum]| {
        let rows: Vec<String> = list
            .iter()
            .take(40)
            .map(|e| {
                format!(
                    "{:.15} {:?} {:?} {:.12e} {:?}{}",
                    e.t,
                    e.quantity,
                    e.kind,
                    e.value,
                    e.mode,
                    if e.at_switch { " (switch)" } else { "" }
                )
            })
            .collect();
        rows.join("\n")
    };
    assert!(
        missed.is_empty() && added.is_empty(),
        "of {} extrema, the screened scan misses {}:\n{}\nand adds {}:\n{}",
        full.len(),
        missed.len(),
        show(&missed),
        added.len(),
        show(&added),
    );
    assert_eq!(screened.len(), full.len());
    assert!(full.len() > 1000, "{} extrema", full.len());
    let off = END_MISMATCH.with(|m| m.get());
    assert!(
        off <= 1e-13,
        "N at a step's end: rate and evaluation differ by {off:e}"
    );
}
