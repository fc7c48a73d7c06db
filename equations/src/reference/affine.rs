//! Quantities that are affine in the state derivatives.
//!
//! The reference never writes the rows of `M(y)·ẏ = f(y)` by hand: it evaluates the balance
//! laws with vectors whose entries carry, besides a number, their exact linear dependence on
//! the unknown derivatives `ẏ`. Every balance law is affine in `ẏ`, so once a law is evaluated
//! its coefficient row is a row of `M` and its constant part is `-f`, exactly (no finite
//! differences, no cancellation from probing).

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};
use std::ops::{Add, Mul, Neg, Sub};

/// Number of states (and unknown derivatives) of every disk model.
pub(crate) const DIM: usize = 12;

/// A scalar `cst + lin · ẏ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Affine {
    /// Coefficients of the derivatives.
    pub lin: SVector<f64, DIM>,
    /// Part independent of the derivatives.
    pub cst: f64,
}

impl Affine {
    /// A known number.
    pub fn constant(cst: f64) -> Self {
        Affine {
            lin: SVector::zeros(),
            cst,
        }
    }

    /// The derivative of state `j`.
    pub fn derivative(j: usize) -> Self {
        let mut lin = SVector::zeros();
        lin[j] = 1.0;
        Affine { lin, cst: 0.0 }
    }

    /// The value once the derivatives are known.
    pub fn eval(&self, dy: &[f64; DIM]) -> f64 {
        self.cst + self.lin.dot(&SVector::from(*dy))
    }
}

impl Add for Affine {
    type Output = Affine;
    fn add(self, o: Affine) -> Affine {
        Affine {
            lin: self.lin + o.lin,
            cst: self.cst + o.cst,
        }
    }
}

impl Sub for Affine {
    type Output = Affine;
    fn sub(self, o: Affine) -> Affine {
        Affine {
            lin: self.lin - o.lin,
            cst: self.cst - o.cst,
        }
    }
}

impl Neg for Affine {
    type Output = Affine;
    fn neg(self) -> Affine {
        Affine {
            lin: -self.lin,
            cst: -self.cst,
        }
    }
}

impl Mul<Affine> for f64 {
    type Output = Affine;
    fn mul(self, o: Affine) -> Affine {
        Affine {
            lin: o.lin * self,
            cst: o.cst * self,
        }
    }
}

/// A spatial vector `cst + lin · ẏ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AffineVec {
    /// Coefficients of the derivatives, one row per spatial component.
    pub lin: SMatrix<f64, 3, DIM>,
    /// Part independent of the derivatives.
    pub cst: Vector3<f64>,
}

impl AffineVec {
    /// A known vector.
    pub fn constant(cst: Vector3<f64>) -> Self {
        AffineVec {
            lin: SMatrix::zeros(),
            cst,
        }
    }

    /// A known direction times an affine magnitude.
    pub fn along(direction: Vector3<f64>, magnitude: Affine) -> Self {
        AffineVec {
            lin: direction * magnitude.lin.transpose(),
            cst: direction * magnitude.cst,
        }
    }

    /// `left × self` for a known vector `left`.
    pub fn crossed_by(&self, left: &Vector3<f64>) -> Self {
        AffineVec {
            lin: left.cross_matrix() * self.lin,
            cst: left.cross(&self.cst),
        }
    }

    /// The same vector in another basis: `basis_change · self`.
    pub fn transformed(&self, basis_change: &Matrix3<f64>) -> Self {
        AffineVec {
            lin: basis_change * self.lin,
            cst: basis_change * self.cst,
        }
    }

    /// One spatial component.
    pub fn component(&self, i: usize) -> Affine {
        Affine {
            lin: self.lin.row(i).transpose(),
            cst: self.cst[i],
        }
    }

    /// The value once the derivatives are known.
    pub fn eval(&self, dy: &[f64; DIM]) -> Vector3<f64> {
        self.cst + self.lin * SVector::from(*dy)
    }
}

impl Add for AffineVec {
    type Output = AffineVec;
    fn add(self, o: AffineVec) -> AffineVec {
        AffineVec {
            lin: self.lin + o.lin,
            cst: self.cst + o.cst,
        }
    }
}

impl Sub for AffineVec {
    type Output = AffineVec;
    fn sub(self, o: AffineVec) -> AffineVec {
        AffineVec {
            lin: self.lin - o.lin,
            cst: self.cst - o.cst,
        }
    }
}

impl Mul<AffineVec> for f64 {
    type Output = AffineVec;
    fn mul(self, o: AffineVec) -> AffineVec {
        AffineVec {
            lin: o.lin * self,
            cst: o.cst * self,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_dy() -> [f64; DIM] {
        std::array::from_fn(|j| 0.5 + j as f64 * 0.75 - (j as f64).sin())
    }

    #[test]
    fn affine_algebra_matches_numbers() {
        let dy = sample_dy();
        let x = 2.0 * Affine::derivative(3) + Affine::constant(1.5);
        let y = Affine::derivative(7) - Affine::constant(0.25);
        assert_eq!((x + y).eval(&dy), x.eval(&dy) + y.eval(&dy));
        assert_eq!((x - y).eval(&dy), x.eval(&dy) - y.eval(&dy));
        assert_eq!((-x).eval(&dy), -x.eval(&dy));
        assert_eq!(x.eval(&dy), 2.0 * dy[3] + 1.5);
    }

    #[test]
    fn vector_operations_commute_with_evaluation() {
        let dy = sample_dy();
        let u = Vector3::new(0.3, -1.2, 2.0);
        let w = Vector3::new(-0.7, 0.4, 0.9);
        let v = AffineVec::along(u, Affine::derivative(2) + Affine::constant(0.5))
            + AffineVec::along(w, Affine::derivative(11))
            + AffineVec::constant(Vector3::new(1.0, 2.0, 3.0));
        let vv = v.eval(&dy);
        let tol = 1e-13 * (1.0 + vv.norm());
        assert!((v.crossed_by(&u).eval(&dy) - u.cross(&vv)).norm() < tol);
        assert!(
            (v.transformed(&nalgebra::Matrix3::from_columns(&[u, w, u.cross(&w)]))
                .eval(&dy)
                - nalgebra::Matrix3::from_columns(&[u, w, u.cross(&w)]) * vv)
                .norm()
                < tol * 10.0
        );
        assert!((v.component(1).eval(&dy) - vv[1]).abs() < tol);
        assert!(((2.0 * v - v).eval(&dy) - vv).norm() < tol);
    }
}
