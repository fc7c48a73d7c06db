//! Runs backward in time (`t_end < t0`): closed forms recovered, the observer and the
//! transition map in the caller's time, a guard's direction along the run (SciPy's rule), a
//! failure dated in `t`.

use crate::common::{info, Forced};
use model_runtime::{
    integrate, Const, Crossed, Direction, Dop853, Dopri5, EvalError, Event, EventHit, GuardSpec,
    HybridOptions, HybridSolver, HybridSystem, Interpolant, Method, Model, ModelInfo, Observed,
    Observer, Output, Problem, Rodas4, Sample, SolveError, SolveFailure, StepOptions, StepView,
    Stepper, StopReason, Termination, Tolerance, Transition, TransitionRecord, WithOutputs,
};

/// `Forced`'s closed form at `t`: `(cos t, −sin t, exp(sin t))`.
fn forced_at(t: f64) -> [f64; 3] {
    [t.cos(), -t.sin(), t.sin().exp()]
}

fn back_and_forth<S: Stepper<Const<3>> + Clone>(stepper: S, name: &str) {
    let tol = Tolerance::scalar(1e-11, 1e-12);
    let opts = StepOptions::default();
    // From t = 2 back to t = -1: the non-autonomous component checks that every stage is
    // evaluated at its own time.
    let back = integrate(
        &Forced,
        stepper.clone(),
        tol,
        opts,
        2.0,
        &forced_at(2.0),
        -1.0,
    )
    .unwrap();
    assert_eq!(back.t, -1.0);
    for (i, (got, want)) in back.y.iter().zip(forced_at(-1.0)).enumerate() {
        assert!(
            (got - want).abs() < 1e-8,
            "{name}: component {i}: {got} vs {want}"
        );
    }
    // And forward again to the start: within what the tolerances allow both ways.
    let again = integrate(&Forced, stepper, tol, opts, -1.0, &back.y, 2.0).unwrap();
    for (got, want) in again.y.iter().zip(forced_at(2.0)) {
        assert!((got - want).abs() < 2e-8, "{name}: {got} vs {want}");
    }
}

#[test]
fn every_method_integrates_backward_to_the_closed_form() {
    back_and_forth(Dop853::new(), "dop853");
    back_and_forth(Dopri5::new(), "dopri5");
    back_and_forth(Rodas4::new(), "rodas4");
}

/// `Forced` written by hand in `s = −t`: `dy/ds = −f(−s, y)`.
struct ForcedReflected;
static FORCED_REFLECTED: ModelInfo = info("forced in -t", &["x", "v", "z"]);
impl Model<3> for ForcedReflected {
    fn info(&self) -> &'static ModelInfo {
        &FORCED_REFLECTED
    }
    fn rhs(&self, s: f64, y: &[f64; 3], dy: &mut [f64; 3]) -> Result<(), EvalError> {
        Forced.rhs(-s, y, dy)?;
        *dy = dy.map(|d| -d);
        Ok(())
    }
}

#[test]
fn a_backward_run_is_the_reflected_forward_run_bit_for_bit() {
    // Nothing is rounded on the way in or out (negation is exact): the backward run and the
    // forward run of the model reflected by hand take the same steps to the same bits.
    let tol = Tolerance::scalar(1e-9, 1e-11);
    let opts = StepOptions::default();
    let y0 = forced_at(2.0);
    let back = integrate(&Forced, Dop853::new(), tol, opts, 2.0, &y0, -1.0).unwrap();
    let reflected = integrate(&ForcedReflected, Dop853::new(), tol, opts, -2.0, &y0, 1.0).unwrap();
    assert_eq!(back.y, reflected.y);
    assert_eq!(back.t, -reflected.t);
    assert_eq!(back.stats.steps, reflected.stats.steps);
    assert_eq!(back.stats.rejected, reflected.stats.rejected);
}

/// `x' = v, v' = −x` from `x = cos t` with the guard `x` of one direction, each crossing
/// passing on (a restart in place).
struct Crossings {
    guards: [GuardSpec<()>; 1],
}

