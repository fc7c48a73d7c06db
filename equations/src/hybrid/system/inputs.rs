//! What the disk's guards read, per phase, slip chart and air: the declaration behind
//! [`model_runtime::HybridSystem::guard_inputs`].
//!
//! Screening estimates outnumber steps four to one in the paper run, and each interpolated all
//! 12 state and 12 derivative components where the guards read four of them. The declaration
//! must follow `DiskSystem::guard_values` exactly: a component it misses only costs time (the
//! guard sees NaN in an estimate and asks for an exact evaluation), one it lists in vain costs
//! a little interpolation. The tests below hold it to the guards bit for bit, in both
//! directions, for both charts and with and without air, on the full and the pruned models.
//!
//! What the guards read (module [`crate::modes`]):
//! * every phase but the bridge: θ, for the inclination floor;
//! * rolling: `V̇_X`, `V̇_Y` (the friction force) and `V̇_Z` (the normal force);
//! * sliding: the slip speed, from `(u_X, u_Y)` or `v_C`, and `V̇_Z` for the normal force;
//! * with air, the normal velocity of the centre: ψ and the centre's velocity, which in sliding
//!   is the no-slip velocity (ψ, θ, `Ω_y`, `Ω_z`) plus the slip (both components);
//! * the bridge: only the time.

use crate::modes::layout::{ALPHA, OMEGA_Y, OMEGA_Z, PSI, THETA, U_X, U_Y, V_C, V_X, V_Y, V_Z};
use crate::modes::{SlipChart, DIM};
use model_runtime::Const;
use model_runtime::GuardInputs;

use super::Phase;

/// The floor guard, in every phase with contact.
const FLOOR: GuardInputs<Const<DIM>> = GuardInputs::of(&[THETA], &[]);
/// Rolling in still air: the contact force from the centre's acceleration.
const ROLLING: GuardInputs<Const<DIM>> = FLOOR.union(GuardInputs::of(&[], &[V_X, V_Y, V_Z]));
/// Rolling with air: the centre's normal velocity too.
const ROLLING_AIR: GuardInputs<Const<DIM>> =
    ROLLING.union(GuardInputs::of(&[PSI, V_X, V_Y, V_Z], &[]));
/// Sliding in still air, either chart: the normal force from `V̇_Z`.
const SLIDING: GuardInputs<Const<DIM>> = FLOOR.union(GuardInputs::of(&[], &[V_Z]));
/// Sliding with air, either chart: the centre's velocity is rebuilt from the no-slip velocity.
const SLIDING_AIR: GuardInputs<Const<DIM>> =
    SLIDING.union(GuardInputs::of(&[PSI, OMEGA_Y, OMEGA_Z, V_Z], &[]));
/// The bridge's guard reads the time only.
const BRIDGE: GuardInputs<Const<DIM>> = GuardInputs::of(&[], &[]);

/// The slip components the stick guard reads in `chart`.
const fn slip_speed(chart: SlipChart) -> GuardInputs<Const<DIM>> {
    match chart {
        SlipChart::Cartesian => GuardInputs::of(&[U_X, U_Y], &[]),
        SlipChart::Polar => GuardInputs::of(&[V_C], &[]),
    }
}

/// The full slip vector of `chart`, which the air's share reads.
const fn slip_vector(chart: SlipChart) -> GuardInputs<Const<DIM>> {
    match chart {
        SlipChart::Cartesian => GuardInputs::of(&[U_X, U_Y], &[]),
        SlipChart::Polar => GuardInputs::of(&[V_C, ALPHA], &[]),
    }
}

/// What the guards of `phase` read, sliding in `chart`, `air` when the air force is on.
pub(super) const fn guard_inputs(
    phase: Phase,
    chart: SlipChart,
    air: bool,
) -> GuardInputs<Const<DIM>> {
    match (phase, air) {
        (Phase::Rolling, false) => ROLLING,
        (Phase::Rolling, true) => ROLLING_AIR,
        (Phase::Sliding, false) => SLIDING.union(slip_speed(chart)),
        (Phase::Sliding, true) => SLIDING_AIR.union(slip_vector(chart)),
        (Phase::Bridge, _) => BRIDGE,
    }
}

#[cfg(test)]
mod tests {
    use super::super::DiskSystem;
    use super::*;
    use crate::hybrid::models::{DiskModels, GeneratedModels, PrunedModels};
    use crate::params::DiskParams;
    use crate::DiskConfig;
    use model_runtime::{HybridSystem, Model};
    use proptest::prelude::*;

