//! The guard semantics of switched models against closed forms: a restart on a guard's
//! surface hides none of its crossings (a ball on a moving floor, a ball with an idle extra
//! state, a ball bouncing down a slope against drag), an event left on another's surface fires
//! where that one really crosses, a guard that holds on entry fires at once (Coulomb friction, a
//! thermostat with a lockout), and accumulations that are not geometric are declared (the
//! moving floor).

use crate::{compile, model};
use model_interpreted::{solve, EventKind, Solution, SolveRequest, Stop};
use model_runtime::Method;

/// The first root after `t0` of a function that is positive just after `t0` and negative
/// somewhere later: the first negative value on a doubling grid from `t0 + 1e-13`, bisected
/// back to the last positive one (exact where the function has one root after `t0`, as every
/// concave flight's gap has).
fn first_root(t0: f64, f: impl Fn(f64) -> f64) -> f64 {
    let mut d = 1e-13;
    while f(t0 + 2.0 * d) > 0.0 {
        d *= 2.0;
        assert!(d < 1e3, "no root after {t0}");
    }
    let (mut lo, mut hi) = (t0 + d, t0 + 2.0 * d);
    while hi - lo > 1e-15 * hi.abs().max(1.0) {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// The column `name` of `solved`'s rows.
fn column(solved: &Solution, name: &str) -> Vec<f64> {
    solved
        .column(name)
        .unwrap_or_else(|| panic!("no column {name}"))
        .to_vec()
}

/// `request` with this method and tolerances.
fn with(method: Method, rtol: f64, atol: f64, t_end: f64) -> SolveRequest {
    let mut request = SolveRequest::new(t_end);
    (request.method, request.rtol, request.atol) = (method, rtol, atol);
    request
}

const METHODS: [Method; 3] = [Method::Dopri5, Method::Dop853, Method::Rodas4];

/// A ball on a floor that moves as `A sin(W t)` (its acceleration `A W^2` below `g`, so the
/// ball ends up riding it), with the impacts' rule.
fn moving_floor(amplitude: f64, rule: bool) -> String {
    let rule = if rule {
        "when impact accumulates -> riding { h = floor; v = floor_v; }"
    } else {
        ""
    };
    format!(
        "mod moving_floor {{
            params {{ g = 9.81, A = {amplitude}, W = 20, e = 0.8 }}
            states {{ h = 1, v }}
            let floor = A * sin(W * t);
            let floor_v = A * W * cos(W * t);
            outputs {{ gap = h - floor; }}
            mode flying {{
                equations {{ der(h) = v; der(v) = -g; }}
                when impact: h < floor {{ v = floor_v - e * (v - floor_v); }}
                {rule}
            }}
            mode riding {{
                equations {{ der(h) = floor_v; der(v) = -A * W^2 * sin(W * t); }}
            }}
        }}"
    )
}

/// The impacts of the moving floor in closed form: each flight a parabola, each impact the
/// first root of the gap after the last one (concave: `A W^2 < g`), until the flights are
/// shorter than `shortest`.
fn moving_floor_impacts(amplitude: f64, shortest: f64) -> Vec<f64> {
    let (g, w, e) = (9.81, 20.0, 0.8);
    let floor = |t: f64| amplitude * (w * t).sin();
    let floor_v = |t: f64| amplitude * w * (w * t).cos();
    // The first impact, from rest at h = 1.
    let mut t0 = first_root(0.0, |t| 1.0 - 0.5 * g * t * t - floor(t));
    let mut v_in = -g * t0;
    let mut impacts = vec![t0];
    loop {
        let h0 = floor(t0);
        let v0 = floor_v(t0) - e * (v_in - floor_v(t0));
        let t1 = first_root(t0, |t| {
            let s = t - t0;
            h0 + v0 * s - 0.5 * g * s * s - floor(t)
        });
        if t1 - t0 < shortest {
            return impacts;
        }
        v_in = v0 - g * (t1 - t0);
        impacts.push(t1);
        t0 = t1;
    }
}

