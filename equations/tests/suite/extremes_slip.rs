//! Vanishing slip: sliding starts with slip speeds from 1e-3 down to 1e-12 m/s, in both slip
//! charts.
//!
//! The polar chart carries `α̇ = w / v_C` (docs/physics.md §4.2, line 7), singular as `v_C → 0`.
//! The driver must never integrate into that singularity: the stick event (`v_C` falls to the stick
//! threshold δ = 1e-9 m/s) fires first and a bridge carries the slip to zero exactly, so every
//! step the integrator takes has `v_C ≥ δ` and a finite `α̇`; a start below δ is decided at
//! once, as rolling. At zero slip the rule of docs/physics.md §7.2 decides: roll if the rolling
//! equations need `T_r / N_r < μ_st` (with `N_r > 0`), otherwise slide on from zero slip. That rule
//! is evaluated here independently, with the hand-written rolling reference at the state where
//! the event fired, and the run's decision must agree.
//!
//! Two starts at θ0 = 0.57, each with a slip that friction brakes to zero: spinning in place (no
//! friction needed: it must roll on) and falling from rest (rolling would need `ν = 0.84 > μ_st`:
//! it must slide on), slipping against the direction rolling would need friction in. Both
//! slips pass exactly through zero: spinning in place the slip decays along its own
//! direction, and the fall is planar (`Ω_x = Ω_z = 0`, slip along the disk's plane). A start
//! that precesses (the paper's, `Ω_x = 1`) turns the slip aside by ~3e-8 m/s as it passes: a
//! near miss of zero (docs/physics.md §6), which is not a stick.

use crate::common::extreme::{dop853, models_in, rolling_state, Rates, Watch};
use equations::formulas::spinning_in_place_rate;
use equations::layout::{V_X, V_Y, V_Z};
use equations::reference::RollingReference;
use equations::DiskParams;
use equations::InitialState;
use equations::{simulate, DiskSample, TransitionRecord, Trigger};
use equations::{Mode, Slip, SlipChart, DIM};
use model_runtime::Model;

/// Slip speeds of the starts (m/s): 1e-3 … 1e-12.
fn slip_speeds() -> impl Iterator<Item = f64> {
    (3..=12).map(|k| 10f64.powi(-k))
}

/// The rule of docs/physics.md §7.2 at a state, by the reference: `(T_r / N_r, N_r)` and whether it
/// rolls.
struct RollingNeed {
    ratio: f64,
    normal: f64,
}

impl RollingNeed {
    fn at(p: &DiskParams, state: &DiskSample) -> Self {
        let mut s = state.state;
        s.project(p, Mode::Rolling);
        let mut dy = [0.0; DIM];
        RollingReference::new(*p)
            .unwrap()
            .rhs(state.t, &s.y, &mut dy)
            .unwrap();
        let normal = p.m * (dy[V_Z] + p.g);
        let friction = p.m * dy[V_X].hypot(dy[V_Y]);
        RollingNeed {
            ratio: friction / normal,
            normal,
        }
    }

    fn rolls(&self, p: &DiskParams) -> bool {
        self.normal > 0.0 && self.ratio < p.mu_st
    }
}

/// The kept step (or sample) at exactly the time of a transition, before it.
fn state_at<'a>(watch: &'a Watch, record: &TransitionRecord) -> &'a DiskSample {
    watch
        .samples()
        .iter()
        .find(|s| s.t == record.t && s.mode == record.from)
        .unwrap_or_else(|| panic!("no step ends at {record:?}"))
}

/// A start: the rolling state and the unit direction of its slip.
struct Case {
    name: &'static str,
    y: [f64; DIM],
    slip_direction: [f64; 2],
    expected: Mode,
}

fn cases(p: &DiskParams) -> [Case; 2] {
    let theta0 = 0.57;
    let rate = spinning_in_place_rate(p, theta0).unwrap();
    [
        Case {
            name: "spinning in place",
            y: rolling_state(
                p,
                0.3,
                theta0,
                Rates {
                    x: -rate * theta0.sin(),
                    y: 0.0,
                    z: 0.0,
                },
            ),
            slip_direction: [0.6, 0.8],
            expected: Mode::Rolling,
        },
        Case {
            name: "falling from rest",
            y: rolling_state(p, 0.0, theta0, Rates::ZERO),
            // Rolling needs friction along −E_X; slipping toward −E_X, friction pushes +E_X.
            slip_direction: [-1.0, 0.0],
            expected: Mode::Sliding,
        },
    ]
}

