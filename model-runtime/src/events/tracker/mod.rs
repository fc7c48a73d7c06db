//! The search of a step for the earliest guard crossing: per-guard reference signs, check
//! points, and the exact location of what fires. The one definition of what fires (see
//! [`super::GuardSpec`]) that the step-end checks, the interior checks, screening and the
//! resumption after a pass all share.

use super::direction::{crossing, Crossed, Direction};
use super::interior::{cubic_keeps_sign, InteriorChecks};
use super::quiet::QuietRange;
use super::{Found, Probe, Quiet};

/// How far the search of a step has come: its check points and the next one to look at.
#[derive(Clone, Copy, Debug, Default)]
struct Walk {
    t0: f64,
    t1: f64,
    /// Interior check points (the step end is check point `points + 1`).
    points: u32,
    screened: bool,
    /// The parts of the step that screening cleared: their check points are skipped.
    cleared: Cleared,
    /// The next check point.
    k: u32,
    /// The last check point passed without an event.
    lo: f64,
    /// The time of the last pass in this step (`t0` before any): no event is earlier.
    floor: f64,
}

/// The parts of a screened step whose cubics kept their sign (see
/// [`GuardTracker::cubic_clear`]): at most the step's three thirds, by their ends in time.
#[derive(Clone, Copy, Debug, Default)]
struct Cleared {
    parts: [(f64, f64); 3],
    len: usize,
}

impl Cleared {
    fn push(&mut self, part: (f64, f64)) {
        self.parts[self.len] = part;
        self.len += 1;
    }

    /// Whether `t` lies in a cleared part (its ends included).
    fn contains(&self, t: f64) -> bool {
        self.parts[..self.len]
            .iter()
            .any(|&(a, b)| a <= t && t <= b)
    }
}

/// Per-guard reference signs and the guard values at the last check point.
#[derive(Clone, Debug, Default)]
pub(crate) struct GuardTracker {
    directions: Vec<Direction>,
    /// Reference sign per guard: -1, +1, or 0 while pending (zero since the segment start).
    reference: Vec<f64>,
    /// For pending guards: whether leaving zero in an admitted direction fires.
    pub(super) departure_fires: Vec<bool>,
    /// Per guard, the values that cannot fire it against its current reference sign
    /// ([`QuietRange`]), kept in step with `reference`.
    quiet: Vec<QuietRange>,
    /// Per guard, the sign of the side where it holds (where its admitted crossings lead):
    /// `+1` for [`Direction::Up`], `-1` for [`Direction::Down`], `0` for [`Direction::Both`].
    holding: Vec<f64>,
    /// Per guard, whether it may be on its holding side without having fired: the named
    /// exceptions of [`super::GuardSpec`] (a departure from zero at the run's start or after
    /// a projection, a guard that passed).
    exempt: Vec<bool>,
    /// Per guard, whether it holds where the segment starts and is still to fire there.
    enters: Vec<bool>,
    /// Whether the guards that are pending (exactly zero) at the next scan take their
    /// departure from a probe just after the step's start (see [`GuardTracker::probe`]).
    fresh: bool,
    /// Whether a guard found within rounding of its surface where the segment starts is
    /// taken to be on it (after a switch or a restart; see [`GuardTracker::on_surface`]).
    rounding_is_surface: bool,
    /// A guard found on its holding side without having fired: the invariant's violation.
    violation: Option<usize>,
    /// Guard values at the last check point (for a guard that passed since: at the pass).
    lo_values: Vec<f64>,
    /// The times of `lo_values`.
    lo_at: Vec<f64>,
    /// Where the search of the current step stands.
    walk: Walk,
    scratch: Vec<f64>,
    at_best: Vec<f64>,
    /// Screening estimates at a third and at two thirds of the step.
    at_third: Vec<f64>,
    at_two_thirds: Vec<f64>,
    /// Screening estimates inside a third of the step.
    inside_third: Vec<f64>,
}

