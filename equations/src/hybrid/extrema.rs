//! Extrema located on each step's dense output, independent of any sampling.
//!
//! An observer that asks for them ([`super::DiskObserver::wants_extrema`]) is told of every
//! maximum and minimum, within a rolling or sliding segment, of
//!
//! * θ: the zeros of θ̇ = Ω_y (a state), found by the root finder on the step's interpolant,
//!   so as exact as the dense output;
//! * the normal force N: an output of the models that depends on the accelerations. On each
//!   step it is evaluated (interpolated state, one model evaluation) at the step's ends, at
//!   [`INTERIOR`] interior points and a hair ([`EDGE`] of the step) inside either end; a point
//!   of that sequence above (below) both neighbours brackets a maximum (minimum), which Brent's
//!   method refines to [`X_TOL`] of the bracket. The two points beside each end give the slope
//!   there, so an extremum within a hair of a step boundary is still seen (as the boundary,
//!   the value then off by the curvature times a hair squared). At a mode switch N jumps: the
//!   value at either side of the switch that lies above (below) its neighbour within the
//!   segment is reported as a maximum (minimum) too;
//! * the slip speed, while sliding, as N (only interior extrema: it is continuous).
//!
//! The scan's points and Brent's iterates are fractions of the step in the variable the run
//! integrates in ([`Interpolant::at_fraction`]): in regularised time fractions of the step in
//! `τ`, whose physical time is read off the clock there, so no point is first placed on the
//! clock by a root search; only the located extrema's times are read, once each. Since the
//! time rises with `τ`, an extremum in `τ` is one in `t`, at the same instant.
//!
//! A pair of extrema of N or v_C less than two thirds of a step apart (in the run's variable)
//! can be missed (farther apart, never): see [`bracketed`]. So in the chatter before a stick,
//! where N and the slip speed ripple many times within a step, which ripples are listed
//! depends on where the points fall and on the run's last bits (docs/physics.md §13; the
//! suite's `extrema_scan` holds the scan to a brute-force one elsewhere). θ's extrema are the
//! zeros of Ω_y found by sign changes on the same points, so a pair of them inside one gap
//! between scan points (a third of the step) is missed (Ω_y has the same sign at the gap's
//! ends); a pair with a point between them is found.
//!
//! Bridges (about 1e-9 s at zero slip) are not scanned. The cost is `INTERIOR + 3` model
//! evaluations per step and about twenty per extremum; a run that does not ask pays nothing.

use super::models::DiskModels;
use super::system::Phase;
use crate::modes::layout::{OMEGA_Y, THETA};
use crate::modes::{slip_speed, ContactForce, Mode, PhysicalState, DIM};
use model_runtime::Const;
use model_runtime::{find_crossing, Interpolant, Model, StepView};

/// Interior points per step at which N and the slip speed are evaluated.
pub const INTERIOR: usize = 2;
/// Where the end slopes are read: this fraction of the step inside each end.
pub const EDGE: f64 = 1e-4;
/// Brent's refinement stops when the bracket is this fraction of its starting width.
pub const X_TOL: f64 = 1e-7;

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
#[derive(Debug, Default)]
pub(crate) struct Scanner {
    last: Option<StepEnd>,
    mode: Option<Mode>,
}

