//! Where inside a step the guards are looked at, and the cheap test that lets a screened step
//! skip most of its sample points (see [`crate::GuardSpec`]).

use crate::error::ParseSettingError;

/// Where, besides the step ends, a step is searched for guard crossings.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum InteriorChecks {
    /// Only at step ends.
    #[default]
    None,
    /// At this many evenly spaced interior points, each with an exact model evaluation.
    Exact(u32),
    /// At this many evenly spaced interior points, estimated from the dense output and its
    /// derivative without a model evaluation; a point whose estimate shows an admitted
    /// crossing or departure (or a non-finite value) is then evaluated exactly.
    Screened(u32),
}

impl InteriorChecks {
    /// The guard-check limit: the most interior points a step may be checked at. Each exact
    /// point costs an evaluation of the model per step; at this limit that is already a
    /// hundred times the work of a Runge–Kutta step, and `exact:4294967295` would never finish.
    pub const MAX_POINTS: u32 = 1024;

    /// Number of interior points.
    pub fn points(self) -> u32 {
        match self {
            InteriorChecks::None => 0,
            InteriorChecks::Exact(n) | InteriorChecks::Screened(n) => n,
        }
    }
}

/// Spelled `none`, `exact:N` or `screened:N`, as in scene files and command lines.
impl std::fmt::Display for InteriorChecks {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            InteriorChecks::None => f.write_str("none"),
            InteriorChecks::Exact(n) => write!(f, "exact:{n}"),
            InteriorChecks::Screened(n) => write!(f, "screened:{n}"),
        }
    }
}

impl std::str::FromStr for InteriorChecks {
    type Err = ParseSettingError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || {
            ParseSettingError {
            setting: "guard checks",
            text: s.to_owned(),
            expected: "none, exact:N or screened:N with N a whole number up to 1024 (the guard-check limit)",
        }
        };
        let points = |n: &str| {
            n.parse::<u32>()
                .ok()
                .filter(|&n| n <= Self::MAX_POINTS)
                .ok_or_else(bad)
        };
        match s.split_once(':') {
            None if s == "none" => Ok(InteriorChecks::None),
            Some(("exact", n)) => points(n).map(InteriorChecks::Exact),
            Some(("screened", n)) => points(n).map(InteriorChecks::Screened),
            _ => Err(bad()),
        }
    }
}

/// Whether the cubic through `(0, a)`, `(1/3, b)`, `(2/3, c)`, `(1, d)` keeps one sign on
/// `[0, 1]` with a margin of half its range (false when all four are NaN; the driver passes
/// only finite values).
///
/// It runs for every guard of every screened step, so it answers early where it can, always
/// with the value the full computation would give: the range only widens as the cubic's
/// interior extrema join the four values, and a wider range never turns "not clear" into
/// "clear". So the four values alone can say "not clear", and a cheap bound on every value the
/// cubic takes (no square root, no division) can say "clear".
pub(crate) fn cubic_keeps_sign(a: f64, b: f64, c: f64, d: f64) -> bool {
    /// Far more than the relative rounding of the coefficients, of Horner's rule and of the
    /// bound itself (a few units of 1e-16).
    const SLACK: f64 = 1e-12;
    let (lo, hi) = (a.min(b).min(c).min(d), a.max(b).max(c).max(d));
    if !clear(lo, hi) {
        return false;
    }
    // Newton's forward differences in u = 3s ∈ [0, 3], expanded to a + c1 u + c2 u² + c3 u³.
    let (d1, d2, d3) = (b - a, c - 2.0 * b + a, d - 3.0 * c + 3.0 * b - a);
    // On [0, 3], |c1| u + |c2| u² + |c3| u³ ≤ 3|c1| + 9|c2| + 27|c3| ≤ 3|d1| + 6|d2| + 10|d3|
    // (from the expansion in `with_interior_extrema`): every value computed there lies within
    // `a ± reach`.
    let reach = (3.0 * d1.abs() + 6.0 * d2.abs() + 10.0 * d3.abs() + SLACK * a.abs())
        * (1.0 + SLACK)
        + f64::MIN_POSITIVE;
    if clear(lo.min(a - reach), hi.max(a + reach)) {
        return true;
    }
    let (lo, hi) = with_interior_extrema(a, (d1, d2, d3), (lo, hi));
    clear(lo, hi)
}

/// Whether the range `[lo, hi]` stays clear of zero by half its width.
fn clear(lo: f64, hi: f64) -> bool {
    let margin = 0.5 * (hi - lo);
    lo > margin || hi < -margin
}

