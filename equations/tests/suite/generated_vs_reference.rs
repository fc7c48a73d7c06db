//! The generated models (the paper's boxes through the equation compiler) against the
//! hand-written reference, at 10⁴ random states per mode, half of them at the extremes:
//! θ within 1e-6 of 0 and of π/2, rates up to 1e3 rad/s, slip speeds down to 1e-12 m/s.
//!
//! Tolerance: every derivative and output agrees to `1e-12 · max(|a|, |b|, scale)`. The
//! derivative scales are the row scales of `common::scales` and the running rounding bounds of
//! the explicit forms (`common::tracked`), floored at ε times the largest scale of the same
//! units; the output scales follow from them through the output's formula (below).

use crate::common;
use crate::common::explicit;
use crate::common::subject::{
    eval, CartesianGen, CartesianRef, Eval, Family, RollingGen, RollingRef, SlidingGen, SlidingRef,
    CARTESIAN_OUTPUTS, ROLLING_OUTPUTS, SLIDING_OUTPUTS,
};
use crate::common::tracked::Tracked;
use crate::common::{scales, Agreement, Layout, Reach, Rng};
use equations::models;
use equations::reference::{rolling, sliding_cartesian as cart, sliding_polar as polar};
use equations::DiskParams;

const STATES_PER_REACH: usize = 5000;

/// The size of the contact force's rounding: `m (g + |V̇|)` with `|V̇|` at its row scale, plus
/// the air force.
fn force_scale(p: &DiskParams, row: &[f64; 12], dy: &[f64; 12], air_speed: f64) -> f64 {
    let accel = (3..6).map(|i| row[i].max(dy[i].abs())).fold(0.0, f64::max);
    p.m * (p.g.abs() + accel) + p.k_F() * air_speed
}

fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

#[allow(clippy::too_many_arguments)]
fn compare_common_outputs<const M: usize>(
    agreement: &mut Agreement,
    y: &[f64; 12],
    gen: &Eval<M>,
    refr: &Eval<M>,
    names: &[&str; M],
    idx: [usize; 4], // N, T, R_X, R_Y
    force: f64,
    energy_scale: f64,
) {
    let [n, t, rx, ry] = idx;
    for i in [n, t, rx, ry] {
        agreement.check(gen.out[i], refr.out[i], force, || {
            format!("{} at {y:?}", names[i])
        });
    }
    let nu = "nu";
    let k = names.iter().position(|x| *x == nu).unwrap();
    // ν = T/N: δν ≈ (δT + ν δN)/N.
    let nu_scale = (1.0 + refr.out[k].abs()) * force / refr.out[n].abs();
    agreement.check(gen.out[k], refr.out[k], nu_scale, || format!("nu at {y:?}"));
    let e = names.iter().position(|x| *x == "energy").unwrap();
    agreement.check(gen.out[e], refr.out[e], energy_scale, || {
        format!("energy at {y:?}")
    });
}

/// Energy's natural scale: the sum of the sizes of its terms.
fn energy_scale(p: &DiskParams, y: &[f64; 12], v_hor: f64) -> f64 {
    let w = [y[9], y[10], y[11]];
    0.5 * p.m * (v_hor * v_hor + y[5] * y[5])
        + 0.5 * p.A() * (w[0] * w[0] + w[1] * w[1])
        + 0.5 * p.C() * w[2] * w[2]
        + (p.m * p.g * y[2]).abs()
}

/// What a mode's comparison at one state expects, besides the two evaluations compared.
struct Expected {
    /// The explicit form's derivatives, with their running rounding bounds.
    dy: [Tracked; 12],
    /// The derivatives' row scales.
    row: [f64; 12],
    /// The speed the air drag acts on (for the force's rounding).
    air_speed: f64,
    /// The centre's horizontal speed (for the energy's scale).
    v_hor: f64,
}

/// The parts of one mode that the comparison needs.
struct ModeCase<const M: usize> {
    layout: &'static Layout,
    names: &'static [&'static str; M],
    /// Output indices of N, T, R_X, R_Y.
    forces: [usize; 4],
}

/// Checks the outputs `(index, scale)`.
fn check_outputs<const M: usize>(
    agreement: &mut Agreement,
    y: &[f64; 12],
    (gen, refr): (&Eval<M>, &Eval<M>),
    names: &[&str; M],
    outputs: &[(usize, f64)],
) {
    for &(i, scale) in outputs {
        agreement.check(gen.out[i], refr.out[i], scale, || {
            format!("{} at {y:?}", names[i])
        });
    }
}