/// The normal force and the slip speed at `y` in `phase` (NaN where the model fails).
fn watched_at<R: Model<DIM>, S: Model<DIM>>(
    models: &DiskModels<R, S>,
    phase: Phase,
    t: f64,
    y: &[f64; DIM],
) -> (f64, f64) {
    let p = &models.params;
    let mut dy = [0.0; DIM];
    match phase {
        Phase::Rolling => match models.rolling.rhs(t, y, &mut dy) {
            Ok(()) => {
                let f = ContactForce::rolling(p, &PhysicalState::from_rolling(y, 0.0), &dy);
                (f.normal, f64::NAN)
            }
            Err(_) => (f64::NAN, f64::NAN),
        },
        _ => {
            // N and the slip speed need no physical state in still air (no `atan2`, no
            // `sin_cos`): what the guards read, the same bits as through it.
            let speed = slip_speed(models.chart, y);
            match models.sliding.rhs(t, y, &mut dy) {
                Ok(()) => (ContactForce::sliding_normal(p, models.chart, y, &dy), speed),
                Err(_) => (f64::NAN, speed),
            }
        }
    }
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
    pub(crate) fn step<R: Model<DIM>, S: Model<DIM>, Md>(
        &mut self,
        models: &DiskModels<R, S>,
        phase: Phase,
        step: &StepView<'_, Const<DIM>, Md>,
        out: &mut impl FnMut(Extremum),
    ) {
        let Some(dense) = step.dense else { return };
        let (t0, t1) = (step.t0, step.t1);
        if phase == Phase::Bridge || t1.partial_cmp(&t0) != Some(std::cmp::Ordering::Greater) {
            return;
        }
        let mode = phase.mode();
        let span = (t0, t1);
        // The scan's points, as fractions of the step in the run's variable (in regularised
        // time `τ`, so that no point has to be placed on the clock): ends, hairs inside them,
        // interior points.
        let us = scan_fractions();
        let mut n = [0.0; INTERIOR + 4];
        let mut slip = [0.0; INTERIOR + 4];
        let mut w = [0.0; INTERIOR + 4];
        let continued = self.last.filter(|e| e.t == t0 && self.mode == Some(mode));
        for (i, &u) in us.iter().enumerate() {
            let ((ni, si), wi) = match (i, continued) {
                (0, Some(e)) => ((e.n.0, e.slip.0), step.y0[OMEGA_Y]),
                (0, None) => (watched_at(models, phase, t0, step.y0), step.y0[OMEGA_Y]),
                _ if i == INTERIOR + 3 => {
                    (watched_at(models, phase, t1, step.y1), step.y1[OMEGA_Y])
                }
                _ => {
                    let (t, y) = at_fraction(dense, span, u);
                    (watched_at(models, phase, t, &y), y[OMEGA_Y])
                }
            };
            n[i] = ni;
            slip[i] = si;
            w[i] = wi;
        }
        self.theta(dense, span, &us, &w, mode, out);
        let value = |q: Watched, u: f64| {
            let (t, y) = at_fraction(dense, span, u);
            let (n, s) = watched_at(models, phase, t, &y);
            match q {
                Watched::NormalForce => n,
                _ => s,
            }
        };
        let mut series = |q: Watched, v: &[f64; INTERIOR + 4], before: Option<(f64, f64)>| {
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
                let (u, f) = brent(us[j - 1], us[j], us[j + 1], sign * v[j], |u| {
                    sign * value(q, u)
                });
                let (t, y) = at_fraction(dense, span, u);
                out(found(q, kind, (t, sign * f, y[THETA]), mode));
            }
        };
        series(Watched::NormalForce, &n, continued.map(|e| e.n));
        if mode == Mode::Sliding {
            series(Watched::SlipSpeed, &slip, continued.map(|e| e.slip));
        }
        let last = INTERIOR + 3;
        self.last = Some(StepEnd {
            t: t1,
            theta: step.y1[THETA],
            n: (n[last], n[last - 1]),
            slip: (slip[last], slip[last - 1]),
        });
        self.mode = Some(mode);
    }

    /// The extrema of θ in the step: the sign changes of Ω_y over the scan's points (`us`,
    /// fractions of the step `span`), each root refined on the interpolant (a zero at a step's end
    /// counts in the step it ends).
    fn theta(
        &self,
        dense: &dyn Interpolant<Const<DIM>>,
        span: (f64, f64),
        us: &[f64],
        w: &[f64],
        mode: Mode,
        out: &mut impl FnMut(Extremum),
    ) {
        for j in 0..us.len() - 1 {
            let (a, b) = (w[j], w[j + 1]);
            let kind = if a > 0.0 && b <= 0.0 {
                ExtremumKind::Max
            } else if a < 0.0 && b >= 0.0 {
                ExtremumKind::Min
            } else {
                continue;
            };
            let sign = a.signum();
            let root = find_crossing(us[j], a, us[j + 1], b, sign, |u| {
                Ok::<f64, std::convert::Infallible>(at_fraction(dense, span, u).1[OMEGA_Y])
            })
            .unwrap_or_else(|never| match never {});
            let (t, y) = at_fraction(dense, span, root.t);
            out(found(Watched::Theta, kind, (t, y[THETA], y[THETA]), mode));
        }
    }
}

/// The scan's points as fractions of a step: its start, a hair ([`EDGE`]) inside it,
/// [`INTERIOR`] points evenly spaced, a hair before the end, the end.
fn scan_fractions() -> [f64; INTERIOR + 4] {
    let mut us = [0.0; INTERIOR + 4];
    us[1] = EDGE;
    for (k, u) in us[2..INTERIOR + 2].iter_mut().enumerate() {
        *u = (k + 1) as f64 / (INTERIOR + 1) as f64;
    }
    us[INTERIOR + 2] = 1.0 - EDGE;
    us[INTERIOR + 3] = 1.0;
    us
}

