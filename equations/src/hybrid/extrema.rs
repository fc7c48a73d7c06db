//! Extrema located on each step's dense output, independent of any sampling.
//!
//! An observer that asks for them ([`super::DiskObserver::wants_extrema`]) is told of every
//! maximum and minimum, within a rolling or sliding segment, of
//!
//! * θ: the zeros of θ̇ = Ω_y (a state), found by the root finder on the step's interpolant,
//!   so as exact as the dense output;
//! * the normal force N: an output of the models that depends on the accelerations. Each step
//!   is scanned at its ends, a hair ([`EDGE`] of the step) inside either end and, where needed,
//!   [`INTERIOR`] interior points; a point of that sequence above (below) both neighbours
//!   brackets a maximum (minimum), which Brent's method refines to [`X_TOL`] of the bracket.
//!   The two points beside each end give the slope there, so an extremum within a hair of a
//!   step boundary is still seen (as the boundary, the value then off by the curvature times a
//!   hair squared). At a mode switch N jumps: the value at either side of the switch that lies
//!   above (below) its neighbour within the segment is reported as a maximum (minimum) too;
//! * the slip speed, while sliding, as N (only interior extrema: it is continuous).
//!
//! What a step costs is what the scan reads beyond the integration. The end's rate is the
//! integrator's own (the last stage of a step is the derivative at its end), so N there costs
//! no model evaluation; the hairs are read on the interpolant (one evaluation each). The values
//! and slopes at the two ends fit a cubic (Hermite's); where both end slopes are within
//! [`MARGIN`] of the chord's and the cubic's slope nowhere falls below that fraction of it, the
//! step is resolved as a monotone stretch and the interior points are skipped (see [`turns`]).
//! Only the other steps, about a third on the paper's scene, are read inside.
//!
//! A pair of extrema of N or v_C less than two thirds of a step apart can be missed (farther
//! apart, never, where the interior points are read: see [`bracketed`]); so can a pair so
//! shallow that the cubic of the ends does not show it, a dip smaller than the cubic's error.
//! θ's extrema are the zeros of Ω_y found by sign changes on the same points, so a pair of
//! them inside one gap between scan points is missed (Ω_y has the same sign at the gap's
//! ends); a pair with a point between them is found.
//!
//! Bridges (about 1e-9 s at zero slip) are not scanned. The cost is two interpolations and two
//! model evaluations per step (one more at a segment's start), two more of each in the steps
//! that may turn, and about twenty per extremum; a run that does not ask pays nothing.

mod brent;
#[cfg(test)]
mod reference;

pub use brent::brent;

use super::models::DiskModels;
use super::system::Phase;
use crate::modes::layout::{OMEGA_Y, THETA};
use crate::modes::{ContactForce, Mode, PhysicalState, DIM};
use model_runtime::Const;
use model_runtime::{find_crossing, Interpolant, Model, StepView};

/// Interior points per step at which N and the slip speed are evaluated (where the ends'
/// cubic does not rule out a turn).
pub const INTERIOR: usize = 2;
/// Where the end slopes are read: this fraction of the step inside each end.
pub const EDGE: f64 = 1e-4;
/// Brent's refinement stops when the bracket is this fraction of its starting width.
pub const X_TOL: f64 = 1e-7;
/// The interior points of a step are skipped only where both end slopes are within this
/// fraction of the chord's slope of it, and the cubic through the ends' values and slopes keeps
/// its slope, everywhere in the step, at least this fraction of the chord's.
pub const MARGIN: f64 = 0.5;

/// A quantity whose extrema are located.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Watched {
    /// The inclination θ (rad).
    Theta,
    /// The normal force N (N).
    NormalForce,
    /// The slip speed v_C (m/s), while sliding.
    SlipSpeed,
}

/// Maximum or minimum.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ExtremumKind {
    /// A local maximum.
    Max,
    /// A local minimum.
    Min,
}

impl ExtremumKind {
    /// `max` or `min`.
    pub fn name(self) -> &'static str {
        match self {
            ExtremumKind::Max => "max",
            ExtremumKind::Min => "min",
        }
    }
}

