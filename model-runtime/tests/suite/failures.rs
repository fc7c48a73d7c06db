//! Every failure is a typed error carrying its numbers, never a hang, panic or NaN state.

use crate::common;
use crate::common::{Blowup, Forced, Fragile, Harmonic};
use model_runtime::Const;
use model_runtime::{
    integrate, ChatterLimit, Dop853, Dopri5, EvalError, HybridOptions, HybridSolver, InputError,
    Rk4, Rodas4, SolveError, StepOptions, Stepper, Tolerance,
};

fn blowup<S: Stepper<Const<1>>>(stepper: S) {
    let err = integrate(
        &Blowup,
        stepper,
        Tolerance::scalar(1e-8, 1e-8),
        StepOptions::default(),
        0.0,
        &[1.0],
        2.0,
    )
    .unwrap_err();
    match err {
        SolveError::StepSizeCollapse {
            t,
            h,
            h_min,
            component,
            error_norm,
        } => {
            println!(
                "{}: collapse at t = {t}, h = {h:e}, h_min = {h_min:e}",
                S::NAME
            );
            assert!((t - 1.0).abs() < 1e-6, "collapse at {t}");
            assert!(h <= h_min && h > 0.0);
            assert_eq!(component, 0);
            assert!(error_norm > 1.0);
        }
        other => panic!("{}: expected a step-size collapse, got {other:?}", S::NAME),
    }
}

#[test]
fn blow_up_is_a_step_size_collapse_naming_t_h_and_component() {
    blowup(Dopri5::new());
    blowup(Dop853::new());
    blowup(Rodas4::new());
}

#[test]
fn a_user_minimum_step_is_honoured() {
    let err = integrate(
        &Blowup,
        Dopri5::new(),
        Tolerance::scalar(1e-8, 1e-8),
        StepOptions {
            h_min: 1e-6,
            ..StepOptions::default()
        },
        0.0,
        &[1.0],
        2.0,
    )
    .unwrap_err();
    assert!(
        matches!(err, SolveError::StepSizeCollapse { h_min, t, .. } if h_min == 1e-6 && t < 1.0),
        "{err:?}"
    );
}

#[test]
fn model_errors_propagate_with_the_time() {
    for result in [
        integrate(
            &Fragile,
            Dopri5::new(),
            Tolerance::scalar(1e-8, 1e-8),
            StepOptions::default(),
            0.0,
            &[0.0],
            5.0,
        ),
        integrate(
            &Fragile,
            Rk4::new(0.1),
            Tolerance::scalar(1e-8, 1e-8),
            StepOptions::default(),
            0.0,
            &[0.0],
            5.0,
        ),
    ] {
        match result.unwrap_err() {
            SolveError::Eval { t, source } => {
                // RK4 fails at its first stage beyond y = 2; the adaptive method first shrinks
                // its steps towards the singular point.
                assert!(t > 1.5 && t <= 2.3, "t = {t}");
                assert!(matches!(
                    source,
                    EvalError::SingularPivot { pivot, .. } if pivot == "2 - y"
                ));
            }
            other => panic!("expected an evaluation error, got {other:?}"),
        }
    }
}

#[test]
fn step_budget_is_a_typed_error() {
    let err = integrate(
        &Harmonic,
        Dopri5::new(),
        Tolerance::scalar(1e-10, 1e-10),
        StepOptions {
            max_steps: 50,
            ..StepOptions::default()
        },
        0.0,
        &[1.0, 0.0],
        1000.0,
    )
    .unwrap_err();
    assert!(matches!(err, SolveError::MaxSteps { steps: 50, t } if t > 0.0 && t < 1000.0));
}

#[test]
fn bad_inputs_are_named() {
    let run = |tol: Tolerance<Const<3>>, opts: StepOptions, y0: [f64; 3], t_end: f64| {
        integrate(&Forced, Dopri5::new(), tol, opts, 0.0, &y0, t_end).unwrap_err()
    };
    let ok_tol = Tolerance::scalar(1e-6, 1e-9);
    let d = StepOptions::default();
    let mut tol = ok_tol;
    tol.rtol[2] = f64::NAN;
    assert!(matches!(
        run(tol, d, Forced::Y0, 1.0),
        SolveError::InvalidInput(InputError::Tolerance { component: 2, .. })
    ));
    assert!(matches!(
        run(ok_tol, d, [1.0, f64::INFINITY, 0.0], 1.0),
        SolveError::InvalidInput(InputError::InitialState { component: 1, .. })
    ));
    assert!(matches!(
        run(ok_tol, d, Forced::Y0, f64::NAN),
        SolveError::InvalidInput(InputError::TimeSpan { .. })
    ));
    assert!(matches!(
        run(
            ok_tol,
            StepOptions {
                h_initial: Some(0.0),
                ..d
            },
            Forced::Y0,
            1.0
        ),
        SolveError::InvalidInput(InputError::StepSize { .. })
    ));
    assert!(matches!(
        integrate(&Forced, Rk4::new(-1.0), ok_tol, d, 0.0, &Forced::Y0, 1.0).unwrap_err(),
        SolveError::InvalidInput(InputError::StepSize { h }) if h == -1.0
    ));
    assert!(matches!(
        HybridSolver::<_, Const<3>>::new(
            Dopri5::new(),
            ok_tol,
            HybridOptions {
                sample_rate: Some(0.0),
                ..Default::default()
            }
        ),
        Err(InputError::SampleRate { .. })
    ));
    assert!(matches!(
        HybridSolver::<_, Const<3>>::new(
            Dopri5::new(),
            ok_tol,
            HybridOptions {
                chatter: ChatterLimit {
                    max_transitions: 0,
                    window: 1.0
                },
                ..Default::default()
            }
        ),
        Err(InputError::ChatterLimit { .. })
    ));
}

#[test]
fn errors_display_their_numbers() {
    let e = SolveError::StepSizeCollapse {
        t: 0.5,
        h: 1e-17,
        h_min: 2e-17,
        component: 3,
        error_norm: 7.0,
    };
    let s = e.to_string();
    assert!(
        s.contains("t = 0.5") && s.contains("component 3") && s.contains("1e-17"),
        "{s}"
    );
}

/// A model whose Jacobian is infinite: no step size makes the iteration matrix usable.
struct SingularJacobian;
static SINGULAR_JACOBIAN: model_runtime::ModelInfo = common::info("singular_jacobian", &["y"]);
impl model_runtime::Model<1> for SingularJacobian {
    fn info(&self) -> &'static model_runtime::ModelInfo {
        &SINGULAR_JACOBIAN
    }
    fn rhs(&self, _t: f64, _y: &[f64; 1], dy: &mut [f64; 1]) -> Result<(), EvalError> {
        dy[0] = 1.0;
        Ok(())
    }
    fn jacobian(&self, _t: f64, _y: &[f64; 1], jac: &mut [[f64; 1]; 1]) -> Result<(), EvalError> {
        // Infinite: the iteration matrix is not finite at any step size.
        jac[0][0] = f64::INFINITY;
        Ok(())
    }
}

#[test]
fn a_singular_iteration_matrix_is_a_typed_error() {
    let err = integrate(
        &SingularJacobian,
        Rodas4::new(),
        Tolerance::scalar(1e-6, 1e-6),
        StepOptions::default(),
        0.0,
        &[0.0],
        1.0,
    )
    .unwrap_err();
    assert!(
        matches!(err, SolveError::SingularIterationMatrix { t, h } if t == 0.0 && h > 0.0),
        "{err:?}"
    );
}