/// The range `(lo, hi)` widened by the values of the cubic `a + c1 u + c2 u² + c3 u³` at its
/// extrema inside `u ∈ (0, 3)`, the cubic given by its forward differences `(d1, d2, d3)`.
fn with_interior_extrema(a: f64, (d1, d2, d3): (f64, f64, f64), range: (f64, f64)) -> (f64, f64) {
    let (mut lo, mut hi) = range;
    let (c1, c2, c3) = (d1 - d2 / 2.0 + d3 / 3.0, (d2 - d3) / 2.0, d3 / 6.0);
    let p = |u: f64| a + u * (c1 + u * (c2 + u * c3));
    let mut visit = |u: f64| {
        if u > 0.0 && u < 3.0 {
            let v = p(u);
            lo = lo.min(v);
            hi = hi.max(v);
        }
    };
    // The extrema: roots of c1 + 2 c2 u + 3 c3 u².
    if c3 == 0.0 {
        if c2 != 0.0 {
            visit(-c1 / (2.0 * c2));
        }
    } else {
        let disc = c2 * c2 - 3.0 * c3 * c1;
        if disc >= 0.0 {
            let r = disc.sqrt();
            visit((-c2 + r) / (3.0 * c3));
            visit((-c2 - r) / (3.0 * c3));
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cubic_test_sees_a_crossing_between_its_points() {
        let at = |g: &dyn Fn(f64) -> f64| (g(0.0), g(1.0 / 3.0), g(2.0 / 3.0), g(1.0));
        let clear = |g: &dyn Fn(f64) -> f64| {
            let (a, b, c, d) = at(g);
            cubic_keeps_sign(a, b, c, d)
        };
        // Far from zero against its variation, either sign: clear.
        assert!(clear(&|s| -1.0 + 0.3 * s));
        assert!(clear(&|s| 2.0 - 0.5 * s * s));
        // All four values negative, but the cubic's bump at s ≈ 0.79 reaches +0.2.
        let bump = |s: f64| -1.0 + 25.0 * s * (1.0 - s) * (s - 0.5);
        let (a, b, c, d) = at(&bump);
        assert!(a < 0.0 && b < 0.0 && c < 0.0 && d < 0.0);
        assert!(!clear(&bump));
        // Approaching zero fast, touching it, or not a number: not clear.
        assert!(!clear(&|s| -1.0 + 0.9 * s));
        assert!(!clear(&|s| -s * s));
        assert!(!clear(&|_| f64::NAN));
    }

    /// The test without its early answers: the oracle for the fast one (the early answers
    /// must never change the verdict of the full range).
    fn cubic_keeps_sign_in_full(a: f64, b: f64, c: f64, d: f64) -> bool {
        let diffs = (b - a, c - 2.0 * b + a, d - 3.0 * c + 3.0 * b - a);
        let range = (a.min(b).min(c).min(d), a.max(b).max(c).max(d));
        let (lo, hi) = with_interior_extrema(a, diffs, range);
        clear(lo, hi)
    }

    /// Values near a decision: a smooth guard sampled at the four points, far from zero or
    /// close to it, with its slope and curvature on either side of the margin.
    fn near_decisions() -> impl Strategy<Value = (f64, f64, f64, f64)> {
        let scale = prop::sample::select(vec![1e-160, 1e-9, 1.0, 1e9, 1e160]);
        (
            -2.0..2.0f64,
            -3.0..3.0f64,
            -3.0..3.0f64,
            -30.0..30.0f64,
            scale,
        )
            .prop_map(|(mean, slope, curve, cubic, scale)| {
                let g = |s: f64| scale * (mean + s * (slope + s * (curve + s * cubic)));
                (g(0.0), g(1.0 / 3.0), g(2.0 / 3.0), g(1.0))
            })
    }

    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]

        #[test]
        fn the_early_answers_are_the_full_computations(
            (a, b, c, d) in near_decisions(),
        ) {
            prop_assert_eq!(cubic_keeps_sign(a, b, c, d), cubic_keeps_sign_in_full(a, b, c, d));
        }

        #[test]
        fn any_four_values_get_the_full_computations_answer(
            a in any::<f64>(), b in any::<f64>(), c in any::<f64>(), d in any::<f64>(),
        ) {
            prop_assert_eq!(cubic_keeps_sign(a, b, c, d), cubic_keeps_sign_in_full(a, b, c, d));
        }
    }

    #[test]
    fn interior_checks_are_spelled_and_read_back() {
        for c in [
            InteriorChecks::None,
            InteriorChecks::Exact(4),
            InteriorChecks::Screened(16),
        ] {
            assert_eq!(c.to_string().parse::<InteriorChecks>(), Ok(c));
        }
        for bad in [
            "",
            "some",
            "exact",
            "exact:",
            "exact:-1",
            "screened:2.5",
            "fast:3",
            "exact:1025",
            "exact:4294967295",
            "screened:4294967296",
        ] {
            let e = bad.parse::<InteriorChecks>().unwrap_err();
            assert!(e.to_string().contains(&format!("{bad:?}")), "{e}");
            let limit = format!(
                "up to {} (the guard-check limit)",
                InteriorChecks::MAX_POINTS
            );
            assert!(e.to_string().contains(&limit), "{e}");
        }
        assert_eq!("exact:1024".parse(), Ok(InteriorChecks::Exact(1024)));
    }
}