/// The generated model `G` against the reference `R` at random states of one mode: both
/// against the explicit form and against each other, then the outputs every mode has;
/// `own(agreement, p, y, (gen, refr), expected, force)` checks the mode's own outputs.
fn agrees<G: Family<M>, R: Family<M>, const M: usize>(
    seed: u64,
    case: ModeCase<M>,
    state: impl Fn(&mut Rng, &DiskParams, Reach) -> [f64; 12],
    expected: impl Fn(&DiskParams, &[f64; 12]) -> Expected,
    own: impl Fn(&mut Agreement, &DiskParams, &[f64; 12], (&Eval<M>, &Eval<M>), &Expected, f64),
) {
    let mut rng = Rng::new(seed);
    let mut agreement = Agreement::default();
    for reach in [Reach::Typical, Reach::Extreme] {
        for _ in 0..STATES_PER_REACH {
            let p = common::some_params(&mut rng);
            let y = state(&mut rng, &p, reach);
            let gen =
                eval(&G::build(&p), &y).unwrap_or_else(|e| panic!("{}: {e} at {y:?}", G::NAME));
            let refr = eval(&R::build(&p), &y).unwrap();
            let ex = expected(&p, &y);
            agreement.check_derivatives(case.layout, &y, &gen.dy, &ex.dy, &ex.row);
            agreement.check_derivatives(case.layout, &y, &refr.dy, &ex.dy, &ex.row);
            let scale = std::array::from_fn(|i| ex.row[i].max(ex.dy[i].scale));
            agreement.check_derivative_pair(case.layout, &y, &gen.dy, &refr.dy, &scale);
            let force = force_scale(&p, &ex.row, &refr.dy, ex.air_speed);
            compare_common_outputs(
                &mut agreement,
                &y,
                &gen,
                &refr,
                case.names,
                case.forces,
                force,
                energy_scale(&p, &y, ex.v_hor),
            );
            own(&mut agreement, &p, &y, (&gen, &refr), &ex, force);
        }
    }
    agreement.assert_within(&format!("{} vs {}", G::NAME, R::NAME));
}

fn rolling_agrees<G: Family<ROLLING_OUTPUTS>, R: Family<ROLLING_OUTPUTS>>() {
    use rolling::output as o;
    let case = ModeCase {
        layout: &common::ROLLING,
        names: &rolling::OUTPUT_NAMES,
        forces: [o::N, o::T, o::R_X, o::R_Y],
    };
    let expected = |p: &DiskParams, y: &[f64; 12]| {
        let dy = explicit::rolling::<Tracked>(p, y).dy;
        let (sp, cp) = y[6].sin_cos();
        let (st, ct) = y[7].sin_cos();
        let v_z = (y[3] * cp + y[4] * sp) * st + y[5] * ct;
        Expected {
            row: scales::rolling(p, y, &dy.map(|x| x.v)),
            dy,
            air_speed: (v_z - p.w_z).abs(),
            v_hor: y[3].hypot(y[4]),
        }
    };
    let own = |agreement: &mut Agreement,
               p: &DiskParams,
               y: &[f64; 12],
               (gen, refr): (&Eval<ROLLING_OUTPUTS>, &Eval<ROLLING_OUTPUTS>),
               _: &Expected,
               force: f64| {
        let gap = angle_gap(gen.out[o::alpha_r], refr.out[o::alpha_r]);
        agreement.check(gap, 0.0, force / refr.out[o::T], || {
            format!("alpha_r at {y:?}")
        });
        let rim = p.a * (y[10].abs() + y[11].abs());
        let outputs = [
            (o::z_residual, y[2].abs() + p.a),
            (o::vz_residual, y[5].abs() + rim),
            (o::vx_residual, y[3].abs() + rim),
            (o::vy_residual, y[4].abs() + rim),
        ];
        check_outputs(agreement, y, (gen, refr), &rolling::OUTPUT_NAMES, &outputs);
    };
    agrees::<G, R, ROLLING_OUTPUTS>(51, case, common::rolling_state, expected, own);
}

