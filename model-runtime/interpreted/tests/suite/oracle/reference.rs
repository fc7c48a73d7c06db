//! The reference driver: the documented guard semantics (`model_runtime::GuardSpec`) written
//! again from scratch, for the random models only, as simply as possible: small fixed steps of
//! the classical Runge–Kutta method, every guard compared at every step end, every crossing
//! bisected on single Runge–Kutta steps from the step's start. It shares nothing with the
//! runtime's integrators or event code, nor with the language's compiler (it reads the
//! model's numbers, not its text).

use super::generate::{Action, Model, Quantity, Relation, Reset};

/// The fixed step.
const H: f64 = 1e-4;
/// Events closer than this (but not simultaneous) are beyond what the fixed step resolves:
/// the comparison ends there.
pub const RESOLVED: f64 = 2e-2;
/// The most events compared.
const MAX_EVENTS: usize = 150;

/// An event of the reference run.
#[derive(Clone, Debug)]
pub struct RefEvent {
    /// The event's name.
    pub name: String,
    /// Its time.
    pub t: f64,
    /// The state there, before the reset.
    pub y: [f64; 2],
}

/// How the reference run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum RefEnd {
    /// At the end time, with this state.
    EndTime([f64; 2]),
    /// A terminal event.
    Stop(String),
    /// More than 100 transitions at one time.
    Chatter,
    /// Beyond what the reference resolves (events too close, a grazing or thin crossing, a
    /// near tie): the events before are compared, nothing after.
    Unresolved(&'static str),
}

/// What the reference makes of a guard within rounding of its surface where a mode is entered
/// (a guard whose own event, located on it, left the state a few ulps to one side, read
/// again when a chain of events at one instant comes back to its mode): whether it departs
/// or holds is decided by those ulps, which the two drivers need not share.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ties {
    /// Beyond what the comparison judges: the events before are compared, nothing after.
    Unresolved,
    /// Taken as the reference computes them (exactly on the surface where its bisection
    /// landed there): for the cases checked one by one.
    AsComputed,
}

/// The reference run of `model` to `t_end`.
pub fn run(model: &Model, t_end: f64) -> (Vec<RefEvent>, RefEnd) {
    run_with(model, t_end, Ties::Unresolved)
}

/// The reference run of `model` to `t_end`, with surface ties taken as `ties` says.
pub fn run_with(model: &Model, t_end: f64, ties: Ties) -> (Vec<RefEvent>, RefEnd) {
    let mut events: Vec<RefEvent> = Vec::new();
    let (mut t, mut y, mut mode) = (0.0, [model.x0, model.v0], 0usize);
    let mut start = Start::Run;
    let mut same_time = 0;
    loop {
        let fired = segment(model, mode, t, y, start, t_end);
        let Some(hit) = fired else {
            return (
                events,
                RefEnd::EndTime(last_state(model, mode, t, y, t_end)),
            );
        };
        let Segment {
            index,
            t: te,
            y: ye,
            unresolved,
        } = hit;
        if let Some(why) = unresolved {
            return (events, RefEnd::Unresolved(why));
        }
        let e = &model.modes[mode].events[index];
        if let Some(prev) = events.last() {
            let dt = te - prev.t;
            if dt > 0.0 && dt < RESOLVED {
                return (
                    events,
                    RefEnd::Unresolved("events closer than the fixed step resolves"),
                );
            }
            same_time = if dt == 0.0 { same_time + 1 } else { 0 };
            if same_time > 100 {
                return (events, RefEnd::Chatter);
            }
        }
        if events.len() == MAX_EVENTS {
            return (events, RefEnd::Unresolved("event count"));
        }
        events.push(RefEvent {
            name: e.name.clone(),
            t: te,
            y: ye,
        });
        match e.action {
            Action::Stop => return (events, RefEnd::Stop(e.name.clone())),
            Action::Go { to, reset } => {
                let mut y2 = ye;
                match reset {
                    Reset::None => {}
                    Reset::Bounce(k) => y2[1] = -k * ye[1],
                    Reset::SetX(c) => y2[0] = c,
                }
                start = match to {
                    None => Start::Restart(index),
                    Some(_) => Start::Switch,
                };
                mode = to.unwrap_or(mode);
                (t, y) = (te, y2);
                if ties == Ties::Unresolved && surface_tie(model, mode, start, reset, t, y) {
                    return (
                        events,
                        RefEnd::Unresolved("a guard within rounding of its surface on entry"),
                    );
                }
            }
        }
    }
}

/// How a segment starts.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Start {
    Run,
    Switch,
    Restart(usize),
}

/// The first event of a segment.
struct Segment {
    index: usize,
    t: f64,
    y: [f64; 2],
    unresolved: Option<&'static str>,
}

