//! The tracker on guards given as closed forms: which crossing wins, directions, zeros at a
//! step's ends, excursions inside a step and their screening, restarts on a surface.

use super::*;

fn run(
    dirs: &[Direction],
    start: &[f64],
    g: impl Fn(f64, &mut [f64]),
    t1: f64,
    checks: u32,
) -> Option<Found> {
    run_quiet(dirs, start, g, t1, checks, Quiet::None)
}

fn run_quiet(
    dirs: &[Direction],
    start: &[f64],
    g: impl Fn(f64, &mut [f64]),
    t1: f64,
    checks: u32,
    quiet: Quiet,
) -> Option<Found> {
    let mut tr = GuardTracker::default();
    tr.start(dirs.iter().copied(), start, quiet, true);
    let mut end = vec![0.0; dirs.len()];
    g(t1, &mut end);
    let checks = match checks {
        0 => InteriorChecks::None,
        n => InteriorChecks::Exact(n),
    };
    tr.scan::<()>(0.0, t1, &end, checks, |t, _, out| {
        g(t, out);
        Ok(())
    })
    .unwrap()
}

/// A screened scan of `[0, 1]` with exact guard `g` and estimate `estimate`: what it found
/// and how many exact evaluations it made.
fn screened(
    dir: Direction,
    g: impl Fn(f64) -> f64,
    estimate: impl Fn(f64) -> f64,
    points: u32,
) -> (Option<Found>, usize) {
    let mut tr = GuardTracker::default();
    // At a run's start, so that only the interior points are counted (after a switch a
    // bad estimate also asks for an exact look just after the start: `on_surface`).
    tr.start([dir].into_iter(), &[g(0.0)], Quiet::Start, true);
    let mut exact = 0;
    let found = tr
        .scan::<()>(
            0.0,
            1.0,
            &[g(1.0)],
            InteriorChecks::Screened(points),
            |t, probe, out| {
                out[0] = match probe {
                    Probe::Exact => {
                        exact += 1;
                        g(t)
                    }
                    Probe::Estimate => estimate(t),
                };
                Ok(())
            },
        )
        .unwrap();
    (found, exact)
}

#[test]
fn earliest_of_two_guards_wins() {
    let g = |t: f64, o: &mut [f64]| {
        o[0] = t - 0.7;
        o[1] = t - 0.3;
    };
    let f = run(&[Direction::Up, Direction::Up], &[-0.7, -0.3], g, 1.0, 0).unwrap();
    assert_eq!(f.index, 1);
    assert!((f.t - 0.3).abs() < 1e-15);
}

#[test]
fn direction_filter_skips_wrong_crossings() {
    let g = |t: f64, o: &mut [f64]| {
        o[0] = 0.3 - t; // down at 0.3
        o[1] = t - 0.6; // up at 0.6
    };
    // (Read as after a projection: guard 0 holds where it starts, and is exempt.)
    let f = run_quiet(
        &[Direction::Up, Direction::Up],
        &[0.3, -0.6],
        g,
        1.0,
        0,
        Quiet::All,
    )
    .unwrap();
    assert_eq!(f.index, 1);
    let f = run(&[Direction::Both, Direction::Up], &[0.3, -0.6], g, 1.0, 0).unwrap();
    assert_eq!((f.index, f.direction), (0, Crossed::Down));
    assert!(run_quiet(
        &[Direction::Down, Direction::Down],
        &[0.3, -0.6],
        |t, o| {
            o[0] = t + 0.3;
            o[1] = t - 0.6;
        },
        1.0,
        0,
        Quiet::All,
    )
    .is_none());
}