fn sliding_agrees<G: Family<SLIDING_OUTPUTS>, R: Family<SLIDING_OUTPUTS>>() {
    use polar::output as o;
    let case = ModeCase {
        layout: &common::POLAR,
        names: &polar::OUTPUT_NAMES,
        forces: [o::N, o::T, o::R_X, o::R_Y],
    };
    let expected = |p: &DiskParams, y: &[f64; 12]| {
        let dy = explicit::sliding_polar::<Tracked>(p, y).dy;
        let row = scales::sliding_polar(p, y, &dy.map(|x| x.v));
        Expected {
            dy,
            air_speed: (-y[3] * (y[4] - y[6]).cos() * y[7].sin()).abs()
                + p.a * y[10].abs()
                + y[5].abs()
                + p.w_z.abs(),
            v_hor: row[0].hypot(row[1]),
            row,
        }
    };
    let own = |agreement: &mut Agreement,
               p: &DiskParams,
               y: &[f64; 12],
               evals: (&Eval<SLIDING_OUTPUTS>, &Eval<SLIDING_OUTPUTS>),
               ex: &Expected,
               force: f64| {
        let row = ex.row;
        let outputs = [
            (o::V_X, row[0]),
            (o::V_Y, row[1]),
            (o::friction_power, p.mu_d * force * y[3].abs()),
            (o::z_residual, y[2].abs() + p.a),
            (o::vz_residual, y[5].abs() + p.a * y[10].abs()),
        ];
        check_outputs(agreement, y, evals, &polar::OUTPUT_NAMES, &outputs);
    };
    agrees::<G, R, SLIDING_OUTPUTS>(52, case, common::sliding_state, expected, own);
}

/// The Cartesian chart's expectations; its row scales follow from the polar form's derivatives.
fn cartesian_expected(p: &DiskParams, y: &[f64; 12]) -> Expected {
    let polar_y = common::cartesian_to_polar(y);
    let polar_dy = explicit::sliding_polar::<f64>(p, &polar_y).dy;
    let row = scales::sliding_cartesian(p, &polar_y, &polar_dy);
    Expected {
        dy: explicit::sliding_cartesian::<Tracked>(p, y).dy,
        air_speed: polar_y[3].abs() + p.a * y[10].abs() + y[5].abs() + p.w_z.abs(),
        v_hor: row[0].hypot(row[1]),
        row,
    }
}

fn cartesian_agrees<G: Family<CARTESIAN_OUTPUTS>, R: Family<CARTESIAN_OUTPUTS>>() {
    use cart::output as o;
    let case = ModeCase {
        layout: &common::CARTESIAN,
        names: &cart::OUTPUT_NAMES,
        forces: [o::N, o::T, o::R_X, o::R_Y],
    };
    let state = |rng: &mut Rng, p: &DiskParams, reach| {
        common::polar_to_cartesian(&common::sliding_state(rng, p, reach))
    };
    let own = |agreement: &mut Agreement,
               p: &DiskParams,
               y: &[f64; 12],
               (gen, refr): (&Eval<CARTESIAN_OUTPUTS>, &Eval<CARTESIAN_OUTPUTS>),
               ex: &Expected,
               force: f64| {
        let row = ex.row;
        let speed = y[3].hypot(y[4]);
        let outputs = [
            (o::V_X, row[0]),
            (o::V_Y, row[1]),
            (o::slip_speed, speed),
            (o::friction_power, p.mu_d * force * speed),
            (o::z_residual, y[2].abs() + p.a),
            (o::vz_residual, y[5].abs() + p.a * y[10].abs()),
        ];
        check_outputs(agreement, y, (gen, refr), &cart::OUTPUT_NAMES, &outputs);
        let gap = angle_gap(gen.out[o::slip_direction], refr.out[o::slip_direction]);
        agreement.check(gap, 0.0, 1.0, || format!("slip_direction at {y:?}"));
    };
    agrees::<G, R, CARTESIAN_OUTPUTS>(53, case, state, cartesian_expected, own);
}