fn rhs(model: &Model, mode: usize, t: f64, y: [f64; 2]) -> [f64; 2] {
    let m = &model.modes[mode];
    [y[1], m.a * y[0] + m.b * y[1] + m.c + m.d * t.sin()]
}

/// One classical Runge–Kutta step of size `h` from `(t, y)`.
fn rk4(model: &Model, mode: usize, t: f64, y: [f64; 2], h: f64) -> [f64; 2] {
    let add = |y: [f64; 2], k: [f64; 2], s: f64| [y[0] + s * k[0], y[1] + s * k[1]];
    let k1 = rhs(model, mode, t, y);
    let k2 = rhs(model, mode, t + h / 2.0, add(y, k1, h / 2.0));
    let k3 = rhs(model, mode, t + h / 2.0, add(y, k2, h / 2.0));
    let k4 = rhs(model, mode, t + h, add(y, k3, h));
    [
        y[0] + h / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]),
        y[1] + h / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]),
    ]
}

/// The guard of event `i` of `mode` at `(t, y)`: `quantity - threshold`.
fn guard(model: &Model, mode: usize, i: usize, t: f64, y: [f64; 2]) -> f64 {
    let e = &model.modes[mode].events[i];
    let q = match e.quantity {
        Quantity::X => y[0],
        Quantity::V => y[1],
        Quantity::T => t,
        Quantity::Let => y[0] + model.k * y[1],
        Quantity::Output => y[0] + model.p * y[1] * y[1],
    };
    q - e.threshold
}

/// The sign of the side where event `i`'s guard holds (0: either way).
fn holding(model: &Model, mode: usize, i: usize) -> f64 {
    match model.modes[mode].events[i].relation {
        Relation::Less => -1.0,
        Relation::Greater => 1.0,
        Relation::Equal => 0.0,
    }
}

fn sign(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// Whether moving from reference sign `r` to value `v` is a crossing event `i` fires on.
fn fires(h: f64, r: f64, v: f64) -> bool {
    let up = r < 0.0 && v >= 0.0;
    let down = r > 0.0 && v <= 0.0;
    (up && h >= 0.0) || (down && h <= 0.0)
}

/// The state at `t_end` (no event before it).
fn last_state(model: &Model, mode: usize, t: f64, y: [f64; 2], t_end: f64) -> [f64; 2] {
    let (mut t, mut y) = (t, y);
    while t < t_end {
        let h = H.min(t_end - t);
        y = rk4(model, mode, t, y, h);
        t += h;
    }
    y
}

/// Integrates `mode` from `(t, y)` until its first event (or `t_end`).
fn segment(
    model: &Model,
    mode: usize,
    t0: f64,
    y0: [f64; 2],
    start: Start,
    t_end: f64,
) -> Option<Segment> {
    let n = model.modes[mode].events.len();
    let g0: Vec<f64> = (0..n).map(|i| guard(model, mode, i, t0, y0)).collect();
    let mut reference: Vec<f64> = g0.iter().map(|&g| sign(g)).collect();
    let mut departs: Vec<bool> = vec![start != Start::Run; n];
    if let Start::Restart(q) = start {
        reference[q] = 0.0;
        departs[q] = false;
    }
    // What holds where the segment starts fires there, the first listed first.
    for (i, &r) in reference.iter().enumerate() {
        let h = holding(model, mode, i);
        if h != 0.0 && r == h {
            return Some(Segment {
                index: i,
                t: t0,
                y: y0,
                unresolved: None,
            });
        }
    }
    let (mut t, mut y) = (t0, y0);
    while t < t_end {
        let h = H.min(t_end - t);
        let y1 = rk4(model, mode, t, y, h);
        let mut best: Option<(f64, usize, [f64; 2])> = None;
        for i in 0..n {
            let g1 = guard(model, mode, i, t + h, y1);
            let hs = holding(model, mode, i);
            if reference[i] == 0.0 {
                if g1 == 0.0 {
                    continue;
                }
                let into = sign(g1);
                // A guard on its surface whose departure turns back within the fixed step
                // (a speed so small that the acceleration wins inside one step) departs
                // one way at the step's scale and the other at the driver's probes, far
                // closer to the start: beyond what this reference resolves.
                let hf = h * 2f64.powi(-20);
                let fine = sign(guard(model, mode, i, t + hf, rk4(model, mode, t, y, hf)));
                if departs[i] && fine != 0.0 && fine != into {
                    return Some(Segment {
                        index: i,
                        t,
                        y,
                        unresolved: Some("a departure that turns within the fixed step"),
                    });
                }
                if departs[i] && (hs == 0.0 || hs == into) {
                    // A departure that fires: at the last point where the guard was zero.
                    if best.is_none_or(|b| t < b.0) {
                        best = Some((t, i, y));
                    }
                }
                continue;
            }
            if !fires(hs, reference[i], g1) {
                continue;
            }
            let r = reference[i];
            let (mut lo, mut hi) = (0.0, h);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                let g = guard(model, mode, i, t + mid, rk4(model, mode, t, y, mid));
                if g * r > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let te = t + hi;
            if best.is_none_or(|b| te < b.0) {
                best = Some((te, i, rk4(model, mode, t, y, hi)));
            }
        }
        if let Some((te, index, ye)) = best {
            let unresolved = doubtful(model, mode, index, te, ye, t, y)
                .or_else(|| thin_before(model, mode, index, te, ye, t0));
            return Some(Segment {
                index,
                t: te,
                y: ye,
                unresolved,
            });
        }
        for (i, r) in reference.iter_mut().enumerate() {
            let g1 = guard(model, mode, i, t + h, y1);
            if g1 != 0.0 {
                *r = sign(g1);
            }
        }
        (t, y) = (t + h, y1);
    }
    None
}

/// Why the event `index` at `(te, ye)` (found in the step from `(t, y)`) cannot be compared:
/// a guard that grazes its threshold, that would hold only for a moment (thinner than the
/// steps an adaptive integrator takes: seen or not depending on them), or another guard
/// crossing within a hair of it.
fn doubtful(
    model: &Model,
    mode: usize,
    index: usize,
    te: f64,
    ye: [f64; 2],
    t: f64,
    y: [f64; 2],
) -> Option<&'static str> {
    if te == t {
        return None;
    }
    let d = 1e-6;
    let g = |i: usize, s: f64| {
        let yy = rk4(model, mode, t, y, s - t);
        guard(model, mode, i, s, yy)
    };
    let slope = (g(index, te + d) - g(index, te - d)) / (2.0 * d);
    if slope.abs() < 1e-2 {
        return Some("a grazing crossing");
    }
    for i in 0..model.modes[mode].events.len() {
        if i != index && sign(g(i, te - 1e-6)) != sign(g(i, te + 1e-6)) {
            return Some("a near tie");
        }
    }
    // How long the guard would hold without the event: a thin excursion is doubtful.
    let h = holding(model, mode, index);
    let (mut s, mut ys) = (te, ye);
    while s < te + 0.2 {
        ys = rk4(model, mode, s, ys, H);
        s += H;
        let v = guard(model, mode, index, s, ys);
        if (h == 0.0 && sign(v) != sign(slope)) || (h != 0.0 && v * h < 0.0) {
            return Some("a thin excursion");
        }
    }
    None
}