#[test]
fn the_stick_event_fires_before_the_slip_singularity_and_decides_by_the_rule() {
    let p = DiskParams::paper();
    let config = dop853(1e-12, 0.01);
    for chart in [SlipChart::Polar, SlipChart::Cartesian] {
        let models = models_in(p, chart);
        let polar = models_in(p, SlipChart::Polar);
        for case in cases(&p) {
            for speed in slip_speeds() {
                let u = case.slip_direction.map(|c| c * speed);
                let initial = InitialState::sliding(&p, 0.0, case.y, Slip::from_vector(u));
                let mut watch = Watch::keeping_steps();
                let out = simulate(&models, &config, &initial, &mut watch)
                    .unwrap_or_else(|e| panic!("{chart:?} {} {speed:e}: {e}", case.name));
                watch.assert_finite(case.name);
                // Every sliding step the integrator took has a finite α̇ = w / v_C, bounded by
                // |w| / δ with |w| a few m/s² at most.
                let mut worst_alpha_rate = 0.0f64;
                for s in watch.samples().iter().filter(|s| s.mode == Mode::Sliding) {
                    // Bridge states (below δ) are not integrated in a slip chart.
                    if s.state.slip.speed < 0.5 * config.stick_threshold {
                        continue;
                    }
                    let y = s.state.sliding_vector(SlipChart::Polar, s.state.slip);
                    let mut dy = [0.0; DIM];
                    polar.sliding.rhs(s.t, &y, &mut dy).unwrap();
                    assert!(dy.iter().all(|v| v.is_finite()), "{s:?}");
                    worst_alpha_rate = worst_alpha_rate.max(dy[4].abs());
                }
                let first = watch.transition_records().first().copied();
                let stick = watch
                    .transition_records()
                    .iter()
                    .find(|r| matches!(r.trigger, Trigger::SlipStopped { .. }))
                    .copied();
                println!(
                    "{chart:?} {} slip {speed:e}: stop {:?}, first {:?}, stick {:?}, max |α̇| {worst_alpha_rate:.3e}",
                    case.name,
                    out.stop,
                    first.map(|r| (r.t, r.from, r.to)),
                    stick.map(|r| (r.t, r.to, r.trigger)),
                );
                assert!(
                    worst_alpha_rate < 1e2 / config.stick_threshold,
                    "{worst_alpha_rate}"
                );
                if speed > config.stick_threshold {
                    // Sliding from the start until the slip stopped, then the rule.
                    assert_eq!(watch.samples()[0].mode, Mode::Sliding);
                    let r = stick.expect("the stick event fired");
                    let Trigger::SlipStopped { rolling_ratio, .. } = r.trigger else {
                        unreachable!()
                    };
                    let need = RollingNeed::at(&p, state_at(&watch, &r));
                    assert!(
                        (need.ratio - rolling_ratio).abs() <= 1e-6 * rolling_ratio.max(1e-3),
                        "{} vs {rolling_ratio}",
                        need.ratio
                    );
                    let by_rule = if need.rolls(&p) {
                        Mode::Rolling
                    } else {
                        Mode::Sliding
                    };
                    assert_eq!(r.to, by_rule);
                    assert_eq!(r.to, case.expected);
                } else {
                    // Below the stick threshold: decided at once, as from zero slip.
                    let need = RollingNeed::at(&p, &watch.samples()[0]);
                    let by_rule = if need.rolls(&p) {
                        Mode::Rolling
                    } else {
                        Mode::Sliding
                    };
                    assert_eq!(by_rule, case.expected);
                    let decided = first.map_or(Mode::Rolling, |r| r.to);
                    assert_eq!(decided, by_rule);
                    assert!(first.is_none_or(|r| r.t == 0.0));
                }
            }
        }
    }
}
