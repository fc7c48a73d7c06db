//! A 12-state rigid body sliding on a plane with Coulomb friction (a thin disk, polar slip
//! variables): a 6×6 coupled block with trigonometric coefficients. Checked against the
//! sequential explicit elimination derived by hand, with air drag switched on.

use std::time::Instant;

use crate::common::{model, sliding};
use model_algebra::Inputs;
use model_algebra::{compile, CompileOptions};

/// `m, a, g, mu_d, mu_st, mu_a, w_z`, with air drag on.
pub const PARAMS: [f64; 7] = [0.4387, 0.03755, 9.81, 0.115, 0.2, 0.02, 0.1];

pub fn state() -> [f64; 12] {
    [
        0.1, -0.2, 0.02, 0.3, 2.5, 0.01, 0.3, 0.57, 0.2, 1.0, 0.4, -2.0,
    ]
}

/// The sequential explicit elimination of the sliding equations.
fn reference(y: &[f64; 12], p: &[f64; 7]) -> [f64; 12] {
    let (m, a, g, mu_d, mu_a, w_z) = (p[0], p[1], p[2], p[3], p[5], p[6]);
    let (aa, cc) = (m * a * a / 4.0, m * a * a / 2.0);
    let k_f = mu_a * std::f64::consts::PI * a * a;
    let k_m = mu_a * std::f64::consts::PI * a.powi(4) / 4.0;
    let (v_c, alpha, v_zz, psi, th) = (y[3], y[4], y[5], y[6], y[7]);
    let (ox, oy, oz) = (y[9], y[10], y[11]);
    let (s, c) = th.sin_cos();
    let (sp, cp) = psi.sin_cos();
    let (ss, kk) = (alpha - psi).sin_cos();
    let k = mu_d * kk * s + c;
    let v_z = -v_c * s * kk + a * oy * s * s + v_zz * c;
    let beta0 = aa + m * a * a * c * k;
    let dpsi = -ox / s;
    let dth = oy;
    let dphi = oz + ox * c / s;
    let dox = -ox * oy * c / s - cc / aa * oy * oz - k_m / aa * ox;
    let doy = (aa * ox * ox * c / s + cc * ox * oz
        - m * g * a * k
        - k_f * a * (v_z - w_z) * c * k
        - k_m * oy
        + m * a * a * k * s * oy * oy)
        / beta0;
    let dvz = a * (c * doy - s * oy * oy);
    let n = m * (dvz + g) + k_f * (v_z - w_z) * c;
    let doz = a * mu_d * n * ss / cc;
    let dvc = -mu_d * n / m
        + a * ((oy * ss * s + oz * kk) * dpsi + oy * oy * kk * c + kk * s * doy - ss * doz)
        + k_f / m * (v_z - w_z) * kk * s;
    let w = -a * ((-oy * kk * s + oz * ss) * dpsi + oy * oy * ss * c + ss * s * doy + kk * doz)
        - k_f / m * (v_z - w_z) * s * ss;
    let dx = -v_c * alpha.cos() + a * (oy * cp * s + oz * sp);
    let dy = -v_c * alpha.sin() + a * (oy * sp * s - oz * cp);
    [
        dx,
        dy,
        v_zz,
        dvc,
        w / v_c,
        dvz,
        dpsi,
        dth,
        dphi,
        dox,
        doy,
        doz,
    ]
}

#[test]
fn sliding_matches_the_sequential_elimination() {
    let spec = model(&sliding());
    let start = Instant::now();
    let m = compile(&spec, &CompileOptions::default()).expect("compiles");
    eprintln!("compile time (with one variant): {:?}", start.elapsed());
    eprintln!("rhs ops {:?} total {}", m.rhs.ops(), m.rhs.ops().total());
    eprintln!("jacobian ops {:?}", m.jacobian.ops());
    eprintln!("pivots {:?}, numeric {:?}", m.pivots, m.numeric_blocks);
    let y = state();
    let names: Vec<&str> = spec.states.iter().map(|s| s.name.as_str()).collect();
    crate::end_to_end::assert_derivatives_match(&m, &names, &y, &PARAMS, &reference(&y, &PARAMS));
}

#[test]
fn pruned_variant_matches_the_full_model_in_still_air() {
    let spec = model(&sliding());
    let m = compile(&spec, &CompileOptions::default()).expect("compiles");
    let v = &m.variants[0];
    // N reads der(V_Z), so V_Z stays (its derivative must be in `dy`); X, Y, Z, phi go.
    assert_eq!(
        v.states,
        vec!["v_C", "alpha", "V_Z", "psi", "theta", "Omega_x", "Omega_y", "Omega_z"]
    );
    assert_eq!(v.outputs, vec!["N", "T", "nu"]);
    let still = [
        PARAMS[0], PARAMS[1], PARAMS[2], PARAMS[3], PARAMS[4], 0.0, 0.0,
    ];
    let y = state();
    let full = m.derivatives(0.0, &y, &still).expect("rhs");
    let keep = [3, 4, 5, 6, 7, 9, 10, 11];
    let reduced_y: Vec<f64> = keep.iter().map(|&i| y[i]).collect();
    let reduced = v.derivatives(0.0, &reduced_y, &still[..5]).expect("rhs");
    for (k, &i) in keep.iter().enumerate() {
        assert!(
            (reduced[k] - full[i]).abs() <= 1e-12 * (1.0 + full[i].abs()),
            "{}: {} vs {}",
            v.states[k],
            reduced[k],
            full[i]
        );
    }
    let n_full = m
        .outputs_program
        .eval(&Inputs {
            t: 0.0,
            states: &y,
            params: &still,
            ders: &full,
        })
        .unwrap()
        .outputs(1)[0];
    let n_reduced = v
        .outputs_program
        .eval(&Inputs {
            t: 0.0,
            states: &reduced_y,
            params: &still[..5],
            ders: &reduced,
        })
        .unwrap()
        .outputs(1)[0];
    assert!((n_full - n_reduced).abs() <= 1e-12 * n_full.abs());
    crate::end_to_end::assert_jacobian_matches(v, &reduced_y, &still[..5]);
}