/// One located extremum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extremum {
    /// Time (s).
    pub t: f64,
    /// Of what.
    pub quantity: Watched,
    /// Maximum or minimum.
    pub kind: ExtremumKind,
    /// The value there (SI units).
    pub value: f64,
    /// θ at that instant (rad).
    pub theta: f64,
    /// The mode in force.
    pub mode: Mode,
    /// Whether it is the one-sided value at a mode switch (N only), not a smooth extremum.
    pub at_switch: bool,
}

/// What the scan of the previous step left for the next one (same segment only).
#[derive(Clone, Copy, Debug)]
struct StepEnd {
    t: f64,
    theta: f64,
    /// N at the end and a hair before it.
    n: (f64, f64),
    /// The slip speed likewise (NaN while rolling).
    slip: (f64, f64),
}

/// Scans each step of a run for extrema (see the module docs).
#[derive(Debug)]
pub(crate) struct Scanner {
    last: Option<StepEnd>,
    mode: Option<Mode>,
    /// Scan every step inside, as before the ends' cubic screened them (the tests' reference).
    #[cfg(test)]
    full: bool,
}

impl Default for Scanner {
    fn default() -> Self {
        Scanner {
            last: None,
            mode: None,
            #[cfg(test)]
            full: reference::FULL_SCAN.with(|f| f.get()),
        }
    }
}

/// The watched values at one scan point: N, the slip speed (NaN while rolling), Ω_y.
#[derive(Clone, Copy, Debug)]
struct Point {
    n: f64,
    slip: f64,
    omega_y: f64,
}

/// The normal force and the slip speed at `y` in `phase` (NaN where the model fails).
fn watched_at<R: Model<DIM>, S: Model<DIM>>(
    models: &DiskModels<R, S>,
    phase: Phase,
    t: f64,
    y: &[f64; DIM],
) -> (f64, f64) {
    let mut dy = [0.0; DIM];
    let evaluated = match phase {
        Phase::Rolling => models.rolling.rhs(t, y, &mut dy),
        _ => models.sliding.rhs(t, y, &mut dy),
    };
    if evaluated.is_err() {
        dy = [f64::NAN; DIM];
    }
    watched_from(models, phase, y, &dy)
}

/// The normal force and the slip speed at `y` in `phase`, whose rate there is `dy` (no model
/// evaluation; N is NaN where `dy` is).
fn watched_from<R: Model<DIM>, S: Model<DIM>>(
    models: &DiskModels<R, S>,
    phase: Phase,
    y: &[f64; DIM],
    dy: &[f64; DIM],
) -> (f64, f64) {
    let p = &models.params;
    match phase {
        Phase::Rolling => {
            let f = ContactForce::rolling(p, &PhysicalState::from_rolling(y, 0.0), dy);
            (f.normal, f64::NAN)
        }
        _ => {
            let state = models.sliding_state(y);
            (
                ContactForce::sliding(p, &state, dy).normal,
                state.slip.speed,
            )
        }
    }
}

/// The scan point at `y` with rate `dy` (no model evaluation).
fn point_from<R: Model<DIM>, S: Model<DIM>>(
    models: &DiskModels<R, S>,
    phase: Phase,
    y: &[f64; DIM],
    dy: &[f64; DIM],
) -> Point {
    let (n, slip) = watched_from(models, phase, y, dy);
    Point {
        n,
        slip,
        omega_y: y[OMEGA_Y],
    }
}

/// The scan point at `t` on the step's interpolant: one interpolation, one model evaluation.
fn interpolated<R: Model<DIM>, S: Model<DIM>>(
    models: &DiskModels<R, S>,
    phase: Phase,
    dense: &dyn Interpolant<Const<DIM>>,
    t: f64,
) -> Point {
    let mut y = [0.0; DIM];
    dense.at(t, &mut y);
    let (n, slip) = watched_at(models, phase, t, &y);
    Point {
        n,
        slip,
        omega_y: y[OMEGA_Y],
    }
}

/// The rate at the end of `step` in `phase`: the integrator's, or a model evaluation where an
/// event cut the step (NaN where the model fails).
fn end_rate<R: Model<DIM>, S: Model<DIM>>(
    models: &DiskModels<R, S>,
    phase: Phase,
    step: &StepView<'_, Const<DIM>, Phase>,
) -> [f64; DIM] {
    if let Some(f1) = step.f1 {
        return *f1;
    }
    let mut dy = [0.0; DIM];
    let evaluated = match phase {
        Phase::Rolling => models.rolling.rhs(step.t1, step.y1, &mut dy),
        _ => models.sliding.rhs(step.t1, step.y1, &mut dy),
    };
    match evaluated {
        Ok(()) => dy,
        Err(_) => [f64::NAN; DIM],
    }
}

