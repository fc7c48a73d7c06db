//! Orders of convergence of every method, and of their dense outputs, on problems with known
//! solutions. Steps are forced to a fixed size (huge tolerances, `h_max = h`), so the measured
//! slope is the method's, not the controller's.

use crate::common::{dist, Forced, Kepler};
use model_runtime::Const;
use model_runtime::{
    integrate, Dop853, Dopri5, Integrator, Model, Observer, Rk4, Rodas4, StepOptions, StepView,
    Stepper, Tolerance,
};

const LOOSE: f64 = 1e6;

fn fixed(h: f64) -> StepOptions {
    StepOptions {
        h_initial: Some(h),
        h_max: h,
        ..StepOptions::default()
    }
}

/// Global error at `t_end` with `n` equal steps.
fn global_error<S: Stepper<Const<3>>>(make: &impl Fn(f64) -> S, n: usize, t_end: f64) -> f64 {
    let h = t_end / n as f64;
    let sol = integrate(
        &Forced,
        make(h),
        Tolerance::scalar(LOOSE, LOOSE),
        fixed(h),
        0.0,
        &Forced::Y0,
        t_end,
    )
    .unwrap();
    assert_eq!(sol.stats.steps, n as u64, "steps were not fixed");
    dist(&sol.y, &Forced::exact(t_end))
}

