//! Dormand–Prince 5(4) with its fourth-order dense output (Hairer's DOPRI5 interpolant).
//!
//! The workhorse explicit method: seven stages, the last of which is `f` at the new point and
//! is reused as the next step's first (first same as last), so an accepted step costs six
//! evaluations and its interpolant none.

use crate::dense::DenseOutput;
use crate::dim::{Array, Const, Dim, Vector};
use crate::error::SolveError;
use crate::stats::Stats;
use crate::stepper::{eval, fill_all, Components, Rhs, StepEnd, StepStart, Stepper};
use crate::tableau::{combine, sum};
use crate::tolerance::{ErrorEstimate, Tolerance};

const C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
/// Row `i` lists the `(stage, a_ij)` pairs of stage `i` (0-based).
const A: [&[(usize, f64)]; 7] = [
    &[],
    &[(0, 0.2)],
    &[(0, 3.0 / 40.0), (1, 9.0 / 40.0)],
    &[(0, 44.0 / 45.0), (1, -56.0 / 15.0), (2, 32.0 / 9.0)],
    &[
        (0, 19372.0 / 6561.0),
        (1, -25360.0 / 2187.0),
        (2, 64448.0 / 6561.0),
        (3, -212.0 / 729.0),
    ],
    &[
        (0, 9017.0 / 3168.0),
        (1, -355.0 / 33.0),
        (2, 46732.0 / 5247.0),
        (3, 49.0 / 176.0),
        (4, -5103.0 / 18656.0),
    ],
    // The fifth-order solution (its stage 7 is f at the new point).
    &[
        (0, 35.0 / 384.0),
        (2, 500.0 / 1113.0),
        (3, 125.0 / 192.0),
        (4, -2187.0 / 6784.0),
        (5, 11.0 / 84.0),
    ],
];
/// Difference between the fifth- and fourth-order weights.
const E: [(usize, f64); 6] = [
    (0, 71.0 / 57600.0),
    (2, -71.0 / 16695.0),
    (3, 71.0 / 1920.0),
    (4, -17253.0 / 339200.0),
    (5, 22.0 / 525.0),
    (6, -1.0 / 40.0),
];
/// Shampine's dense-output weights.
const D: [(usize, f64); 6] = [
    (0, -12715105075.0 / 11282082432.0),
    (2, 87487479700.0 / 32700410799.0),
    (3, -10690763975.0 / 1880347072.0),
    (4, 701980252875.0 / 199316789632.0),
    (5, -1453857185.0 / 822651844.0),
    (6, 69997945.0 / 29380423.0),
];

/// Dormand–Prince 5(4).
#[derive(Clone, Debug)]
pub struct Dopri5<D: Dim> {
    dim: D,
    k: [Vector<D>; 7],
    cont: Dopri5Dense<D>,
}

/// Dormand–Prince 5(4)'s dense output of one step: the five coefficient rows of its quartic
/// interpolant ([`crate::DenseOutput`]).
#[derive(Clone, Debug)]
pub struct Dopri5Dense<D: Dim> {
    c: [Vector<D>; 5],
}

impl<const N: usize> Dopri5<Const<N>> {
    /// A stepper.
    pub fn new() -> Self {
        Self::new_in(Const)
    }
}

impl<D: Dim> Dopri5<D> {
    /// A stepper for states of size `dim`.
    pub fn new_in(dim: D) -> Self {
        Dopri5 {
            dim,
            k: std::array::from_fn(|_| dim.zeros()),
            cont: Dopri5Dense {
                c: std::array::from_fn(|_| dim.zeros()),
            },
        }
    }
}

impl<const N: usize> Default for Dopri5<Const<N>> {
    fn default() -> Self {
        Self::new()
    }
}

impl<D: Dim> Stepper<D> for Dopri5<D> {
    const NAME: &'static str = "DOPRI5";
    const ERROR_ORDER: u32 = 4;
    #[inline(always)]
    fn dim(&self) -> D {
        self.dim
    }

    const DENSE_ORDER: u32 = 4;
    type Dense = Dopri5Dense<D>;

    fn dense_output(&self) -> &Dopri5Dense<D> {
        &self.cont
    }