/// Whether a quantity whose values at a step's ends and a hair inside them are `v`
/// (`[start, hair, hair, end]`) may turn inside the step: unless the step is a resolved
/// monotone stretch, both hair slopes within [`MARGIN`] of the chord's slope and the cubic
/// through the end values with those slopes monotone, its slope everywhere at least
/// [`MARGIN`] of the chord's. Where the end slopes differ from the chord's by more, the step
/// is curved enough that a turn the cubic does not show is possible (the paper's scene has
/// one, a ripple of 1e-3 N within 3e-9 s near a stick). NaN (a model that failed, the slip
/// while rolling) rules nothing out.
///
/// In the step's unit `s ∈ [0, 1]` the cubic's slope is the quadratic with `q(0) = a`,
/// `q(1) = b` and mean `Δ = v₃ − v₀`; its smallest value on `[0, 1]` is at an end or at its
/// vertex.
fn turns(v: [f64; 4]) -> bool {
    let a = (v[1] - v[0]) / EDGE;
    let b = (v[3] - v[2]) / EDGE;
    let chord = v[3] - v[0];
    if !(a.is_finite() && b.is_finite() && chord.is_finite()) || chord == 0.0 {
        return true;
    }
    let sign = chord.signum();
    // q(s) = a + c1 s + c2 s², taken in the chord's direction.
    let (a, b) = (sign * a, sign * b);
    let delta = chord.abs();
    let c1 = -4.0 * a - 2.0 * b + 6.0 * delta;
    let c2 = 3.0 * a + 3.0 * b - 6.0 * delta;
    let mut lowest = a.min(b);
    if c2 > 0.0 {
        let vertex = -c1 / (2.0 * c2);
        if vertex > 0.0 && vertex < 1.0 {
            lowest = lowest.min(a + vertex * (c1 + vertex * c2));
        }
    }
    let near_chord = |slope: f64| (slope - delta).abs() <= MARGIN * delta;
    !(near_chord(a) && near_chord(b)) || lowest < MARGIN * delta
}

impl Scanner {
    /// Ends the current segment (a transition or the end of the run): the one-sided extremum
    /// of N at its end, if the value there is one.
    pub(crate) fn end_segment(&mut self, out: &mut impl FnMut(Extremum)) {
        if let (Some(end), Some(mode)) = (self.last.take(), self.mode.take()) {
            let (n, before) = end.n;
            if let Some(kind) = one_sided(n, before) {
                out(Extremum {
                    at_switch: true,
                    ..found(Watched::NormalForce, kind, (end.t, n, end.theta), mode)
                });
            }
        }
    }

