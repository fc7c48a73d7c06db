//! Guards that declare what they read: screening estimates fill only that, the rest is NaN, and
//! a wrong declaration costs exact evaluations but never changes an event.

use crate::common::Forced;
use model_runtime::Const;

use model_runtime::{
    Components, Direction, Dop853, Dopri5, EvalError, EventHit, GuardInputs, GuardSpec,
    HybridOptions, HybridSolver, HybridSystem, Integrator, InteriorChecks, Model, Rk4, Rodas4,
    Stats, StepEnd, StepOptions, StepStart, Stepper, Tolerance, Transition,
};
use std::cell::Cell;

/// The guard reads `x` and `v'`: `x + v'/2 - 0.2 = cos(t)/2 - 0.2` on the forced oscillator.
const READS: GuardInputs<Const<3>> = GuardInputs::of(&[0], &[1]);

const UP: [GuardSpec<()>; 1] = [GuardSpec {
    id: (),
    direction: Direction::Up,
}];

/// [`Forced`] with that guard, restarting in place at each crossing, declaring `inputs`.
struct Declared {
    inputs: GuardInputs<Const<3>>,
    /// Guard evaluations that saw NaN in every undeclared component and in no declared one.
    masked_calls: Cell<u64>,
    /// Guard evaluations that saw NaN in a component they read.
    nan_reads: Cell<u64>,
    events: Vec<f64>,
}

impl Declared {
    fn new(inputs: GuardInputs<Const<3>>) -> Self {
        Declared {
            inputs,
            masked_calls: Cell::new(0),
            nan_reads: Cell::new(0),
            events: Vec::new(),
        }
    }
}

impl HybridSystem<Const<3>> for Declared {
    type Mode = ();
    type Guard = ();
    type Stop = ();
    type Note = ();
    fn rhs(&self, _: (), t: f64, y: &[f64; 3], dy: &mut [f64; 3]) -> Result<(), EvalError> {
        Forced.rhs(t, y, dy)
    }
    fn guards(&self, _: ()) -> &[GuardSpec<()>] {
        &UP
    }
    fn guard_inputs(&self, _: ()) -> Option<GuardInputs<Const<3>>> {
        Some(self.inputs)
    }
    fn guard_values(
        &self,
        _: (),
        _t: f64,
        y: &[f64; 3],
        dy: &[f64; 3],
        g: &mut [f64],
    ) -> Result<(), EvalError> {
        let nan_where = |v: &[f64; 3], which: &Components<Const<3>>, inside: bool| {
            (0..3).all(|i| which.contains(i) != inside || v[i].is_nan())
        };
        let none_where = |v: &[f64; 3], which: &Components<Const<3>>| {
            which.indices().iter().all(|&i| !v[i].is_nan())
        };
        let inputs = self.inputs;
        if nan_where(y, &inputs.state, false)
            && nan_where(dy, &inputs.rates, false)
            && none_where(y, &inputs.state)
            && none_where(dy, &inputs.rates)
        {
            self.masked_calls.set(self.masked_calls.get() + 1);
        }
        if y[0].is_nan() || dy[1].is_nan() {
            self.nan_reads.set(self.nan_reads.get() + 1);
        }
        g[0] = y[0] + 0.5 * dy[1] - 0.2;
        Ok(())
    }
    fn on_event(
        &mut self,
        _: (),
        hit: &EventHit<Const<3>, ()>,
    ) -> Result<Transition<Const<3>, (), ()>, EvalError> {
        self.events.push(hit.t);
        Ok(Transition::Continue { y: hit.y, note: () })
    }
}

/// What a run of [`Declared`] did.
#[derive(Debug)]
struct Run {
    events: Vec<u64>,
    final_state: Vec<u64>,
    guard_evals: u64,
    estimates: u64,
    masked_calls: u64,
    nan_reads: u64,
}

