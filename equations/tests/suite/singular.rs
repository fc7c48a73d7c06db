//! Singular and bad states give typed errors naming the pivot, never NaN: the flat disk
//! (`sin θ = 0`), zero slip in the slip charts, the sliding determinant `β0 = 0`, and
//! non-finite input. Bad parameters are rejected by name before any model is built.

use crate::common::subject::{
    eval, CartesianGen, CartesianRef, Family, RollingGen, RollingRef, SlidingGen, SlidingRef,
};
use equations::formulas;
use equations::reference::{RollingReference, SlidingPolarReference, Slip};
use equations::{DiskParams, ParamError};
use model_runtime::{EvalError, Model};
use std::f64::consts::PI;

fn a_state() -> [f64; 12] {
    let p = DiskParams::paper();
    let theta: f64 = 0.6;
    [
        0.1,
        -0.2,
        p.a * theta.sin(),
        0.3,
        -0.1,
        0.05,
        0.4,
        theta,
        1.0,
        2.0,
        -1.5,
        7.0,
    ]
}

fn pivot_of<M: Model<12>>(model: &M, y: &[f64; 12]) -> String {
    let mut dy = [0.0; 12];
    match model.rhs(0.0, y, &mut dy) {
        Err(EvalError::SingularPivot { pivot, value, .. }) => {
            assert!(
                value == 0.0 || !value.is_finite() || value.abs() < 1e-12,
                "{pivot} = {value}"
            );
            pivot.to_string()
        }
        other => panic!(
            "{}: expected a singular pivot at {y:?}, got {other:?} with {dy:?}",
            model.info().name
        ),
    }
}

#[test]
fn a_flat_disk_is_singular_in_every_model() {
    let p = DiskParams::paper();
    let mut y = a_state();
    y[7] = 0.0;
    assert_eq!(pivot_of(&RollingRef::build(&p), &y), "sin(theta)");
    assert_eq!(pivot_of(&SlidingRef::build(&p), &y), "sin(theta)");
    assert_eq!(pivot_of(&CartesianRef::build(&p), &y), "sin(theta)");
    assert!(pivot_of(&RollingGen::build(&p), &y).contains("sin(theta)"));
    assert!(pivot_of(&SlidingGen::build(&p), &y).contains("sin(theta)"));
    assert!(pivot_of(&CartesianGen::build(&p), &y).contains("sin(theta)"));
}

#[test]
fn zero_slip_is_singular_in_the_slip_charts() {
    let p = DiskParams::paper();
    let mut y = a_state();
    y[3] = 0.0;
    y[4] = 0.0;
    assert_eq!(pivot_of(&SlidingRef::build(&p), &y), "v_C");
    assert_eq!(pivot_of(&CartesianRef::build(&p), &y), "v_C");
    assert!(pivot_of(&SlidingGen::build(&p), &y).contains("v_C"));
    // The generated Cartesian model divides by |u| = sqrt(u_X^2 + u_Y^2) (the direction
    // `alpha = atan2(-u_Y, -u_X)` becomes `-u/|u|`): the radicand is a checked pivot.
    assert_eq!(pivot_of(&CartesianGen::build(&p), &y), "u_X^2 + u_Y^2");
    // The onset helper stays regular there.
    let onset = SlidingPolarReference::new(p)
        .unwrap()
        .slip_acceleration(
            &y,
            Slip {
                speed: 0.0,
                alpha: 1.0,
            },
        )
        .unwrap();
    assert!(onset.along.is_finite() && onset.across.is_finite());
}

/// The Painlevé regime (docs/physics.md §10): `β0 = A + m a² cos θ (μ_d cos(α - ψ) sin θ + cos θ)`
/// can vanish once `μ_d ≥ √5/2`; with `μ_d = 3` and `cos(α - ψ) = -1`,
/// `β0(θ) / m a² = 1/4 + cos²θ - 3 sin θ cos θ`: -3/4 at π/4, 1/4 at π/2.
fn painleve_disk() -> DiskParams {
    DiskParams {
        mu_d: 3.0,
        mu_st: 3.0,
        ..DiskParams::paper()
    }
}

