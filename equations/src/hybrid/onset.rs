//! The consistent slip direction at the onset of sliding (docs/physics.md §7.1).
//!
//! At `v_C = 0` the sliding equations leave the friction direction `α` free, but only a few
//! directions are consistent: those where the contact particle's acceleration is parallel to the
//! slip it starts (`w(α) = 0`) and points away from rest (`v̇_C(α) > 0`). Starting anywhere else
//! makes `α̇ = w / v_C` unbounded, which is what broke an independent polar-chart run. The
//! search is one-dimensional and periodic, so it is done here once for every chart and model:
//! the caller supplies `α ↦ (v̇_C, w)` and receives the root nearest the direction of the
//! friction that rolling needed.

use model_runtime::find_crossing;
use model_runtime::EvalError;
use std::f64::consts::PI;

/// The contact particle's acceleration at zero slip, split along the slip direction
/// `e_s = -(cos α, sin α)` and across it, `e_s⊥ = (sin α, -cos α)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlipAcceleration {
    /// `v̇_C`: growth rate of the slip speed (m/s²).
    pub along: f64,
    /// `w = v_C α̇`: the part that turns the slip (m/s²).
    pub across: f64,
}

/// A consistent onset direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlipOnset {
    /// The consistent friction direction `α0` (rad), within `π` of `guess`.
    pub direction: f64,
    /// The first guess: the direction of the friction rolling needed, `α_r`.
    pub guess: f64,
    /// Contact acceleration at `α0`; `across` is zero to round-off, and `along > 0` unless the
    /// onset is of second order.
    pub acceleration: SlipAcceleration,
    /// Whether small deviations from `α0` die out as the slip grows (`dw/dα < 0` at the root),
    /// so that the onset does not depend on how exactly sliding is started.
    pub attracting: bool,
    /// Whether the slip leaves zero at second order: `|v̇_C|` at `α0` is below 1e-9 of the
    /// contact acceleration with the friction reversed, i.e. zero to round-off. This is the
    /// onset at `μ_st = μ_d` (docs/physics.md §7.1): sliding friction equals the friction that
    /// rolling needed, the contact accelerates by nothing at first order, and the slip grows as
    /// `½ v̈_C s²` from the friction limit on. `acceleration.along` is then no usable rate.
    pub second_order: bool,
    /// Evaluations of the sliding model spent.
    pub evaluations: u32,
}

/// Why no consistent onset direction exists.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum OnsetError {
    /// No direction has `w = 0` with `v̇_C > 0` (or `v̇_C` zero to round-off): the slip cannot
    /// start in any direction.
    #[error("no consistent slip direction: no root of w(alpha) with dv_C/dt > 0 (searched around alpha_r = {guess})")]
    NoConsistentDirection {
        /// The direction of the friction rolling needed.
        guess: f64,
    },
    /// The sliding model failed at a probed direction.
    #[error("sliding model failed at alpha = {alpha}: {source}")]
    Model {
        /// The probed direction.
        alpha: f64,
        /// The model's error.
        source: EvalError,
    },
}

/// Angular resolution of the outward scan: two roots closer than this may be seen as none.
const SCAN_STEP: f64 = PI / 90.0;

/// A slip rate `|v̇_C|` at onset below this fraction of the contact acceleration's size is zero
/// to round-off (~1e-15 of it) or a friction jump `μ_st − μ_d` below ~1e-10: the slip leaves
/// zero at second order ([`SlipOnset::second_order`]).
const DEGENERATE_GROWTH: f64 = 1e-9;

