//! Long runs: energy drift of DOP853 over many periods, and the cost per step of the hybrid
//! driver with many events (the scale of the disk's scene: about a million steps).

use crate::common::{up_crossings, Harmonic};
use model_runtime::{Dop853, HybridOptions, HybridSolver, Tolerance};

#[test]
fn harmonic_energy_drift_over_1000_periods_is_below_1e_10() {
    let periods = 1000.0;
    let t_end = periods * 2.0 * std::f64::consts::PI;
    let sol = model_runtime::integrate(
        &Harmonic,
        Dop853::new(),
        Tolerance::scalar(1e-12, 1e-12),
        Default::default(),
        0.0,
        &[1.0, 0.0],
        t_end,
    )
    .unwrap();
    let energy = 0.5 * (sol.y[0] * sol.y[0] + sol.y[1] * sol.y[1]);
    let drift = (energy - 0.5).abs() / 0.5;
    println!(
        "relative energy drift {drift:e} after {} steps",
        sol.stats.steps
    );
    assert!(drift < 1e-10, "drift {drift:e}");
    // And the phase: back at (1, 0).
    assert!(
        (sol.y[0] - 1.0).abs() < 1e-8 && sol.y[1].abs() < 1e-8,
        "{:?}",
        sol.y
    );
}

#[test]
fn events_every_period_do_not_change_the_solution() {
    let periods = 200.0;
    let period = 2.0 * std::f64::consts::PI;
    let mut solver = HybridSolver::new(
        Dop853::new(),
        Tolerance::scalar(1e-12, 1e-12),
        HybridOptions::default(),
    )
    .unwrap();
    let start = std::time::Instant::now();
    let out = solver
        .run(
            // The oscillator, watched for x crossing upwards: events that restart in place.
            &mut up_crossings(Harmonic, 0),
            (),
            0.0,
            &[1.0, 0.0],
            periods * period,
            &mut (),
        )
        .unwrap();
    let elapsed = start.elapsed();
    println!(
        "{} events, {:?}, {:?} ({:.0} ns per step)",
        out.transitions,
        out.stats,
        elapsed,
        elapsed.as_nanos() as f64 / out.stats.steps as f64
    );
    // x crosses upwards at 3π/2 + 2πk: 200 times in [0, 200 periods].
    assert_eq!(out.transitions, 200);
    assert!(
        (out.y[0] - 1.0).abs() < 1e-8 && out.y[1].abs() < 1e-8,
        "{:?}",
        out.y
    );
}
