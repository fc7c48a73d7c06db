//! `by FUNCTION`: an event whose new state a Rust function computes. The same ball twice, its
//! impact written in the DSL and computed in Rust, must bounce at the same instants to the bit;
//! a function's error ends the run naming the event's transition.

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
            model: "limited",
            quantity: "the impact speed (the law holds up to 4 m/s)",
            value: v,
        });
    }
    new[limited::state::v] = -model.params[limited::param::e] * v;
    Ok(())
}

fn tolerance() -> Tolerance<2> {
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
    let HybridError::Transition { t, source, .. } = &failure.error else {
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