impl GuardTracker {
    /// Starts a segment with these guards and their values at the start; `quiet` says which
    /// guards are on their own surface and how the others' values are read, `entry` whether
    /// a guard that holds there fires at once (see [`super::GuardSpec`]).
    pub(crate) fn start(
        &mut self,
        directions: impl Iterator<Item = Direction>,
        values: &[f64],
        quiet: Quiet,
        entry: bool,
    ) {
        let n = values.len();
        self.directions.clear();
        self.directions.extend(directions);
        self.holding.clear();
        self.holding
            .extend(self.directions.iter().map(|&d| holding_sign(d)));
        self.reference.clear();
        self.reference.extend(values.iter().map(|&v| sign(v)));
        // The guard that just fired is on its surface, whatever rounding left in its value:
        // its departure decides.
        if let Quiet::Guard(q) = quiet {
            self.reference[q] = 0.0;
        }
        let departures_fire = !matches!(quiet, Quiet::Start | Quiet::All);
        self.departure_fires.clear();
        self.departure_fires.resize(n, departures_fire);
        self.exempt.clear();
        self.exempt.resize(n, !departures_fire);
        if let Quiet::Guard(q) = quiet {
            // It has fired: on whichever side it leaves to, it moves on from there.
            self.departure_fires[q] = false;
            self.exempt[q] = true;
        }
        self.enters.clear();
        self.enters.extend((0..n).map(|i| {
            entry
                && !matches!(quiet, Quiet::All)
                && self.holding[i] != 0.0
                && self.reference[i] == self.holding[i]
        }));
        self.fresh = true;
        self.rounding_is_surface = matches!(quiet, Quiet::None | Quiet::Guard(_));
        self.violation = None;
        self.quiet.clear();
        self.quiet.extend((0..n).map(|i| {
            QuietRange::of(
                self.reference[i],
                self.directions[i],
                self.departure_fires[i],
            )
        }));
        self.lo_values.clear();
        self.lo_values.extend_from_slice(values);
        self.lo_at.clear();
        self.lo_at.resize(n, 0.0);
        self.scratch.clear();
        self.scratch.resize(n, 0.0);
        self.at_best.clear();
        self.at_best.resize(n, 0.0);
        self.at_third.clear();
        self.at_third.resize(n, 0.0);
        self.at_two_thirds.clear();
        self.at_two_thirds.resize(n, 0.0);
        self.inside_third.clear();
        self.inside_third.resize(n, 0.0);
    }

    /// A guard found on its holding side without having fired, and without one of the
    /// exceptions of [`super::GuardSpec`]: the driver's invariant, violated (checked after
    /// every accepted step that found no event).
    pub(crate) fn violation(&self) -> Option<usize> {
        self.violation
    }

    /// Records that the event last found, guard `index` at `t` with exact value `value` there,
    /// passed (see "Passes" at [`super::GuardSpec`]); [`GuardTracker::resume`] then goes on.
    pub(crate) fn pass(&mut self, index: usize, t: f64, value: f64) {
        self.reference[index] = sign(value);
        self.departure_fires[index] = false;
        self.exempt[index] = true;
        self.enters[index] = false;
        self.quiet[index] = QuietRange::of(self.reference[index], self.directions[index], false);
        self.lo_values[index] = value;
        self.lo_at[index] = t;
        self.walk.floor = t;
    }

    /// Number of guards.
    pub(crate) fn len(&self) -> usize {
        self.directions.len()
    }

    /// Looks for the earliest admitted crossing in the step `[t0, t1]` with guard values
    /// `end_values` at `t1`, checking the interior points of `checks` first.
    /// `eval(t, probe, out)` evaluates all guards at an interior time on the dense output,
    /// exactly or as an estimate. When nothing fires, the reference signs advance to the end
    /// of the step.
    pub(crate) fn scan<E>(
        &mut self,
        t0: f64,
        t1: f64,
        end_values: &[f64],
        checks: InteriorChecks,
        mut eval: impl FnMut(f64, Probe, &mut [f64]) -> Result<(), E>,
    ) -> Result<Option<Found>, E> {
        let n = self.len();
        if n == 0 {
            return Ok(None);
        }
        let screened = matches!(checks, InteriorChecks::Screened(_));
        let mut cleared = Cleared::default();
        let points = if screened && self.cubic_clear(t0, t1, end_values, &mut cleared, &mut eval)? {
            0
        } else {
            checks.points()
        };
        self.lo_at.fill(t0);
        self.walk = Walk {
            t0,
            t1,
            points,
            screened,
            cleared,
            k: 1,
            lo: t0,
            floor: t0,
        };
        self.resume(end_values, eval)
    }

