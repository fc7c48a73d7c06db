//! The paper's scene at t = 0 (docs/physics.md §11): rolling would need ν = 0.8355 with
//! N/mg = 0.4345, more than μ_st allows, so the disk slides from the start with
//! α0 = π and v̇_C(0) = 4.239 m/s².

use equations::reference::{rolling, RollingReference, SlidingPolarReference, Slip};
use equations::DiskParams;
use model_runtime::{Model, WithOutputs};
use std::f64::consts::{FRAC_PI_2, PI};

fn initial_state(p: &DiskParams) -> [f64; 12] {
    let theta0 = FRAC_PI_2 - 1.0;
    let mut y = [0.0; 12];
    y[rolling::state::Z] = p.a * theta0.sin();
    y[rolling::state::theta] = theta0;
    y[rolling::state::Omega_x] = 1.0;
    y
}

#[test]
fn rolling_at_t0_needs_more_friction_than_available() {
    let p = DiskParams::paper();
    let model = RollingReference::new(p).unwrap();
    let y = initial_state(&p);
    let mut dy = [0.0; 12];
    model.rhs(0.0, &y, &mut dy).unwrap();
    let mut out = [0.0; rolling::N_OUTPUTS];
    model.outputs(0.0, &y, &dy, &mut out).unwrap();
    let n_over_mg = out[rolling::output::N] / (p.m * p.g);
    let nu = out[rolling::output::nu];
    assert!((n_over_mg - 0.4345).abs() < 5e-5, "N/mg = {n_over_mg}");
    assert!((nu - 0.8355).abs() < 5e-5, "nu = {nu}");
    assert!(nu > p.mu_st);
    // The needed friction points along -E_X: α_r = π (symmetry).
    assert!((out[rolling::output::alpha_r].abs() - PI).abs() < 1e-12);
    // The state is rolling-consistent.
    for i in [
        rolling::output::z_residual,
        rolling::output::vz_residual,
        rolling::output::vx_residual,
        rolling::output::vy_residual,
    ] {
        assert_eq!(out[i], 0.0, "{}", rolling::OUTPUT_NAMES[i]);
    }
}

#[test]
fn sliding_starts_with_the_papers_slip_acceleration() {
    let p = DiskParams::paper();
    let model = SlidingPolarReference::new(p).unwrap();
    let y = initial_state(&p);
    let onset = model
        .slip_acceleration(
            &y,
            Slip {
                speed: 0.0,
                alpha: PI,
            },
        )
        .unwrap();
    assert!(
        (onset.along - 4.239).abs() < 5e-4,
        "dv_C/dt = {}",
        onset.along
    );
    // α0 = π is consistent: the contact accelerates along e_s, not across it.
    assert!(
        onset.across.abs() < 1e-12 * onset.along,
        "w = {}",
        onset.across
    );
}
