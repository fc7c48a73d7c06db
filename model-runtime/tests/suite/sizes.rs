//! One code path for both kinds of size: a model run with its size known at compile time
//! (`Const`, arrays) and the same model run with its size known only at run time (`Dyn`,
//! vectors) take the same steps to the bit; embedding it in more states with zero derivatives
//! (the padding the interpreter used before models of any size ran) gives the same solution
//! to round-off; and a run-time size that does not match is an input error, never a panic.

use crate::common::Forced;
use model_runtime::{
    Const, Dyn, EvalError, Event, InputError, Method, Model, ModelInfo, Output, Problem, Rhs,
    SolveError, SolveFailure, System, SystemOutputs, Tolerance, Trajectory, WithOutputs,
};

/// A compile-time model with no outputs, as `Problem` records it.
struct Plain<M>(M);

impl<M: Model<N>, const N: usize> Model<N> for Plain<M> {
    fn info(&self) -> &'static ModelInfo {
        self.0.info()
    }
    fn rhs(&self, t: f64, y: &[f64; N], dy: &mut [f64; N]) -> Result<(), EvalError> {
        self.0.rhs(t, y, dy)
    }
    fn jacobian(&self, t: f64, y: &[f64; N], jac: &mut [[f64; N]; N]) -> Result<(), EvalError> {
        self.0.jacobian(t, y, jac)
    }
}

impl<M: Model<N>, const N: usize> WithOutputs<N, 0> for Plain<M> {
    fn outputs(
        &self,
        _: f64,
        _: &[f64; N],
        _: &[f64; N],
        _: &mut [f64; 0],
    ) -> Result<(), EvalError> {
        Ok(())
    }
}

/// The same model seen as one whose size is known only at run time, as a file's model is.
struct AtRunTime<M, const N: usize>(M);

impl<M: Model<N>, const N: usize> Rhs<Dyn> for AtRunTime<M, N> {
    fn rhs(&self, t: f64, y: &Vec<f64>, dy: &mut Vec<f64>) -> Result<(), EvalError> {
        let mut out = [0.0; N];
        self.0.rhs(t, &array(y), &mut out)?;
        dy.copy_from_slice(&out);
        Ok(())
    }
    fn jacobian(&self, t: f64, y: &Vec<f64>, jac: &mut Vec<Vec<f64>>) -> Result<(), EvalError> {
        let mut out = [[0.0; N]; N];
        self.0.jacobian(t, &array(y), &mut out)?;
        for (row, values) in jac.iter_mut().zip(&out) {
            row.copy_from_slice(values);
        }
        Ok(())
    }
}

impl<M: Model<N>, const N: usize> System<Dyn> for AtRunTime<M, N> {
    fn info(&self) -> &ModelInfo {
        self.0.info()
    }
    fn dim(&self) -> Dyn {
        Dyn(N)
    }
}

impl<M: Model<N>, const N: usize> SystemOutputs<Dyn, 0> for AtRunTime<M, N> {
    fn outputs(
        &self,
        _: f64,
        _: &Vec<f64>,
        _: &Vec<f64>,
        _: &mut [f64; 0],
    ) -> Result<(), EvalError> {
        Ok(())
    }
}

/// The model's `N` states in the first of `P` components; the others have zero derivatives.
struct Padded<M, const N: usize>(M);

impl<M: Model<N>, const N: usize, const P: usize> Model<P> for Padded<M, N> {
    fn info(&self) -> &'static ModelInfo {
        self.0.info()
    }
    fn rhs(&self, t: f64, y: &[f64; P], dy: &mut [f64; P]) -> Result<(), EvalError> {
        let mut out = [0.0; N];
        self.0.rhs(t, &array(&y[..N]), &mut out)?;
        *dy = [0.0; P];
        dy[..N].copy_from_slice(&out);
        Ok(())
    }
}

impl<M: Model<N>, const N: usize, const P: usize> WithOutputs<P, 0> for Padded<M, N> {
    fn outputs(
        &self,
        _: f64,
        _: &[f64; P],
        _: &[f64; P],
        _: &mut [f64; 0],
    ) -> Result<(), EvalError> {
        Ok(())
    }
}

fn array<const N: usize>(y: &[f64]) -> [f64; N] {
    std::array::from_fn(|i| y[i])
}

const METHODS: [Method; 4] = [
    Method::Dopri5,
    Method::Dop853,
    Method::Rodas4,
    Method::Rk4 { h: 0.01 },
];

/// An event on each kind of run: `x = cos t` crossing zero (at t = π/2 in the span).
fn crossing() -> Event {
    Event::new("x = 0", |_t, y, _dy| y[0])
}