#[test]
fn the_ball_on_a_moving_floor_never_falls_through_and_rides_it() {
    for amplitude in [0.001, 0.005, 0.01, 0.02] {
        let reference = moving_floor_impacts(amplitude, 1e-3);
        let file = compile("moving_floor.dsl", &moving_floor(amplitude, true));
        for method in METHODS {
            for (rtol, atol) in [(1e-8, 1e-10), (1e-12, 1e-14)] {
                let case = format!("A = {amplitude}, {method:?}, rtol {rtol}");
                let solved = solve(model(&file), &with(method, rtol, atol, 5.0))
                    .unwrap_or_else(|e| panic!("{case}: {e}"));
                assert_eq!(solved.stop, Stop::EndTime, "{case}");
                // Never below the floor, at any recorded row.
                let gap = column(&solved, "gap");
                let lowest = gap.iter().cloned().fold(f64::INFINITY, f64::min);
                assert!(lowest > -1e-7, "{case}: gap {lowest}");
                // The impacts where the closed form has them, every one of them.
                let impacts: Vec<f64> = (solved.events.iter())
                    .filter(|e| e.kind == EventKind::Crossing)
                    .map(|e| e.t())
                    .collect();
                assert!(impacts.len() > reference.len(), "{case}");
                let tol = if rtol < 1e-10 { 1e-8 } else { 1e-4 };
                for (k, (got, want)) in impacts.iter().zip(&reference).enumerate() {
                    assert!(
                        (got - want).abs() < tol,
                        "{case}: impact {k}: {got} vs {want}"
                    );
                }
                // Then the accumulation, and the ride to the end on the floor.
                let [acc] = &solved.accumulations[..] else {
                    panic!("{case}: {:?}", solved.accumulations)
                };
                assert_eq!(acc.continued_in.as_deref(), Some("riding"), "{case}");
                assert!(acc.t > *reference.last().unwrap(), "{case}");
                assert!(gap.last().unwrap().abs() < 1e-7, "{case}: {:?}", gap.last());
            }
        }
    }
}

#[test]
fn without_a_rule_the_moving_floor_stops_at_its_accumulation() {
    let file = compile("moving_floor.dsl", &moving_floor(0.01, false));
    let solved = solve(model(&file), &SolveRequest::new(5.0)).unwrap();
    assert_eq!(
        solved.stop,
        Stop::Event {
            name: "impact".into(),
            kind: EventKind::Accumulation
        }
    );
    let gap = column(&solved, "gap");
    assert!(gap.iter().all(|&g| g > -1e-7), "{gap:?}");
    let end = solved.t_end().unwrap();
    assert!(end < 5.0 && end > *moving_floor_impacts(0.01, 1e-3).last().unwrap());
}

#[test]
fn an_idle_extra_state_changes_no_bounce_of_the_ball() {
    let text = include_str!("../../../../model-macros/examples/bouncing_ball.dsl").replace(
        "v = 0.0,\n    }",
        "v = 0.0,\n        x = 5,\n        u = 0,\n    }",
    );
    let text = text.replace(
        "equations { der(h) = v; der(v) = -g; }",
        "equations { der(h) = v; der(v) = -g; der(x) = u; der(u) = 0; }",
    );
    let text = text.replace(
        "equations { der(h) = 0; der(v) = 0; }",
        "equations { der(h) = 0; der(v) = 0; der(x) = u; der(u) = 0; }",
    );
    assert!(
        text.contains("der(x) = u") && text.contains("x = 5"),
        "{text}"
    );
    let file = compile("idle_ball.dsl", &text);
    let (g, e, h0) = (9.81f64, 0.8f64, 1.0f64);
    let v1 = (2.0 * g * h0).sqrt();
    let t_inf = (2.0 * h0 / g).sqrt() + 2.0 * e * v1 / (g * (1.0 - e));
    for method in METHODS {
        let solved = solve(model(&file), &with(method, 1e-8, 1e-10, 10.0)).unwrap();
        let h = column(&solved, "h");
        assert!(h.iter().all(|&h| h > -1e-7), "{method:?}");
        assert_eq!(solved.stop, Stop::EndTime);
        let [acc] = &solved.accumulations[..] else {
            panic!("{method:?}: {:?}", solved.accumulations)
        };
        assert!(
            (acc.t - t_inf).abs() < 1e-5,
            "{method:?}: {} vs {t_inf}",
            acc.t
        );
        let mut expected = (2.0 * h0 / g).sqrt();
        for (k, impact) in (solved.events.iter())
            .filter(|e| e.kind == EventKind::Crossing)
            .take(20)
            .enumerate()
        {
            assert!(
                (impact.t() - expected).abs() < 1e-6,
                "{method:?}: impact {k}"
            );
            expected += 2.0 * e.powi(k as i32 + 1) * v1 / g;
        }
        let x = *column(&solved, "x").last().unwrap();
        assert!((x - 5.0).abs() < 1e-12, "{method:?}: {x}");
    }
}