/// Finds the consistent slip direction nearest `guess` (docs/physics.md §7.1).
///
/// `accel(α)` must return the contact acceleration at zero slip with friction direction `α`.
/// The size of the contact acceleration with the friction reversed (at `guess + π`) sets the
/// scale of round-off. If `w(guess)` already vanishes to round-off (e.g. by symmetry) `guess`
/// is returned as is. Otherwise the scan walks outward from `guess` in both directions in steps
/// of 2°, and the first bracket of a sign change of `w` whose root has `v̇_C > 0` is refined to
/// a few ulps. A root whose `|v̇_C|` is below 1e-9 of the scale counts as `v̇_C = 0` (its sign
/// is round-off) and is admissible: the slip leaves it at second order, which the caller must
/// start differently ([`SlipOnset::second_order`]).
pub fn consistent_slip_direction(
    guess: f64,
    mut accel: impl FnMut(f64) -> Result<SlipAcceleration, EvalError>,
) -> Result<SlipOnset, OnsetError> {
    let alpha = guess + PI;
    let reversed = accel(alpha).map_err(|source| OnsetError::Model { alpha, source })?;
    let floor = DEGENERATE_GROWTH * reversed.along.hypot(reversed.across);
    let mut onset = nearest_root(guess, floor, &mut accel)?;
    onset.evaluations += 1;
    onset.second_order = onset.acceleration.along <= floor;
    Ok(onset)
}

/// The root of `w` with `v̇_C > -floor` nearest `guess` (see [`consistent_slip_direction`]).
fn nearest_root(
    guess: f64,
    floor: f64,
    mut accel: impl FnMut(f64) -> Result<SlipAcceleration, EvalError>,
) -> Result<SlipOnset, OnsetError> {
    let mut evaluations = 0u32;
    let mut eval = |alpha: f64| {
        evaluations += 1;
        accel(alpha).map_err(|source| OnsetError::Model { alpha, source })
    };
    let at_guess = eval(guess)?;
    let scale = at_guess.along.hypot(at_guess.across);
    if at_guess.along > -floor && at_guess.across.abs() <= 8.0 * f64::EPSILON * scale {
        let right = eval(guess + SCAN_STEP)?;
        return Ok(SlipOnset {
            direction: guess,
            guess,
            acceleration: at_guess,
            attracting: right.across < 0.0,
            second_order: false,
            evaluations,
        });
    }
    // Outward scan: `left`/`right` are the inner ends of the next brackets on each side.
    let (mut left_alpha, mut left) = (guess, at_guess);
    let (mut right_alpha, mut right) = (guess, at_guess);
    let steps = (PI / SCAN_STEP).ceil() as usize;
    for k in 1..=steps {
        let r_alpha = guess + k as f64 * SCAN_STEP;
        let r = eval(r_alpha)?;
        let l_alpha = guess - k as f64 * SCAN_STEP;
        let l = eval(l_alpha)?;
        let mut best: Option<(f64, SlipAcceleration, bool)> = None;
        for (lo, f_lo, hi, f_hi) in [
            (right_alpha, right, r_alpha, r),
            (l_alpha, l, left_alpha, left),
        ] {
            if f_lo.across.signum() == f_hi.across.signum() && f_hi.across != 0.0 {
                continue;
            }
            let root = refine(lo, f_lo.across, hi, f_hi.across, &mut eval)?;
            let at_root = eval(root)?;
            let nearer = match best {
                None => true,
                Some((b, _, _)) => (root - guess).abs() < (b - guess).abs(),
            };
            if at_root.along > -floor && nearer {
                // w falls through zero as alpha grows: deviations shrink (dα/d ln t = w/v̇_C).
                best = Some((root, at_root, f_lo.across > 0.0));
            }
        }
        if let Some((direction, acceleration, attracting)) = best {
            return Ok(SlipOnset {
                direction,
                guess,
                acceleration,
                attracting,
                second_order: false,
                evaluations,
            });
        }
        (right_alpha, right) = (r_alpha, r);
        (left_alpha, left) = (l_alpha, l);
    }
    Err(OnsetError::NoConsistentDirection { guess })
}