fn times() -> Output {
    Output::Times((0..=40).map(|k| 0.1 * k as f64).collect())
}

#[test]
fn a_run_time_size_takes_the_compile_time_steps_to_the_bit() {
    for method in METHODS {
        let fixed: Trajectory<Const<3>, 0> = Problem::new(&Plain(Forced), Forced::Y0, (0.0, 4.0))
            .method(method)
            .tolerances(1e-9, 1e-10)
            .output(times())
            .event(crossing())
            .solve()
            .unwrap();
        let at_run_time: Trajectory<Dyn, 0> =
            Problem::new(&AtRunTime(Forced), Forced::Y0.to_vec(), (0.0, 4.0))
                .method(method)
                .tolerances(1e-9, 1e-10)
                .output(times())
                .event(crossing())
                .solve()
                .unwrap();
        assert_eq!(fixed.stats, at_run_time.stats, "{method:?}");
        assert_eq!(fixed.t, at_run_time.t, "{method:?}");
        for (a, b) in fixed.y.iter().zip(&at_run_time.y) {
            assert_eq!(a.as_slice(), b.as_slice(), "{method:?}");
        }
        assert_eq!(fixed.events.len(), 1, "{method:?}");
        let at = fixed.events[0].t - std::f64::consts::FRAC_PI_2;
        assert!(at.abs() < 1e-6, "{method:?}: {at}");
        for (a, b) in fixed.events.iter().zip(&at_run_time.events) {
            assert_eq!((a.t, a.y.as_slice()), (b.t, b.y.as_slice()), "{method:?}");
        }
        // And both are the solution.
        let last = at_run_time.y.last().unwrap();
        let exact = Forced::exact(4.0);
        for k in 0..3 {
            assert!((last[k] - exact[k]).abs() < 1e-5, "{method:?}: {last:?}");
        }
    }
}

#[test]
fn padding_with_scaled_tolerances_gave_the_unpadded_solution() {
    const PADDED: usize = 32;
    let (rtol, atol) = (1e-10, 1e-12);
    let unpadded: Trajectory<Dyn, 0> =
        Problem::new(&AtRunTime(Forced), Forced::Y0.to_vec(), (0.0, 4.0))
            .method(Method::Dop853)
            .tolerances(rtol, atol)
            .solve()
            .unwrap();
    // The embedding the interpreter used: zero derivatives past the model's states and
    // tolerances scaled by sqrt(n / 32), which makes the error norm that of the 3 states.
    let scale = (3.0 / PADDED as f64).sqrt();
    let mut y0 = [0.0; PADDED];
    y0[..3].copy_from_slice(&Forced::Y0);
    let padded: Trajectory<Const<PADDED>, 0> = Problem::new(&Padded(Forced), y0, (0.0, 4.0))
        .method(Method::Dop853)
        .tolerance(Tolerance::per_component(
            [rtol * scale; PADDED],
            [atol * scale; PADDED],
        ))
        .solve()
        .unwrap();
    // The same norm up to the rounding of the scaling: the same steps, the same states to
    // round-off, the padding untouched.
    assert_eq!(unpadded.stats.steps, padded.stats.steps);
    assert_eq!(unpadded.t.len(), padded.t.len());
    for ((ta, a), (tb, b)) in unpadded
        .t
        .iter()
        .zip(&unpadded.y)
        .zip(padded.t.iter().zip(&padded.y))
    {
        assert!((ta - tb).abs() <= 1e-12 * ta.abs().max(1.0), "{ta} {tb}");
        for k in 0..3 {
            assert!((a[k] - b[k]).abs() <= 1e-12, "t = {ta}: {a:?} {b:?}");
        }
        assert!(b[3..].iter().all(|&v| v == 0.0));
    }
}

#[test]
fn a_run_time_size_that_does_not_match_is_an_input_error() {
    let short = Problem::new(&AtRunTime(Forced), vec![1.0, 0.0], (0.0, 1.0)).solve::<0>();
    assert!(
        matches!(
            short,
            Err(SolveFailure::Solve {
                error: SolveError::InvalidInput(InputError::Size {
                    expected: 3,
                    found: 2,
                    ..
                }),
                ..
            })
        ),
        "{short:?}"
    );
    let tolerance = Tolerance::scalar_in(Dyn(4), 1e-6, 1e-9);
    let wide = Problem::new(&AtRunTime(Forced), Forced::Y0.to_vec(), (0.0, 1.0))
        .tolerance(tolerance)
        .solve::<0>();
    assert!(
        matches!(
            wide,
            Err(SolveFailure::Solve {
                error: SolveError::InvalidInput(InputError::Size {
                    expected: 3,
                    found: 4,
                    ..
                }),
                ..
            })
        ),
        "{wide:?}"
    );
}