    /// Scans one accepted step of `phase` over its dense output.
    pub(crate) fn step<R: Model<DIM>, S: Model<DIM>>(
        &mut self,
        models: &DiskModels<R, S>,
        phase: Phase,
        step: &StepView<'_, Const<DIM>, Phase>,
        out: &mut impl FnMut(Extremum),
    ) {
        #[cfg(test)]
        if self.full {
            return self.full_step(models, phase, step, out);
        }
        let Some(dense) = step.dense else { return };
        let (t0, t1) = (step.t0, step.t1);
        if phase == Phase::Bridge || t1.partial_cmp(&t0) != Some(std::cmp::Ordering::Greater) {
            return;
        }
        let mode = phase.mode();
        let h = t1 - t0;
        let continued = self.last.filter(|e| e.t == t0 && self.mode == Some(mode));
        let first = match continued {
            Some(e) => Point {
                n: e.n.0,
                slip: e.slip.0,
                omega_y: step.y0[OMEGA_Y],
            },
            // A segment's first step: N evaluated at its start, as the reference scan does (the
            // rate the integrator restarted with differs from it in the last bits, enough to
            // move a bracket where N starts flat).
            None => {
                let (n, slip) = watched_at(models, phase, t0, step.y0);
                Point {
                    n,
                    slip,
                    omega_y: step.y0[OMEGA_Y],
                }
            }
        };
        let f1 = end_rate(models, phase, step);
        // The scan's points: ends, hairs inside them, and the interior points where needed.
        let ends = [
            first,
            interpolated(models, phase, dense, t0 + EDGE * h),
            interpolated(models, phase, dense, t1 - EDGE * h),
            point_from(models, phase, step.y1, &f1),
        ];
        let inside =
            turns(ends.map(|p| p.n)) || (mode == Mode::Sliding && turns(ends.map(|p| p.slip)));
        let mut ts = [0.0; INTERIOR + 4];
        let mut points = [first; INTERIOR + 4];
        let count = if inside { INTERIOR + 4 } else { 4 };
        let edge = count - 2;
        (ts[0], points[0]) = (t0, ends[0]);
        (ts[1], points[1]) = (t0 + EDGE * h, ends[1]);
        (ts[edge], points[edge]) = (t1 - EDGE * h, ends[2]);
        (ts[edge + 1], points[edge + 1]) = (t1, ends[3]);
        if inside {
            for k in 0..INTERIOR {
                let t = t0 + h * (k + 1) as f64 / (INTERIOR + 1) as f64;
                (ts[k + 2], points[k + 2]) = (t, interpolated(models, phase, dense, t));
            }
        }
        let (ts, points) = (&ts[..count], &points[..count]);
        let mut n = [0.0; INTERIOR + 4];
        let mut slip = [0.0; INTERIOR + 4];
        let mut w = [0.0; INTERIOR + 4];
        for (i, p) in points.iter().enumerate() {
            (n[i], slip[i], w[i]) = (p.n, p.slip, p.omega_y);
        }
        let last = count - 1;
        self.scan(
            models,
            (phase, step, dense),
            ts,
            (&n[..count], &slip[..count], &w[..count]),
            continued,
            out,
        );
        self.last = Some(StepEnd {
            t: t1,
            theta: step.y1[THETA],
            n: (n[last], n[last - 1]),
            slip: (slip[last], slip[last - 1]),
        });
        self.mode = Some(mode);
    }

    /// The extrema that a step's scan points (times `ts`; N, the slip speed and Ω_y there)
    /// bracket, each refined on the interpolant; and N's one-sided ones at the step's start
    /// (after a switch, or a turn at the boundary with the previous step, `continued`).
    #[allow(clippy::too_many_arguments)]
    fn scan<R: Model<DIM>, S: Model<DIM>>(
        &self,
        models: &DiskModels<R, S>,
        (phase, step, dense): (
            Phase,
            &StepView<'_, Const<DIM>, Phase>,
            &dyn Interpolant<Const<DIM>>,
        ),
        ts: &[f64],
        (n, slip, w): (&[f64], &[f64], &[f64]),
        continued: Option<StepEnd>,
        out: &mut impl FnMut(Extremum),
    ) {
        let mode = phase.mode();
        let t0 = step.t0;
        self.theta(dense, ts, w, mode, out);
        let value = |q: Watched, t: f64| {
            let mut y = [0.0; DIM];
            dense.at(t, &mut y);
            let (n, s) = watched_at(models, phase, t, &y);
            match q {
                Watched::NormalForce => n,
                _ => s,
            }
        };
        let mut series = |q: Watched, v: &[f64], before: Option<(f64, f64)>| {
            // The boundary with the previous step: its slope before the end against ours after.
            match before {
                Some((end, hair)) => {
                    if let (Some(a), Some(b)) = (one_sided(end, hair), one_sided(v[0], v[1])) {
                        if a == b {
                            out(found(q, a, (t0, v[0], step.y0[THETA]), mode));
                        }
                    }
                }
                None if q == Watched::NormalForce => {
                    if let Some(kind) = one_sided(v[0], v[1]) {
                        out(Extremum {
                            at_switch: true,
                            ..found(q, kind, (t0, v[0], step.y0[THETA]), mode)
                        });
                    }
                }
                None => {}
            }
            for (j, kind) in bracketed(v) {
                let sign = if kind == ExtremumKind::Max { -1.0 } else { 1.0 };
                let (t, f) = brent(ts[j - 1], ts[j], ts[j + 1], sign * v[j], |t| {
                    sign * value(q, t)
                });
                let theta = dense.component_at(t, THETA);
                out(found(q, kind, (t, sign * f, theta), mode));
            }
        };
        series(Watched::NormalForce, n, continued.map(|e| e.n));
        if mode == Mode::Sliding {
            series(Watched::SlipSpeed, slip, continued.map(|e| e.slip));
        }
    }

