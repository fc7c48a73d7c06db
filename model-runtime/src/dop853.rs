//! DOP853: Dormand–Prince 8(5,3) with Hairer's seventh-order dense output.
//!
//! Twelve stages for the eighth-order solution, an error estimate that blends a fifth- and a
//! third-order embedded solution (Hairer's formula), and three extra stages, computed only when
//! an interpolant is asked for, that raise the dense output to order seven. Exact event times
//! rest on that interpolant, so it is tested against exact solutions at interior points.
//!
//! Coefficients: E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential
//! Equations I*, 2nd ed., and the authors' DOP853 code.

// The coefficients are kept digit for digit as published.
#![allow(clippy::excessive_precision)]

use crate::dense::DenseOutput;
use crate::dim::{Array, Const, Dim, Vector};
use crate::error::SolveError;
use crate::stats::Stats;
use crate::stepper::{eval, fill_all, Components, Rhs, StepEnd, StepStart, Stepper};
use crate::tableau::{combine, sum};
use crate::tolerance::{ErrorEstimate, Tolerance};

/// Stage abscissae; index = stage number - 1 (stages 13..16: `f` at the new point and the
/// three dense-output stages).
const C: [f64; 16] = [
    0.0,
    0.526001519587677318785587544488e-01,
    0.789002279381515978178381316732e-01,
    0.118350341907227396726757197510e+00,
    0.281649658092772603273242802490e+00,
    0.333333333333333333333333333333e+00,
    0.25e+00,
    0.307692307692307692307692307692e+00,
    0.651282051282051282051282051282e+00,
    0.6e+00,
    0.857142857142857142857142857142e+00,
    1.0,
    1.0,
    0.1e+00,
    0.2e+00,
    0.777777777777777777777777777778e+00,
];

/// `(stage, a_ij)` pairs per stage (0-based stage indices).
const A: [&[(usize, f64)]; 16] = [
    &[],
    &[(0, 5.26001519587677318785587544488e-2)],
    &[
        (0, 1.97250569845378994544595329183e-2),
        (1, 5.91751709536136983633785987549e-2),
    ],
    &[
        (0, 2.95875854768068491816892993775e-2),
        (2, 8.87627564304205475450678981324e-2),
    ],
    &[
        (0, 2.41365134159266685502369798665e-1),
        (2, -8.84549479328286085344864962717e-1),
        (3, 9.24834003261792003115737966543e-1),
    ],
    &[
        (0, 3.7037037037037037037037037037e-2),
        (3, 1.70828608729473871279604482173e-1),
        (4, 1.25467687566822425016691814123e-1),
    ],
    &[
        (0, 3.7109375e-2),
        (3, 1.70252211019544039314978060272e-1),
        (4, 6.02165389804559606850219397283e-2),
        (5, -1.7578125e-2),
    ],
    &[
        (0, 3.70920001185047927108779319836e-2),
        (3, 1.70383925712239993810214054705e-1),
        (4, 1.07262030446373284651809199168e-1),
        (5, -1.53194377486244017527936158236e-2),
        (6, 8.27378916381402288758473766002e-3),
    ],
    &[
        (0, 6.24110958716075717114429577812e-1),
        (3, -3.36089262944694129406857109825e0),
        (4, -8.68219346841726006818189891453e-1),
        (5, 2.75920996994467083049415600797e1),
        (6, 2.01540675504778934086186788979e1),
        (7, -4.34898841810699588477366255144e1),
    ],
    &[
        (0, 4.77662536438264365890433908527e-1),
        (3, -2.48811461997166764192642586468e0),
        (4, -5.90290826836842996371446475743e-1),
        (5, 2.12300514481811942347288949897e1),
        (6, 1.52792336328824235832596922938e1),
        (7, -3.32882109689848629194453265587e1),
        (8, -2.03312017085086261358222928593e-2),
    ],
    &[
        (0, -9.3714243008598732571704021658e-1),
        (3, 5.18637242884406370830023853209e0),
        (4, 1.09143734899672957818500254654e0),
        (5, -8.14978701074692612513997267357e0),
        (6, -1.85200656599969598641566180701e1),
        (7, 2.27394870993505042818970056734e1),
        (8, 2.49360555267965238987089396762e0),
        (9, -3.0467644718982195003823669022e0),
    ],
    &[
        (0, 2.27331014751653820792359768449e0),
        (3, -1.05344954667372501984066689879e1),
        (4, -2.00087205822486249909675718444e0),
        (5, -1.79589318631187989172765950534e1),
        (6, 2.79488845294199600508499808837e1),
        (7, -2.85899827713502369474065508674e0),
        (8, -8.87285693353062954433549289258e0),
        (9, 1.23605671757943030647266201528e1),
        (10, 6.43392746015763530355970484046e-1),
    ],
    // Stage 13 is f at the eighth-order solution, whose weights are these.
    &[
        (0, 5.42937341165687622380535766363e-2),
        (5, 4.45031289275240888144113950566e0),
        (6, 1.89151789931450038304281599044e0),
        (7, -5.8012039600105847814672114227e0),
        (8, 3.1116436695781989440891606237e-1),
        (9, -1.52160949662516078556178806805e-1),
        (10, 2.01365400804030348374776537501e-1),
        (11, 4.47106157277725905176885569043e-2),
    ],
    &[
        (0, 5.61675022830479523392909219681e-2),
        (6, 2.53500210216624811088794765333e-1),
        (7, -2.46239037470802489917441475441e-1),
        (8, -1.24191423263816360469010140626e-1),
        (9, 1.5329179827876569731206322685e-1),
        (10, 8.20105229563468988491666602057e-3),
        (11, 7.56789766054569976138603589584e-3),
        (12, -8.298e-3),
    ],
    &[
        (0, 3.18346481635021405060768473261e-2),
        (5, 2.83009096723667755288322961402e-2),
        (6, 5.35419883074385676223797384372e-2),
        (7, -5.49237485713909884646569340306e-2),
        (10, -1.08347328697249322858509316994e-4),
        (11, 3.82571090835658412954920192323e-4),
        (12, -3.40465008687404560802977114492e-4),
        (13, 1.41312443674632500278074618366e-1),
    ],
    &[
        (0, -4.28896301583791923408573538692e-1),
        (5, -4.69762141536116384314449447206e0),
        (6, 7.68342119606259904184240953878e0),
        (7, 4.06898981839711007970213554331e0),
        (8, 3.56727187455281109270669543021e-1),
        (12, -1.39902416515901462129418009734e-3),
        (13, 2.9475147891527723389556272149e0),
        (14, -9.15095847217987001081870187138e0),
    ],
];