/// The time and the state a fraction `u` through the step `span` of `dense`, in the run's
/// variable.
fn at_fraction(dense: &dyn Interpolant<Const<DIM>>, span: (f64, f64), u: f64) -> (f64, [f64; DIM]) {
    let mut y = [0.0; DIM];
    let t = dense.at_fraction(span, u, &mut y);
    (t, y)
}

/// The scan points `j` whose value is above (a maximum) or below (a minimum) both neighbours:
/// each brackets an extremum between the points `j − 1` and `j + 1`.
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

/// Brent's minimisation of `f` on `[a, c]`, starting from `b` inside with `f(b) = fb` below
/// both ends; stops when the bracket is [`X_TOL`] of its width (or a few ulps of `t`).
/// Returns the best point and its value.
pub fn brent(a: f64, b: f64, c: f64, fb: f64, mut f: impl FnMut(f64) -> f64) -> (f64, f64) {
    const GOLD: f64 = 0.381_966_011_250_105_1;
    let (mut lo, mut hi) = (a, c);
    let tol_abs = X_TOL * (c - a) + 4.0 * f64::EPSILON * b.abs();
    let (mut x, mut w, mut v) = (b, b, b);
    let (mut fx, mut fw, mut fv) = (fb, fb, fb);
    let (mut d, mut e) = (0.0f64, 0.0f64);
    for _ in 0..100 {
        let m = 0.5 * (lo + hi);
        let tol = tol_abs;
        if (x - m).abs() <= 2.0 * tol - 0.5 * (hi - lo) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol {
            // A parabola through x, w, v.
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            if p.abs() < (0.5 * q * e).abs() && p > q * (lo - x) && p < q * (hi - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - lo < 2.0 * tol || hi - u < 2.0 * tol {
                    d = if x < m { tol } else { -tol };
                }
                golden = false;
            }
        }
        if golden {
            e = if x >= m { lo - x } else { hi - x };
            d = GOLD * e;
        }
        let u = if d.abs() >= tol {
            x + d
        } else {
            x + tol.copysign(d)
        };
        let fu = f(u);
        if fu.is_nan() {
            break;
        }
        if fu <= fx {
            if u >= x {
                lo = x;
            } else {
                hi = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                lo = u;
            } else {
                hi = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    (x, fx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brent_finds_a_sharp_peak_to_the_curvature() {
        // A peak of width 1e-4 at an irrational time: N-like, 1/(w² + (t − t*)²).
        let (t_star, width) = (0.123_456_789_012_345, 1e-4);
        let peak = |t: f64| 1.0 / (width * width + (t - t_star).powi(2));
        let (a, c) = (0.1234, 0.1236);
        let b = 0.12345;
        let mut evals = 0;
        let (t, f) = brent(a, b, c, -peak(b), |t| {
            evals += 1;
            -peak(t)
        });
        // The time to the stopping width (X_TOL of the bracket); the value, flat at the top, to
        // the curvature times that width squared: round-off.
        assert!((t - t_star).abs() <= X_TOL * (c - a), "t = {t}");
        assert!(((-f) - peak(t_star)).abs() <= 1e-12 * peak(t_star), "{f}");
        assert!(evals < 60, "{evals} evaluations");
    }

    /// A rising line with a bump: a maximum near `a` and a minimum near `a + d` (a cubic
    /// with those turning points, on a slope that keeps the rest of the step rising).
    fn pair(a: f64, d: f64) -> impl Fn(f64) -> f64 {
        let b = a + d;
        // f' = (t − a)(t − b): maximum at a, minimum at b; f rises outside [a, b].
        move |t: f64| t * t * t / 3.0 - (a + b) * t * t / 2.0 + a * b * t
    }

    fn found(f: impl Fn(f64) -> f64) -> Vec<(usize, ExtremumKind)> {
        let v: Vec<f64> = scan_fractions().iter().map(|&t| f(t)).collect();
        bracketed(&v).collect()
    }

    #[test]
    fn pairs_two_gaps_apart_are_always_bracketed() {
        // The widest two neighbouring gaps between the hairs: two thirds of the step, less a
        // hair. A pair farther apart has two scan points between its extrema.
        let ts = scan_fractions();
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

    #[test]
    fn one_sided_extrema() {
        assert_eq!(one_sided(2.0, 1.0), Some(ExtremumKind::Max));
        assert_eq!(one_sided(1.0, 2.0), Some(ExtremumKind::Min));
        assert_eq!(one_sided(1.0, 1.0), None);
    }
}
