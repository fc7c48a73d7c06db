//! The two sliding charts describe one motion: mapping a polar state to the Cartesian chart
//! and the polar derivatives through `u̇ = v̇_C e_s + v_C α̇ e_s⊥` must give the Cartesian
//! derivatives, and every shared output must agree.

use crate::common;
use crate::common::subject::{
    eval, CartesianGen, CartesianRef, Family, SlidingGen, SlidingRef, CARTESIAN_OUTPUTS,
    SLIDING_OUTPUTS,
};
use crate::common::tracked::Tracked;
use crate::common::{explicit, scales, Reach, Rng};
use equations::reference::{sliding_cartesian as cart, sliding_polar as polar};

const STATES: usize = 3000;

fn charts_agree<P: Family<SLIDING_OUTPUTS>, C: Family<CARTESIAN_OUTPUTS>>() {
    let mut rng = Rng::new(41);
    let mut agreement = common::Agreement::default();
    for reach in [Reach::Typical, Reach::Extreme] {
        for _ in 0..STATES {
            let p = common::some_params(&mut rng);
            let y = common::sliding_state(&mut rng, &p, reach);
            let yc = common::polar_to_cartesian(&y);
            let ep = eval(&P::build(&p), &y).unwrap();
            let ec = eval(&C::build(&p), &yc).unwrap();
            let (v_c, alpha) = (y[polar::state::v_C], y[polar::state::alpha]);
            let (sa, ca) = alpha.sin_cos();
            let (vd, ad) = (ep.dy[polar::state::v_C], ep.dy[polar::state::alpha]);
            let mut mapped = ep.dy;
            mapped[cart::state::u_X] = -vd * ca + v_c * ad * sa;
            mapped[cart::state::u_Y] = -vd * sa - v_c * ad * ca;
            // Row scales, and the rounding bounds of the explicit forms in both charts (angles
            // many turns from zero carry rounding proportional to their size).
            let ex_polar = explicit::sliding_polar::<Tracked>(&p, &y);
            let ex_cart = explicit::sliding_cartesian::<Tracked>(&p, &yc);
            let rows = scales::sliding_cartesian(&p, &y, &ep.dy);
            let pair = ex_polar.dy[3].scale + v_c.abs() * ex_polar.dy[4].scale;
            let scales: [f64; 12] = std::array::from_fn(|i| {
                let polar_scale = if i == 3 || i == 4 {
                    pair
                } else {
                    ex_polar.dy[i].scale
                };
                rows[i].max(polar_scale).max(ex_cart.dy[i].scale)
            });
            agreement.check_derivative_pair(&common::CARTESIAN, &y, &ec.dy, &mapped, &scales);
            let force = p.m * (p.g + rows[polar::state::V_Z]);
            for (ci, pi, scale) in [
                (cart::output::N, polar::output::N, force),
                (cart::output::T, polar::output::T, force),
                (cart::output::R_X, polar::output::R_X, force),
                (cart::output::R_Y, polar::output::R_Y, force),
                (cart::output::nu, polar::output::nu, p.mu_d),
                (cart::output::V_X, polar::output::V_X, rows[0]),
                (cart::output::V_Y, polar::output::V_Y, rows[1]),
                (
                    cart::output::energy,
                    polar::output::energy,
                    ec.out[cart::output::energy].abs(),
                ),
                (cart::output::z_residual, polar::output::z_residual, p.a),
                (
                    cart::output::vz_residual,
                    polar::output::vz_residual,
                    rows[2],
                ),
            ] {
                agreement.check(ec.out[ci], ep.out[pi], scale, || {
                    format!("{} at {y:?}", cart::OUTPUT_NAMES[ci])
                });
            }
            agreement.check(ec.out[cart::output::slip_speed], v_c, v_c, || {
                format!("v_C at {y:?}")
            });
            let turned =
                (ec.out[cart::output::slip_direction] - alpha).rem_euclid(std::f64::consts::TAU);
            let off = turned.min(std::f64::consts::TAU - turned);
            agreement.check(off, 0.0, 1.0 + alpha.abs(), || format!("alpha at {y:?}"));
        }
    }
    agreement.assert_within(&format!("{} vs {}", P::NAME, C::NAME));
}

#[test]
fn reference_charts_agree() {
    charts_agree::<SlidingRef, CartesianRef>();
}

#[test]
fn generated_charts_agree() {
    charts_agree::<SlidingGen, CartesianGen>();
}