/// Refines a sign change of `w` on `[lo, hi]` to a few ulps.
fn refine(
    lo: f64,
    w_lo: f64,
    hi: f64,
    w_hi: f64,
    eval: &mut impl FnMut(f64) -> Result<SlipAcceleration, OnsetError>,
) -> Result<f64, OnsetError> {
    if w_lo == 0.0 {
        return Ok(lo);
    }
    let crossing = find_crossing(lo, w_lo, hi, w_hi, w_lo.signum(), |alpha| {
        eval(alpha).map(|a| a.across)
    })?;
    // The far-side point or the near-side one, whichever has the smaller |w|.
    let near = eval(crossing.before)?.across;
    Ok(if near.abs() < crossing.value.abs() {
        crossing.before
    } else {
        crossing.t
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An anisotropic "contact inverse inertia": acceleration `G f` for friction along `f`.
    fn anisotropic(alpha: f64) -> SlipAcceleration {
        // Friction force direction f = (cos α, sin α); slip direction e_s = -f.
        let (s, c) = alpha.sin_cos();
        let push = [0.8, -0.3]; // acceleration the contact would have without friction
        let g = [[2.0, 0.7], [0.7, 1.0]];
        let mu_n = 0.4;
        let acc = [
            push[0] + mu_n * (g[0][0] * c + g[0][1] * s),
            push[1] + mu_n * (g[1][0] * c + g[1][1] * s),
        ];
        SlipAcceleration {
            along: -(acc[0] * c + acc[1] * s),
            across: acc[0] * s - acc[1] * c,
        }
    }

    #[test]
    fn the_root_is_consistent_to_round_off() {
        let guess = (-0.3f64).atan2(0.8) + PI;
        let onset = consistent_slip_direction(guess, |a| Ok(anisotropic(a))).unwrap();
        let at = anisotropic(onset.direction);
        assert!(at.across.abs() <= 1e-15, "{onset:?}");
        assert!(at.along > 0.0);
        assert!((onset.direction - guess).abs() < PI);
    }

    #[test]
    fn a_symmetric_guess_is_kept_exactly() {
        let f = |alpha: f64| {
            Ok(SlipAcceleration {
                along: 2.0 - alpha.cos(),
                across: 0.5 * (alpha - PI).sin(),
            })
        };
        let onset = consistent_slip_direction(PI, f).unwrap();
        assert_eq!(onset.direction, PI);
    }

    #[test]
    fn no_admissible_root_is_a_typed_error() {
        let f = |alpha: f64| {
            Ok(SlipAcceleration {
                along: -1.0,
                across: alpha.sin(),
            })
        };
        assert!(matches!(
            consistent_slip_direction(0.3, f),
            Err(OnsetError::NoConsistentDirection { .. })
        ));
    }

    /// Sliding friction equal to what rolling needed (`μ_st = μ_d`): the contact acceleration
    /// vanishes at `α_r` itself, `v̇_C` there is round-off of either sign, and the root is
    /// still the onset, of second order. A `v̇_C` just above round-off is first order.
    #[test]
    fn a_slip_rate_at_round_off_is_a_second_order_onset() {
        for (jump, second_order) in [(0.0, true), (-3e-14, true), (3e-14, true), (1e-6, false)] {
            // G f − G f_r, with G the isotropic unit response and f_r along α_r = π, plus a
            // friction jump along the slip.
            let f = move |alpha: f64| {
                let (s, c) = f64::sin_cos(alpha);
                let acc = [c + 1.0, s];
                Ok(SlipAcceleration {
                    along: jump - (acc[0] * c + acc[1] * s),
                    across: acc[0] * s - acc[1] * c,
                })
            };
            let onset = consistent_slip_direction(PI + 0.1, f).unwrap();
            assert!((onset.direction - PI).abs() < 1e-12, "{jump}: {onset:?}");
            assert_eq!(onset.second_order, second_order, "{jump}: {onset:?}");
        }
    }

    #[test]
    fn the_nearest_admissible_root_wins() {
        // Roots of sin(2α) at 0, π/2, π, 3π/2; v̇_C > 0 only near π/2 and 3π/2.
        let f = |alpha: f64| {
            Ok(SlipAcceleration {
                along: alpha.sin().abs() - 0.5,
                across: (2.0 * alpha).sin(),
            })
        };
        let onset = consistent_slip_direction(2.0, f).unwrap();
        assert!((onset.direction - PI / 2.0).abs() < 1e-14, "{onset:?}");
        let onset = consistent_slip_direction(4.0, f).unwrap();
        assert!((onset.direction - 1.5 * PI).abs() < 1e-14, "{onset:?}");
    }
}