fn run<S: Stepper<Const<3>>>(stepper: S, inputs: GuardInputs<Const<3>>) -> Run {
    let options = HybridOptions {
        guard_checks: InteriorChecks::Screened(16),
        ..HybridOptions::default()
    };
    let mut solver = HybridSolver::new(stepper, Tolerance::scalar(1e-9, 1e-9), options).unwrap();
    let mut sys = Declared::new(inputs);
    let out = solver
        .run(&mut sys, (), 0.0, &Forced::Y0, 20.0, &mut ())
        .unwrap();
    Run {
        events: sys.events.iter().map(|t| t.to_bits()).collect(),
        final_state: out.y.iter().map(|v| v.to_bits()).collect(),
        guard_evals: out.stats.guard_evals,
        estimates: out.stats.guard_estimates,
        masked_calls: sys.masked_calls.get(),
        nan_reads: sys.nan_reads.get(),
    }
}

fn declarations_change_only_the_cost<S: Stepper<Const<3>>>(make: impl Fn() -> S) {
    let all = run(make(), GuardInputs::ALL);
    let exact = run(make(), READS);
    // Reads `x` and `v'`, declares only `v'`.
    let short = run(make(), GuardInputs::of(&[], &[1]));
    // cos(t)/2 - 0.2 crosses upwards three times in 20 s.
    assert_eq!(all.events.len(), 3, "{}: {all:?}", S::NAME);
    // A right declaration: the same run bit for bit, with the same estimates and exact
    // evaluations as declaring everything, each estimate with NaN exactly outside the
    // declaration, none read by the guard.
    assert_eq!(exact.events, all.events, "{}", S::NAME);
    assert_eq!(exact.final_state, all.final_state, "{}", S::NAME);
    assert!(exact.estimates > 0);
    assert_eq!(
        (exact.estimates, exact.guard_evals),
        (all.estimates, all.guard_evals)
    );
    assert_eq!(exact.masked_calls, exact.estimates, "{}", S::NAME);
    assert_eq!(exact.nan_reads, 0);
    // A short one: every estimate reads NaN and asks for an exact evaluation. The events are
    // the same; only where the root finder's bracket starts moves (to the exact check point
    // before the crossing), so their times may differ in the last few bits.
    assert_eq!(short.nan_reads, short.estimates, "{}", S::NAME);
    assert_eq!(short.events.len(), all.events.len(), "{}", S::NAME);
    for (a, b) in short.events.iter().zip(&all.events) {
        let (a, b) = (f64::from_bits(*a), f64::from_bits(*b));
        assert!(
            (a - b).abs() <= 8.0 * f64::EPSILON * b,
            "{}: {a} {b}",
            S::NAME
        );
    }
    assert!(
        short.guard_evals >= all.guard_evals + short.estimates / 2,
        "{}: {short:?} {all:?}",
        S::NAME
    );
}

#[test]
fn every_stepper_screens_with_the_declared_inputs_only() {
    declarations_change_only_the_cost(Dopri5::new);
    declarations_change_only_the_cost(Dop853::new);
    declarations_change_only_the_cost(Rodas4::new);
    declarations_change_only_the_cost(|| Rk4::new(0.01));
}

const SETS: [Components<Const<3>>; 4] = [
    Components::ALL,
    Components::NONE,
    Components::of(&[1]),
    Components::of(&[0, 2]),
];

/// `full` in the components of `set`, NaN elsewhere, as bits.
fn chosen(full: &[f64; 3], set: &Components<Const<3>>) -> [u64; 3] {
    std::array::from_fn(|i| {
        if set.contains(i) {
            full[i].to_bits()
        } else {
            f64::NAN.to_bits()
        }
    })
}

