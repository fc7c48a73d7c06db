//! The generated Jacobians (symbolic derivatives of the solved systems) against finite
//! differences of the generated right-hand sides, Richardson-extrapolated (error O(h⁴)).

use crate::common;
use crate::common::{Reach, Rng};
use equations::models;
use equations::DiskParams;
use model_runtime::Model;

/// Fourth-order central difference of column `j`: `(8 (f(+h) - f(-h)) - (f(+2h) - f(-2h))) / 12h`.
fn column<M: Model<12>>(model: &M, y: &[f64; 12], j: usize, h: f64) -> [f64; 12] {
    let at = |step: f64| {
        let mut yy = *y;
        yy[j] += step;
        let mut f = [0.0; 12];
        model.rhs(0.0, &yy, &mut f).unwrap();
        f
    };
    let (p1, m1, p2, m2) = (at(h), at(-h), at(2.0 * h), at(-2.0 * h));
    std::array::from_fn(|i| (8.0 * (p1[i] - m1[i]) - (p2[i] - m2[i])) / (12.0 * h))
}

/// Step for state `j`: small against the scale on which the right-hand side varies — absolute
/// for angles (periodic: their size means nothing), relative to the slip speed for the slip
/// states (the chart is singular at zero slip), relative to the value otherwise.
type Step = fn(&[f64; 12], usize) -> f64;

fn generic_step(y: &[f64; 12], j: usize) -> f64 {
    match j {
        6..=8 => 1e-4,
        _ => 1e-4 * y[j].abs().max(0.1),
    }
}

fn polar_step(y: &[f64; 12], j: usize) -> f64 {
    match j {
        3 => 1e-4 * y[3].abs(),
        4 => 1e-4,
        _ => generic_step(y, j),
    }
}

fn cartesian_step(y: &[f64; 12], j: usize) -> f64 {
    match j {
        3 | 4 => 1e-4 * y[3].hypot(y[4]),
        _ => generic_step(y, j),
    }
}

fn jacobian_matches_differences<M: Model<12>>(
    build: impl Fn(&DiskParams) -> M,
    state: impl Fn(&mut Rng, &DiskParams) -> [f64; 12],
    step: Step,
) {
    let mut rng = Rng::new(61);
    let mut worst = 0.0f64;
    for _ in 0..300 {
        let p = common::some_params(&mut rng);
        let y = state(&mut rng, &p);
        let model = build(&p);
        let mut jac = [[0.0; 12]; 12];
        model.jacobian(0.0, &y, &mut jac).unwrap();
        let mut f = [0.0; 12];
        model.rhs(0.0, &y, &mut f).unwrap();
        for j in 0..12 {
            let h = step(&y, j);
            let fd = column(&model, &y, j, h);
            for i in 0..12 {
                // Truncation error is O(h⁴ f⁽⁵⁾); rounding error is about ε |f_i| / h. Both are
                // far below 1e-6 of the row's size: Σ_k |J_ik| h_k plus |f_i|, per unit step h_j.
                let row: f64 = (0..12).map(|k| jac[i][k].abs() * step(&y, k)).sum();
                let scale = (row + 1e-4 * f[i].abs()) / h;
                let ratio = (jac[i][j] - fd[i]).abs() / (1e-6 * scale.max(f64::MIN_POSITIVE));
                assert!(
                    ratio <= 1.0,
                    "{}: d der({}) / d {} = {:e}, differences give {:e} at {y:?}",
                    model.info().name,
                    &model.info().state_names[i],
                    &model.info().state_names[j],
                    jac[i][j],
                    fd[i]
                );
                worst = worst.max(ratio);
            }
        }
    }
    println!("worst Jacobian disagreement {worst:.3e} × tolerance");
}

#[test]
fn rolling_jacobian_matches_differences() {
    jacobian_matches_differences(
        |p| models::rolling::Model::new(p.to_array()),
        |rng, p| common::rolling_state(rng, p, Reach::Typical),
        generic_step,
    );
}

#[test]
fn sliding_jacobian_matches_differences() {
    jacobian_matches_differences(
        |p| models::sliding::Model::new(p.to_array()),
        |rng, p| common::sliding_state(rng, p, Reach::Typical),
        polar_step,
    );
}

#[test]
fn cartesian_sliding_jacobian_matches_differences() {
    jacobian_matches_differences(
        |p| models::sliding_cartesian::Model::new(p.to_array()),
        |rng, p| common::polar_to_cartesian(&common::sliding_state(rng, p, Reach::Typical)),
        cartesian_step,
    );
}
