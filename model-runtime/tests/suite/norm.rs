//! The error norm with vector groups: what grouping must leave alone (single components, the
//! default run), what it must make frame-independent (rotations of a vector and its error),
//! and the count of the component that limits each step.

use crate::common::info;
use model_runtime::Const;
use model_runtime::{
    integrate, Dop853, Dopri5, EvalError, GroupProblem, InputError, Model, ModelInfo, Rk4, Rodas4,
    Solution, StepOptions, Stepper, Tolerance,
};
use proptest::prelude::*;

/// A rotation matrix from a unit quaternion `q / |q|`.
fn rotation(q: [f64; 4]) -> [[f64; 3]; 3] {
    let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    let [w, x, y, z] = q.map(|v| v / n);
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// `v` with components `at..at + 3` rotated by `r`.
fn rotated<const N: usize>(r: &[[f64; 3]; 3], v: &[f64; N], at: usize) -> [f64; N] {
    let mut out = *v;
    for i in 0..3 {
        out[at + i] = (0..3).map(|j| r[i][j] * v[at + j]).sum();
    }
    out
}

fn vector5() -> impl Strategy<Value = [f64; 5]> {
    prop::array::uniform5(-10.0..10.0f64)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// A group of one component is that component: |y_i| = sqrt(y_i²) exactly in binary
    /// floating point, so the scales and the norm agree to the bit.
    #[test]
    fn a_single_component_group_is_the_per_component_norm(
        y0 in vector5(), y1 in vector5(), err in vector5(),
        rtol in prop::array::uniform5(1e-12..1e-3f64),
        atol in prop::array::uniform5(1e-14..1e-6f64),
        i in 0..5usize,
    ) {
        let plain = Tolerance::<Const<5>>::per_component(rtol, atol);
        let grouped = plain.with_group(i..i + 1).unwrap();
        prop_assert_eq!(grouped.scales(&y0, &y1), plain.scales(&y0, &y1));
        for k in 0..5 {
            prop_assert_eq!(plain.scales(&y0, &y1)[k], plain.scale(k, y0[k], y1[k]));
        }
        prop_assert_eq!(grouped.norm(&err, &y0, &y1), plain.norm(&err, &y0, &y1));
    }

    /// Rotating a grouped vector, its other end point and its error together leaves the norm
    /// unchanged, whatever the rotation; the components outside the group are untouched.
    #[test]
    fn a_rotated_vector_has_the_same_grouped_norm(
        y0 in vector5(), y1 in vector5(), err in prop::array::uniform5(-1e-6..1e-6f64),
        q in prop::array::uniform4(-1.0..1.0f64),
    ) {
        prop_assume!(q.iter().map(|v| v * v).sum::<f64>() > 1e-2);
        let tol = Tolerance::<Const<5>>::scalar(1e-6, 1e-9).with_group(1..4).unwrap();
        let r = rotation(q);
        let before = tol.norm(&err, &y0, &y1).norm;
        let after = tol
            .norm(&rotated(&r, &err, 1), &rotated(&r, &y0, 1), &rotated(&r, &y1, 1))
            .norm;
        prop_assert!((after - before).abs() <= 1e-12 * before, "{} vs {}", before, after);
    }
}

/// The per-component norm of the same rotated vector does change, by about the ratio of the
/// component magnitudes: the case the grouping exists for (an angular velocity whose third
/// component is 70 times smaller than the vector, with its error along that component, turned
/// by 45° so that both components are large).
#[test]
fn a_rotated_vector_changes_the_per_component_norm() {
    let omega = [5.0, 0.0, 0.07];
    let err = [0.0, 0.0, 1e-8];
    let half = std::f64::consts::PI / 8.0;
    let turn = |v: &[f64; 3]| rotated(&rotation([half.cos(), 0.0, half.sin(), 0.0]), v, 0);
    let (rtol, atol) = (1e-8, 1e-10);
    let plain = Tolerance::<Const<3>>::scalar(rtol, atol);
    let grouped = plain.with_group(0..3).unwrap();
    let norm = |tol: &Tolerance<Const<3>>, e: &[f64; 3], y: &[f64; 3]| tol.norm(e, y, y).norm;
    let (p0, p1) = (
        norm(&plain, &err, &omega),
        norm(&plain, &turn(&err), &turn(&omega)),
    );
    assert!(p0 > 30.0 * p1, "per component: {p0} before, {p1} after");
    let (g0, g1) = (
        norm(&grouped, &err, &omega),
        norm(&grouped, &turn(&err), &turn(&omega)),
    );
    assert!((g0 - g1).abs() <= 1e-12 * g0, "grouped: {g0} vs {g1}");
    // Grouped, the error is measured against the vector's length.
    let length = omega.iter().map(|v| v * v).sum::<f64>().sqrt();
    let expected = 1e-8 / (atol + rtol * length) / 3f64.sqrt();
    assert!(
        (g0 - expected).abs() <= 1e-12 * expected,
        "{g0} vs {expected}"
    );
}

#[test]
fn an_unusable_group_is_refused_by_name() {
    let tol = Tolerance::<Const<4>>::scalar(1e-6, 1e-9);
    assert_eq!(
        tol.with_group(0..2).and_then(|t| t.with_group(1..4)),
        Err(InputError::ComponentGroup {
            group: 1,
            start: 1,
            end: 4,
            problem: GroupProblem::Overlaps { other: 0 },
        })
    );
    assert!(matches!(
        tol.with_group(2..5),
        Err(InputError::ComponentGroup {
            group: 0,
            problem: GroupProblem::OutOfRange { dim: 4 },
            ..
        })
    ));
}

/// `a' = -a` beside `b' = 30 cos(30 t)`: the fast oscillation sets the step size.
struct SlowAndFast;
static SLOW_AND_FAST: ModelInfo = info("slow and fast", &["a", "b"]);
impl Model<2> for SlowAndFast {
    fn info(&self) -> &'static ModelInfo {
        &SLOW_AND_FAST
    }
    fn rhs(&self, t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
        *dy = [-y[0], 30.0 * (30.0 * t).cos()];
        Ok(())
    }
    fn jacobian(&self, _t: f64, _y: &[f64; 2], jac: &mut [[f64; 2]; 2]) -> Result<(), EvalError> {
        *jac = [[-1.0, 0.0], [0.0, 0.0]];
        Ok(())
    }
}