/// A ball bouncing down a slope `y = -s x` against linear drag `c`: every flight in closed
/// form, `vx(t) = vx0 exp(-c t)`, `vy(t) = (vy0 + g/c) exp(-c t) - g/c`.
const SLOPE: &str = "mod slope {
    params { g = 9.81, s = 0.3, c = 0.1, e = 0.7 }
    states { x = 0, y = 1, vx = 1, vy = 0 }
    outputs { gap = y + s * x; }
    equations { der(x) = vx; der(y) = vy; der(vx) = -c * vx; der(vy) = -g - c * vy; }
    when impact: y + s * x < 0 {
        vx = vx - (1 + e) * s * (s * vx + vy) / (1 + s^2);
        vy = vy - (1 + e) * (s * vx + vy) / (1 + s^2);
    }
}";

/// The slope's impacts in closed form, until a flight is shorter than `shortest`.
fn slope_impacts(t_end: f64, shortest: f64) -> Vec<f64> {
    let (g, s, c, e) = (9.81, 0.3, 0.1, 0.7);
    let (mut t0, mut st) = (0.0, [0.0, 1.0, 1.0, 0.0]);
    let flight = |st: [f64; 4], dt: f64| {
        let [x, y, vx, vy] = st;
        let decay = (-c * dt).exp();
        [
            x + vx * (1.0 - decay) / c,
            y + (vy + g / c) * (1.0 - decay) / c - g * dt / c,
            vx * decay,
            (vy + g / c) * decay - g / c,
        ]
    };
    let mut impacts = Vec::new();
    loop {
        let st0 = st;
        let t1 = first_root(t0, |t| {
            let [x, y, ..] = flight(st0, t - t0);
            y + s * x
        });
        if t1 - t0 < shortest || t1 > t_end {
            return impacts;
        }
        let [x, y, vx, vy] = flight(st0, t1 - t0);
        let k = (s * vx + vy) / (1.0 + s * s);
        st = [x, y, vx - (1.0 + e) * s * k, vy - (1.0 + e) * k];
        impacts.push(t1);
        t0 = t1;
    }
}

#[test]
fn a_ball_bouncing_down_a_slope_finds_every_impact() {
    let reference = slope_impacts(4.0, 1e-3);
    assert!(reference.len() >= 8);
    let file = compile("slope.dsl", SLOPE);
    for method in METHODS {
        let solved = solve(model(&file), &with(method, 1e-8, 1e-10, 4.0)).unwrap();
        let gap = column(&solved, "gap");
        assert!(gap.iter().all(|&g| g > -1e-7), "{method:?}");
        let impacts: Vec<f64> = solved.events.iter().map(|e| e.t()).collect();
        assert!(impacts.len() >= reference.len(), "{method:?}");
        for (k, (got, want)) in impacts.iter().zip(&reference).enumerate() {
            assert!(
                (got - want).abs() < 1e-4,
                "{method:?}: impact {k}: {got} vs {want}"
            );
        }
        // The bounces accumulate (no rule says what follows): the run stops there, named.
        assert_eq!(
            solved.stop,
            Stop::Event {
                name: "impact".into(),
                kind: EventKind::Accumulation
            },
            "{method:?}"
        );
    }
}

#[test]
fn an_event_left_on_its_surface_fires_where_it_comes_back_not_at_the_reset() {
    // At t = 1 the reset leaves x exactly on `up`'s surface heading down (v = -0.001); x
    // comes back up through zero at t = 1.002, with v = +0.001.
    let file = compile(
        "rearm.dsl",
        "mod rearm { states { x = -1, v }
            equations { der(x) = v; der(v) = 1; }
            when drop: t > 1 { x = 0; v = -0.001; }
            when up: x > 0 -> stop; }",
    );
    for method in METHODS {
        let solved = solve(model(&file), &with(method, 1e-8, 1e-10, 3.0)).unwrap();
        let names: Vec<&str> = solved.events.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(names, ["drop", "up"], "{method:?}");
        let up = &solved.events[1];
        assert!((up.t() - 1.002).abs() < 1e-9, "{method:?}: {}", up.t());
        assert!((up.row[2] - 0.001).abs() < 1e-9, "{method:?}: {:?}", up.row);
    }
}

