//! Discrete values, a mode's own coordinates and a first step, compiled by `model!`: the
//! ball that counts its bounces and falls in its downward speed bounces at the closed-form
//! instants, its count and the time of its last bounce held in its parameters, and its first
//! step the declared one. The same text runs interpreted in `model-interpreted`'s tests.

use model_runtime::{run_switched, Dop853, HybridOptions, SwitchedModel, Tolerance};

model_macros::model! {
    /// A ball that counts its bounces, falling in its downward speed `w` (dropped: it starts
    /// falling).
    mod ball {
        params { g = 9.81, e = 0.8 }
        states { h = 1.0, v = 0.0 }
        discrete { bounces = 0, t_last = -1 }
        mode falling {
            states { w } replace { v }
            equations { der(h) = -w; der(w) = g; }
            when impact: h < 0 -> rising { v = e * w; bounces = bounces + 1; t_last = t; }
        }
        mode rising {
            equations { der(h) = v; der(v) = -g; }
            first_step = abs(v / der(v)) / 100;
            when apex: v < 0 -> falling { w = -v; }
        }
    }
}

/// The impact instants of a ball dropped from `h0`: `t1 = sqrt(2 h0 / g)`, then
/// `t_{k+1} = t_k + 2 e^k v1 / g`.
fn impacts(n: usize) -> Vec<f64> {
    let (g, e, h0) = (9.81f64, 0.8f64, 1.0f64);
    let v1 = (2.0 * g * h0).sqrt();
    let mut t = (2.0 * h0 / g).sqrt();
    (0..n)
        .map(|k| {
            let now = t;
            t += 2.0 * e.powi(k as i32 + 1) * v1 / g;
            now
        })
        .collect()
}

#[test]
fn the_ball_bounces_on_time_and_holds_its_count() {
    let mut model = ball::Model::default();
    assert_eq!(ball::N_DISCRETE, 2);
    assert_eq!(ball::N_PARAMS, 4);
    assert_eq!(ball::PARAM_NAMES, ["g", "e", "bounces", "t_last"]);
    assert_eq!(model.params[ball::discrete::t_last], -1.0);
    assert_eq!(ball::falling::state::w, ball::rising::state::v);
    assert_eq!(ball::STATE_NAMES, ["h", "w"]);
    let tolerance = Tolerance::scalar(1e-11, 1e-13);
    let start = (0.0, ball::INITIAL);
    let run = run_switched(
        &mut model,
        Dop853::new(),
        tolerance,
        HybridOptions::default(),
        start,
        3.5,
    )
    .expect("the ball runs");
    let seen = run.times("impact", model_runtime::Fired::Reset);
    let expected: Vec<f64> = impacts(40).into_iter().filter(|&t| t < 3.5).collect();
    assert_eq!(seen.len(), expected.len(), "impacts before 3.5 s");
    for (k, (t, x)) in seen.iter().zip(&expected).enumerate() {
        assert!((t - x).abs() < 1e-9, "impact {k}: {t} against {x}");
    }
    // The apexes halfway between the impacts.
    let apexes = run.times("apex", model_runtime::Fired::Reset);
    assert!(
        apexes.len() + 1 >= expected.len(),
        "{} apexes",
        apexes.len()
    );
    for (k, t) in apexes.iter().enumerate().take(expected.len() - 1) {
        let mid = 0.5 * (expected[k] + expected[k + 1]);
        assert!((t - mid).abs() < 1e-9, "apex {k}: {t} against {mid}");
    }
    // Held between events: the count and the last impact's time.
    assert_eq!(model.params[ball::discrete::bounces], seen.len() as f64);
    assert_eq!(model.params[ball::discrete::t_last], *seen.last().unwrap());
}

#[test]
fn the_first_step_is_the_declared_one_where_it_is_positive() {
    let model = ball::Model::default();
    let rising = ball::mode::rising;
    let h = model.first_step(rising, 0.0, &[0.5, 3.0]).unwrap();
    assert!((h - 3.0 / 9.81 / 100.0).abs() < 1e-15, "{h}");
    // At the top of a throw the declared step is zero: the integrator chooses.
    assert_eq!(model.first_step(rising, 0.0, &[1.0, 0.0]), None);
    // A mode that declares none.
    assert_eq!(
        model.first_step(ball::mode::falling, 0.0, &[1.0, 1.0]),
        None
    );
}
