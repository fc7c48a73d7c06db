//! Shared pieces of the integration tests: random states, the explicit third implementation,
//! and a comparison that reports the worst disagreement in units of its tolerance.
#![allow(dead_code)]

pub mod dual;
pub mod explicit;
pub mod extreme;
pub mod scales;
pub mod subject;
pub mod tracked;

use equations::DiskParams;
use equations::TransitionRecord;
use std::f64::consts::{FRAC_PI_2, PI};

/// Two runs made the same mode decisions: the same number, the same kinds in the same order,
/// and times within `dt` of each other.
pub fn assert_same_decisions(a: &[TransitionRecord], b: &[TransitionRecord], dt: f64) {
    assert_eq!(a.len(), b.len(), "number of transitions");
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        assert_eq!((x.from, x.to), (y.from, y.to), "transition {k}");
        assert!((x.t - y.t).abs() < dt, "transition {k}: {} vs {}", x.t, y.t);
    }
}

/// A small deterministic generator (SplitMix64), so that every failure is reproducible.
pub struct Rng(u64);

impl Rng {
    /// A generator for one test; `EQUATIONS_TEST_SEED=k` shifts every test to another
    /// reproducible stream, to look beyond the default states.
    pub fn new(seed: u64) -> Self {
        let shift = std::env::var("EQUATIONS_TEST_SEED")
            .ok()
            .and_then(|s| s.parse::<u64>().ok())
            .unwrap_or(0);
        Rng(seed ^ shift.wrapping_mul(0xD6E8_FEB8_6659_FD93))
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Log-uniform in `[lo, hi]`, both positive.
    pub fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.unit()).exp()
    }

    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    pub fn sign(&mut self) -> f64 {
        if self.chance(0.5) {
            1.0
        } else {
            -1.0
        }
    }
}

/// How far from the regular interior a random state may go.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reach {
    /// Moderate inclinations and rates.
    Typical,
    /// Also θ within 1e-6 of 0 and of π/2, rates up to 1e3 rad/s, slip down to 1e-12 m/s.
    Extreme,
}

/// A random inclination in `(0, π)`.
pub fn theta(rng: &mut Rng, reach: Reach) -> f64 {
    let r = rng.unit();
    match reach {
        Reach::Extreme if r < 0.2 => rng.log_uniform(1e-12, 1e-6),
        Reach::Extreme if r < 0.4 => FRAC_PI_2 + rng.sign() * rng.log_uniform(1e-12, 1e-6),
        _ if r < 0.9 => rng.uniform(0.02, FRAC_PI_2 - 0.02),
        _ => rng.uniform(FRAC_PI_2 - 0.02, PI - 0.02),
    }
}

/// A random angular rate (rad/s), sometimes exactly zero.
pub fn rate(rng: &mut Rng, reach: Reach) -> f64 {
    if rng.chance(0.05) {
        return 0.0;
    }
    let hi = match reach {
        Reach::Typical => 50.0,
        Reach::Extreme => 1e3,
    };
    rng.sign() * rng.log_uniform(1e-3, hi)
}

/// A random angle; occasionally many turns away from the principal range.
pub fn angle(rng: &mut Rng) -> f64 {
    if rng.chance(0.1) {
        rng.uniform(-60.0, 60.0)
    } else {
        rng.uniform(-PI, PI)
    }
}

/// Random physical parameters (`mu_d <= mu_st <= 1`), with air drag half of the time.
pub fn params(rng: &mut Rng) -> DiskParams {
    let mu_st = rng.uniform(0.0, 1.0);
    let with_air = rng.chance(0.5);
    DiskParams {
        m: rng.log_uniform(0.05, 5.0),
        a: rng.log_uniform(0.01, 0.3),
        g: rng.uniform(1.0, 20.0),
        mu_d: rng.uniform(0.0, mu_st),
        mu_st,
        mu_a: if with_air { rng.uniform(0.0, 2.0) } else { 0.0 },
        w_z: if with_air && rng.chance(0.5) {
            rng.uniform(-1.0, 1.0)
        } else {
            0.0
        },
    }
    .validated()
    .expect("generated parameters are valid")
}

/// Either the paper's disk or a random one.
pub fn some_params(rng: &mut Rng) -> DiskParams {
    if rng.chance(0.3) {
        DiskParams::paper()
    } else {
        params(rng)
    }
}

fn perturb(rng: &mut Rng, x: f64, size: f64) -> f64 {
    if rng.chance(0.5) {
        x
    } else {
        x + rng.uniform(-1.0, 1.0) * size
    }
}