/// Fifth-order error weights (difference to the eighth-order solution).
const ER: [(usize, f64); 8] = [
    (0, 0.1312004499419488073250102996e-01),
    (5, -0.1225156446376204440720569753e+01),
    (6, -0.4957589496572501915214079952e+00),
    (7, 0.1664377182454986536961530415e+01),
    (8, -0.3503288487499736816886487290e+00),
    (9, 0.3341791187130174790297318841e+00),
    (10, 0.8192320648511571246570742613e-01),
    (11, -0.2235530786388629525884427845e-01),
];
/// Third-order embedded weights.
const BHH: [(usize, f64); 3] = [
    (0, 0.244094488188976377952755905512e+00),
    (8, 0.733846688281611857341361741547e+00),
    (11, 0.220588235294117647058823529412e-01),
];

/// Dense-output weights for the coefficients 5..8 of the interpolant (rows d4..d7).
const DENSE: [[(usize, f64); 12]; 4] = [
    [
        (0, -0.84289382761090128651353491142e+01),
        (5, 0.56671495351937776962531783590e+00),
        (6, -0.30689499459498916912797304727e+01),
        (7, 0.23846676565120698287728149680e+01),
        (8, 0.21170345824450282767155149946e+01),
        (9, -0.87139158377797299206789907490e+00),
        (10, 0.22404374302607882758541771650e+01),
        (11, 0.63157877876946881815570249290e+00),
        (12, -0.88990336451333310820698117400e-01),
        (13, 0.18148505520854727256656404962e+02),
        (14, -0.91946323924783554000451984436e+01),
        (15, -0.44360363875948939664310572000e+01),
    ],
    [
        (0, 0.10427508642579134603413151009e+02),
        (5, 0.24228349177525818288430175319e+03),
        (6, 0.16520045171727028198505394887e+03),
        (7, -0.37454675472269020279518312152e+03),
        (8, -0.22113666853125306036270938578e+02),
        (9, 0.77334326684722638389603898808e+01),
        (10, -0.30674084731089398182061213626e+02),
        (11, -0.93321305264302278729567221706e+01),
        (12, 0.15697238121770843886131091075e+02),
        (13, -0.31139403219565177677282850411e+02),
        (14, -0.93529243588444783865713862664e+01),
        (15, 0.35816841486394083752465898540e+02),
    ],
    [
        (0, 0.19985053242002433820987653617e+02),
        (5, -0.38703730874935176555105901742e+03),
        (6, -0.18917813819516756882830838328e+03),
        (7, 0.52780815920542364900561016686e+03),
        (8, -0.11573902539959630126141871134e+02),
        (9, 0.68812326946963000169666922661e+01),
        (10, -0.10006050966910838403183860980e+01),
        (11, 0.77771377980534432092869265740e+00),
        (12, -0.27782057523535084065932004339e+01),
        (13, -0.60196695231264120758267380846e+02),
        (14, 0.84320405506677161018159903784e+02),
        (15, 0.11992291136182789328035130030e+02),
    ],
    [
        (0, -0.25693933462703749003312586129e+02),
        (5, -0.15418974869023643374053993627e+03),
        (6, -0.23152937917604549567536039109e+03),
        (7, 0.35763911791061412378285349910e+03),
        (8, 0.93405324183624310003907691704e+02),
        (9, -0.37458323136451633156875139351e+02),
        (10, 0.10409964950896230045147246184e+03),
        (11, 0.29840293426660503123344363579e+02),
        (12, -0.43533456590011143754432175058e+02),
        (13, 0.96324553959188282948394950600e+02),
        (14, -0.39177261675615439165231486172e+02),
        (15, -0.14972683625798562581422125276e+03),
    ],
];