/// The slow-and-fast system over 3 s from (1, 0).
fn slow_and_fast<S: Stepper<Const<2>>>(stepper: S, tol: Tolerance<Const<2>>) -> Solution<Const<2>> {
    integrate(
        &SlowAndFast,
        stepper,
        tol,
        StepOptions::default(),
        0.0,
        &[1.0, 0.0],
        3.0,
    )
    .unwrap()
}

fn limiting_counts<S: Stepper<Const<2>>>(stepper: S, tol: Tolerance<Const<2>>) -> (u64, u64, u64) {
    let sol = slow_and_fast(stepper, tol);
    let l = sol.stats.limiting;
    (sol.stats.steps, l.get(1), l.total())
}

#[test]
fn every_adaptive_method_counts_the_limiting_component_on_request() {
    let tol = Tolerance::<Const<2>>::scalar(1e-8, 1e-10);
    let tracked = tol.tracking_limiting();
    let runs = [
        ("DOPRI5", limiting_counts(Dopri5::new(), tracked)),
        ("DOP853", limiting_counts(Dop853::new(), tracked)),
        ("Rodas4", limiting_counts(Rodas4::new(), tracked)),
    ];
    for (name, (steps, fast, total)) in runs {
        assert_eq!(total, steps, "{name}: one count per accepted step");
        assert!(
            10 * fast >= 9 * steps,
            "{name}: b limited {fast} of {steps}"
        );
    }
    // Off by default, and a method without error control has no limiting component.
    assert_eq!(limiting_counts(Dopri5::new(), tol).2, 0);
    assert_eq!(limiting_counts(Rk4::new(1e-2), tracked).2, 0);
    // Tracking does not change the run.
    let plain = slow_and_fast(Dopri5::new(), tol);
    let counted = slow_and_fast(Dopri5::new(), tracked);
    assert_eq!(plain.y, counted.y);
    assert_eq!(plain.stats.steps, counted.stats.steps);
}
