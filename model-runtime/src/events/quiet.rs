//! The values of a guard that fire nothing, as an interval: screening's inner test.
//!
//! Every estimate and every check point asks, for each guard, whether its new value departs
//! from zero or crosses the reference sign in a direction the filter admits. Spelled out, that
//! is a handful of branches on the reference sign, the filter and the pending state; but those
//! change only when a reference sign does, so the answer is kept ready as an interval and the
//! question becomes two comparisons.

use super::direction::{Crossed, Direction};

/// The finite values that neither cross a guard's reference sign in a direction its filter
/// admits nor, while it is pending, depart from zero in a way that fires: a closed interval,
/// so that screening an estimate costs two comparisons per guard (NaN and infinities fall
/// outside it). The one definition of what fires stays in [`super::GuardTracker::departure`] and
/// [`super::GuardTracker::admitted_crossing`]; a unit test holds this range to them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct QuietRange {
    lo: f64,
    hi: f64,
}

impl QuietRange {
    /// The smallest positive value: `v < 0` is `v <= -TINY` for finite `v`.
    const TINY: f64 = f64::from_bits(1);

    /// The range for a guard with this reference sign (`0` while pending), filter, and
    /// whether its departure from zero fires.
    pub(super) fn of(reference: f64, direction: Direction, departure_fires: bool) -> Self {
        let (any, below, above) = (-f64::MAX..=f64::MAX, -f64::MAX..=0.0, 0.0..=f64::MAX);
        let range = if reference < 0.0 && direction.admits(Crossed::Up) {
            -f64::MAX..=-Self::TINY
        } else if reference > 0.0 && direction.admits(Crossed::Down) {
            Self::TINY..=f64::MAX
        } else if reference != 0.0 || !departure_fires {
            any
        } else {
            match (
                direction.admits(Crossed::Up),
                direction.admits(Crossed::Down),
            ) {
                (true, true) => 0.0..=0.0,
                (true, false) => below,
                (false, true) => above,
                (false, false) => any,
            }
        };
        QuietRange {
            lo: *range.start(),
            hi: *range.end(),
        }
    }

    /// Whether `v` fires nothing (false for NaN and infinities).
    #[inline]
    pub(super) fn contains(&self, v: f64) -> bool {
        v >= self.lo && v <= self.hi
    }
}

#[cfg(test)]
mod tests {
    use super::super::{GuardTracker, Quiet};
    use super::*;

    #[test]
    fn the_quiet_range_is_what_neither_departs_nor_crosses() {
        let values = [
            f64::NEG_INFINITY,
            -f64::MAX,
            -1.0,
            -f64::MIN_POSITIVE,
            -QuietRange::TINY,
            -0.0,
            0.0,
            QuietRange::TINY,
            1.0,
            f64::MAX,
            f64::INFINITY,
            f64::NAN,
        ];
        for reference in [-1.0, 0.0, 1.0] {
            for direction in [Direction::Up, Direction::Down, Direction::Both] {
                for fires in [false, true] {
                    let mut tr = GuardTracker::default();
                    tr.start([direction].into_iter(), &[reference], Quiet::None, true);
                    tr.departure_fires[0] = fires;
                    let range = QuietRange::of(reference, direction, fires);
                    for v in values {
                        let fires_now = !v.is_finite()
                            || tr.departure(0, v).is_some()
                            || tr.admitted_crossing(0, v).is_some();
                        assert_eq!(
                            range.contains(v),
                            !fires_now,
                            "{reference} {direction:?} {fires} {v}"
                        );
                    }
                }
            }
        }
    }
}
