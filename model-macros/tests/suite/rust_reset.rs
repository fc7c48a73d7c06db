//! `by FUNCTION`: an event whose new state a Rust function computes. The same ball twice, its
//! impact written in the DSL and computed in Rust, must bounce at the same instants to the bit;
//! a function's error ends the run naming the event's transition. A function may also decide
//! where the run goes (`-> a | b | stop by FUNCTION`): the ball that comes to rest once its
//! impacts are slow, at the closed-form instant.

use model_runtime::Const;
use model_runtime::{
    run_switched, Dop853, EvalError, Fired, HybridError, HybridOptions, Tolerance,
};

model_macros::model! {
    /// The ball with its impact law written out.
    mod written {
        params { g = 9.81, e = 0.8 }
        states { h = 1.0, v = 0.0 }
        mode flying {
            equations { der(h) = v; der(v) = -g; }
            when impact: h < 0 { v = -e * v; }
            when impact accumulates -> resting { h = 0; v = 0; }
        }
        mode resting {
            equations { der(h) = 0; der(v) = 0; }
        }
    }
}

model_macros::model! {
    /// The same ball, its impact and its rest computed by Rust functions.
    mod computed {
        params { g = 9.81, e = 0.8 }
        states { h = 1.0, v = 0.0 }
        mode flying {
            equations { der(h) = v; der(v) = -g; }
            when impact: h < 0 by bounce;
            when impact accumulates -> resting by come_to_rest;
        }
        mode resting {
            equations { der(h) = 0; der(v) = 0; }
        }
    }
}

model_macros::model! {
    /// A ball whose impact law holds only up to 4 m/s: dropped from 1 m it arrives faster.
    mod limited {
        params { g = 9.81, e = 0.8 }
        states { h = 1.0, v = 0.0 }
        equations { der(h) = v; der(v) = -g; }
        when impact: h < 0 by bounce_below_4;
    }
}

model_macros::model! {
    /// A ball that stays on the floor once it lands slower than `v_min`, and cracks (the run
    /// stops) when it lands faster than `v_crack`.
    mod landing {
        params { g = 9.81, e = 0.8, v_min = 2.0, v_crack = 100.0 }
        states { h = 1.0, v = 0.0 }
        mode flying {
            equations { der(h) = v; der(v) = -g; }
            when impact: h < 0 -> flying | resting | stop by land;
        }
        mode resting {
            equations { der(h) = 0; der(v) = 0; }
        }
    }
}

model_macros::model! {
    /// A ball whose landing names a mode the event does not list.
    mod confused {
        params { g = 9.81 }
        states { h = 1.0, v = 0.0 }
        mode flying {
            equations { der(h) = v; der(v) = -g; }
            when impact: h < 0 -> flying | stop by land_anywhere;
        }
        mode resting {
            equations { der(h) = 0; der(v) = 0; }
        }
    }
}

/// Where `landing` goes: cracks, rests or bounces, by its impact speed.
fn land(
    model: &landing::Model,
    _t: f64,
    y: &[f64; landing::N_STATES],
    _dy: &[f64; landing::N_STATES],
    new: &mut [f64; landing::N_STATES],
) -> Result<Option<usize>, EvalError> {
    use landing::param;
    let p = &model.params;
    let speed = y[landing::state::v].abs();
    if speed > p[param::v_crack] {
        return Ok(None);
    }
    if speed < p[param::v_min] {
        *new = [0.0, 0.0];
        return Ok(Some(landing::mode::resting));
    }
    new[landing::state::v] = -p[param::e] * y[landing::state::v];
    Ok(Some(landing::mode::flying))
}

/// Names `resting`, which `confused`'s impact does not list.
fn land_anywhere(
    _model: &confused::Model,
    _t: f64,
    _y: &[f64; confused::N_STATES],
    _dy: &[f64; confused::N_STATES],
    _new: &mut [f64; confused::N_STATES],
) -> Result<Option<usize>, EvalError> {
    Ok(Some(confused::mode::resting))
}

/// The impact of `computed`: `v⁺ = −e v⁻`, the written law's operations.
fn bounce(
    model: &computed::Model,
    _t: f64,
    y: &[f64; computed::N_STATES],
    _dy: &[f64; computed::N_STATES],
    new: &mut [f64; computed::N_STATES],
) -> Result<(), EvalError> {
    let e = model.params[computed::param::e];
    new[computed::state::v] = -(y[computed::state::v] * e);
    Ok(())
}

/// The rest of `computed`: on the floor, still.
fn come_to_rest(
    _model: &computed::Model,
    _t: f64,
    _y: &[f64; computed::N_STATES],
    _dy: &[f64; computed::N_STATES],
    new: &mut [f64; computed::N_STATES],
) -> Result<(), EvalError> {
    *new = [0.0; computed::N_STATES];
    Ok(())
}