    /// Goes on searching the step of the last [`GuardTracker::scan`] from the check point at
    /// which the last event was found (after a [`GuardTracker::pass`]); `end_values` are the
    /// guard values at the step's end, as for the scan.
    pub(crate) fn resume<E>(
        &mut self,
        end_values: &[f64],
        mut eval: impl FnMut(f64, Probe, &mut [f64]) -> Result<(), E>,
    ) -> Result<Option<Found>, E> {
        let n = self.len();
        let Walk {
            t0,
            t1,
            points,
            screened,
            cleared,
            ..
        } = self.walk;
        if self.fresh {
            // The segment's first step: first what holds where it starts, then the departures.
            if self.rounding_is_surface {
                self.rounding_is_surface = false;
                self.on_surface(t0, t1, &mut eval)?;
            }
            if let Some(index) = self.enters.iter().position(|&e| e) {
                self.enters[index] = false;
                return Ok(Some(Found {
                    index,
                    t: t0,
                    before: t0,
                    direction: crossed_to(self.holding[index]),
                }));
            }
            self.fresh = false;
            if self.reference.contains(&0.0) {
                if let Some(found) = self.probe(t0, t1, &mut eval)? {
                    return Ok(Some(found));
                }
            }
        }
        while self.walk.k <= points + 1 {
            let (k, lo) = (self.walk.k, self.walk.lo);
            let tk = if k == points + 1 {
                self.scratch.copy_from_slice(end_values);
                t1
            } else {
                let tk = t0 + (t1 - t0) * (k as f64 / (points + 1) as f64);
                if screened {
                    if cleared.contains(tk) {
                        self.walk.k += 1;
                        continue;
                    }
                    eval(tk, Probe::Estimate, &mut self.scratch)?;
                    if !self.may_fire() {
                        self.walk.k += 1;
                        continue;
                    }
                }
                eval(tk, Probe::Exact, &mut self.scratch)?;
                tk
            };
            // Values inside every quiet range fire nothing (the common case, two comparisons
            // per guard); otherwise find out what fires.
            if self.may_fire() {
                // A departure from zero happened at `lo` at the latest: before any crossing.
                let at = lo.max(self.walk.floor);
                for i in 0..n {
                    if let Some(c) = self.departure(i, self.scratch[i]) {
                        return Ok(Some(Found {
                            index: i,
                            t: at,
                            before: at,
                            direction: c,
                        }));
                    }
                }
                if (0..n).any(|i| self.admitted_crossing(i, self.scratch[i]).is_some()) {
                    return self.locate(tk, &mut eval);
                }
            }
            for i in 0..n {
                let v = self.scratch[i];
                if v != 0.0 && sign(v) != self.reference[i] {
                    self.settle(i, v);
                }
                self.lo_values[i] = v;
                self.lo_at[i] = tk;
            }
            self.walk.lo = tk;
            self.walk.k += 1;
        }
        Ok(None)
    }