    const PHASES: [Phase; 3] = [Phase::Rolling, Phase::Sliding, Phase::Bridge];
    const CHARTS: [SlipChart; 2] = [SlipChart::Cartesian, SlipChart::Polar];

    fn with_air(air: bool) -> DiskParams {
        let p = DiskParams::paper();
        if air {
            DiskParams {
                mu_a: 0.8,
                w_z: 0.3,
                ..p
            }
        } else {
            p
        }
    }

    /// The guard values of `phase` at `(y, dy)`.
    fn values<R: Model<DIM>, S: Model<DIM>>(
        system: &DiskSystem<'_, R, S>,
        phase: Phase,
        y: &[f64; DIM],
        dy: &[f64; DIM],
    ) -> Vec<f64> {
        let mut g = vec![0.0; system.guards(phase).len()];
        system.guard_values(phase, 0.25, y, dy, &mut g).unwrap();
        g
    }

    /// `v` with NaN in every component outside `keep`.
    fn masked(v: &[f64; DIM], keep: impl Fn(usize) -> bool) -> [f64; DIM] {
        std::array::from_fn(|i| if keep(i) { v[i] } else { f64::NAN })
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    /// In every phase: with NaN outside the declaration the guards give the same bits as with
    /// the full vectors; with NaN in any one declared component, some guard is not finite.
    fn declaration_is_exact<R: Model<DIM>, S: Model<DIM>>(
        models: &DiskModels<R, S>,
        y: &[f64; DIM],
        dy: &[f64; DIM],
    ) -> Result<(), TestCaseError> {
        let system = DiskSystem::new(models, &DiskConfig::paper());
        for phase in PHASES {
            let inputs = system
                .guard_inputs(phase)
                .expect("the disk declares its inputs");
            let full = values(&system, phase, y, dy);
            // (The bridge's end time is unset here, so its guard is infinite.)
            let contact = phase != Phase::Bridge;
            prop_assert!(!contact || full.iter().all(|g| g.is_finite()), "{full:?}");
            let (y_in, dy_in) = (
                masked(y, |i| inputs.state.contains(i)),
                masked(dy, |i| inputs.rates.contains(i)),
            );
            let seen = values(&system, phase, &y_in, &dy_in);
            prop_assert_eq!(bits(&seen), bits(&full), "{:?} {:?}", phase, models.chart);
            for &i in inputs.state.indices() {
                let g = values(&system, phase, &masked(y, |j| j != i), dy);
                prop_assert!(g.iter().any(|v| v.is_nan()), "{phase:?} needs no y[{i}]");
            }
            for &i in inputs.rates.indices() {
                let g = values(&system, phase, y, &masked(dy, |j| j != i));
                prop_assert!(g.iter().any(|v| v.is_nan()), "{phase:?} needs no dy[{i}]");
            }
        }
        Ok(())
    }

    fn vector(range: std::ops::Range<f64>) -> impl Strategy<Value = [f64; DIM]> {
        prop::array::uniform12(range)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn the_guards_read_exactly_what_is_declared(
            mut y in vector(-3.0..3.0),
            dy in vector(-30.0..30.0),
            theta in 0.05..3.09f64,
        ) {
            y[THETA] = theta;
            for chart in CHARTS {
                for air in [false, true] {
                    let models = GeneratedModels::generated(with_air(air), chart).unwrap();
                    declaration_is_exact(&models, &y, &dy)?;
                }
                let pruned = PrunedModels::pruned(with_air(false), chart).unwrap();
                declaration_is_exact(&pruned, &y, &dy)?;
            }
        }
    }

    /// The pruned models freeze `X`, `Y`, `Z` and `φ`; a guard reading one of them would watch
    /// a constant. They run only in still air.
    #[test]
    fn the_pruned_models_integrate_everything_the_guards_read() {
        for chart in CHARTS {
            let models = PrunedModels::pruned(with_air(false), chart).unwrap();
            let embedding = models.rolling.embedding();
            for phase in PHASES {
                let inputs = guard_inputs(phase, chart, false);
                for &i in inputs.state.indices().iter().chain(inputs.rates.indices()) {
                    assert!(embedding.keeps(i), "{phase:?} {chart:?} reads frozen {i}");
                }
            }
            let sliding = match models.sliding {
                crate::hybrid::models::SlidingModel::Cartesian(m) => m.embedding(),
                crate::hybrid::models::SlidingModel::Polar(m) => m.embedding(),
            };
            let inputs = guard_inputs(Phase::Sliding, chart, false);
            for &i in inputs.state.indices().iter().chain(inputs.rates.indices()) {
                assert!(sliding.keeps(i), "sliding {chart:?} reads frozen {i}");
            }
        }
    }
}
