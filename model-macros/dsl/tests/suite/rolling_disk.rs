//! A 12-state rigid body rolling on a plane (a thin disk): the size of model the compiler is
//! built for. Checked against the hand-derived explicit form and for compile time.

use std::time::Instant;

use crate::common::{model, rolling, with_variant};
use model_algebra::Inputs;
use model_algebra::{compile, CompileOptions};

/// The rolling disk of the `equations` crate, with a variant that keeps only the spin.
pub fn rolling_with_spin() -> String {
    with_variant(
        &rolling(),
        "variant spin { keep { theta, Omega_x } fix { mu_a = 0, w_z = 0 } }",
    )
}

/// `m, a, g, mu_d, mu_st, mu_a, w_z`.
pub const PARAMS: [f64; 7] = [0.4387, 0.03755, 9.81, 0.115, 0.2, 0.0, 0.0];

pub fn state() -> [f64; 12] {
    [
        0.1, -0.2, 0.02, 0.05, -0.03, 0.01, 0.3, 0.57, 0.2, 1.0, 0.4, -2.0,
    ]
}

/// The reduced explicit form of the rolling equations (μ_a = 0), derived by hand.
fn reference(y: &[f64; 12], p: &[f64; 7]) -> [f64; 12] {
    let (m, a, g) = (p[0], p[1], p[2]);
    let (aa, cc) = (m * a * a / 4.0, m * a * a / 2.0);
    let (psi, th) = (y[6], y[7]);
    let (ox, oy, oz) = (y[9], y[10], y[11]);
    let (s, c) = th.sin_cos();
    let (sp, cp) = psi.sin_cos();
    let dpsi = -ox / s;
    let dth = oy;
    let dphi = oz + ox * c / s;
    let dox = -ox * oy * c / s - cc / aa * oy * oz;
    let doy =
        (aa * ox * ox * c / s + (cc + m * a * a) * ox * oz - m * g * a * c) / (aa + m * a * a);
    let doz = -m * a * a * ox * oy / (cc + m * a * a);
    let dvx = a * (s * cp * doy + sp * doz + c * cp * oy * dth + (oz * cp - oy * s * sp) * dpsi);
    let dvy = a * (s * sp * doy - cp * doz + c * sp * oy * dth + (oy * s * cp + oz * sp) * dpsi);
    let dvz = a * (c * doy - s * oy * dth);
    [
        y[3], y[4], y[5], dvx, dvy, dvz, dpsi, dth, dphi, dox, doy, doz,
    ]
}

#[test]
fn rolling_matches_the_reduced_explicit_form() {
    let spec = model(&rolling_with_spin());
    let start = Instant::now();
    let m = compile(&spec, &CompileOptions::default()).expect("compiles");
    let elapsed = start.elapsed();
    eprintln!("compile time (with one variant): {elapsed:?}");
    eprintln!("rhs ops {:?}", m.rhs.ops());
    eprintln!("jacobian ops {:?}", m.jacobian.ops());
    eprintln!("outputs ops {:?}", m.outputs_program.ops());
    eprintln!("pivots {:?}, numeric {:?}", m.pivots, m.numeric_blocks);
    eprintln!("{}", m.rhs);
    let y = state();
    let names: Vec<&str> = spec.states.iter().map(|s| s.name.as_str()).collect();
    crate::end_to_end::assert_derivatives_match(&m, &names, &y, &PARAMS, &reference(&y, &PARAMS));
}

/// The variant `spin` added to the disk's own (`pruned`, `still`).
fn spin(m: &model_algebra::CompiledModel) -> &model_algebra::CompiledModel {
    let spin = m.variants.iter().find(|v| v.name == "spin");
    spin.expect("the variant `spin` is compiled")
}

#[test]
fn variant_keeps_what_its_quantities_need() {
    let spec = model(&rolling_with_spin());
    let m = compile(&spec, &CompileOptions::default()).expect("compiles");
    let v = spin(&m);
    // der(theta) = Omega_y; der(Omega_x) reads theta, Omega_x, Omega_y, Omega_z.
    assert_eq!(v.states, vec!["theta", "Omega_x", "Omega_y", "Omega_z"]);
    let names: Vec<&str> = v.params.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, vec!["m", "a", "g", "mu_d", "mu_st"]);
    assert!(v.outputs.is_empty());
    let y = state();
    let full = m.derivatives(0.0, &y, &PARAMS).expect("rhs");
    let reduced_y = [y[7], y[9], y[10], y[11]];
    let reduced = v.derivatives(0.0, &reduced_y, &PARAMS[..5]).expect("rhs");
    for (k, &i) in [7, 9, 10, 11].iter().enumerate() {
        assert!(
            (reduced[k] - full[i]).abs() <= 1e-13 * (1.0 + full[i].abs()),
            "{}: {} vs {}",
            v.states[k],
            reduced[k],
            full[i]
        );
    }
    crate::end_to_end::assert_jacobian_matches(v, &reduced_y, &PARAMS[..5]);
}

#[test]
fn flat_disk_is_a_singular_pivot_everywhere() {
    let spec = model(&rolling_with_spin());
    let m = compile(&spec, &CompileOptions::default()).expect("compiles");
    let mut y = state();
    y[7] = 0.0;
    let flat = |p: &model_algebra::Program, y: &[f64], params: &[f64]| {
        p.eval(&Inputs {
            t: 0.0,
            states: y,
            params,
            ders: &[],
        })
    };
    let expected = Err(model_algebra::EvalFailure::SingularPivot {
        text: "sin(theta)".into(),
        value: 0.0,
    });
    assert_eq!(flat(&m.rhs, &y, &PARAMS), expected);
    assert_eq!(flat(&m.jacobian, &y, &PARAMS), expected);
    let v = spin(&m);
    let reduced = [0.0, y[9], y[10], y[11]];
    assert_eq!(flat(&v.rhs, &reduced, &PARAMS[..5]), expected);
    assert_eq!(flat(&v.jacobian, &reduced, &PARAMS[..5]), expected);
}
