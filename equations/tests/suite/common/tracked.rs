//! Numbers that carry a first-order bound of their own rounding error.
//!
//! Comparing two implementations "to 1e-12 relative" needs a scale per component: a derivative
//! that is a sum of large cancelling terms can only be known to ε times the size of those terms,
//! not to ε times the (small) result. Evaluating the explicit formulas with [`Tracked`] numbers
//! gives exactly that scale, as Wilkinson's running error bound: `|computed - exact| <~ ε·scale`.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// The arithmetic the explicit formulas are written in: plain `f64` or [`Tracked`].
pub trait Scalar:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// An exactly known number: a literal, a parameter, a state other than an angle.
    fn exact(x: f64) -> Self;
    /// An angle that enters through sines and cosines of sums and differences (`ψ`, `φ`,
    /// `α`): known to an absolute ε. An implementation that builds `sin(α - ψ)` from the
    /// frame and the slip direction (products of sines and cosines) gets it to ε, not to
    /// ε |sin(α - ψ)|; the explicit form, which subtracts the angles first, would otherwise
    /// claim a precision no vector formulation has near `α = ψ`.
    fn angle(x: f64) -> Self {
        Self::exact(x)
    }
    /// Sine.
    fn sin(self) -> Self;
    /// Cosine.
    fn cos(self) -> Self;
    /// The number.
    fn value(self) -> f64;
}

impl Scalar for f64 {
    fn exact(x: f64) -> Self {
        x
    }
    fn sin(self) -> Self {
        f64::sin(self)
    }
    fn cos(self) -> Self {
        f64::cos(self)
    }
    fn value(self) -> f64 {
        self
    }
}

/// A value and a bound `scale` such that its rounding error is at most about `ε · scale`.
#[derive(Clone, Copy, Debug)]
pub struct Tracked {
    pub v: f64,
    pub scale: f64,
}

impl Tracked {
    fn rounded(v: f64, propagated: f64) -> Self {
        Tracked {
            v,
            scale: propagated + v.abs(),
        }
    }
}

impl Scalar for Tracked {
    fn exact(x: f64) -> Self {
        Tracked { v: x, scale: 0.0 }
    }
    fn angle(x: f64) -> Self {
        Tracked { v: x, scale: 1.0 }
    }
    fn sin(self) -> Self {
        Tracked::rounded(self.v.sin(), self.v.cos().abs() * self.scale)
    }
    fn cos(self) -> Self {
        Tracked::rounded(self.v.cos(), self.v.sin().abs() * self.scale)
    }
    fn value(self) -> f64 {
        self.v
    }
}

impl Add for Tracked {
    type Output = Tracked;
    fn add(self, o: Tracked) -> Tracked {
        Tracked::rounded(self.v + o.v, self.scale + o.scale)
    }
}

impl Sub for Tracked {
    type Output = Tracked;
    fn sub(self, o: Tracked) -> Tracked {
        Tracked::rounded(self.v - o.v, self.scale + o.scale)
    }
}

impl Mul for Tracked {
    type Output = Tracked;
    fn mul(self, o: Tracked) -> Tracked {
        Tracked::rounded(
            self.v * o.v,
            self.v.abs() * o.scale + o.v.abs() * self.scale,
        )
    }
}

impl Div for Tracked {
    type Output = Tracked;
    fn div(self, o: Tracked) -> Tracked {
        let q = self.v / o.v;
        Tracked::rounded(q, (self.scale + q.abs() * o.scale) / o.v.abs())
    }
}

impl Neg for Tracked {
    type Output = Tracked;
    fn neg(self) -> Tracked {
        Tracked {
            v: -self.v,
            scale: self.scale,
        }
    }
}