static OSC: ModelInfo = info("osc", &["x", "v"]);
struct Osc;
impl Model<2> for Osc {
    fn info(&self) -> &'static ModelInfo {
        &OSC
    }
    fn rhs(&self, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
        *dy = [y[1], -y[0]];
        Ok(())
    }
}

impl HybridSystem<Const<2>> for Crossings {
    type Mode = ();
    type Guard = ();
    type Stop = ();
    type Note = ();
    fn rhs(&self, _: (), t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
        Osc.rhs(t, y, dy)
    }
    fn guards(&self, _: ()) -> &[GuardSpec<()>] {
        &self.guards
    }
    fn guard_values(
        &self,
        _: (),
        _t: f64,
        y: &[f64; 2],
        dy: &[f64; 2],
        g: &mut [f64],
    ) -> Result<(), EvalError> {
        // The guard is handed dx/dt, which is v: a reversed derivative would show here.
        assert!((dy[0] - y[1]).abs() < 1e-6, "dy = {dy:?} at y = {y:?}");
        g[0] = y[0];
        Ok(())
    }
    fn on_event(
        &mut self,
        _: (),
        hit: &EventHit<Const<2>, ()>,
    ) -> Result<Transition<Const<2>, (), ()>, EvalError> {
        Ok(Transition::Continue { y: hit.y, note: () })
    }
}

/// What the observer was handed.
#[derive(Default)]
struct Seen {
    steps: Vec<(f64, f64)>,
    samples: Vec<(f64, f64)>,
    hits: Vec<(f64, Crossed, f64)>,
}

impl Observer<Const<2>, (), ()> for Seen {
    fn wants_dense(&self) -> bool {
        true
    }
    fn on_step(&mut self, step: &StepView<'_, Const<2>, ()>) -> Observed {
        // The step's start derivative and interpolant, in t.
        assert_eq!(step.f0[0], step.y0[1]);
        let dense = step.dense.expect("asked for");
        let mid = (step.t0 + step.t1) / 2.0;
        let mut y = [0.0; 2];
        dense.at(mid, &mut y);
        assert!((y[0] - mid.cos()).abs() < 1e-8, "{mid}: {y:?}");
        let mut stored = [0.0; 2];
        dense.stored().at(mid, &mut stored);
        assert_eq!(stored, y);
        self.steps.push((step.t0, step.t1));
        Ok(())
    }
    fn on_sample(&mut self, s: &Sample<'_, Const<2>, ()>) -> Observed {
        self.samples.push((s.t, s.y[0]));
        Ok(())
    }
    fn on_transition(&mut self, r: TransitionRecord<Const<2>, (), ()>) -> Observed {
        self.hits.push((r.hit.t, r.hit.direction, r.hit.dy[0]));
        Ok(())
    }
}

fn crossings_back(direction: Direction) -> (Seen, f64) {
    let mut system = Crossings {
        guards: [GuardSpec { id: (), direction }],
    };
    let options = HybridOptions {
        sample_rate: Some(10.0),
        ..HybridOptions::default()
    };
    let mut solver =
        HybridSolver::new(Dop853::new(), Tolerance::scalar(1e-11, 1e-12), options).unwrap();
    let mut seen = Seen::default();
    let y0 = [3f64.cos(), -3f64.sin()];
    let out = solver
        .run(&mut system, (), 3.0, &y0, 0.0, &mut seen)
        .unwrap();
    assert_eq!(out.stop, StopReason::EndTime);
    (seen, out.t)
}