/// The inclination where `β0` vanishes for `α - ψ = π`, by bisection of `formulas::beta0`.
fn beta0_root(p: &DiskParams) -> f64 {
    let (mut lo, mut hi) = (PI / 4.0, PI / 2.0);
    assert!(formulas::beta0(p, lo, PI) < 0.0 && formulas::beta0(p, hi, PI) > 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if formulas::beta0(p, mid, PI) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// A sliding state at inclination `theta` with `α - ψ = π`, in the polar slip chart.
fn painleve_state(p: &DiskParams, theta: f64) -> [f64; 12] {
    let mut y = a_state();
    y[2] = p.a * theta.sin();
    y[7] = theta;
    y[6] = 0.2;
    y[4] = 0.2 + PI;
    y
}

/// The same state in the Cartesian slip chart, `u = -v_C (cos α, sin α)`.
fn in_cartesian_chart(polar: &[f64; 12]) -> [f64; 12] {
    let mut y = *polar;
    y[3] = -polar[3] * polar[4].cos();
    y[4] = -polar[3] * polar[4].sin();
    y
}

/// The generated models' text of `β0`.
fn beta0_pivot(info: &model_runtime::ModelInfo) -> &str {
    let beta = (info.pivots.iter()).find(|p| p.contains("mu_d") && p.contains("cos(theta)"));
    beta.unwrap_or_else(|| panic!("{}: no β0 among {:?}", info.name, info.pivots))
}

/// At the root `β0` is round-off (its terms cancel to ~1e-16 of their size): every sliding
/// model refuses the state by naming it, where an exact-zero test would let it through with
/// accelerations of ~1e17.
#[test]
fn the_painleve_determinant_is_a_named_pivot_at_its_root() {
    let p = painleve_disk();
    let theta = beta0_root(&p);
    let y = painleve_state(&p, theta);
    // The bisection's root is a root to round-off: β0 is ~1e-15 of its terms (A is one).
    let beta0 = formulas::beta0(&p, theta, PI);
    assert!(beta0.abs() < 1e-14 * p.A(), "β0 = {beta0:e} at the root");
    assert_eq!(pivot_of(&SlidingRef::build(&p), &y), "beta0");
    let info = &equations::models::sliding::INFO;
    assert_eq!(pivot_of(&SlidingGen::build(&p), &y), beta0_pivot(info));
    let info = &equations::models::sliding_cartesian::INFO;
    let yc = in_cartesian_chart(&y);
    assert_eq!(pivot_of(&CartesianGen::build(&p), &yc), beta0_pivot(info));
}

/// A little away from the root `β0` is small but holds its digits: the generated models give
/// the (large) accelerations the hand-written reference gives.
#[test]
fn near_the_painleve_root_the_answer_is_finite_and_right() {
    let p = painleve_disk();
    let root = beta0_root(&p);
    let regular = eval(&SlidingRef::build(&p), &painleve_state(&p, 1.2)).unwrap();
    for offset in [1e-4, -1e-6] {
        let y = painleve_state(&p, root + offset);
        let want = eval(&SlidingRef::build(&p), &y).unwrap().dy;
        let polar = eval(&SlidingGen::build(&p), &y).unwrap().dy;
        let yc = in_cartesian_chart(&y);
        let want_c = eval(&CartesianRef::build(&p), &yc).unwrap().dy;
        let cartesian = eval(&CartesianGen::build(&p), &yc).unwrap().dy;
        // der(Omega_y) = ... / β0 is large here: this is the near-singular regime.
        assert!(
            want[10].abs() > 30.0 * regular.dy[10].abs(),
            "{offset}: {} vs {}",
            want[10],
            regular.dy[10]
        );
        let size = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for k in 0..12 {
            for (got, want, chart) in [
                (polar[k], want[k], "polar"),
                (cartesian[k], want_c[k], "cartesian"),
            ] {
                assert!(
                    (got - want).abs() <= 1e-9 * size,
                    "{chart} der {k} at θ = root + {offset}: {got} vs {want}"
                );
            }
        }
    }
}

/// A hybrid run started sliding exactly at the root stops with a typed error naming `β0` and
/// the time.
#[test]
fn a_hybrid_run_at_the_painleve_root_reports_the_pivot_and_the_time() {
    use equations::SlipChart;
    use equations::{simulate, GeneratedModels, SimError};
    use equations::{DiskConfig, InitialState, Integrator};
    use model_runtime::SolveError;

    let p = painleve_disk();
    let theta = beta0_root(&p);
    let (psi, w) = (
        0.2,
        formulas::BodyRates {
            omega_x: 2.0,
            omega_y: -1.5,
            omega_z: 7.0,
        },
    );
    let rolling = formulas::rolling_consistent(&p, psi, theta, &w);
    // The contact particle slips along (cos ψ, sin ψ): the friction force points the other
    // way, `α = ψ + π`.
    let slip = 0.3;
    let mut y = [0.0; 12];
    y[2] = rolling.z;
    y[3] = rolling.velocity.x + slip * psi.cos();
    y[4] = rolling.velocity.y + slip * psi.sin();
    y[5] = rolling.velocity.z;
    y[6] = psi;
    y[7] = theta;
    y[9] = w.omega_x;
    y[10] = w.omega_y;
    y[11] = w.omega_z;
    let initial = InitialState::from_velocity(&p, 0.25, y);
    let config = DiskConfig {
        integrator: Integrator::Dop853,
        t_end: 1.0,
        ..DiskConfig::paper()
    };
    let models = GeneratedModels::generated(p, SlipChart::Cartesian).unwrap();
    let error = simulate(&models, &config, &initial, &mut ())
        .unwrap_err()
        .error;
    let (t, source) = match &error {
        SimError::Transition { t, source, .. } => (*t, source.clone()),
        SimError::Solve {
            error: SolveError::Eval { t, source },
            ..
        } => (*t, source.clone()),
        other => panic!("expected the β0 pivot, got {other:?}"),
    };
    // In still air the run integrates the Cartesian chart's `still` variant: its pivot, by
    // its name.
    let info = model_runtime::Model::info(&models.sliding);
    assert_eq!(
        info.name,
        equations::models::sliding_cartesian::still::INFO.name
    );
    match source {
        EvalError::SingularPivot { pivot, model, .. } => {
            assert_eq!(pivot, beta0_pivot(info));
            assert_eq!(model, info.name);
        }
        other => panic!("expected the β0 pivot, got {other:?}"),
    }
    assert_eq!(t, 0.25);
    let message = error.to_string();
    println!("{message}");
    assert!(
        message.contains("t = 0.25") && message.contains(beta0_pivot(info)),
        "{message}"
    );
}

#[test]
fn non_finite_input_is_an_error_not_a_nan() {
    let p = DiskParams::paper();
    // Every slot for the reference (it checks its input); the slots that feed the
    // derivatives for the generated models.
    for k in [0, 3, 7, 9, 11] {
        let mut y = a_state();
        y[k] = f64::NAN;
        let check = |r: Result<(), EvalError>, dy: &[f64; 12], name: &str| match r {
            Err(_) => {}
            Ok(()) => panic!("{name}: NaN in slot {k} gave {dy:?}"),
        };
        let mut dy = [0.0; 12];
        check(
            RollingRef::build(&p).rhs(0.0, &y, &mut dy),
            &dy,
            "rolling reference",
        );
        check(
            SlidingRef::build(&p).rhs(0.0, &y, &mut dy),
            &dy,
            "sliding reference",
        );
        check(
            CartesianRef::build(&p).rhs(0.0, &y, &mut dy),
            &dy,
            "cartesian reference",
        );
        if k == 0 {
            continue;
        }
        check(
            RollingGen::build(&p).rhs(0.0, &y, &mut dy),
            &dy,
            "rolling generated",
        );
        check(
            SlidingGen::build(&p).rhs(0.0, &y, &mut dy),
            &dy,
            "sliding generated",
        );
        check(
            CartesianGen::build(&p).rhs(0.0, &y, &mut dy),
            &dy,
            "cartesian generated",
        );
    }
}

#[test]
fn outputs_never_report_nan() {
    // Zero normal force makes ν = T/N undefined: an error naming `nu`, never a NaN.
    let p = DiskParams::paper();
    let model = RollingReference::new(p).unwrap();
    let y = a_state();
    let e = eval(&model, &y).unwrap();
    assert!(e.out.iter().all(|x| x.is_finite()));
    let mut out = [0.0; 11];
    let mut dy = e.dy;
    dy[5] = -p.g; // free fall: N = m (V̇_Z + g) = 0
    let err = model_runtime::WithOutputs::outputs(&model, 0.0, &y, &dy, &mut out).unwrap_err();
    assert!(
        matches!(&err, EvalError::NonFinite { quantity, .. } if quantity == "nu"),
        "{err:?}"
    );
}

#[test]
fn bad_parameters_are_refused_by_name() {
    let bad = DiskParams {
        a: -0.01,
        ..DiskParams::paper()
    };
    assert_eq!(
        RollingReference::new(bad).unwrap_err(),
        ParamError::NotPositive {
            name: "a",
            value: -0.01
        }
    );
    assert!(SlidingPolarReference::new(DiskParams {
        mu_a: f64::NAN,
        ..DiskParams::paper()
    })
    .is_err());
}

/// Evaluates `rhs` and then `outputs`; any `Ok` must hold only finite numbers.
fn number_or_error<M: model_runtime::WithOutputs<12, K>, const K: usize>(
    model: &M,
    y: &[f64; 12],
) -> Result<(), String> {
    let mut dy = [0.0; 12];
    if model.rhs(0.0, y, &mut dy).is_err() {
        return Ok(());
    }
    if dy.iter().any(|v| !v.is_finite()) {
        return Err(format!("{}: rhs gave {dy:?}", model.info().name));
    }
    let mut out = [0.0; K];
    if model.outputs(0.0, y, &dy, &mut out).is_ok() && out.iter().any(|v| !v.is_finite()) {
        return Err(format!("{}: outputs gave {out:?}", model.info().name));
    }
    Ok(())
}

fn any_number() -> impl proptest::strategy::Strategy<Value = f64> {
    use proptest::prelude::*;
    prop_oneof![
        -10.0..10.0f64,
        -1e3..1e3f64,
        prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO,
    ]
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(3000))]

    /// Any finite state, however absurd: a number or a typed error, never NaN or infinity.
    #[test]
    fn every_model_answers_a_number_or_an_error(y in proptest::array::uniform12(any_number())) {
        let p = DiskParams::paper();
        for result in [
            number_or_error(&RollingRef::build(&p), &y),
            number_or_error(&SlidingRef::build(&p), &y),
            number_or_error(&CartesianRef::build(&p), &y),
            number_or_error(&RollingGen::build(&p), &y),
            number_or_error(&SlidingGen::build(&p), &y),
            number_or_error(&CartesianGen::build(&p), &y),
        ] {
            proptest::prop_assert!(result.is_ok(), "{}", result.unwrap_err());
        }
    }
}