/// DOP853.
#[derive(Clone, Debug)]
pub struct Dop853<D: Dim> {
    dim: D,
    k: [Vector<D>; 16],
    cont: Dop853Dense<D>,
}

/// DOP853's dense output of one step: the eight coefficient rows of its seventh-order
/// interpolant ([`crate::DenseOutput`]).
#[derive(Clone, Debug)]
pub struct Dop853Dense<D: Dim> {
    c: [Vector<D>; 8],
}

impl<const N: usize> Dop853<Const<N>> {
    /// A stepper.
    pub fn new() -> Self {
        Self::new_in(Const)
    }
}

impl<D: Dim> Dop853<D> {
    /// A stepper for states of size `dim`.
    pub fn new_in(dim: D) -> Self {
        Dop853 {
            dim,
            k: std::array::from_fn(|_| dim.zeros()),
            cont: Dop853Dense {
                c: std::array::from_fn(|_| dim.zeros()),
            },
        }
    }
}

impl<const N: usize> Default for Dop853<Const<N>> {
    fn default() -> Self {
        Self::new()
    }
}

impl<D: Dim> Dop853<D> {
    /// Evaluates stage `s` (0-based) from the stages before it.
    #[inline(always)]
    fn stage<F: Rhs<D>>(
        &mut self,
        sys: &F,
        t: f64,
        y: &Vector<D>,
        h: f64,
        s: usize,
        stats: &mut Stats,
    ) -> Result<(), SolveError> {
        let mut yt = self.dim.zeros();
        combine::<D>(y, h, A[s], &self.k, &mut yt);
        let mut ks = self.dim.zeros();
        eval(sys, t + C[s] * h, &yt, &mut ks, stats)?;
        self.k[s] = ks;
        Ok(())
    }
}

impl<D: Dim> Stepper<D> for Dop853<D> {
    const NAME: &'static str = "DOP853";
    const ERROR_ORDER: u32 = 7;
    #[inline(always)]
    fn dim(&self) -> D {
        self.dim
    }

    const DENSE_ORDER: u32 = 7;
    type Dense = Dop853Dense<D>;