/// A mass on a spring under Coulomb friction, written as a first-time user writes it.
const COULOMB: &str = "mod coulomb {
    params { m = 1, k = 4, mu_s = 0.1, mu_k = 0.1, g = 9.81 }
    states { x = 1, v, s = -1 }
    mode slipping {
        equations { der(x) = v; m * der(v) = -k * x - mu_k * m * g * s; der(s) = 0; }
        when halt: s * v < 0 -> stuck { v = 0; }
    }
    mode stuck {
        equations { der(x) = 0; der(v) = 0; der(s) = 0; }
        when breakaway: k * abs(x) > mu_s * m * g -> slipping { s = -sign(x); }
    }
}";

#[test]
fn a_coulomb_mass_slips_on_at_once_where_friction_cannot_hold_it() {
    let file = compile("coulomb.dsl", COULOMB);
    // Half a period (pi / 2) per slip about the shifted centre +-mu g / k.
    let xe = 0.1 * 9.81 / 4.0;
    let x1 = 2.0 * xe - 1.0;
    let x2 = -2.0 * xe - x1;
    let pi = std::f64::consts::PI;
    for method in METHODS {
        let solved = solve(model(&file), &with(method, 1e-10, 1e-12, 10.0)).unwrap();
        let seen: Vec<(&str, f64)> = (solved.events.iter())
            .map(|e| (e.name.as_str(), e.t()))
            .collect();
        let names: Vec<&str> = seen.iter().map(|e| e.0).collect();
        assert_eq!(names, ["halt", "breakaway", "halt"], "{method:?}");
        for ((_, t), want) in seen.iter().zip([pi / 2.0, pi / 2.0, pi]) {
            assert!((t - want).abs() < 1e-7, "{method:?}: {seen:?}");
        }
        assert!((solved.events[0].row[1] - x1).abs() < 1e-7);
        assert_eq!(solved.stop, Stop::EndTime);
        let x = column(&solved, "x");
        assert!((x.last().unwrap() - x2).abs() < 1e-7, "{:?}", x.last());
        assert!((x2 - 0.0190).abs() < 1e-4);
    }
}

#[test]
fn a_thermostat_whose_lockout_ends_in_the_cold_heats_again_at_once() {
    let file = compile(
        "thermostat.dsl",
        "mod thermostat {
            params { k = 0.5, Th = 30, Ta = 10, lock = 3 }
            states { T = 18, c = 0 }
            mode heating {
                equations { der(T) = k * (Th - T); der(c) = 0; }
                when hot: T > 22 -> lockout { c = t + lock; }
            }
            mode lockout {
                equations { der(T) = -k * (T - Ta); der(c) = 0; }
                when unlocked: t > c -> off;
            }
            mode off {
                equations { der(T) = -k * (T - Ta); der(c) = 0; }
                when cold: T < 19 -> heating;
            }
        }",
    );
    let k: f64 = 0.5;
    // Heating from T0 reaches 22 after ln((30 - T0) / 8) / k; the lockout cools from 22 to
    // 10 + 12 exp(-1.5) < 19, so `cold` holds as it ends.
    let mut expected = Vec::new();
    let (mut t, mut temp) = (0.0, 18.0);
    for _ in 0..3 {
        t += ((30.0 - temp) / 8.0f64).ln() / k;
        expected.push(("hot", t));
        t += 3.0;
        expected.push(("unlocked", t));
        expected.push(("cold", t));
        temp = 10.0 + 12.0 * (-3.0 * k).exp();
    }
    let solved = solve(model(&file), &with(Method::Dop853, 1e-10, 1e-12, t + 0.1)).unwrap();
    let seen: Vec<(&str, f64)> = (solved.events.iter())
        .map(|e| (e.name.as_str(), e.t()))
        .collect();
    assert_eq!(seen.len(), expected.len(), "{seen:?}");
    for (got, want) in seen.iter().zip(&expected) {
        assert_eq!(got.0, want.0, "{seen:?}");
        assert!((got.1 - want.1).abs() < 1e-7, "{seen:?}");
    }
}

#[test]
fn a_guard_that_holds_at_the_start_of_a_run_fires_there() {
    let file = compile(
        "below.dsl",
        "mod below { states { h = -0.5, v }
            equations { der(h) = v; der(v) = -9.81; }
            when impact: h < 0 -> stop; }",
    );
    let solved = solve(model(&file), &SolveRequest::new(1.0)).unwrap();
    let [impact] = &solved.events[..] else {
        panic!("{:?}", solved.events)
    };
    assert_eq!((impact.name.as_str(), impact.t()), ("impact", 0.0));
    // On the surface at the start, it waits for its next crossing.
    let file = compile(
        "thrown.dsl",
        "mod thrown { states { h = 0, v = 4.905 }
            equations { der(h) = v; der(v) = -9.81; }
            when impact: h < 0 -> stop; }",
    );
    let solved = solve(model(&file), &SolveRequest::new(3.0)).unwrap();
    assert!((solved.t_end().unwrap() - 1.0).abs() < 1e-9);
}

