//! RODAS4: a stiffly accurate, L-stable Rosenbrock method of order 4(3) with a third-order
//! dense output (Hairer & Wanner, *Solving ODEs II*, §IV.7, and their RODAS code).
//!
//! Used for stiff stretches: each step solves six linear systems with the iteration matrix
//! `I/(h γ) - J`, where `J` comes from [`crate::Model::jacobian`] (symbolic for emitted models),
//! so there is no Newton iteration to fail. Non-autonomous systems are handled with a
//! finite-difference `∂f/∂t`.

// The coefficients are kept digit for digit as published.
#![allow(clippy::excessive_precision)]

use crate::dense::DenseOutput;
use crate::dim::{Const, Dim, Vector};
use crate::error::SolveError;
use crate::lu::Lu;
use crate::stats::Stats;
use crate::stepper::{eval, Rhs, StepEnd, StepStart, Stepper};
use crate::tolerance::{ErrorEstimate, Tolerance};

const GAMMA: f64 = 0.25;
const C2: f64 = 0.386;
const C3: f64 = 0.21;
const C4: f64 = 0.63;
const DI: [f64; 4] = [0.25, -0.1043, 0.1035, -0.3620000000000023e-01];
const A21: f64 = 0.1544000000000000e+01;
const A31: f64 = 0.9466785280815826e+00;
const A32: f64 = 0.2557011698983284e+00;
const A41: f64 = 0.3314825187068521e+01;
const A42: f64 = 0.2896124015972201e+01;
const A43: f64 = 0.9986419139977817e+00;
const A51: f64 = 0.1221224509226641e+01;
const A52: f64 = 0.6019134481288629e+01;
const A53: f64 = 0.1253708332932087e+02;
const A54: f64 = -0.6878860361058950e+00;
/// `C[i]` lists the coupling coefficients `c_{i+2, j+1}` of stage `i + 2`.
const C: [&[f64]; 5] = [
    &[-0.5668800000000000e+01],
    &[-0.2430093356833875e+01, -0.2063599157091915e+00],
    &[
        -0.1073529058151375e+00,
        -0.9594562251023355e+01,
        -0.2047028614809616e+02,
    ],
    &[
        0.7496443313967647e+01,
        -0.1024680431464352e+02,
        -0.3399990352819905e+02,
        0.1170890893206160e+02,
    ],
    &[
        0.8083246795921522e+01,
        -0.7981132988064893e+01,
        -0.3152159432874371e+02,
        0.1631930543123136e+02,
        -0.6058818238834054e+01,
    ],
];
const D2: [f64; 5] = [
    0.1012623508344586e+02,
    -0.7487995877610167e+01,
    -0.3480091861555747e+02,
    -0.7992771707568823e+01,
    0.1025137723295662e+01,
];
const D3: [f64; 5] = [
    -0.6762803392801253e+00,
    0.6087714651680015e+01,
    0.1643084320892478e+02,
    0.2476722511418386e+02,
    -0.6594389125716872e+01,
];

/// RODAS4.
#[derive(Clone, Debug)]
pub struct Rodas4<D: Dim> {
    dim: D,
    k: [Vector<D>; 6],
    cont: Rodas4Dense<D>,
}

/// RODAS4's dense output of one step: the four coefficient rows of its cubic interpolant
/// ([`crate::DenseOutput`]).
#[derive(Clone, Debug)]
pub struct Rodas4Dense<D: Dim> {
    c: [Vector<D>; 4],
}

impl<const N: usize> Rodas4<Const<N>> {
    /// A stepper.
    pub fn new() -> Self {
        Self::new_in(Const)
    }
}

impl<D: Dim> Rodas4<D> {
    /// A stepper for states of size `dim`.
    pub fn new_in(dim: D) -> Self {
        Rodas4 {
            dim,
            k: std::array::from_fn(|_| dim.zeros()),
            cont: Rodas4Dense {
                c: std::array::from_fn(|_| dim.zeros()),
            },
        }
    }
}

impl<const N: usize> Default for Rodas4<Const<N>> {
    fn default() -> Self {
        Self::new()
    }
}

impl<D: Dim> Stepper<D> for Rodas4<D> {
    const NAME: &'static str = "RODAS4";
    const ERROR_ORDER: u32 = 3;
    #[inline(always)]
    fn dim(&self) -> D {
        self.dim
    }

    const DENSE_ORDER: u32 = 3;
    type Dense = Rodas4Dense<D>;

    fn dense_output(&self) -> &Rodas4Dense<D> {
        &self.cont
    }

