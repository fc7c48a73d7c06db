//! The classical fixed-step Runge–Kutta method of order four, with a cubic Hermite interpolant.
//!
//! No error control: useful as a simple, predictable baseline and for cross-checks.

use crate::dense::DenseOutput;
use crate::dim::{Array, Const, Dim, Vector};
use crate::error::SolveError;
use crate::stats::Stats;
use crate::stepper::{eval, Rhs, StepEnd, StepStart, Stepper};
use crate::tolerance::{ErrorEstimate, Tolerance};

/// Classical RK4 with a fixed step size.
#[derive(Clone, Debug)]
pub struct Rk4<D: Dim> {
    dim: D,
    h: f64,
    dense: Rk4Dense<D>,
}

/// RK4's dense output of one step: the ends and slopes of its cubic Hermite interpolant
/// ([`crate::DenseOutput`]).
#[derive(Clone, Debug)]
pub struct Rk4Dense<D: Dim> {
    y0: Vector<D>,
    y1: Vector<D>,
    f0: Vector<D>,
    f1: Vector<D>,
    h: f64,
}

impl<const N: usize> Rk4<Const<N>> {
    /// A stepper with step size `h` (checked when the integrator is built).
    pub fn new(h: f64) -> Self {
        Self::new_in(Const, h)
    }
}

impl<D: Dim> Rk4<D> {
    /// A stepper for states of size `dim` with step size `h` (checked when the integrator is
    /// built).
    pub fn new_in(dim: D, h: f64) -> Self {
        Rk4 {
            dim,
            h,
            dense: Rk4Dense {
                y0: dim.zeros(),
                y1: dim.zeros(),
                f0: dim.zeros(),
                f1: dim.zeros(),
                h: 0.0,
            },
        }
    }
}

impl<D: Dim> Stepper<D> for Rk4<D> {
    const NAME: &'static str = "RK4";
    const ERROR_ORDER: u32 = 3;
    #[inline(always)]
    fn dim(&self) -> D {
        self.dim
    }

    const DENSE_ORDER: u32 = 3;
    type Dense = Rk4Dense<D>;

    fn dense_output(&self) -> &Rk4Dense<D> {
        &self.dense
    }

    fn fixed_step(&self) -> Option<f64> {
        Some(self.h)
    }

    fn attempt<F: Rhs<D>>(
        &mut self,
        sys: &F,
        start: StepStart<'_, D>,
        h: f64,
        _tol: &Tolerance<D>,
        end: StepEnd<'_, D>,
        stats: &mut Stats,
    ) -> Result<ErrorEstimate, SolveError> {
        let (t, y, k1) = (start.t, start.y, start.f);
        let mut yt = self.dim.zeros();
        let (mut k2, mut k3, mut k4) = (self.dim.zeros(), self.dim.zeros(), self.dim.zeros());
        for i in 0..self.dim.size() {
            yt[i] = y[i] + 0.5 * h * k1[i];
        }
        eval(sys, t + 0.5 * h, &yt, &mut k2, stats)?;
        for i in 0..self.dim.size() {
            yt[i] = y[i] + 0.5 * h * k2[i];
        }
        eval(sys, t + 0.5 * h, &yt, &mut k3, stats)?;
        for i in 0..self.dim.size() {
            yt[i] = y[i] + h * k3[i];
        }
        eval(sys, t + h, &yt, &mut k4, stats)?;
        for i in 0..self.dim.size() {
            end.y[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
        }
        eval(sys, t + h, end.y, end.f, stats)?;
        Ok(ErrorEstimate::NONE)
    }

    fn prepare_dense<F: Rhs<D>>(
        &mut self,
        _sys: &F,
        start: StepStart<'_, D>,
        end_y: &Vector<D>,
        end_f: &Vector<D>,
        h: f64,
        _stats: &mut Stats,
    ) -> Result<(), SolveError> {
        let d = &mut self.dense;
        d.y0.assign(start.y);
        d.f0.assign(start.f);
        d.y1.assign(end_y);
        d.f1.assign(end_f);
        d.h = h;
        Ok(())
    }

    fn interpolate(&self, s: f64, out: &mut Vector<D>) {
        self.dense.value(s, out);
    }
}

impl<D: Dim> DenseOutput<D> for Rk4Dense<D> {
    fn dim(&self) -> D {
        D::of(&self.y0)
    }

    fn value(&self, s: f64, out: &mut Vector<D>) {
        hermite::<D>(s, self.h, &self.y0, &self.f0, &self.y1, &self.f1, out);
    }
}

/// The cubic Hermite interpolant through `(y0, f0)` and `(y1, f1)` over a step `h`, at
/// `theta = s`.
pub(crate) fn hermite<D: Dim>(
    s: f64,
    h: f64,
    y0: &Vector<D>,
    f0: &Vector<D>,
    y1: &Vector<D>,
    f1: &Vector<D>,
    out: &mut Vector<D>,
) {
    let s2 = s * s;
    let s3 = s2 * s;
    let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    let h10 = s3 - 2.0 * s2 + s;
    let h01 = -2.0 * s3 + 3.0 * s2;
    let h11 = s3 - s2;
    for i in 0..out.as_ref().len() {
        out[i] = h00 * y0[i] + h * h10 * f0[i] + h01 * y1[i] + h * h11 * f1[i];
    }
}
