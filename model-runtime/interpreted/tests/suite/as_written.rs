//! A model runs as its file says: the initial values written on its states are where a run
//! starts (smooth and switched alike, a request's values overriding them), and what the run
//! writes is what the file asks for at each time, or an error naming why not.

use crate::{compile, model, tight};
use model_interpreted::{initial_state, solve, SolveRequest};

/// `x = 2 e^-kt`, `y = 3`, from the values written on the states.
pub const DECAY: &str = "mod decay {
    params { k = 1.0 }
    states { x = 2.0, y = 3.0 }
    equations { der(x) = -k * x; der(y) = 0; }
}";

/// The same decay with modes: a switched model reads the same initial values.
const SWITCHED_DECAY: &str = "mod decay {
    params { k = 1.0 }
    states { x = 2.0, y = 3.0 }
    mode only {
        equations { der(x) = -k * x; der(y) = 0; }
        when never: t > 100 { x = 0; }
    }
}";

#[test]
fn a_smooth_model_starts_at_its_written_initial_values() {
    for text in [DECAY, SWITCHED_DECAY] {
        let file = compile("decay.dsl", text);
        assert_eq!(initial_state(model(&file), &[]).unwrap(), [2.0, 3.0]);
        let solved = solve(model(&file), &tight(SolveRequest::new(1.0))).unwrap();
        assert_eq!(solved.row(0)[1..3], [2.0, 3.0], "{text}");
        let last = solved.last_row().unwrap();
        assert_eq!(last[0], 1.0);
        assert!((last[1] - 2.0 * (-1.0f64).exp()).abs() < 1e-11, "{last:?}");
        assert_eq!(last[2], 3.0);
        // A value given by name overrides the file's; the other keeps the file's.
        let request = SolveRequest {
            state: vec![("x".into(), 1.0)],
            ..tight(SolveRequest::new(1.0))
        };
        let last = solve(model(&file), &request).unwrap().last_row().unwrap();
        assert!((last[1] - (-1.0f64).exp()).abs() < 1e-11, "{last:?}");
        assert_eq!(last[2], 3.0);
    }
}

/// A state without a written value starts at zero, beside one with a value.
#[test]
fn a_state_without_a_written_value_starts_at_zero() {
    let file = compile(
        "partial.dsl",
        "mod partial { states { x = 5, v } equations { der(x) = v; der(v) = 0; } }",
    );
    assert_eq!(initial_state(model(&file), &[]).unwrap(), [5.0, 0.0]);
}
