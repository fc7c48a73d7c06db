//! The pruned variants (still air, only what the mode switching needs) against their full
//! models: same derivatives for the states they keep, same outputs, matched by name.

use crate::common;
use crate::common::{scales, Agreement, Reach, Rng};
use equations::models;
use equations::DiskParams;
use model_runtime::{Names, WithOutputs};

fn index(names: &Names, name: &str) -> usize {
    (names.position(name)).unwrap_or_else(|| panic!("no `{name}` in {names:?}"))
}

/// Still-air parameters in the variants' order (`mu_a`, `w_z` fixed away).
fn still_air(rng: &mut Rng) -> DiskParams {
    DiskParams {
        mu_a: 0.0,
        w_z: 0.0,
        ..common::some_params(rng)
    }
}

fn variant_params(p: &DiskParams) -> [f64; 5] {
    [p.m, p.a, p.g, p.mu_d, p.mu_st]
}

#[allow(clippy::too_many_arguments)]
fn variant_matches<F, V, const M: usize, const N: usize, const K: usize>(
    full: &F,
    variant: &V,
    y: &[f64; 12],
    row: &[f64; 12],
    force: f64,
    agreement: &mut Agreement,
) where
    F: WithOutputs<12, M>,
    V: WithOutputs<N, K>,
{
    let (fi, vi) = (full.info(), variant.info());
    let mut dy = [0.0; 12];
    full.rhs(0.0, y, &mut dy).unwrap();
    let mut out = [0.0; M];
    full.outputs(0.0, y, &dy, &mut out).unwrap();
    let yv: [f64; N] = std::array::from_fn(|i| y[index(&fi.state_names, &vi.state_names[i])]);
    let mut dyv = [0.0; N];
    variant.rhs(0.0, &yv, &mut dyv).unwrap();
    let mut outv = [0.0; K];
    variant.outputs(0.0, &yv, &dyv, &mut outv).unwrap();
    for (i, name) in vi.state_names.iter().enumerate() {
        let j = index(&fi.state_names, name);
        agreement.check(dyv[i], dy[j], row[j], || {
            format!("{}: der({name}) at {y:?}", vi.name)
        });
    }
    for (i, name) in vi.output_names.iter().enumerate() {
        let j = index(&fi.output_names, name);
        let scale = match name {
            "N" | "T" => force,
            "nu" => force / out[index(&fi.output_names, "N")].abs(),
            _ => force / out[index(&fi.output_names, "T")].abs(),
        };
        agreement.check(outv[i], out[j], scale, || {
            format!("{}: {name} at {y:?}", vi.name)
        });
    }
}

fn force_scale(p: &DiskParams, row: &[f64; 12]) -> f64 {
    p.m * (p.g + row[3].max(row[4]).max(row[5]))
}

/// The variant against its full model at 4000 random still-air states of one mode, half of
/// them at the extremes; `models` builds the pair from the parameters.
fn variant_agrees<F, V, const M: usize, const N: usize, const K: usize>(
    seed: u64,
    label: &str,
    state: impl Fn(&mut Rng, &DiskParams, Reach) -> [f64; 12],
    row: impl Fn(&DiskParams, &[f64; 12]) -> [f64; 12],
    models: impl Fn(&DiskParams) -> (F, V),
) where
    F: WithOutputs<12, M>,
    V: WithOutputs<N, K>,
{
    let mut rng = Rng::new(seed);
    let mut agreement = Agreement::default();
    for reach in [Reach::Typical, Reach::Extreme] {
        for _ in 0..2000 {
            let p = still_air(&mut rng);
            let y = state(&mut rng, &p, reach);
            let row = row(&p, &y);
            let (full, variant) = models(&p);
            let force = force_scale(&p, &row);
            variant_matches(&full, &variant, &y, &row, force, &mut agreement);
        }
    }
    agreement.assert_within(label);
}

#[test]
fn pruned_rolling_agrees_with_rolling() {
    use models::rolling::{pruned, Model};
    variant_agrees(
        71,
        "rolling::pruned",
        common::rolling_state,
        scales::rolling_full,
        |p| {
            (
                Model::new(p.to_array()),
                pruned::Model::new(variant_params(p)),
            )
        },
    );
}

#[test]
fn pruned_sliding_agrees_with_sliding() {
    use models::sliding::{pruned, Model};
    variant_agrees(
        72,
        "sliding::pruned",
        common::sliding_state,
        scales::sliding_polar_full,
        |p| {
            (
                Model::new(p.to_array()),
                pruned::Model::new(variant_params(p)),
            )
        },
    );
}

#[test]
fn pruned_cartesian_sliding_agrees_with_cartesian_sliding() {
    use models::sliding_cartesian::{pruned, Model};
    variant_agrees(
        73,
        "sliding_cartesian::pruned",
        |rng, p, reach| common::polar_to_cartesian(&common::sliding_state(rng, p, reach)),
        scales::sliding_cartesian_full,
        |p| {
            (
                Model::new(p.to_array()),
                pruned::Model::new(variant_params(p)),
            )
        },
    );
}

#[test]
fn pruned_variants_drop_position_and_spin_angle() {
    for info in [
        &models::rolling::pruned::INFO,
        &models::sliding::pruned::INFO,
        &models::sliding_cartesian::pruned::INFO,
    ] {
        for kept in ["theta", "psi", "Omega_x", "Omega_y", "Omega_z"] {
            assert!(info.state_names.contains(kept), "{}: {kept}", info.name);
        }
        for dropped in ["X", "Y", "Z", "phi"] {
            assert!(
                !info.state_names.contains(dropped),
                "{}: {dropped}",
                info.name
            );
        }
        assert_eq!(info.param_names, ["m", "a", "g", "mu_d", "mu_st"]);
    }
}