    // The hints on `attempt` and `prepare_dense` keep them inlined into the integrator's
    // step: left to the optimiser, the choice follows how the crates are cut into codegen
    // units, and a change far from here once cost the DP5 run 4 % more instructions.
    #[inline]
    fn attempt<F: Rhs<D>>(
        &mut self,
        sys: &F,
        start: StepStart<'_, D>,
        h: f64,
        tol: &Tolerance<D>,
        end: StepEnd<'_, D>,
        stats: &mut Stats,
    ) -> Result<ErrorEstimate, SolveError> {
        self.k[0].assign(start.f);
        let mut yt = self.dim.zeros();
        for s in 1..6 {
            combine::<D>(start.y, h, A[s], &self.k, &mut yt);
            let mut ks = self.dim.zeros();
            eval(sys, start.t + C[s] * h, &yt, &mut ks, stats)?;
            self.k[s] = ks;
        }
        combine::<D>(start.y, h, A[6], &self.k, end.y);
        eval(sys, start.t + h, end.y, end.f, stats)?;
        self.k[6].assign(end.f);
        let mut err = self.dim.zeros();
        sum::<D>(&E, &self.k, &mut err);
        for e in err.as_mut().iter_mut() {
            *e *= h;
        }
        Ok(tol.norm(&err, start.y, end.y))
    }

    #[inline]
    fn prepare_dense<F: Rhs<D>>(
        &mut self,
        _sys: &F,
        start: StepStart<'_, D>,
        end_y: &Vector<D>,
        end_f: &Vector<D>,
        h: f64,
        _stats: &mut Stats,
    ) -> Result<(), SolveError> {
        let mut d = self.dim.zeros();
        sum::<D>(&D, &self.k, &mut d);
        for i in 0..self.dim.size() {
            let ydiff = end_y[i] - start.y[i];
            let bspl = h * start.f[i] - ydiff;
            self.cont.c[0][i] = start.y[i];
            self.cont.c[1][i] = ydiff;
            self.cont.c[2][i] = bspl;
            self.cont.c[3][i] = ydiff - h * end_f[i] - bspl;
            self.cont.c[4][i] = h * d[i];
        }
        Ok(())
    }

    fn interpolate(&self, s: f64, out: &mut Vector<D>) {
        fill_all::<D>(out, |i| self.cont.value_at(s, i));
    }

    fn interpolate_derivative(&self, s: f64, h: f64, out: &mut Vector<D>) {
        fill_all::<D>(out, |i| self.cont.rate(s, h, i));
    }

    /// Component by component: the unchosen ones cost nothing.
    fn interpolate_components(&self, s: f64, which: &Components<D>, out: &mut Vector<D>) {
        which.fill(out, |i| self.cont.value_at(s, i));
    }

    fn interpolate_component(&self, s: f64, i: usize) -> f64 {
        self.cont.value_at(s, i)
    }

    fn interpolate_derivative_components(
        &self,
        s: f64,
        h: f64,
        which: &Components<D>,
        out: &mut Vector<D>,
    ) {
        which.fill(out, |i| self.cont.rate(s, h, i));
    }
}

impl<D: Dim> DenseOutput<D> for Dopri5Dense<D> {
    fn dim(&self) -> D {
        D::of(&self.c[0])
    }

    fn value(&self, theta: f64, out: &mut Vector<D>) {
        fill_all::<D>(out, |i| self.value_at(theta, i));
    }

    fn component(&self, theta: f64, i: usize) -> f64 {
        self.value_at(theta, i)
    }
}

impl<D: Dim> Dopri5Dense<D> {
    /// Component `i` of the quartic interpolant at `s`.
    #[inline(always)]
    fn value_at(&self, s: f64, i: usize) -> f64 {
        let s1 = 1.0 - s;
        let c = &self.c;
        c[0][i] + s * (c[1][i] + s1 * (c[2][i] + s * (c[3][i] + s1 * c[4][i])))
    }

    /// Component `i` of the interpolant's exact derivative at `s` (step `h`), by the product
    /// rule on its nested form.
    #[inline(always)]
    fn rate(&self, s: f64, h: f64, i: usize) -> f64 {
        let s1 = 1.0 - s;
        let c = &self.c;
        let q = c[3][i] + s1 * c[4][i];
        let r = c[2][i] + s * q;
        let dr = q - s * c[4][i];
        let outer = c[1][i] + s1 * r;
        let d_outer = s1 * dr - r;
        (outer + s * d_outer) / h
    }
}