#[test]
fn zero_at_segment_start_fires_only_on_an_admitted_departure() {
    let g = |t: f64, o: &mut [f64]| o[0] = t;
    // Leaves zero upwards: a Down guard stays quiet, an Up guard fires at the start.
    assert!(run(&[Direction::Down], &[0.0], g, 1.0, 0).is_none());
    let f = run(&[Direction::Up], &[0.0], g, 1.0, 0).unwrap();
    assert_eq!((f.t, f.direction), (0.0, Crossed::Up));
    // The guard that just fired (after a Continue) is quiet.
    assert!(run_quiet(&[Direction::Both], &[0.0], g, 1.0, 0, Quiet::Guard(0)).is_none());
    assert!(run_quiet(&[Direction::Up], &[0.0], g, 1.0, 0, Quiet::All).is_none());
    // A departure wins over a crossing of another guard in the same step.
    let g2 = |t: f64, o: &mut [f64]| {
        o[0] = t - 0.5;
        o[1] = -t;
    };
    let f = run(&[Direction::Up, Direction::Down], &[-0.5, 0.0], g2, 1.0, 0).unwrap();
    assert_eq!((f.index, f.t), (1, 0.0));
}

#[test]
fn a_guard_within_rounding_of_its_surface_after_a_switch_is_on_it() {
    // A hair on its holding side (the rounding an event located there leaves), leaving it
    // at once: on its surface, departing to the other side, so nothing fires...
    let g = |t: f64, o: &mut [f64]| o[0] = 1e-15 - t;
    assert!(run(&[Direction::Up], &[1e-15], g, 1.0, 0).is_none());
    // ... where at the start of a run it holds, and fires at once.
    let f = run_quiet(&[Direction::Up], &[1e-15], g, 1.0, 0, Quiet::Start).unwrap();
    assert_eq!((f.t, f.direction), (0.0, Crossed::Up));
    // A hair on the other side of a guard that fires either way, leaving: a departure
    // through its surface, an event at the start.
    let g = |t: f64, o: &mut [f64]| o[0] = -1e-15 - t;
    let f = run(&[Direction::Both], &[-1e-15], g, 1.0, 0).unwrap();
    assert_eq!((f.t, f.direction), (0.0, Crossed::Down));
    // Farther than it moves in h 2^-30: holds strictly, fires on entry.
    let g = |t: f64, o: &mut [f64]| o[0] = 1e-8 - t;
    let f = run(&[Direction::Up], &[1e-8], g, 1.0, 0).unwrap();
    assert_eq!((f.t, f.direction), (0.0, Crossed::Up));
}

#[test]
fn zero_at_step_end_fires() {
    let g = |t: f64, o: &mut [f64]| o[0] = t - 1.0;
    let f = run(&[Direction::Up], &[-1.0], g, 1.0, 0).unwrap();
    assert_eq!(f.t, 1.0);
}

#[test]
fn sign_change_and_back_needs_interior_checks() {
    // Negative, positive on (0.4, 0.6), negative again at the end.
    let g = |t: f64, o: &mut [f64]| o[0] = 0.01 - (t - 0.5) * (t - 0.5);
    assert!(run(&[Direction::Up], &[g0(g)], g, 1.0, 0).is_none());
    let f = run(&[Direction::Up], &[g0(g)], g, 1.0, 3).unwrap();
    assert!((f.t - 0.4).abs() < 1e-14, "{f:?}");
}

/// A screened scan of `[0, 1]` at 64 points whose estimates are the exact guard `g`: what
/// it found and how many estimates it made.
fn screened_64(g: impl Fn(f64) -> f64) -> (Option<Found>, u32) {
    let mut tr = GuardTracker::default();
    tr.start([Direction::Up].into_iter(), &[g(0.0)], Quiet::Start, true);
    let mut estimates = 0;
    let found = tr
        .scan::<()>(
            0.0,
            1.0,
            &[g(1.0)],
            InteriorChecks::Screened(64),
            |t, probe, out| {
                estimates += u32::from(probe == Probe::Estimate);
                out[0] = g(t);
                Ok(())
            },
        )
        .unwrap();
    (found, estimates)
}

