//! The classical fixed-step Runge–Kutta method of order four, with a cubic Hermite interpolant.
//!
//! No error control: useful as a simple, predictable baseline and for cross-checks.

use crate::error::SolveError;
use crate::stats::Stats;
use crate::stepper::{eval, Rhs, StepEnd, StepStart, Stepper};
use crate::tolerance::{ErrorEstimate, Tolerance};

/// Classical RK4 with a fixed step size.
#[derive(Clone, Debug)]
pub struct Rk4<const N: usize> {
    h: f64,
    y0: [f64; N],
    y1: [f64; N],
    f0: [f64; N],
    f1: [f64; N],
    h_last: f64,
}

impl<const N: usize> Rk4<N> {
    /// A stepper with step size `h` (checked when the integrator is built).
    pub fn new(h: f64) -> Self {
        Rk4 {
            h,
            y0: [0.0; N],
            y1: [0.0; N],
            f0: [0.0; N],
            f1: [0.0; N],
            h_last: 0.0,
        }
    }
}

impl<const N: usize> Stepper<N> for Rk4<N> {
    const NAME: &'static str = "RK4";
    const ERROR_ORDER: u32 = 3;
    const DENSE_ORDER: u32 = 3;

    fn fixed_step(&self) -> Option<f64> {
        Some(self.h)
    }

    fn attempt<F: Rhs<N>>(
        &mut self,
        sys: &F,
        start: StepStart<'_, N>,
        h: f64,
        _tol: &Tolerance<N>,
        end: StepEnd<'_, N>,
        stats: &mut Stats,
    ) -> Result<ErrorEstimate, SolveError> {
        let (t, y, k1) = (start.t, start.y, start.f);
        let mut yt = [0.0; N];
        let (mut k2, mut k3, mut k4) = ([0.0; N], [0.0; N], [0.0; N]);
        for i in 0..N {
            yt[i] = y[i] + 0.5 * h * k1[i];
        }
        eval(sys, t + 0.5 * h, &yt, &mut k2, stats)?;
        for i in 0..N {
            yt[i] = y[i] + 0.5 * h * k2[i];
        }
        eval(sys, t + 0.5 * h, &yt, &mut k3, stats)?;
        for i in 0..N {
            yt[i] = y[i] + h * k3[i];
        }
        eval(sys, t + h, &yt, &mut k4, stats)?;
        for i in 0..N {
            end.y[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
        }
        eval(sys, t + h, end.y, end.f, stats)?;
        Ok(ErrorEstimate::NONE)
    }

    fn prepare_dense<F: Rhs<N>>(
        &mut self,
        _sys: &F,
        start: StepStart<'_, N>,
        end_y: &[f64; N],
        end_f: &[f64; N],
        h: f64,
        _stats: &mut Stats,
    ) -> Result<(), SolveError> {
        self.y0 = *start.y;
        self.f0 = *start.f;
        self.y1 = *end_y;
        self.f1 = *end_f;
        self.h_last = h;
        Ok(())
    }

    fn interpolate(&self, s: f64, out: &mut [f64; N]) {
        hermite(s, self.h_last, &self.y0, &self.f0, &self.y1, &self.f1, out);
    }
}

/// The cubic Hermite interpolant through `(y0, f0)` and `(y1, f1)` over a step `h`, at
/// `theta = s`.
pub(crate) fn hermite<const N: usize>(
    s: f64,
    h: f64,
    y0: &[f64; N],
    f0: &[f64; N],
    y1: &[f64; N],
    f1: &[f64; N],
    out: &mut [f64; N],
) {
    let s2 = s * s;
    let s3 = s2 * s;
    let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    let h10 = s3 - 2.0 * s2 + s;
    let h01 = -2.0 * s3 + 3.0 * s2;
    let h11 = s3 - s2;
    for i in 0..N {
        out[i] = h00 * y0[i] + h * h10 * f0[i] + h01 * y1[i] + h * h11 * f1[i];
    }
}