/// Whether the crossing of guard `index` at `(te, ye)` ends an excursion that began inside
/// the segment (started at `t0`) by a crossing the other way less than about two ordinary
/// steps before (`0.25/ω`, with the mode's `ω = √|a|`; the adaptive steps at the compared
/// tolerances are about `0.13/ω`): a guard that leaves its side and comes back within one
/// step leaves no trace at the step ends (the documented need for interior checks), so
/// whether it is seen depends on the steps taken. An excursion that begins at the segment's
/// start (a flight after a bounce) is not thin in this sense: the driver probes it.
fn thin_before(
    model: &Model,
    mode: usize,
    index: usize,
    te: f64,
    ye: [f64; 2],
    t0: f64,
) -> Option<&'static str> {
    let d = 1e-6;
    let g = |s: f64| guard(model, mode, index, s, rk4(model, mode, te, ye, s - te));
    let side = -sign(g(te + d) - g(te - d));
    let (mut s, mut ys) = (te, ye);
    let window = 0.25 / model.modes[mode].a.abs().sqrt().max(1.0);
    while s > (te - window).max(t0) + H {
        ys = rk4(model, mode, s, ys, -H);
        s -= H;
        if sign(guard(model, mode, index, s, ys)) != side {
            return Some("a thin excursion");
        }
    }
    None
}

/// Whether a guard of `mode` other than the one that restarted it is within rounding of its
/// surface at `(t, y)`, where the run enters it after a reset `reset`: unless the reset set
/// the guard's quantity to its threshold exactly (which both drivers compute alike).
fn surface_tie(
    model: &Model,
    mode: usize,
    start: Start,
    reset: Reset,
    t: f64,
    y: [f64; 2],
) -> bool {
    let events = &model.modes[mode].events;
    (0..events.len()).any(|i| {
        let e = &events[i];
        let exact =
            matches!(reset, Reset::SetX(c) if e.quantity == Quantity::X && c == e.threshold);
        start != Start::Restart(i) && !exact && guard(model, mode, i, t, y).abs() < 1e-12
    })
}