#[test]
fn screening_skips_the_thirds_that_clear_and_looks_at_the_others_point_by_point() {
    // Far below zero for two thirds of the step, then rising steeply towards it: the
    // step's cubic does not clear, its first two thirds do.
    let rise = |t: f64| -1.0 + 0.95 * t.powi(8);
    // The 21 of the 64 points in the last third, after two estimates for the step and two
    // for each third (66 for the step's 64 points before the thirds were looked at).
    let (found, estimates) = screened_64(rise);
    assert_eq!((found, estimates), (None, 2 + 3 * 2 + 21));
    // A short excursion above zero in the last third (0.888 … 0.912, over two check
    // points) is found where exact checks at all 64 points find it, to the bit (the last
    // time before it, from another bracket, to a few ulps).
    let bump = |t: f64| rise(t) + 0.7 * (-((t - 0.9) / 0.03).powi(2)).exp();
    let found = screened_64(bump).0.unwrap();
    let exact = run(
        &[Direction::Up],
        &[bump(0.0)],
        |t, o| o[0] = bump(t),
        1.0,
        64,
    )
    .unwrap();
    assert_eq!(
        (found.index, found.t, found.direction),
        (exact.index, exact.t, exact.direction)
    );
    assert!(found.t - found.before <= 8.0 * f64::EPSILON, "{found:?}");
}

#[test]
fn screened_checks_evaluate_only_where_an_estimate_fires() {
    // Negative, positive on (0.4, 0.6), negative again at the end.
    let g = |t: f64| 0.01 - (t - 0.5) * (t - 0.5);
    let close = |t: f64| g(t) + 1e-4;
    // Nothing near a crossing: no exact evaluation at all.
    let (f, exact) = screened(Direction::Up, |t| g(t) - 1.0, |t| close(t) - 1.0, 4);
    assert_eq!((f, exact), (None, 0));
    // A good estimate triggers the exact check at t = 0.5; the event is located exactly.
    let (f, exact) = screened(Direction::Up, g, close, 4);
    let f = f.unwrap();
    assert!((f.t - 0.4).abs() < 1e-14, "{f:?}");
    assert!(exact > 1);
    // An estimate that wrongly shows a crossing cannot fire: the exact value decides.
    let (f, exact) = screened(Direction::Up, |t| g(t) - 1.0, |_| 1.0, 4);
    assert_eq!((f, exact), (None, 4));
    // A non-finite estimate is checked exactly rather than trusted or ignored.
    let (f, exact) = screened(Direction::Up, |t| g(t) - 1.0, |_| f64::NAN, 2);
    assert_eq!((f, exact), (None, 2));
    // An estimate that misses the excursion misses it (the documented limitation).
    let (f, _) = screened(Direction::Up, g, |t| g(t) - 1.0, 4);
    assert!(f.is_none());
}

#[test]
fn a_restart_on_the_surface_does_not_hide_the_return_through_it() {
    // A bounce: the guard that fired is a hair on its holding side, leaves it upwards and
    // comes back down at 0.7, all inside one step.
    let g = |t: f64, o: &mut [f64]| o[0] = -1e-17 + t * (0.7 - t);
    let f = run_quiet(&[Direction::Down], &[-1e-17], g, 1.0, 0, Quiet::Guard(0)).unwrap();
    assert_eq!(f.direction, Crossed::Down);
    assert!((f.t - 0.7).abs() < 1e-14, "{f:?}");
    // Also an excursion much shorter than the step, right at its start.
    let g = |t: f64, o: &mut [f64]| o[0] = t * (0.001 - t);
    let f = run_quiet(&[Direction::Down], &[0.0], g, 1.0, 0, Quiet::Guard(0)).unwrap();
    assert!((f.t - 0.001).abs() < 1e-15, "{f:?}");
    // The same excursion of another guard left exactly on its surface, heading the way
    // its filter does not fire: its return fires, at the return, not at the restart.
    let g = |t: f64, o: &mut [f64]| o[0] = -t * (0.4 - t);
    let f = run(&[Direction::Up], &[0.0], g, 1.0, 0).unwrap();
    assert_eq!(f.direction, Crossed::Up);
    assert!((f.t - 0.4).abs() < 1e-15, "{f:?}");
}