    /// The departures of the guards pending at a segment's start (exactly zero there, or the
    /// guard whose event restarted the mode), read from the guards' values just after the
    /// start of its first step `[t0, t1]`, at probes `t0 + h 2^-k` from the nearest out: a
    /// guard with a holding side departed to its other side if any probe finds it there (the
    /// nearest ones may still be in the rounding of its surface, the farther ones past a
    /// short excursion), and into its holding side if every nonzero probe finds it there; a
    /// guard that fires either way departs to the side of its nearest nonzero probe. A
    /// departure that fires is an event at `t0`; any other becomes the guard's reference
    /// sign, with the probe that showed it as its last check point, so that a return through
    /// the surface later in the same step is a crossing, located after the excursion's
    /// turning point. A guard zero at every probe stays pending.
    fn probe<E>(
        &mut self,
        t0: f64,
        t1: f64,
        eval: &mut impl FnMut(f64, Probe, &mut [f64]) -> Result<(), E>,
    ) -> Result<Option<Found>, E> {
        const PROBES: [i32; 5] = [-30, -24, -18, -12, -6];
        let n = self.len();
        let pending: Vec<usize> = (0..n).filter(|&i| self.reference[i] == 0.0).collect();
        // Per pending guard: the first probe on its non-holding side (or, for `==`, its
        // first nonzero one), and the last nonzero one.
        let mut away: Vec<Option<(f64, f64)>> = vec![None; pending.len()];
        let mut last: Vec<Option<(f64, f64)>> = vec![None; pending.len()];
        for k in PROBES {
            let td = t0 + (t1 - t0) * 2f64.powi(k);
            if td <= t0 || td >= t1 {
                continue;
            }
            eval(td, Probe::Exact, &mut self.scratch)?;
            for (j, &i) in pending.iter().enumerate() {
                let v = self.scratch[i];
                if v == 0.0 || away[j].is_some() {
                    continue;
                }
                last[j] = Some((td, v));
                if self.holding[i] == 0.0 || sign(v) != self.holding[i] {
                    away[j] = Some((td, v));
                }
            }
            if away.iter().all(Option::is_some) {
                break;
            }
        }
        for (j, &i) in pending.iter().enumerate() {
            let Some((td, v)) = away[j].or(last[j]) else {
                continue;
            };
            if let Some(direction) = self.departure(i, v) {
                return Ok(Some(Found {
                    index: i,
                    t: t0,
                    before: t0,
                    direction,
                }));
            }
            self.settle(i, v);
            self.lo_values[i] = v;
            self.lo_at[i] = td;
        }
        Ok(None)
    }

    /// After a switch or a restart, a guard that starts closer to its surface than it moves
    /// in the first probe's time (`t0 + h 2^-30`) is on its surface, pending, so that its
    /// departure decides (see [`super::GuardSpec`]): an event located on its surface leaves
    /// the state a few ulps to one side of it, and a mode entered at that instant must not
    /// read a guard that is leaving its holding side as holding (an immediate switch back, a
    /// chatter the model does not have), nor one that leaves through its surface as not
    /// crossing it.
    fn on_surface<E>(
        &mut self,
        t0: f64,
        t1: f64,
        eval: &mut impl FnMut(f64, Probe, &mut [f64]) -> Result<(), E>,
    ) -> Result<(), E> {
        let td = t0 + (t1 - t0) * 2f64.powi(-30);
        if td <= t0 || td >= t1 || !self.reference.iter().any(|&r| r != 0.0) {
            return Ok(());
        }
        // The estimate (no model evaluation) says which guards may be that close; the exact
        // values decide.
        eval(td, Probe::Estimate, &mut self.scratch)?;
        // (A non-finite estimate is near: the exact look decides.)
        let clear = |i: usize| {
            let (v, v0) = (self.scratch[i], self.lo_values[i]);
            self.reference[i] == 0.0 || (v - v0).abs() <= 0.5 * v0.abs()
        };
        if (0..self.len()).all(clear) {
            return Ok(());
        }
        eval(td, Probe::Exact, &mut self.scratch)?;
        for i in 0..self.len() {
            let (v0, v) = (self.lo_values[i], self.scratch[i]);
            if self.reference[i] != 0.0 && v.is_finite() && (v - v0).abs() > v0.abs() {
                self.reference[i] = 0.0;
                self.enters[i] = false;
                self.quiet[i] = QuietRange::of(0.0, self.directions[i], self.departure_fires[i]);
            }
        }
        Ok(())
    }