/// A random rolling state `(X, Y, Z, V_X, V_Y, V_Z, ψ, θ, φ, Ω_x, Ω_y, Ω_z)`: half on the
/// contact manifold, half off it (the equations hold for any state).
pub fn rolling_state(rng: &mut Rng, p: &DiskParams, reach: Reach) -> [f64; 12] {
    let theta = theta(rng, reach);
    let (psi, phi) = (angle(rng), angle(rng));
    let w = [rate(rng, reach), rate(rng, reach), rate(rng, reach)];
    let (sp, cp) = psi.sin_cos();
    let (st, ct) = theta.sin_cos();
    let a = p.a;
    let size = a * (w[0].abs() + w[1].abs() + w[2].abs()) + 0.1;
    [
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
        perturb(rng, a * st, 0.1 * a),
        perturb(rng, a * (w[1] * cp * st + w[2] * sp), size),
        perturb(rng, a * (w[1] * sp * st - w[2] * cp), size),
        perturb(rng, a * w[1] * ct, size),
        psi,
        theta,
        phi,
        w[0],
        w[1],
        w[2],
    ]
}

/// A random rolling-consistent state (Box 2): on the contact manifold, not slipping.
pub fn rolling_consistent_state(rng: &mut Rng, p: &DiskParams, reach: Reach) -> [f64; 12] {
    let mut y = rolling_state(rng, p, reach);
    make_rolling_consistent(p, &mut y);
    y
}

/// Overwrites `Z, V_X, V_Y, V_Z` with the Box 2 values.
pub fn make_rolling_consistent(p: &DiskParams, y: &mut [f64; 12]) {
    let w = equations::formulas::BodyRates {
        omega_x: y[9],
        omega_y: y[10],
        omega_z: y[11],
    };
    let c = equations::formulas::rolling_consistent(p, y[6], y[7], &w);
    y[2] = c.z;
    y[3] = c.velocity.x;
    y[4] = c.velocity.y;
    y[5] = c.velocity.z;
}

/// A random polar sliding state on the contact manifold (`Z = a sin θ`, `V_Z = a Ω_y cos θ`).
pub fn sliding_consistent_state(rng: &mut Rng, p: &DiskParams, reach: Reach) -> [f64; 12] {
    let mut y = rolling_consistent_state(rng, p, reach);
    y[3] = slip_speed(rng, reach);
    y[4] = angle(rng);
    y
}

/// A random slip speed (m/s), down to 1e-12 in the extreme reach.
pub fn slip_speed(rng: &mut Rng, reach: Reach) -> f64 {
    match reach {
        Reach::Typical => rng.log_uniform(1e-3, 3.0),
        Reach::Extreme => rng.log_uniform(1e-12, 3.0),
    }
}

/// A random polar sliding state `(X, Y, Z, v_C, α, V_Z, ψ, θ, φ, Ω_x, Ω_y, Ω_z)`.
pub fn sliding_state(rng: &mut Rng, p: &DiskParams, reach: Reach) -> [f64; 12] {
    let mut y = rolling_state(rng, p, reach);
    y[3] = slip_speed(rng, reach);
    y[4] = angle(rng);
    y
}

/// The same slip in the Cartesian chart: `u = v_C e_s = -v_C (cos α, sin α)`.
pub fn polar_to_cartesian(y: &[f64; 12]) -> [f64; 12] {
    let mut c = *y;
    c[3] = -y[3] * y[4].cos();
    c[4] = -y[3] * y[4].sin();
    c
}

/// The slip back in the polar chart: `v_C = |u|`, `α = atan2(-u_Y, -u_X)`.
pub fn cartesian_to_polar(y: &[f64; 12]) -> [f64; 12] {
    let mut c = *y;
    c[3] = y[3].hypot(y[4]);
    c[4] = (-y[4]).atan2(-y[3]);
    c
}

/// Physical kind (units) of a derivative.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// m/s: rates of the position.
    Velocity,
    /// m/s²: rates of velocities.
    Acceleration,
    /// rad/s: rates of angles.
    AngleRate,
    /// rad/s²: rates of angular velocities.
    AngularAcceleration,
}

use Kind::{Acceleration as Ac, AngleRate as Ar, AngularAcceleration as Aa, Velocity as Ve};

/// Kinds of the rolling and Cartesian sliding derivatives.
pub const KINDS_VELOCITY_PAIR: [Kind; 12] = [Ve, Ve, Ve, Ac, Ac, Ac, Ar, Ar, Ar, Aa, Aa, Aa];
/// Kinds of the polar sliding derivatives (`α̇` is an angle rate).
pub const KINDS_POLAR: [Kind; 12] = [Ve, Ve, Ve, Ac, Ar, Ac, Ar, Ar, Ar, Aa, Aa, Aa];