    fn attempt<F: Rhs<D>>(
        &mut self,
        sys: &F,
        start: StepStart<'_, D>,
        h: f64,
        tol: &Tolerance<D>,
        end: StepEnd<'_, D>,
        stats: &mut Stats,
    ) -> Result<ErrorEstimate, SolveError> {
        let (t, y) = (start.t, start.y);
        let mut jac = self.dim.zero_matrix();
        stats.jacobian_evals += 1;
        sys.jacobian(t, y, &mut jac).map_err(crate::error::at(t))?;
        // ∂f/∂t by a forward difference (zero for autonomous systems, up to round-off).
        let delt = (f64::EPSILON * t.abs().max(1e-5)).sqrt();
        let mut ft = self.dim.zeros();
        eval(sys, t + delt, y, &mut ft, stats)?;
        for i in 0..self.dim.size() {
            ft[i] = (ft[i] - start.f[i]) / delt;
        }
        let fac = 1.0 / (h * GAMMA);
        let mut m = self.dim.zero_matrix();
        for i in 0..self.dim.size() {
            for j in 0..self.dim.size() {
                m[i][j] = -jac[i][j];
            }
            m[i][i] += fac;
        }
        stats.decompositions += 1;
        let Ok(lu) = Lu::<D>::new(m) else {
            // The driver retries with a smaller step (which shifts the matrix by a larger
            // multiple of the identity) before reporting this.
            return Err(SolveError::SingularIterationMatrix { t, h });
        };
        let a: [&[f64]; 4] = [&[A21], &[A31, A32], &[A41, A42, A43], &[A51, A52, A53, A54]];
        let cs = [C2, C3, C4, 1.0];
        // Stage 1.
        for i in 0..self.dim.size() {
            self.k[0][i] = start.f[i] + h * DI[0] * ft[i];
        }
        lu.solve(&mut self.k[0]);
        // Stages 2..5.
        let mut yt = self.dim.zeros();
        let mut fy = self.dim.zeros();
        for s in 1..5 {
            for i in 0..self.dim.size() {
                let mut v = y[i];
                for (j, aij) in a[s - 1].iter().enumerate() {
                    v += aij * self.k[j][i];
                }
                yt[i] = v;
            }
            eval(sys, t + cs[s - 1] * h, &yt, &mut fy, stats)?;
            let hd = if s < 4 { h * DI[s] } else { 0.0 };
            let mut rhs = self.dim.zeros();
            for i in 0..self.dim.size() {
                let mut v = fy[i] + hd * ft[i];
                for (j, cij) in C[s - 1].iter().enumerate() {
                    v += cij / h * self.k[j][i];
                }
                rhs[i] = v;
            }
            lu.solve(&mut rhs);
            self.k[s] = rhs;
        }
        // Stage 6 (the embedded solution is y + Σ a5j k_j + k5; the new one adds k6).
        for i in 0..self.dim.size() {
            yt[i] += self.k[4][i];
        }
        eval(sys, t + h, &yt, &mut fy, stats)?;
        let mut rhs = self.dim.zeros();
        for i in 0..self.dim.size() {
            let mut v = fy[i];
            for (j, cij) in C[4].iter().enumerate() {
                v += cij / h * self.k[j][i];
            }
            rhs[i] = v;
        }
        lu.solve(&mut rhs);
        self.k[5] = rhs;
        for i in 0..self.dim.size() {
            end.y[i] = yt[i] + self.k[5][i];
        }
        let est = tol.norm(&self.k[5], y, end.y);
        if est.norm <= 1.0 {
            eval(sys, t + h, end.y, end.f, stats)?;
        }
        Ok(est)
    }

    fn prepare_dense<F: Rhs<D>>(
        &mut self,
        _sys: &F,
        start: StepStart<'_, D>,
        end_y: &Vector<D>,
        _end_f: &Vector<D>,
        _h: f64,
        _stats: &mut Stats,
    ) -> Result<(), SolveError> {
        for i in 0..self.dim.size() {
            let (mut d2, mut d3) = (0.0, 0.0);
            for j in 0..5 {
                d2 += D2[j] * self.k[j][i];
                d3 += D3[j] * self.k[j][i];
            }
            self.cont.c[0][i] = start.y[i];
            self.cont.c[1][i] = end_y[i];
            self.cont.c[2][i] = d2;
            self.cont.c[3][i] = d3;
        }
        Ok(())
    }

    fn interpolate(&self, s: f64, out: &mut Vector<D>) {
        self.cont.value(s, out);
    }
}

impl<D: Dim> DenseOutput<D> for Rodas4Dense<D> {
    fn dim(&self) -> D {
        D::of(&self.c[0])
    }

    fn value(&self, s: f64, out: &mut Vector<D>) {
        let s1 = 1.0 - s;
        let c = &self.c;
        for i in 0..self.dim().size() {
            out[i] = c[0][i] * s1 + s * (c[1][i] + s1 * (c[2][i] + s * c[3][i]));
        }
    }
}