#[test]
fn a_guard_that_holds_on_entry_fires_at_once() {
    let g = |t: f64, o: &mut [f64]| {
        o[0] = -1.0 - t;
        o[1] = 2.0 + t;
    };
    // Both hold; the first listed fires, at the start, in the direction that leads there.
    for quiet in [Quiet::None, Quiet::Start] {
        let f = run_quiet(
            &[Direction::Down, Direction::Up],
            &[-1.0, 2.0],
            g,
            1.0,
            0,
            quiet,
        )
        .unwrap();
        assert_eq!((f.index, f.t, f.direction), (0, 0.0, Crossed::Down));
    }
    // Not after a projection, and never for a guard that fires either way.
    let g = |t: f64, o: &mut [f64]| o[0] = -1.0 - t;
    assert!(run_quiet(&[Direction::Down], &[-1.0], g, 1.0, 0, Quiet::All).is_none());
    assert!(run(&[Direction::Both], &[-1.0], g, 1.0, 0).is_none());
    // The guard that restarted its mode has fired: leaving its surface to its holding
    // side, it moves on.
    assert!(run_quiet(
        &[Direction::Down],
        &[0.0],
        |t, o| o[0] = -t,
        1.0,
        0,
        Quiet::Guard(0)
    )
    .is_none());
}

#[test]
fn a_departure_at_the_start_of_a_run_is_quiet_and_exempt() {
    let g = |t: f64, o: &mut [f64]| o[0] = -t;
    let mut tr = GuardTracker::default();
    tr.start([Direction::Down].into_iter(), &[0.0], Quiet::Start, true);
    let found = tr
        .scan::<()>(0.0, 1.0, &[-1.0], InteriorChecks::None, |t, _, o| {
            g(t, o);
            Ok(())
        })
        .unwrap();
    assert_eq!((found, tr.violation()), (None, None));
}

/// The events of one step `[0, 1]` of guards `g` with `checks`, every one passing.
fn passes(dirs: &[Direction], g: impl Fn(f64, &mut [f64]), checks: InteriorChecks) -> Vec<Found> {
    let mut tr = GuardTracker::default();
    let (mut start, mut end) = (vec![0.0; dirs.len()], vec![0.0; dirs.len()]);
    g(0.0, &mut start);
    g(1.0, &mut end);
    tr.start(dirs.iter().copied(), &start, Quiet::None, true);
    let mut eval = |t: f64, _: Probe, out: &mut [f64]| -> Result<(), ()> {
        g(t, out);
        Ok(())
    };
    let mut found = tr.scan(0.0, 1.0, &end, checks, &mut eval).unwrap();
    let mut all = Vec::new();
    let mut at = vec![0.0; dirs.len()];
    while let Some(f) = found {
        assert!(all.len() < 10, "{all:?}");
        g(f.t, &mut at);
        tr.pass(f.index, f.t, at[f.index]);
        all.push(f);
        found = tr.resume(&end, &mut eval).unwrap();
    }
    all
}

#[test]
fn a_guard_that_passed_fires_again_only_when_it_crosses_back() {
    // Down at 0.3 and back up at 0.6 in one step, and another guard up at 0.8.
    let g = |t: f64, o: &mut [f64]| {
        o[0] = (t - 0.3) * (t - 0.6);
        o[1] = t - 0.8;
    };
    let found = passes(
        &[Direction::Both, Direction::Up],
        g,
        InteriorChecks::Exact(4),
    );
    let seen: Vec<_> = found.iter().map(|f| (f.index, f.direction)).collect();
    assert_eq!(
        seen,
        [(0, Crossed::Down), (0, Crossed::Up), (1, Crossed::Up)]
    );
    for (f, t) in found.iter().zip([0.3, 0.6, 0.8]) {
        assert!((f.t - t).abs() < 1e-14, "{f:?}");
    }
    // Exactly zero at the pass (a check point): pending, and its departure is quiet.
    let found = passes(
        &[Direction::Both],
        |t, o| o[0] = t - 0.5,
        InteriorChecks::Exact(1),
    );
    assert_eq!(found.len(), 1);
    assert_eq!((found[0].t, found[0].direction), (0.5, Crossed::Up));
}

fn g0(g: impl Fn(f64, &mut [f64])) -> f64 {
    let mut o = [0.0];
    g(0.0, &mut o);
    o[0]
}