/// Norm-wise accuracy asked of every derivative, in ε of the largest derivative of its kind.
pub const NORMWISE_ULPS: f64 = 1.0;

/// Names and kinds of one chart's derivatives.
pub struct Layout {
    pub names: [&'static str; 12],
    pub kinds: [Kind; 12],
}

/// Rolling: `(X, Y, Z, V_X, V_Y, V_Z, ψ, θ, φ, Ω)`.
pub const ROLLING: Layout = Layout {
    names: equations::reference::rolling::STATE_NAMES,
    kinds: KINDS_VELOCITY_PAIR,
};
/// Polar sliding: `v_C, α` in place of `V_X, V_Y`.
pub const POLAR: Layout = Layout {
    names: equations::reference::sliding_polar::STATE_NAMES,
    kinds: KINDS_POLAR,
};
/// Cartesian sliding: `u_X, u_Y` in place of `V_X, V_Y`.
pub const CARTESIAN: Layout = Layout {
    names: equations::reference::sliding_cartesian::STATE_NAMES,
    kinds: KINDS_VELOCITY_PAIR,
};

/// Worst disagreement seen, in units of the tolerance (`<= 1` passes).
pub struct Agreement {
    /// The relative tolerance: 1e-12 unless a test says otherwise.
    pub rel: f64,
    pub worst: f64,
    pub what: String,
    pub checked: usize,
}

impl Default for Agreement {
    fn default() -> Self {
        Agreement {
            rel: 1e-12,
            worst: 0.0,
            what: String::new(),
            checked: 0,
        }
    }
}

impl Agreement {
    /// Records `|a - b| / (rel · max(|a|, |b|, scale))`, where `scale` is the component's
    /// natural size (the running rounding bound of its explicit formula, see `tracked`).
    pub fn check(&mut self, a: f64, b: f64, scale: f64, what: impl FnOnce() -> String) {
        let bound = self.rel * a.abs().max(b.abs()).max(scale);
        let ratio = match (a - b).abs() / bound {
            _ if a == b => 0.0,
            r if r.is_nan() => f64::INFINITY,
            r => r,
        };
        self.checked += 1;
        if ratio > self.worst {
            self.worst = ratio;
            self.what = format!("{} : {a:e} vs {b:e} (scale {scale:e})", what());
        }
    }

    /// Checks all twelve derivatives against the explicit ones, each on the larger of its
    /// running rounding bound and its row scale.
    pub fn check_derivatives(
        &mut self,
        layout: &Layout,
        y: &[f64; 12],
        dy: &[f64; 12],
        expected: &[tracked::Tracked; 12],
        row_scales: &[f64; 12],
    ) {
        let scales = std::array::from_fn(|i| expected[i].scale.max(row_scales[i]));
        let values = expected.map(|x| x.v);
        self.check_derivative_pair(layout, y, dy, &values, &scales);
    }

    /// Checks two sets of derivatives, each component on its scale. A derivative that is
    /// exactly zero (say `Ω̇_z` at `Ω_x = 0`) has zero scale of its own, but a coupled solve
    /// (LU, symbolic elimination) is only accurate norm-wise there: it leaves noise of a few ε
    /// times the other derivatives of the same units. So every component also passes within
    /// `NORMWISE_ULPS` ε of the largest scale of its kind.
    pub fn check_derivative_pair(
        &mut self,
        layout: &Layout,
        y: &[f64; 12],
        got: &[f64; 12],
        want: &[f64; 12],
        scales: &[f64; 12],
    ) {
        let (names, kinds) = (&layout.names, &layout.kinds);
        for i in 0..12 {
            let same_kind = (0..12)
                .filter(|&j| kinds[j] == kinds[i])
                .map(|j| scales[j])
                .fold(0.0, f64::max);
            let floor = NORMWISE_ULPS * f64::EPSILON / self.rel * same_kind;
            let scale = scales[i].max(floor);
            self.check(got[i], want[i], scale, || {
                format!("der({}) at {y:?}", names[i])
            });
        }
    }

    pub fn assert_within(&self, label: &str) {
        assert!(self.checked > 0, "{label}: nothing checked");
        println!(
            "{label}: {} comparisons, worst {:.3e} × tolerance at {}",
            self.checked, self.worst, self.what
        );
        assert!(
            self.worst <= 1.0,
            "{label}: worst disagreement {:.3} × tolerance at {}",
            self.worst,
            self.what
        );
    }
}