    /// Guard `i`'s reference sign becomes the sign of its new value `v` (nonzero) without an
    /// event: on its holding side, that is the invariant's violation unless the guard is
    /// exempt.
    fn settle(&mut self, i: usize, v: f64) {
        self.reference[i] = sign(v);
        if self.reference[i] == self.holding[i] && !self.exempt[i] {
            self.violation.get_or_insert(i);
        }
        self.quiet[i] = QuietRange::of(
            self.reference[i],
            self.directions[i],
            self.departure_fires[i],
        );
    }

    /// Screening's first look at a step: estimates at 1/3 and 2/3 of it and the exact values
    /// at its ends define a cubic per guard; when every cubic keeps its sign with a margin of
    /// half its range, the guards are taken to stay clear of zero and the step's other
    /// interior points are skipped. A step is short against the guards' time scales (the
    /// error control keeps the state polynomial-like across it), so a guard that does change
    /// sign inside it shows it in its cubic; the margin covers the part that is not cubic.
    ///
    /// When the step's cubics do not clear it, each third of it is looked at the same way
    /// (two more estimates inside it, the values at its ends), and the check points in the
    /// thirds that clear are skipped: the same test on a part three times shorter, where the
    /// guards are closer still to cubics. The check points of the thirds that do not clear
    /// are screened one by one, as in a step whose cubics did not clear.
    fn cubic_clear<E>(
        &mut self,
        t0: f64,
        t1: f64,
        end_values: &[f64],
        cleared: &mut Cleared,
        eval: &mut impl FnMut(f64, Probe, &mut [f64]) -> Result<(), E>,
    ) -> Result<bool, E> {
        let h = t1 - t0;
        let (t_third, t_two_thirds) = (t0 + h / 3.0, t0 + 2.0 * h / 3.0);
        eval(t_third, Probe::Estimate, &mut self.scratch)?;
        if self.may_fire() {
            return Ok(false);
        }
        self.at_third.copy_from_slice(&self.scratch);
        eval(t_two_thirds, Probe::Estimate, &mut self.scratch)?;
        if self.may_fire() {
            return Ok(false);
        }
        self.at_two_thirds.copy_from_slice(&self.scratch);
        let (start, third, two_thirds) = (&self.lo_values, &self.at_third, &self.at_two_thirds);
        if (0..self.len())
            .all(|i| cubic_keeps_sign(start[i], third[i], two_thirds[i], end_values[i]))
        {
            return Ok(true);
        }
        // The thirds, each between two of the values above.
        let ends = [t0, t_third, t_two_thirds, t1];
        let mut values = [
            std::mem::take(&mut self.lo_values),
            std::mem::take(&mut self.at_third),
            std::mem::take(&mut self.at_two_thirds),
        ];
        let mut result = Ok(());
        for part in 0..3 {
            let (a, b) = (ends[part], ends[part + 1]);
            let (va, vb) = match part {
                2 => (&values[2][..], end_values),
                _ => (&values[part][..], &values[part + 1][..]),
            };
            match self.part_clear(a, b, va, vb, eval) {
                Ok(true) => cleared.push((a, b)),
                Ok(false) => {}
                Err(e) => {
                    result = Err(e);
                    break;
                }
            }
        }
        std::mem::swap(&mut self.lo_values, &mut values[0]);
        std::mem::swap(&mut self.at_third, &mut values[1]);
        std::mem::swap(&mut self.at_two_thirds, &mut values[2]);
        result.map(|()| false)
    }

    /// Whether the part `[a, b]` of a step, with guard values `va` at `a` and `vb` at `b`,
    /// clears by the cubic test of [`GuardTracker::cubic_clear`] (estimates at a third and
    /// two thirds of it).
    fn part_clear<E>(
        &mut self,
        a: f64,
        b: f64,
        va: &[f64],
        vb: &[f64],
        eval: &mut impl FnMut(f64, Probe, &mut [f64]) -> Result<(), E>,
    ) -> Result<bool, E> {
        let h = b - a;
        eval(a + h / 3.0, Probe::Estimate, &mut self.scratch)?;
        if self.may_fire() {
            return Ok(false);
        }
        self.inside_third.copy_from_slice(&self.scratch);
        eval(a + 2.0 * h / 3.0, Probe::Estimate, &mut self.scratch)?;
        if self.may_fire() {
            return Ok(false);
        }
        let (third, two_thirds) = (&self.inside_third, &self.scratch);
        Ok((0..self.len()).all(|i| cubic_keeps_sign(va[i], third[i], two_thirds[i], vb[i])))
    }