/// A linearised rimless wheel pushed uphill (`theta'' = theta - gamma` about its stance
/// spoke; a spoke `2 alpha` ahead or behind lands when `|theta| = alpha`, the wheel pivots
/// onto it keeping `c` of its speed). It falls back over its rear spoke and then rocks
/// between two spokes ever faster: every reset leaves the wheel on the other spoke's surface,
/// each rock an excursion shorter than the step before it (once a missed landing and a wheel
/// at `theta = -3e15`).
const RIMLESS: &str = "mod rimless {
    params { gamma = 0.05, alpha = 0.2, c = 0.5 }
    states { theta = 0, omega = 0.02 }
    equations { der(theta) = omega; der(omega) = theta - gamma; }
    when back: theta < -alpha { theta = alpha; omega = c * omega; }
    when ahead: theta > alpha { theta = -alpha; omega = c * omega; }
}";

/// The rimless wheel's landings in closed form (`theta(t) = gamma + (theta0 - gamma) cosh t +
/// omega0 sinh t` about each spoke), until a rock is shorter than `shortest`.
fn rimless_landings(shortest: f64) -> Vec<(&'static str, f64)> {
    let (gamma, alpha, c) = (0.05f64, 0.2f64, 0.5f64);
    let (mut t0, mut theta0, mut omega0) = (0.0, 0.0, 0.02);
    let mut landings = Vec::new();
    loop {
        let (a, b) = (theta0 - gamma, omega0);
        // The way from the spoke, `theta - theta0`, without cancellation (`cosh s - 1 =
        // 2 sinh^2(s/2)`): the last rocks are far smaller than `theta`'s rounding.
        let way = move |s: f64| a * 2.0 * (s / 2.0).sinh().powi(2) + b * s.sinh();
        let dt = first_root(0.0, |s| {
            ((alpha - theta0) - way(s)).min((theta0 + alpha) + way(s))
        });
        if dt < shortest {
            return landings;
        }
        let omega = a * dt.sinh() + b * dt.cosh();
        let back = theta0 + way(dt) < 0.0;
        landings.push((if back { "back" } else { "ahead" }, t0 + dt));
        (t0, theta0, omega0) = (t0 + dt, if back { alpha } else { -alpha }, c * omega);
    }
}

#[test]
fn a_rimless_wheel_rocking_between_two_spokes_lands_on_every_one() {
    let reference = rimless_landings(1e-4);
    assert!(reference.len() >= 6, "{reference:?}");
    let file = compile("rimless.dsl", RIMLESS);
    for method in METHODS {
        let solved = solve(model(&file), &with(method, 1e-8, 1e-10, 10.0)).unwrap();
        let theta = column(&solved, "theta");
        assert!(
            theta.iter().all(|th| th.abs() < 0.2 + 1e-7),
            "{method:?}: the wheel left its spokes"
        );
        let landings: Vec<_> = (solved.events.iter())
            .filter(|e| e.kind == EventKind::Crossing)
            .map(|e| (e.name.as_str(), e.t()))
            .collect();
        assert!(
            landings.len() >= reference.len(),
            "{method:?}: {landings:?}"
        );
        for (k, (got, want)) in landings.iter().zip(&reference).enumerate() {
            assert!(
                got.0 == want.0 && (got.1 - want.1).abs() < 1e-6,
                "{method:?}: landing {k}: {got:?} vs {want:?}"
            );
        }
        // The rocks accumulate where the closed form's do (no rule: the run stops there),
        // within what the tolerances resolve: a rock of speed w rises w^2 / (2 (alpha +
        // gamma)), below rtol * alpha once w < 3e-5, where the rocks left add up to 1e-4 s
        // (dop853 and dopri5 come within 1e-6; rodas4's dense output ends the rocks there).
        let last = rimless_landings(1e-12).last().unwrap().1;
        assert!(
            matches!(
                &solved.stop,
                Stop::Event {
                    kind: EventKind::Accumulation,
                    ..
                }
            ),
            "{method:?}: {:?}",
            solved.stop
        );
        let rest = *solved.times().last().unwrap();
        assert!((rest - last).abs() < 1e-4, "{method:?}: {rest} vs {last}");
    }
}
