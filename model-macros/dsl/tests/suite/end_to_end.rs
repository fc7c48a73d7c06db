//! Small non-disk models compiled end to end and compared with hand-written derivatives.

use crate::common::model;
use model_algebra::CompiledModel;
use model_algebra::Inputs;
use model_algebra::{compile, CompileOptions};

fn rhs(m: &CompiledModel, t: f64, y: &[f64], p: &[f64]) -> Vec<f64> {
    let stores = m
        .rhs
        .eval(&Inputs {
            t,
            states: y,
            params: p,
            ders: &[],
        })
        .expect("rhs evaluates");
    stores.ders(y.len())
}

pub const PENDULUM: &str = "
mod m {
    params { m = 1.5, g = 9.81 }
    states { x, y, vx, vy, P }
    equations {
        kx: der(x) = vx;
        ky: der(y) = vy;
        mx: m*der(vx) = -der(P)*x;
        my: m*der(vy) = -der(P)*y - m*g;
        c: der(x*vx + y*vy) = 0;
    }
    outputs {
        lambda = der(P);
        energy = m/2*(vx^2 + vy^2) + m*g*y;
    }
}
";

#[test]
fn cartesian_pendulum_matches_hand_derivation() {
    let spec = model(PENDULUM);
    let m = compile(&spec, &CompileOptions::default()).expect("compiles");
    let p = [1.5, 9.81];
    for (x, y, vx, vy) in [
        (0.6, -0.8, 0.3, 0.7),
        (1.0, 0.2, -0.5, 2.0),
        (-0.3, -0.4, 1.0, 0.1),
    ] {
        let (mass, g) = (p[0], p[1]);
        let lam = mass * (vx * vx + vy * vy - g * y) / (x * x + y * y);
        let expected = [vx, vy, -lam * x / mass, -lam * y / mass - g, lam];
        let got = rhs(&m, 0.0, &[x, y, vx, vy, 0.0], &p);
        for k in 0..5 {
            assert!(
                (got[k] - expected[k]).abs() <= 1e-12 * (1.0 + expected[k].abs()),
                "der {k}: {} vs {}",
                got[k],
                expected[k]
            );
        }
    }
}

/// The compiled model's derivatives at `(y, p)` against `want` (to 1e-12 relative, each named
/// by its state), and its Jacobian against differences of the derivatives.
pub fn assert_derivatives_match(
    m: &CompiledModel,
    names: &[&str],
    y: &[f64],
    p: &[f64],
    want: &[f64],
) {
    let got = m.derivatives(0.0, y, p).expect("rhs evaluates");
    assert_eq!(got.len(), want.len());
    for k in 0..want.len() {
        assert!(
            (got[k] - want[k]).abs() <= 1e-12 * (1.0 + want[k].abs()),
            "der({}): {} vs {}",
            names[k],
            got[k],
            want[k]
        );
    }
    assert_jacobian_matches(m, y, p);
}

pub fn assert_jacobian_matches(m: &CompiledModel, y: &[f64], p: &[f64]) {
    let n = y.len();
    let stores = m
        .jacobian
        .eval(&Inputs {
            t: 0.0,
            states: y,
            params: p,
            ders: &[],
        })
        .expect("jacobian evaluates");
    let jac = stores.jacobian(n);
    let fd = m
        .finite_difference_jacobian(y, p, 1e-6)
        .expect("rhs evaluates");
    let scale = fd.iter().flatten().fold(1.0f64, |a, b| a.max(b.abs()));
    for i in 0..n {
        for j in 0..n {
            assert!(
                (jac[i][j] - fd[i][j]).abs() <= 1e-6 * scale,
                "jac[{i}][{j}] = {} but differences give {}",
                jac[i][j],
                fd[i][j]
            );
        }
    }
}

#[test]
fn cartesian_pendulum_jacobian_and_outputs() {
    let spec = model(PENDULUM);
    let m = compile(&spec, &CompileOptions::default()).expect("compiles");
    let p = [1.5, 9.81];
    let y = [0.6, -0.8, 0.3, 0.7, 0.0];
    assert_jacobian_matches(&m, &y, &p);
    let dy = rhs(&m, 0.0, &y, &p);
    let out = m
        .outputs_program
        .eval(&Inputs {
            t: 0.0,
            states: &y,
            params: &p,
            ders: &dy,
        })
        .unwrap()
        .outputs(2);
    assert_eq!(out[0], dy[4]);
    let energy = 1.5 / 2.0 * (0.09 + 0.49) + 1.5 * 9.81 * -0.8;
    assert!((out[1] - energy).abs() < 1e-13);
    assert_eq!(m.outputs, vec!["lambda", "energy"]);
}

#[test]
fn numeric_fallback_has_a_correct_jacobian() {
    let spec = model(PENDULUM);
    let m = compile(
        &spec,
        &CompileOptions {
            swell_bound: 0,
            ..CompileOptions::default()
        },
    )
    .expect("compiles");
    assert_eq!(m.numeric_blocks, vec!["der(vx), der(vy), der(P)"]);
    let p = [1.5, 9.81];
    let y = [0.6, -0.8, 0.3, 0.7, 0.0];
    let symbolic = compile(&spec, &CompileOptions::default()).unwrap();
    let a = rhs(&m, 0.0, &y, &p);
    let b = rhs(&symbolic, 0.0, &y, &p);
    for k in 0..5 {
        assert!((a[k] - b[k]).abs() <= 1e-12 * (1.0 + b[k].abs()));
    }
    assert_jacobian_matches(&m, &y, &p);
}

/// A slip velocity written in polar form through its Cartesian components: every entry of the
/// 2×2 block vanishes on an axis, the block itself only at `u = 0`.
const POLAR_SLIP: &str = "
mod m {
    params { m = 2 }
    states { ux, uy }
    let v = sqrt(ux^2 + uy^2);
    let alpha = atan2(-uy, -ux);
    equations {
        turn: m*v*der(alpha) = 1;
        push: -m*der(v) = 3;
    }
}
";

#[test]
fn block_whose_entries_vanish_on_axes_is_regular_there() {
    let spec = model(POLAR_SLIP);
    let m = compile(&spec, &CompileOptions::default()).expect("compiles");
    // Cramer's rule: the only pivot is the determinant, which is the constant m^2 here.
    assert_eq!(m.pivots, vec!["m^2"]);
    for (ux, uy) in [
        (0.0, 0.7),
        (0.7, 0.0),
        (-0.3, 0.0),
        (0.4, -0.5),
        (1e-9, 2.0),
    ] {
        let got = rhs(&m, 0.0, &[ux, uy], &[2.0]);
        let v = f64::hypot(ux, uy);
        let (dv, dalpha) = (-3.0 / 2.0, 1.0 / (2.0 * v));
        let want = [dv * ux / v - dalpha * uy, dv * uy / v + dalpha * ux];
        for k in 0..2 {
            assert!(
                (got[k] - want[k]).abs() <= 1e-12 * (1.0 + want[k].abs()),
                "at ({ux}, {uy}): {got:?} vs {want:?}"
            );
        }
    }
    assert_jacobian_matches(&m, &[0.0, 0.7], &[2.0]);
}