    /// Whether the values in `self.scratch` would fire a guard (or are not finite), judged
    /// against the reference signs: a departure or an admitted crossing.
    fn may_fire(&self) -> bool {
        self.scratch
            .iter()
            .zip(&self.quiet)
            .any(|(&v, q)| !q.contains(v))
    }

    /// The departure from zero of pending guard `i` to the value `v`, if it fires.
    pub(super) fn departure(&self, i: usize, v: f64) -> Option<Crossed> {
        if self.reference[i] != 0.0 || v == 0.0 || !self.departure_fires[i] {
            return None;
        }
        let c = if v > 0.0 { Crossed::Up } else { Crossed::Down };
        self.directions[i].admits(c).then_some(c)
    }

    /// The crossing of guard `i`'s reference sign by the value `v`, if its filter admits it.
    pub(super) fn admitted_crossing(&self, i: usize, v: f64) -> Option<Crossed> {
        crossing(self.reference[i], v).filter(|&c| self.directions[i].admits(c))
    }

    /// Locates the earliest admitted crossing before `hi`, each guard's from its own last
    /// value (`self.lo_values` at `self.lo_at`: the last check point, or its pass since);
    /// `self.scratch` holds the values at `hi`. Nothing is reported before the step's last
    /// pass.
    fn locate<E>(
        &mut self,
        hi: f64,
        eval: &mut impl FnMut(f64, Probe, &mut [f64]) -> Result<(), E>,
    ) -> Result<Option<Found>, E> {
        let n = self.len();
        let mut best: Option<Found> = None;
        for i in 0..n {
            let r = self.reference[i];
            let Some(c) = self.admitted_crossing(i, self.scratch[i]) else {
                continue;
            };
            let (upper, f_upper) = match best {
                None => (hi, self.scratch[i]),
                Some(b) => {
                    // Only a crossing already complete at the best time can be earlier.
                    if crossing(r, self.at_best[i]).is_none() {
                        continue;
                    }
                    (b.t, self.at_best[i])
                }
            };
            // The value at `lo` may be an exact zero left by a filtered crossing: any value of
            // the reference sign keeps the bracket valid (the finder then bisects).
            let f_lo = if self.lo_values[i] * r > 0.0 {
                self.lo_values[i]
            } else {
                r * f64::MIN_POSITIVE
            };
            let scratch = &mut self.at_best;
            let root = crate::root::find_crossing(self.lo_at[i], f_lo, upper, f_upper, r, |t| {
                eval(t, Probe::Exact, scratch)?;
                Ok(scratch[i])
            })?;
            let floor = self.walk.floor;
            let b = match best {
                Some(b) if b.t <= root.t.max(floor) => b,
                _ => Found {
                    index: i,
                    t: root.t.max(floor),
                    before: root.before,
                    direction: c,
                },
            };
            best = Some(b);
            // Keep `at_best` consistent with the best time for the next guards.
            if b.t == hi {
                self.at_best.copy_from_slice(&self.scratch);
            } else {
                eval(b.t, Probe::Exact, &mut self.at_best)?;
            }
        }
        Ok(best)
    }
}

/// The sign of the side where a guard with this filter holds (`0`: either side).
fn holding_sign(d: Direction) -> f64 {
    match d {
        Direction::Up => 1.0,
        Direction::Down => -1.0,
        Direction::Both => 0.0,
    }
}

/// The crossing that leads to the side of sign `s`.
fn crossed_to(s: f64) -> Crossed {
    if s > 0.0 {
        Crossed::Up
    } else {
        Crossed::Down
    }
}

#[inline]
fn sign(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests;