    /// The extrema of θ in the step: the sign changes of Ω_y over the scan's times, each
    /// root refined on the interpolant (a zero at a step's end counts in the step it ends).
    fn theta(
        &self,
        dense: &dyn Interpolant<Const<DIM>>,
        ts: &[f64],
        w: &[f64],
        mode: Mode,
        out: &mut impl FnMut(Extremum),
    ) {
        for j in 0..ts.len() - 1 {
            let (a, b) = (w[j], w[j + 1]);
            let kind = if a > 0.0 && b <= 0.0 {
                ExtremumKind::Max
            } else if a < 0.0 && b >= 0.0 {
                ExtremumKind::Min
            } else {
                continue;
            };
            let sign = a.signum();
            let root = find_crossing(ts[j], a, ts[j + 1], b, sign, |t| {
                Ok::<f64, std::convert::Infallible>(dense.component_at(t, OMEGA_Y))
            })
            .unwrap_or_else(|never| match never {});
            let theta = dense.component_at(root.t, THETA);
            out(found(Watched::Theta, kind, (root.t, theta, theta), mode));
        }
    }
}

/// The scan points `j` whose value is above (a maximum) or below (a minimum) both neighbours:
/// each brackets an extremum in `[ts[j − 1], ts[j + 1]]`.
///
/// This is what bounds the scan. A maximum and the minimum after it (or the reverse), both
/// between the hairs, are both bracketed when two scan points lie between them (the values
/// then fall from one to the next, a descent that a maximum starts and a minimum ends): so
/// always when they are more than two thirds of the step apart ([`INTERIOR`] = 2, gaps of a
/// third). Closer pairs can be missed, even with one scan point between them: whether they
/// are seen depends on where the points fall on the curve (the tests show both cases). Of two
/// maxima in one bracket, Brent's method reports one.
fn bracketed(v: &[f64]) -> impl Iterator<Item = (usize, ExtremumKind)> + '_ {
    (1..v.len().saturating_sub(1)).filter_map(move |j| {
        if v[j - 1] < v[j] && v[j] >= v[j + 1] {
            Some((j, ExtremumKind::Max))
        } else if v[j - 1] > v[j] && v[j] <= v[j + 1] {
            Some((j, ExtremumKind::Min))
        } else {
            None
        }
    })
}

/// An extremum inside a segment.
fn found(
    quantity: Watched,
    kind: ExtremumKind,
    (t, value, theta): (f64, f64, f64),
    mode: Mode,
) -> Extremum {
    Extremum {
        t,
        quantity,
        kind,
        value,
        theta,
        mode,
        at_switch: false,
    }
}

