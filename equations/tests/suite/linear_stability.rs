//! Linearised motion about the steady motions of docs/physics.md §9, from the generated
//! Jacobian: the nutation frequencies of spinning in place (the table of docs/physics.md §9) and
//! the upright stability threshold `n² > g/(3a)` with its characteristic polynomial `λ² (5aλ² +
//! 12an² - 4g)`. With `μ_a = 0` the subsystem `(θ, Ω_x, Ω_y, Ω_z)` is closed, so its 4×4 block
//! carries them.

use crate::common;
use equations::formulas;
use equations::models::rolling;
use equations::DiskParams;
use model_runtime::Model;
use nalgebra::{Complex, Matrix4};

/// Eigenvalues of the closed `(θ, Ω_x, Ω_y, Ω_z)` block of the rolling Jacobian at `y`.
fn block_eigenvalues(p: &DiskParams, y: &[f64; 12]) -> Vec<Complex<f64>> {
    let model = rolling::Model::new(p.to_array());
    let mut jac = [[0.0; 12]; 12];
    model.jacobian(0.0, y, &mut jac).unwrap();
    let idx = [
        rolling::state::theta,
        rolling::state::Omega_x,
        rolling::state::Omega_y,
        rolling::state::Omega_z,
    ];
    let block = Matrix4::from_fn(|i, j| jac[idx[i]][idx[j]]);
    block.complex_eigenvalues().iter().copied().collect()
}

fn spinning_in_place(p: &DiskParams, theta0: f64) -> [f64; 12] {
    let rate = formulas::spinning_in_place_rate(p, theta0).unwrap();
    let mut y = [0.0; 12];
    y[rolling::state::theta] = theta0;
    y[rolling::state::Omega_x] = -rate * theta0.sin();
    common::make_rolling_consistent(p, &mut y);
    y
}

#[test]
fn nutation_about_spinning_in_place_matches_the_table() {
    // docs/physics.md §9: θ0, |p|, nutation ω (rad/s), for the paper's disk.
    let table = [
        (0.57, 44.0, 35.7),
        (0.30, 59.5, 46.7),
        (0.10, 102.3, 79.4),
        (0.05, 144.6, 112.1),
        (0.03, 186.7, 144.6),
        (0.02, 228.6, 177.1),
    ];
    let p = DiskParams::paper();
    for (theta0, rate, omega) in table {
        let y = spinning_in_place(&p, theta0);
        let p_rate = formulas::spinning_in_place_rate(&p, theta0).unwrap();
        assert!(
            (p_rate - rate).abs() < 0.05,
            "θ0 = {theta0}: |p| = {p_rate}"
        );
        let eig = block_eigenvalues(&p, &y);
        let nutation = eig.iter().map(|l| l.im.abs()).fold(0.0, f64::max);
        let growth = eig.iter().map(|l| l.re.abs()).fold(0.0, f64::max);
        assert!(
            (nutation - omega).abs() < 0.05,
            "θ0 = {theta0}: ω = {nutation}, eig {eig:?}"
        );
        assert!(
            growth < 1e-6 * nutation,
            "θ0 = {theta0}: not neutral, eig {eig:?}"
        );
    }
}

#[test]
fn upright_rolling_is_stable_above_g_over_3a() {
    let p = DiskParams::paper();
    let threshold = formulas::upright_stability_threshold(&p).sqrt();
    for factor in [0.5, 0.9, 1.1, 2.0, 5.0] {
        let n = factor * threshold;
        let mut y = [0.0; 12];
        y[rolling::state::theta] = std::f64::consts::FRAC_PI_2;
        y[rolling::state::Omega_z] = n;
        common::make_rolling_consistent(&p, &mut y);
        let eig = block_eigenvalues(&p, &y);
        // λ² = (4g - 12 a n²) / (5a) for the nontrivial pair.
        let lambda2 = (4.0 * p.g - 12.0 * p.a * n * n) / (5.0 * p.a);
        let growth = eig.iter().map(|l| l.re).fold(f64::MIN, f64::max);
        let squares: Vec<f64> = eig.iter().map(|l| (l * l).re).collect();
        assert!(
            squares
                .iter()
                .any(|s| (s - lambda2).abs() < 1e-9 * lambda2.abs()),
            "n = {n}: λ² = {lambda2} not among {squares:?}"
        );
        if factor > 1.0 {
            assert!(
                growth.abs() < 1e-9 * lambda2.abs().sqrt(),
                "n = {n}: {eig:?}"
            );
        } else {
            assert!(
                (growth - lambda2.sqrt()).abs() < 1e-9 * lambda2.sqrt(),
                "n = {n}: {eig:?}"
            );
        }
    }
}