    fn dense_output(&self) -> &Dop853Dense<D> {
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
        for s in 1..12 {
            self.stage(sys, start.t, start.y, h, s, stats)?;
        }
        let mut b = self.dim.zeros();
        sum::<D>(A[12], &self.k, &mut b);
        for i in 0..self.dim.size() {
            end.y[i] = start.y[i] + h * b[i];
        }
        // Hairer's blended estimate: err5^2 / sqrt(err5^2 + 0.01 err3^2), which behaves like
        // the fifth-order estimate but cannot vanish by accident.
        let mut e5 = self.dim.zeros();
        sum::<D>(&ER, &self.k, &mut e5);
        let mut e3 = self.dim.zeros();
        sum::<D>(&BHH, &self.k, &mut e3);
        let scales = tol.scales(start.y, end.y);
        let (mut err5, mut err3) = (0.0, 0.0);
        for i in 0..self.dim.size() {
            let sk = scales[i];
            let a = e5[i] / sk;
            let c = (b[i] - e3[i]) / sk;
            err5 += a * a;
            err3 += c * c;
        }
        let mut deno = err5 + 0.01 * err3;
        if deno <= 0.0 {
            deno = 1.0;
        }
        let norm = if self.dim.size() == 0 {
            0.0
        } else {
            h.abs() * err5 * (1.0 / (self.dim.size() as f64 * deno)).sqrt()
        };
        if norm <= 1.0 {
            eval(sys, start.t + h, end.y, end.f, stats)?;
            self.k[12].assign(end.f);
        }
        // The fifth-order estimate names the worst component.
        Ok(tol.estimate(norm, &e5, &scales))
    }

    #[inline]
    fn prepare_dense<F: Rhs<D>>(
        &mut self,
        sys: &F,
        start: StepStart<'_, D>,
        end_y: &Vector<D>,
        end_f: &Vector<D>,
        h: f64,
        stats: &mut Stats,
    ) -> Result<(), SolveError> {
        self.k[12].assign(end_f);
        for s in 13..16 {
            self.stage(sys, start.t, start.y, h, s, stats)?;
        }
        for (row, d) in DENSE.iter().enumerate() {
            let mut v = self.dim.zeros();
            sum::<D>(d, &self.k, &mut v);
            for i in 0..self.dim.size() {
                self.cont.c[4 + row][i] = h * v[i];
            }
        }
        for i in 0..self.dim.size() {
            let ydiff = end_y[i] - start.y[i];
            let bspl = h * start.f[i] - ydiff;
            self.cont.c[0][i] = start.y[i];
            self.cont.c[1][i] = ydiff;
            self.cont.c[2][i] = bspl;
            self.cont.c[3][i] = ydiff - h * end_f[i] - bspl;
        }
        Ok(())
    }

    fn interpolate(&self, s: f64, out: &mut Vector<D>) {
        fill_all::<D>(out, |i| self.cont.value_at(s, i));
    }

    /// Component by component: the unchosen ones cost nothing.
    fn interpolate_components(&self, s: f64, which: &Components<D>, out: &mut Vector<D>) {
        which.fill(out, |i| self.cont.value_at(s, i));
    }

    fn interpolate_component(&self, s: f64, i: usize) -> f64 {
        self.cont.value_at(s, i)
    }

    fn interpolate_derivative(&self, s: f64, h: f64, out: &mut Vector<D>) {
        fill_all::<D>(out, |i| self.cont.rate(s, h, i));
    }

    /// Component by component, like the values.
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

impl<D: Dim> DenseOutput<D> for Dop853Dense<D> {
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

impl<D: Dim> Dop853Dense<D> {
    /// Component `i` of the seventh-order interpolant at `s`.
    #[inline(always)]
    fn value_at(&self, s: f64, i: usize) -> f64 {
        let s1 = 1.0 - s;
        let c = &self.c;
        c[0][i]
            + s * (c[1][i]
                + s1 * (c[2][i]
                    + s * (c[3][i]
                        + s1 * (c[4][i] + s * (c[5][i] + s1 * (c[6][i] + s * c[7][i]))))))
    }

    /// Component `i` of the interpolant's exact derivative at `s` (step `h`): the product rule
    /// through the nesting of [`Self::value_at`], innermost first (each level is
    /// `a_k = c_k + w·a_{k+1}` with `w` alternating between `s` and `1 − s`).
    #[inline(always)]
    fn rate(&self, s: f64, h: f64, i: usize) -> f64 {
        let s1 = 1.0 - s;
        let c = &self.c;
        let a6 = c[6][i] + s * c[7][i];
        let d6 = c[7][i];
        let a5 = c[5][i] + s1 * a6;
        let d5 = s1 * d6 - a6;
        let a4 = c[4][i] + s * a5;
        let d4 = s * d5 + a5;
        let a3 = c[3][i] + s1 * a4;
        let d3 = s1 * d4 - a4;
        let a2 = c[2][i] + s * a3;
        let d2 = s * d3 + a3;
        let a1 = c[1][i] + s1 * a2;
        let d1 = s1 * d2 - a2;
        (a1 + s * d1) / h
    }
}