/// A partial interpolation gives the full one's bits in the chosen components and leaves the
/// others untouched, for every stepper (each its own fast path or the default).
fn partial_is_full_where_chosen<S: Stepper<Const<3>>>(mut stepper: S, h: f64) {
    let t0 = 0.3;
    let y0 = Forced::exact(t0);
    let (mut f0, mut y1, mut f1) = ([0.0; 3], [0.0; 3], [0.0; 3]);
    Forced.rhs(t0, &y0, &mut f0).unwrap();
    let start = StepStart {
        t: t0,
        y: &y0,
        f: &f0,
    };
    let (tol, mut stats) = (Tolerance::scalar(1e-6, 1e-6), Stats::default());
    let end = StepEnd {
        y: &mut y1,
        f: &mut f1,
    };
    stepper
        .attempt(&Forced, start, h, &tol, end, &mut stats)
        .unwrap();
    stepper
        .prepare_dense(&Forced, start, &y1, &f1, h, &mut stats)
        .unwrap();
    for k in 0..=8 {
        let theta = k as f64 / 8.0;
        let (mut y, mut dy) = ([0.0; 3], [0.0; 3]);
        stepper.interpolate(theta, &mut y);
        stepper.interpolate_derivative(theta, h, &mut dy);
        for (i, yi) in y.iter().enumerate() {
            let single = stepper.interpolate_component(theta, i);
            assert_eq!(single.to_bits(), yi.to_bits(), "{} {theta} #{i}", S::NAME);
        }
        for set in SETS {
            let (mut ys, mut dys) = ([f64::NAN; 3], [f64::NAN; 3]);
            stepper.interpolate_components(theta, &set, &mut ys);
            stepper.interpolate_derivative_components(theta, h, &set, &mut dys);
            let bits = |v: [f64; 3]| v.map(f64::to_bits);
            assert_eq!(bits(ys), chosen(&y, &set), "{} {theta}", S::NAME);
            assert_eq!(bits(dys), chosen(&dy, &set), "{} {theta}", S::NAME);
        }
    }
}

/// At a step's end points the integrator copies the exact values, in the chosen components.
#[test]
fn partial_values_at_step_ends_are_the_exact_ones() {
    let mut it = Integrator::new(
        Dopri5::new(),
        Tolerance::scalar(1e-6, 1e-6),
        StepOptions::default(),
    )
    .unwrap();
    it.restart(&Forced, 0.3, &Forced::exact(0.3)).unwrap();
    it.step(&Forced, 2.0).unwrap();
    let ends = [
        (it.t_prev(), *it.y_prev(), *it.f_prev()),
        (it.t(), *it.y(), *it.f()),
    ];
    for (t, y, f) in ends {
        for (state, rates) in SETS.iter().zip(SETS.iter().rev()) {
            let (mut ys, mut dys) = ([f64::NAN; 3], [f64::NAN; 3]);
            it.interpolate_components(&Forced, t, state, rates, &mut ys, &mut dys)
                .unwrap();
            assert_eq!(ys.map(f64::to_bits), chosen(&y, state));
            assert_eq!(dys.map(f64::to_bits), chosen(&f, rates));
        }
    }
}

#[test]
fn partial_interpolation_is_the_full_one_in_the_chosen_components() {
    partial_is_full_where_chosen(Dopri5::new(), 0.2);
    partial_is_full_where_chosen(Dop853::new(), 0.2);
    partial_is_full_where_chosen(Rodas4::new(), 0.2);
    partial_is_full_where_chosen(Rk4::new(0.2), 0.2);
}

#[test]
fn component_sets_hold_what_they_were_given() {
    let set = Components::<Const<5>>::of(&[3, 1, 3]);
    assert_eq!(set.indices(), &[1, 3]);
    assert!(set.contains(1) && set.contains(3) && !set.contains(0) && !set.contains(7));
    assert_eq!(set.union(Components::of(&[0])).indices(), &[0, 1, 3]);
    assert!(Components::<Const<5>>::ALL.is_all() && !set.is_all());
    assert_eq!(Components::<Const<5>>::NONE.indices(), &[] as &[usize]);
    let mut to = [f64::NAN; 5];
    set.copy(&[1.0, 2.0, 3.0, 4.0, 5.0], &mut to);
    assert!(to[0].is_nan() && to[2].is_nan() && to[4].is_nan());
    assert_eq!((to[1], to[3]), (2.0, 4.0));
}