/// Whether `v` is above (a maximum) or below (a minimum) its neighbour `next` on one side.
fn one_sided(v: f64, next: f64) -> Option<ExtremumKind> {
    if v > next {
        Some(ExtremumKind::Max)
    } else if v < next {
        Some(ExtremumKind::Min)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scan's times on a step `[0, 1]`, as [`Scanner::step`] lays them out.
    fn scan_times() -> [f64; INTERIOR + 4] {
        let mut ts = [0.0, EDGE, 0.0, 0.0, 1.0 - EDGE, 1.0];
        for (k, t) in ts[2..INTERIOR + 2].iter_mut().enumerate() {
            *t = (k + 1) as f64 / (INTERIOR + 1) as f64;
        }
        ts
    }

    /// A rising line with a bump: a maximum near `a` and a minimum near `a + d` (a cubic
    /// with those turning points, on a slope that keeps the rest of the step rising).
    fn pair(a: f64, d: f64) -> impl Fn(f64) -> f64 {
        let b = a + d;
        // f' = (t − a)(t − b): maximum at a, minimum at b; f rises outside [a, b].
        move |t: f64| t * t * t / 3.0 - (a + b) * t * t / 2.0 + a * b * t
    }

    fn found(f: impl Fn(f64) -> f64) -> Vec<(usize, ExtremumKind)> {
        let v: Vec<f64> = scan_times().iter().map(|&t| f(t)).collect();
        bracketed(&v).collect()
    }

    #[test]
    fn pairs_two_gaps_apart_are_always_bracketed() {
        // The widest two neighbouring gaps between the hairs: two thirds of the step, less a
        // hair. A pair farther apart has two scan points between its extrema.
        let ts = scan_times();
        let two_gaps = ts[1..INTERIOR + 3]
            .windows(3)
            .map(|w| w[2] - w[0])
            .fold(0.0, f64::max);
        assert!((two_gaps - (2.0 / 3.0 - EDGE)).abs() < 1e-15, "{two_gaps}");
        let d = two_gaps * 1.001;
        for k in 0..200 {
            let a = EDGE + (1.0 - 2.0 * EDGE - d) * (k as f64 + 0.5) / 200.0;
            let kinds: Vec<ExtremumKind> = found(pair(a, d)).into_iter().map(|x| x.1).collect();
            assert_eq!(kinds, [ExtremumKind::Max, ExtremumKind::Min], "a = {a}");
        }
    }

    #[test]
    fn closer_pairs_can_be_missed() {
        // Inside one gap (1/3, 2/3): the scan sees a rising sequence and neither extremum.
        assert!(found(pair(0.45, 0.1)).is_empty());
        // With one scan point between them (2/3, or 1/3), missed or found by where it falls.
        assert!(found(pair(0.6, 0.1)).is_empty());
        assert!(found(pair(0.1382, 0.334)).is_empty());
        let kinds: Vec<ExtremumKind> = found(pair(0.2, 0.4)).into_iter().map(|x| x.1).collect();
        assert_eq!(kinds, [ExtremumKind::Max, ExtremumKind::Min]);
    }

    /// `f` read as the screen reads it on a step `[0, 1]`: ends and hairs.
    fn ends(f: impl Fn(f64) -> f64) -> [f64; 4] {
        [f(0.0), f(EDGE), f(1.0 - EDGE), f(1.0)]
    }

    #[test]
    fn the_screen_passes_monotone_steps_and_flags_turns() {
        assert!(!turns(ends(|t| 3.0 + 2.0 * t)));
        assert!(!turns(ends(|t| -(t + 0.3 * t * t))));
        // One turn: the end slopes differ in sign.
        assert!(turns(ends(|t| (t - 0.4).powi(2))));
        // Two turns, the end slopes alike: only the cubic's interior shows them.
        assert!(turns(ends(pair(0.3, 0.3))));
        // Monotone, but flat in the middle (slope 0 at 1/2): below the margin.
        assert!(turns(ends(|t| (t - 0.5).powi(3))));
        // Flat, or a model that failed.
        assert!(turns([1.0; 4]));
        assert!(turns([1.0, f64::NAN, 2.0, 3.0]));
    }

    proptest::proptest! {
        /// A cubic with a turning point inside the step, or one that comes within the margin
        /// of turning, is never screened out; nor is one the scan's points see turning.
        #[test]
        fn cubics_that_turn_are_scanned(
            a in 0.01f64..0.99, d in 0.0f64..1.0, slope in -2.0f64..2.0, scale in 0.1f64..10.0,
        ) {
            // f' = scale (t − a)(t − b) + slope·(something small): turns inside where f' = 0.
            let b = a + d;
            let f = move |t: f64| scale * (t * t * t / 3.0 - (a + b) * t * t / 2.0 + a * b * t) + slope * t;
            let fp = |t: f64| scale * (t - a) * (t - b) + slope;
            let turning = (1..1000).any(|k| {
                let (t0, t1) = ((k - 1) as f64 / 999.0, k as f64 / 999.0);
                fp(t0).signum() != fp(t1).signum()
            });
            let v: Vec<f64> = scan_times().iter().map(|&t| f(t)).collect();
            if turning || bracketed(&v).next().is_some() {
                proptest::prop_assert!(turns(ends(f)));
            }
        }
    }

    #[test]
    fn one_sided_extrema() {
        assert_eq!(one_sided(2.0, 1.0), Some(ExtremumKind::Max));
        assert_eq!(one_sided(1.0, 2.0), Some(ExtremumKind::Min));
        assert_eq!(one_sided(1.0, 1.0), None);
    }
}