/// The impact of `limited`: refuses speeds above 4 m/s.
fn bounce_below_4(
    model: &limited::Model,
    _t: f64,
    y: &[f64; limited::N_STATES],
    _dy: &[f64; limited::N_STATES],
    new: &mut [f64; limited::N_STATES],
) -> Result<(), EvalError> {
    let v = y[limited::state::v];
    if v.abs() > 4.0 {
        return Err(EvalError::NonFinite {
            model: "limited".into(),
            quantity: "the impact speed (the law holds up to 4 m/s)".into(),
            value: v,
        });
    }
    new[limited::state::v] = -model.params[limited::param::e] * v;
    Ok(())
}

fn tolerance() -> Tolerance<Const<2>> {
    Tolerance::scalar(1e-10, 1e-12)
}

#[test]
fn a_reset_by_a_rust_function_is_the_written_reset_to_the_bit() {
    let options = HybridOptions::default();
    let a = run_switched(
        written::Model::default(),
        Dop853::new(),
        tolerance(),
        options,
        (0.0, written::INITIAL),
        10.0,
    )
    .unwrap();
    let b = run_switched(
        computed::Model::default(),
        Dop853::new(),
        tolerance(),
        options,
        (0.0, computed::INITIAL),
        10.0,
    )
    .unwrap();
    let bits = |ts: Vec<f64>| ts.iter().map(|t| t.to_bits()).collect::<Vec<_>>();
    let (impacts, rest) = (
        a.times("impact", Fired::Reset),
        a.times("impact", Fired::Accumulated),
    );
    assert!(impacts.len() > 20, "{impacts:?}");
    assert!((impacts[0] - (2.0f64 / 9.81).sqrt()).abs() < 1e-12);
    assert_eq!(bits(b.times("impact", Fired::Reset)), bits(impacts));
    assert_eq!(bits(b.times("impact", Fired::Accumulated)), bits(rest));
    assert_eq!((b.mode.as_str(), b.y), ("resting", [0.0, 0.0]));
    assert_eq!(a.y.map(f64::to_bits), b.y.map(f64::to_bits));
}

#[test]
fn an_error_of_the_rust_function_ends_the_run_at_the_event() {
    let failure = run_switched(
        limited::Model::default(),
        Dop853::new(),
        tolerance(),
        HybridOptions::default(),
        (0.0, limited::INITIAL),
        10.0,
    )
    .expect_err("the law refuses 4.43 m/s");
    let HybridError::Transition { t, source, .. } = &*failure.error else {
        panic!("{failure}")
    };
    assert!((t - (2.0f64 / 9.81).sqrt()).abs() < 1e-9, "{t}");
    assert!(source.to_string().contains("up to 4 m/s"), "{source}");
    assert!(failure.to_string().contains("up to 4 m/s"), "{failure}");
}

#[test]
fn the_table_of_modes_names_the_rust_function() {
    assert!(
        computed::SWITCHING_MARKDOWN.contains("the state `by bounce` (Rust), restart `flying`"),
        "{}",
        computed::SWITCHING_MARKDOWN
    );
}

fn landing_run(params: landing::Params) -> model_runtime::SwitchedRun<Const<2>> {
    run_switched(
        landing::Model::from_params(params),
        Dop853::new(),
        tolerance(),
        HybridOptions::default(),
        (0.0, landing::INITIAL),
        10.0,
    )
    .unwrap()
}

#[test]
fn a_rust_function_decides_where_the_run_goes() {
    let (g, e) = (9.81f64, 0.8f64);
    // Impact speeds v1 e^k: 4.43, 3.54, 2.84, 2.27, then 1.81 < 2: resting at the fifth.
    let run = landing_run(landing::Params::default());
    let impacts = run.times("impact", Fired::Reset);
    assert_eq!(impacts.len(), 5, "{impacts:?}");
    let v1 = (2.0 * g).sqrt();
    let mut want = (2.0 / g).sqrt();
    for (k, t) in impacts.iter().enumerate() {
        assert!((t - want).abs() < 1e-9, "impact {k}: {t} vs {want}");
        want += 2.0 * e.powi(k as i32 + 1) * v1 / g;
    }
    assert_eq!(
        (run.mode.as_str(), run.y, run.stopped_by),
        ("resting", [0.0, 0.0], None)
    );

    // Faster than it can take: the first impact stops the run, with the event as the reason.
    let fragile = landing::Params {
        v_crack: 4.0,
        ..landing::Params::default()
    };
    let run = landing_run(fragile);
    assert_eq!(run.stopped_by.as_deref(), Some("impact"));
    assert!((run.t - (2.0 / g).sqrt()).abs() < 1e-9, "{}", run.t);
    assert!(landing::SWITCHING_MARKDOWN.contains(
        "the state `by land` (Rust), go to one of `flying`, `resting`, stop, as it decides"
    ));
}

#[test]
fn a_decision_for_a_mode_the_event_does_not_list_fails_the_run() {
    let failure = run_switched(
        confused::Model::default(),
        Dop853::new(),
        tolerance(),
        HybridOptions::default(),
        (0.0, confused::INITIAL),
        10.0,
    )
    .expect_err("resting is not listed");
    let HybridError::Transition { source, .. } = &*failure.error else {
        panic!("{failure}")
    };
    assert_eq!(
        *source,
        EvalError::Undecided {
            event: "flying.impact".to_string(),
            mode: Some(confused::mode::resting),
        }
    );
}