#[test]
fn generated_models_name_things_like_the_reference() {
    assert_eq!(models::rolling::STATE_NAMES, rolling::STATE_NAMES);
    assert_eq!(models::rolling::OUTPUT_NAMES, rolling::OUTPUT_NAMES);
    assert_eq!(models::sliding::STATE_NAMES, polar::STATE_NAMES);
    assert_eq!(models::sliding::OUTPUT_NAMES, polar::OUTPUT_NAMES);
    assert_eq!(models::sliding_cartesian::STATE_NAMES, cart::STATE_NAMES);
    assert_eq!(models::sliding_cartesian::OUTPUT_NAMES, cart::OUTPUT_NAMES);
    for names in [
        models::rolling::PARAM_NAMES,
        models::sliding::PARAM_NAMES,
        models::sliding_cartesian::PARAM_NAMES,
    ] {
        assert_eq!(names, DiskParams::NAMES);
    }
    let paper = DiskParams::paper().to_array().map(Some);
    assert_eq!(models::rolling::PARAM_DEFAULTS, paper);
    assert_eq!(models::sliding::PARAM_DEFAULTS, paper);
    assert_eq!(models::sliding_cartesian::PARAM_DEFAULTS, paper);
}

#[test]
fn generated_rolling_matches_the_reference() {
    rolling_agrees::<RollingGen, RollingRef>();
}

#[test]
fn generated_sliding_matches_the_reference() {
    sliding_agrees::<SlidingGen, SlidingRef>();
}

#[test]
fn generated_cartesian_sliding_matches_the_reference() {
    cartesian_agrees::<CartesianGen, CartesianRef>();
}

/// Slip exactly along an axis, or nearly: the Cartesian chart is regular there (only `u = 0`
/// is singular), so both implementations must agree as anywhere else.
#[test]
fn generated_cartesian_sliding_is_regular_along_the_axes() {
    let mut rng = Rng::new(54);
    let mut agreement = Agreement::default();
    for k in 0..2000 {
        let p = common::some_params(&mut rng);
        let mut y =
            common::polar_to_cartesian(&common::sliding_state(&mut rng, &p, Reach::Typical));
        let (small, large) = if k % 2 == 0 { (3, 4) } else { (4, 3) };
        y[small] = match k % 8 {
            0 | 1 => 0.0,
            _ => y[large] * rng.sign() * rng.log_uniform(1e-12, 1e-6),
        };
        let gen = eval(&CartesianGen::build(&p), &y)
            .unwrap_or_else(|e| panic!("{}: {e} at {y:?}", CartesianGen::NAME));
        let refr = eval(&CartesianRef::build(&p), &y).unwrap();
        let ex = cartesian_expected(&p, &y);
        agreement.check_derivatives(&common::CARTESIAN, &y, &gen.dy, &ex.dy, &ex.row);
        agreement.check_derivatives(&common::CARTESIAN, &y, &refr.dy, &ex.dy, &ex.row);
    }
    agreement.assert_within("cartesian sliding along the axes");
}

/// Expression swell fails here: the emitted code of each model stays within about 1.5 times
/// the operation counts measured when the models were written, and each pruned variant is
/// cheaper than its full model.
#[test]
fn generated_code_stays_small() {
    let bounds = [
        (&models::rolling::INFO, 150, 400),
        (&models::sliding::INFO, 240, 900),
        (&models::sliding_cartesian::INFO, 280, 1400),
    ];
    for (info, rhs, jac) in bounds {
        assert!(
            info.rhs_ops.total() <= rhs,
            "{}: rhs {:?}",
            info.name,
            info.rhs_ops
        );
        assert!(
            info.jacobian_ops.total() <= jac,
            "{}: jacobian {:?}",
            info.name,
            info.jacobian_ops
        );
        assert!(
            info.numeric_blocks.is_empty(),
            "{}: {:?}",
            info.name,
            info.numeric_blocks
        );
    }
    for (full, pruned) in [
        (&models::rolling::INFO, &models::rolling::pruned::INFO),
        (&models::sliding::INFO, &models::sliding::pruned::INFO),
        (
            &models::sliding_cartesian::INFO,
            &models::sliding_cartesian::pruned::INFO,
        ),
    ] {
        assert!(
            pruned.rhs_ops.total() < full.rhs_ops.total(),
            "{}",
            pruned.name
        );
        assert!(
            pruned.state_names.len() < full.state_names.len(),
            "{}",
            pruned.name
        );
        for dropped in ["X", "Y", "phi"] {
            assert!(
                !pruned.state_names.contains(dropped),
                "{}: {dropped}",
                pruned.name
            );
        }
    }
}