/// log2 of successive error ratios when the step is halved.
fn slopes(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

/// Least-squares slope of log2(error) against the number of halvings.
fn fitted_slope(errors: &[f64]) -> f64 {
    let n = errors.len() as f64;
    let xs: Vec<f64> = (0..errors.len()).map(|i| i as f64).collect();
    let ys: Vec<f64> = errors.iter().map(|e| -e.log2()).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

fn assert_order(name: &str, errors: &[f64], order: f64) {
    let fit = fitted_slope(errors);
    assert!(
        (fit - order).abs() < 0.3,
        "{name}: fitted slope {fit} (pairwise {:?}, errors {errors:?}), expected {order}",
        slopes(errors)
    );
    // Every halving must gain at least most of the order (no plateau hidden in the fit).
    for s in slopes(errors) {
        assert!(
            s > order - 0.7,
            "{name}: pairwise slope {s} (errors {errors:?})"
        );
    }
}

fn check_global<S: Stepper<Const<3>>>(
    make: impl Fn(f64) -> S,
    ns: &[usize],
    t_end: f64,
    order: f64,
) {
    let errors: Vec<f64> = ns.iter().map(|&n| global_error(&make, n, t_end)).collect();
    println!(
        "{}: errors {errors:.3?} slopes {:?}",
        S::NAME,
        slopes(&errors)
    );
    assert_order(S::NAME, &errors, order);
}

#[test]
fn dopri5_is_fifth_order() {
    check_global(|_| Dopri5::new(), &[20, 40, 80, 160], 3.0, 5.0);
}

#[test]
fn dop853_is_eighth_order() {
    check_global(|_| Dop853::new(), &[10, 20, 40], 10.0, 8.0);
}

#[test]
fn rodas4_is_fourth_order() {
    check_global(|_| Rodas4::new(), &[40, 80, 160, 320], 3.0, 4.0);
}

#[test]
fn rk4_is_fourth_order() {
    check_global(Rk4::new, &[20, 40, 80, 160], 3.0, 4.0);
}

/// Start of the single steps whose dense output is checked.
const T0: f64 = 0.3;

/// An integrator that has taken one step of size `h` from `T0` on the exact solution.
fn one_step<S: Stepper<Const<3>>>(make: &impl Fn(f64) -> S, h: f64) -> Integrator<S, Const<3>> {
    let mut it = Integrator::new(make(h), Tolerance::scalar(LOOSE, LOOSE), fixed(h)).unwrap();
    it.restart(&Forced, T0, &Forced::exact(T0)).unwrap();
    it.step(&Forced, T0 + h).unwrap();
    it
}

/// Max interpolation error over interior points of one step of size `h` from `T0`.
fn dense_error<S: Stepper<Const<3>>>(make: &impl Fn(f64) -> S, h: f64) -> f64 {
    let (t0, mut it) = (T0, one_step(make, h));
    let mut worst: f64 = 0.0;
    for k in 1..10 {
        let t = t0 + h * k as f64 / 10.0;
        let mut y = [0.0; 3];
        it.interpolate(&Forced, t, &mut y).unwrap();
        worst = worst.max(dist(&y, &Forced::exact(t)));
    }
    worst
}

fn check_dense<S: Stepper<Const<3>>>(make: impl Fn(f64) -> S, hs: &[f64]) {
    let errors: Vec<f64> = hs.iter().map(|&h| dense_error(&make, h)).collect();
    println!(
        "{} dense: errors {errors:.3?} slopes {:?}",
        S::NAME,
        slopes(&errors)
    );
    // A dense output of order q has a local error O(h^(q+1)) at interior points.
    assert_order(S::NAME, &errors, S::DENSE_ORDER as f64 + 1.0);
}

#[test]
fn dense_outputs_have_their_orders() {
    check_dense(|_| Dopri5::new(), &[0.4, 0.2, 0.1, 0.05]);
    check_dense(|_| Dop853::new(), &[0.4, 0.2, 0.1]);
    check_dense(|_| Rodas4::new(), &[0.2, 0.1, 0.05, 0.025]);
    check_dense(Rk4::new, &[0.4, 0.2, 0.1, 0.05]);
}

/// Max error of the interpolant's derivative against the exact `f` over interior points of
/// one step of size `h`.
fn dense_derivative_error<S: Stepper<Const<3>>>(make: &impl Fn(f64) -> S, h: f64) -> f64 {
    let (t0, mut it) = (T0, one_step(make, h));
    let mut worst: f64 = 0.0;
    for k in 0..=10 {
        let t = t0 + h * k as f64 / 10.0;
        let (mut y, mut dy, mut f) = ([0.0; 3], [0.0; 3], [0.0; 3]);
        it.interpolate_with_derivative(&Forced, t, &mut y, &mut dy)
            .unwrap();
        Forced.rhs(t, &Forced::exact(t), &mut f).unwrap();
        worst = worst.max(dist(&dy, &f));
    }
    worst
}

#[test]
fn dense_derivatives_follow_the_solution() {
    // DP5 and DOP853 differentiate their polynomials exactly: an interpolant of order q has
    // a derivative error O(h^q).
    let hs = [0.2, 0.1, 0.05, 0.025];
    let errors: Vec<f64> = hs
        .iter()
        .map(|&h| dense_derivative_error(&|_| Dopri5::<Const<3>>::new(), h))
        .collect();
    println!("DOPRI5 dense derivative: errors {errors:?}");
    assert_order(
        "DOPRI5 derivative",
        &errors,
        Dopri5::<Const<3>>::DENSE_ORDER as f64,
    );
    let errors: Vec<f64> = [0.4, 0.2, 0.1]
        .iter()
        .map(|&h| dense_derivative_error(&|_| Dop853::<Const<3>>::new(), h))
        .collect();
    println!("DOP853 dense derivative: errors {errors:?}");
    assert_order(
        "DOP853 derivative",
        &errors,
        Dop853::<Const<3>>::DENSE_ORDER as f64,
    );
    // The others differentiate their interpolant by a central difference: the derivative
    // keeps the interpolant's order where the interpolant's own error dominates.
    let rodas: Vec<f64> = [0.2, 0.1, 0.05]
        .iter()
        .map(|&h| dense_derivative_error(&|_| Rodas4::<Const<3>>::new(), h))
        .collect();
    let rk4: Vec<f64> = [0.2, 0.1, 0.05]
        .iter()
        .map(|&h| dense_derivative_error(&Rk4::<Const<3>>::new, h))
        .collect();
    println!("Rodas4 {rodas:?}, RK4 {rk4:?}");
    assert_order(
        "Rodas4 derivative",
        &rodas,
        Rodas4::<Const<3>>::DENSE_ORDER as f64,
    );
    assert_order("RK4 derivative", &rk4, Rk4::<Const<3>>::DENSE_ORDER as f64);
}

/// Checks every accepted step's interpolant at interior points against the exact orbit.
struct DenseChecker {
    e: f64,
    worst_interior: f64,
    worst_end: f64,
    steps: u64,
}

impl Observer<Const<4>, (), ()> for DenseChecker {
    fn wants_dense(&self) -> bool {
        true
    }
    fn on_step(&mut self, s: &StepView<'_, Const<4>, ()>) -> model_runtime::Observed {
        let dense = s.dense.expect("dense output requested");
        self.steps += 1;
        self.worst_end = self.worst_end.max(dist(s.y1, &Kepler::exact(self.e, s.t1)));
        for k in 1..16 {
            let t = s.t0 + (s.t1 - s.t0) * k as f64 / 16.0;
            let mut y = [0.0; 4];
            dense.at(t, &mut y);
            self.worst_interior = self.worst_interior.max(dist(&y, &Kepler::exact(self.e, t)));
        }
        Ok(())
    }
}

/// A one-mode hybrid system without guards, to stream steps to an observer.
struct Plain<M>(M);
impl<M: model_runtime::Model<4>> model_runtime::HybridSystem<Const<4>> for Plain<M> {
    type Mode = ();
    type Guard = ();
    type Stop = ();
    type Note = ();
    fn rhs(
        &self,
        _: (),
        t: f64,
        y: &[f64; 4],
        dy: &mut [f64; 4],
    ) -> Result<(), model_runtime::EvalError> {
        self.0.rhs(t, y, dy)
    }
    fn guards(&self, _: ()) -> &[model_runtime::GuardSpec<()>] {
        &[]
    }
    fn guard_values(
        &self,
        _: (),
        _: f64,
        _: &[f64; 4],
        _: &[f64; 4],
        _: &mut [f64],
    ) -> Result<(), model_runtime::EvalError> {
        Ok(())
    }
    fn on_event(
        &mut self,
        _: (),
        _: &model_runtime::EventHit<Const<4>, ()>,
    ) -> Result<model_runtime::Transition<Const<4>, (), ()>, model_runtime::EvalError> {
        Ok(model_runtime::Transition::Stop(()))
    }
}

#[test]
fn dop853_dense_output_matches_the_exact_orbit_inside_every_step() {
    let e = 0.5;
    for (rtol, bound) in [(1e-6, 1e-3), (1e-9, 1e-6), (1e-12, 1e-9)] {
        let mut solver = model_runtime::HybridSolver::new(
            Dop853::new(),
            Tolerance::scalar(rtol, rtol),
            model_runtime::HybridOptions::default(),
        )
        .unwrap();
        let mut obs = DenseChecker {
            e,
            worst_interior: 0.0,
            worst_end: 0.0,
            steps: 0,
        };
        let period = 2.0 * std::f64::consts::PI;
        solver
            .run(
                &mut Plain(Kepler),
                (),
                0.0,
                &Kepler::periapsis(e),
                3.0 * period,
                &mut obs,
            )
            .unwrap();
        println!(
            "rtol {rtol:e}: {} steps, worst interior error {:e}, worst end-point error {:e}",
            obs.steps, obs.worst_interior, obs.worst_end
        );
        // The interpolant is as accurate as the steps themselves: interior errors stay within
        // a small multiple of the end-point (global) errors.
        assert!(obs.steps > 20);
        assert!(
            obs.worst_interior <= 3.0 * obs.worst_end + 10.0 * rtol * 1e-3,
            "rtol {rtol}: interior {:e} vs ends {:e}",
            obs.worst_interior,
            obs.worst_end
        );
        assert!(
            obs.worst_interior < bound,
            "rtol {rtol}: {:e}",
            obs.worst_interior
        );
    }
}

/// Drives a stepper by hand: one step of size `h` from `t0`, then its interpolant at both ends
/// and at interior points, checked against the step's own end points and the exact solution.
fn interpolant_ends<S: Stepper<Const<3>>>(mut stepper: S, h: f64) {
    use model_runtime::{Stats, StepEnd, StepStart};
    let t0 = 0.7;
    let y0 = Forced::exact(t0);
    let mut f0 = [0.0; 3];
    model_runtime::Model::rhs(&Forced, t0, &y0, &mut f0).unwrap();
    let (mut y1, mut f1) = ([0.0; 3], [0.0; 3]);
    let mut stats = Stats::default();
    let tol = Tolerance::scalar(1e-6, 1e-6);
    let start = StepStart {
        t: t0,
        y: &y0,
        f: &f0,
    };
    let est = stepper
        .attempt(
            &Forced,
            start,
            h,
            &tol,
            StepEnd {
                y: &mut y1,
                f: &mut f1,
            },
            &mut stats,
        )
        .unwrap();
    assert!(est.norm <= 1.0, "{}: {est:?}", S::NAME);
    stepper
        .prepare_dense(&Forced, start, &y1, &f1, h, &mut stats)
        .unwrap();
    let mut y = [0.0; 3];
    stepper.interpolate(0.0, &mut y);
    assert!(
        dist(&y, &y0) <= 4.0 * f64::EPSILON * 3.0,
        "{}: start {y:?} vs {y0:?}",
        S::NAME
    );
    stepper.interpolate(1.0, &mut y);
    assert!(
        dist(&y, &y1) <= 4.0 * f64::EPSILON * 3.0,
        "{}: end {y:?} vs {y1:?}",
        S::NAME
    );
    // Just inside the end the interpolant is continuous with the end point.
    stepper.interpolate(1.0 - 1e-9, &mut y);
    assert!(dist(&y, &y1) < 1e-8, "{}", S::NAME);
    // And inside, it is as accurate as the step (local error ~1e-7 at h = 0.05 for RK4).
    for k in 1..10 {
        let theta = k as f64 / 10.0;
        stepper.interpolate(theta, &mut y);
        let err = dist(&y, &Forced::exact(t0 + theta * h));
        assert!(err < 1e-6, "{} at theta {theta}: {err:e}", S::NAME);
    }
}

#[test]
fn interpolants_meet_the_step_end_points() {
    interpolant_ends(Dopri5::new(), 0.05);
    interpolant_ends(Dop853::new(), 0.05);
    interpolant_ends(Rodas4::new(), 0.05);
    interpolant_ends(Rk4::new(0.05), 0.05);
}
