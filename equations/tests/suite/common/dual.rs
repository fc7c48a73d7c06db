//! Forward-mode dual numbers: exact directional derivatives of the energy, so the energy
//! balance can be checked to round-off rather than to a finite-difference error.

use super::tracked::Scalar;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// `v + d·h` with `h² = 0`.
#[derive(Clone, Copy, Debug)]
pub struct Dual {
    pub v: f64,
    pub d: f64,
}

impl Dual {
    pub fn new(v: f64, d: f64) -> Self {
        Dual { v, d }
    }
}

impl Scalar for Dual {
    fn exact(x: f64) -> Self {
        Dual { v: x, d: 0.0 }
    }
    fn sin(self) -> Self {
        Dual::new(self.v.sin(), self.d * self.v.cos())
    }
    fn cos(self) -> Self {
        Dual::new(self.v.cos(), -self.d * self.v.sin())
    }
    fn value(self) -> f64 {
        self.v
    }
}

impl Add for Dual {
    type Output = Dual;
    fn add(self, o: Dual) -> Dual {
        Dual::new(self.v + o.v, self.d + o.d)
    }
}

impl Sub for Dual {
    type Output = Dual;
    fn sub(self, o: Dual) -> Dual {
        Dual::new(self.v - o.v, self.d - o.d)
    }
}

impl Mul for Dual {
    type Output = Dual;
    fn mul(self, o: Dual) -> Dual {
        Dual::new(self.v * o.v, self.d * o.v + self.v * o.d)
    }
}

impl Div for Dual {
    type Output = Dual;
    fn div(self, o: Dual) -> Dual {
        let q = self.v / o.v;
        Dual::new(q, (self.d - q * o.d) / o.v)
    }
}

impl Neg for Dual {
    type Output = Dual;
    fn neg(self) -> Dual {
        Dual::new(-self.v, -self.d)
    }
}

/// The chart a state is written in, for the energy's centre velocity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Chart {
    /// `(V_X, V_Y)` in slots 3, 4.
    Rolling,
    /// `(v_C, α)`.
    SlidingPolar,
    /// `(u_X, u_Y)`.
    SlidingCartesian,
}

/// Total energy (docs/physics.md §8) as a function of the state in `chart`, with the centre's
/// horizontal velocity from the secondary formulas in sliding.
#[allow(non_snake_case)]
pub fn energy<T: Scalar>(p: &equations::DiskParams, chart: Chart, y: &[T; 12]) -> T {
    let [_, _, Z, s3, s4, V_Z, psi, theta, _, Ox, Oy, Oz] = *y;
    let a = T::exact(p.a);
    let rim_x = a * (Oy * psi.cos() * theta.sin() + Oz * psi.sin());
    let rim_y = a * (Oy * psi.sin() * theta.sin() - Oz * psi.cos());
    let (V_X, V_Y) = match chart {
        Chart::Rolling => (s3, s4),
        Chart::SlidingPolar => (-s3 * s4.cos() + rim_x, -s3 * s4.sin() + rim_y),
        Chart::SlidingCartesian => (s3 + rim_x, s4 + rim_y),
    };
    let half = T::exact(0.5);
    half * T::exact(p.m) * (V_X * V_X + V_Y * V_Y + V_Z * V_Z)
        + half * T::exact(p.A()) * (Ox * Ox + Oy * Oy)
        + half * T::exact(p.C()) * Oz * Oz
        + T::exact(p.m * p.g) * Z
}

/// `∇E · dy` and the scale `Σ_i |∂E/∂y_i| · scale_i` its rounding is measured against.
pub struct EnergyRate {
    pub rate: f64,
    pub scale: f64,
}

/// The energy's rate along `dy`, exactly (forward mode), with its scale for derivative
/// component scales `scales`.
pub fn energy_rate(
    p: &equations::DiskParams,
    chart: Chart,
    y: &[f64; 12],
    dy: &[f64; 12],
    scales: &[f64; 12],
) -> EnergyRate {
    let seeded: [Dual; 12] = std::array::from_fn(|i| Dual::new(y[i], dy[i]));
    let rate = energy(p, chart, &seeded).d;
    let scale = (0..12)
        .map(|j| {
            let unit: [Dual; 12] =
                std::array::from_fn(|i| Dual::new(y[i], if i == j { 1.0 } else { 0.0 }));
            energy(p, chart, &unit).d.abs() * scales[j].max(dy[j].abs())
        })
        .sum();
    EnergyRate { rate, scale }
}
