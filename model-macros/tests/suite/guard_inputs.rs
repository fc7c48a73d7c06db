//! What a switched model's guards read is derived from their compiled program: the generated
//! `guard_inputs` lists exactly those components, and a run that screens with them fires every
//! event at the same instant, to the bit, as one that interpolates everything.

use model_runtime::Const;
use model_runtime::{
    run_switched, Dop853, EvalError, GuardInputs, HybridOptions, ModeGraph, SwitchedModel,
    Tolerance,
};

model_macros::model! {
    /// A damped oscillator that bounces off a wall, records its turning points (where its
    /// velocity, `der(x)`, changes sign) and is caught once it pulls harder than a
    /// slackening limit.
    mod oscillator {
        params { k = 4.0, c = 0.1, r = 0.9 }
        states { x = 1.0, v = 0.0, caught = 0.0 }
        mode free {
            equations { der(x) = v; der(v) = -k * x - c * v; der(caught) = 0; }
            when turn: der(x) < 0;
            when wall: x < -0.5 { v = -r * v; }
            when pulls: der(v) > 3.9 - t / 5 -> held { caught = t; }
        }
        mode held {
            equations { der(x) = 0; der(v) = 0; der(caught) = 0; }
        }
    }
}

/// A model that declares nothing: its guards are screened on every component.
struct Everything(oscillator::Model);

impl SwitchedModel<Const<3>> for Everything {
    fn graph(&self) -> &ModeGraph {
        self.0.graph()
    }
    fn rhs(&self, mode: usize, t: f64, y: &[f64; 3], dy: &mut [f64; 3]) -> Result<(), EvalError> {
        self.0.rhs(mode, t, y, dy)
    }
    fn event_values(
        &self,
        mode: usize,
        t: f64,
        y: &[f64; 3],
        dy: &[f64; 3],
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        self.0.event_values(mode, t, y, dy, values)
    }
    fn reset(
        &mut self,
        mode: usize,
        event: usize,
        accumulation: bool,
        t: f64,
        y: &[f64; 3],
        dy: &[f64; 3],
        out: &mut [f64; 3],
    ) -> Result<(), EvalError> {
        self.0.reset(mode, event, accumulation, t, y, dy, out)
    }
}

#[test]
fn the_guards_inputs_are_what_their_program_reads() {
    let (x, v) = (oscillator::state::x, oscillator::state::v);
    let model = oscillator::Model::default();
    let free = model
        .guard_inputs(oscillator::mode::free)
        .expect("declared");
    // turn reads der(x), wall reads x, pulls reads der(v).
    assert_eq!(free.state.indices(), &[x]);
    assert_eq!(free.rates.indices(), &[x, v]);
    let held = model
        .guard_inputs(oscillator::mode::held)
        .expect("declared");
    assert_eq!(held, GuardInputs::of(&[], &[]));
    // Checked against the guards themselves: NaN outside the declaration changes no bit,
    // NaN in a declared component spoils some guard.
    let (y, dy) = ([0.3, -1.2, 0.0], [-1.2, -1.08, 0.0]);
    let values = |y: &[f64; 3], dy: &[f64; 3]| {
        let mut g = [0.0; 3];
        model
            .event_values(oscillator::mode::free, 0.5, y, dy, &mut g)
            .unwrap();
        g.map(f64::to_bits)
    };
    let masked = |full: &[f64; 3], keep: &dyn Fn(usize) -> bool| -> [f64; 3] {
        std::array::from_fn(|i| if keep(i) { full[i] } else { f64::NAN })
    };
    let full = values(&y, &dy);
    let seen = values(
        &masked(&y, &|i| free.state.contains(i)),
        &masked(&dy, &|i| free.rates.contains(i)),
    );
    assert_eq!(seen, full);
    for &i in free.state.indices() {
        let g = values(&masked(&y, &|j| j != i), &dy);
        assert!(g.iter().any(|b| f64::from_bits(*b).is_nan()), "y[{i}]");
    }
    for &i in free.rates.indices() {
        let g = values(&y, &masked(&dy, &|j| j != i));
        assert!(g.iter().any(|b| f64::from_bits(*b).is_nan()), "dy[{i}]");
    }
}

#[test]
fn screening_with_the_derived_inputs_changes_no_event() {
    let run = |declared: bool| {
        let model = oscillator::Model::default();
        let tolerance = Tolerance::scalar(1e-10, 1e-12);
        let (options, start) = (HybridOptions::default(), (0.0, oscillator::INITIAL));
        let out = if declared {
            run_switched(model, Dop853::new(), tolerance, options, start, 20.0)
        } else {
            run_switched(
                Everything(model),
                Dop853::new(),
                tolerance,
                options,
                start,
                20.0,
            )
        };
        out.unwrap()
    };
    let (declared, everything) = (run(true), run(false));
    let events = |r: &model_runtime::SwitchedRun<Const<3>>| -> Vec<(String, u64)> {
        (r.events.iter())
            .map(|e| (e.event.clone(), e.t.to_bits()))
            .collect()
    };
    let names: Vec<String> = events(&declared).into_iter().map(|(n, _)| n).collect();
    for name in ["turn", "wall", "pulls"] {
        assert!(names.iter().any(|n| n == name), "no {name} in {names:?}");
    }
    assert_eq!(events(&declared), events(&everything));
    assert_eq!(declared.y.map(f64::to_bits), everything.y.map(f64::to_bits));
    assert_eq!(declared.stats.steps, everything.stats.steps);
}