#[test]
fn a_backward_run_hands_everything_over_in_t_and_fires_along_the_run() {
    // From t = 3 back to 0, x = cos t goes from -0.99 through 0 at pi/2 up to 1: an up
    // crossing as the run proceeds (SciPy's `direction = +1`), though dx/dt = -1 there.
    let (up, end) = crossings_back(Direction::Up);
    assert_eq!(end, 0.0);
    assert_eq!(up.hits.len(), 1, "{:?}", up.hits);
    let (t, crossed, dxdt) = up.hits[0];
    assert!((t - std::f64::consts::FRAC_PI_2).abs() < 1e-10, "{t}");
    assert_eq!(crossed, Crossed::Up);
    assert!((dxdt + 1.0).abs() < 1e-8, "{dxdt}");
    let (down, _) = crossings_back(Direction::Down);
    assert!(down.hits.is_empty(), "{:?}", down.hits);
    // Steps go back in time, each from where the last one ended, from 3 to 0.
    assert_eq!(up.steps.first().unwrap().0, 3.0);
    assert_eq!(up.steps.last().unwrap().1, 0.0);
    for pair in up.steps.windows(2) {
        assert!(pair[0].1 < pair[0].0);
        assert_eq!(pair[0].1, pair[1].0);
    }
    // Samples at 3 - k/10, on the closed form.
    assert_eq!(up.samples.len(), 31);
    for (k, &(t, x)) in up.samples.iter().enumerate() {
        assert!((t - (3.0 - k as f64 / 10.0)).abs() < 1e-14, "{k}: {t}");
        assert!((x - t.cos()).abs() < 1e-9, "{t}: {x}");
    }
}

#[test]
fn a_problem_runs_backward_with_decreasing_output_times() {
    let times: Vec<f64> = (0..=20).map(|k| 2.0 - 0.1 * k as f64).collect();
    let solution = Problem::new(&Forced, forced_at(2.0), (2.0, 0.0))
        .method(Method::Dop853)
        .tolerances(1e-11, 1e-12)
        .output(Output::Times(times.clone()))
        .event(Event::new("x", |_t, y, _dy| y[0]).direction(Direction::Up))
        .solve::<0>()
        .unwrap();
    assert_eq!(solution.t, times);
    for (t, y) in solution.t.iter().zip(&solution.y) {
        assert!((y[2] - t.sin().exp()).abs() < 1e-9, "{t}");
    }
    assert_eq!(solution.stop, Termination::EndTime);
    assert_eq!(solution.events.len(), 1);
    assert!((solution.events[0].t - std::f64::consts::FRAC_PI_2).abs() < 1e-10);
    // Increasing times are out of a backward run's order.
    let refused = Problem::new(&Forced, forced_at(2.0), (2.0, 0.0))
        .output(Output::Times(vec![0.5, 1.0]))
        .solve::<0>()
        .unwrap_err();
    assert!(
        matches!(refused, SolveFailure::OutputTime { index: 1, .. }),
        "{refused}"
    );
}

impl WithOutputs<3, 0> for Forced {
    fn outputs(
        &self,
        _: f64,
        _: &[f64; 3],
        _: &[f64; 3],
        _: &mut [f64; 0],
    ) -> Result<(), EvalError> {
        Ok(())
    }
}

impl WithOutputs<1, 0> for Singular {
    fn outputs(
        &self,
        _: f64,
        _: &[f64; 1],
        _: &[f64; 1],
        _: &mut [f64; 0],
    ) -> Result<(), EvalError> {
        Ok(())
    }
}

/// `y' = 1`, which cannot be evaluated before `t = 0.5`.
struct Singular;
static SINGULAR: ModelInfo = info("singular", &["y"]);
impl Model<1> for Singular {
    fn info(&self) -> &'static ModelInfo {
        &SINGULAR
    }
    fn rhs(&self, t: f64, _y: &[f64; 1], dy: &mut [f64; 1]) -> Result<(), EvalError> {
        if t < 0.5 {
            return Err(EvalError::singular("singular", "t - 0.5", t - 0.5));
        }
        dy[0] = 1.0;
        Ok(())
    }
}

#[test]
fn a_backward_failure_is_dated_in_t() {
    let error = integrate(
        &Singular,
        Dop853::new(),
        Tolerance::scalar(1e-8, 1e-10),
        StepOptions::default(),
        1.0,
        &[1.0],
        0.0,
    )
    .unwrap_err();
    let t = error.time().expect("a dated failure");
    assert!(t < 0.5 && t > 0.49, "{error}");
    assert!(matches!(error, SolveError::Eval { .. }), "{error}");
    let failed = Problem::new(&Singular, [1.0], (1.0, 0.0))
        .solve::<0>()
        .unwrap_err();
    match &failed {
        SolveFailure::Solve { error, .. } => {
            let t = error.time().expect("a dated failure");
            assert!(t < 0.5 && t > 0.49, "{failed}");
        }
        other => panic!("{other}"),
    }
}
