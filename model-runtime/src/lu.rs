//! LU decomposition with partial pivoting for the implicit method's small dense systems.

use crate::dim::{Dim, Matrix, Vector};

/// An LU factorisation `P A = L U` of an `N×N` matrix, stored in place.
#[derive(Clone, Debug)]
pub(crate) struct Lu<D: Dim> {
    lu: Matrix<D>,
    perm: D::Array<usize>,
}

/// The matrix is singular (a zero or non-finite pivot) at this column.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Singular {
    #[allow(dead_code)]
    pub column: usize,
}

impl<D: Dim> Lu<D> {
    /// Factorises `a`.
    pub(crate) fn new(mut a: Matrix<D>) -> Result<Self, Singular> {
        let n = D::of(&a).size();
        let mut perm = D::of(&a).tabulate(|i| i);
        for k in 0..n {
            let mut p = k;
            let mut best = a[k][k].abs();
            for (i, row) in a.as_ref().iter().enumerate().skip(k + 1) {
                if row[k].abs() > best {
                    best = row[k].abs();
                    p = i;
                }
            }
            if !(best > 0.0 && best.is_finite()) {
                return Err(Singular { column: k });
            }
            a.as_mut().swap(k, p);
            perm.as_mut().swap(k, p);
            let pivot = a[k][k];
            for i in k + 1..n {
                let m = a[i][k] / pivot;
                a[i][k] = m;
                if m != 0.0 {
                    for j in k + 1..n {
                        a[i][j] -= m * a[k][j];
                    }
                }
            }
        }
        Ok(Lu { lu: a, perm })
    }

    /// Solves `A x = b` in place.
    pub(crate) fn solve(&self, b: &mut Vector<D>) {
        let n = self.perm.as_ref().len();
        let mut x = D::of(b).zeros();
        for i in 0..n {
            x[i] = b[self.perm[i]];
        }
        for i in 0..n {
            let mut s = x[i];
            for j in 0..i {
                s -= self.lu[i][j] * x[j];
            }
            x[i] = s;
        }
        for i in (0..n).rev() {
            let mut s = x[i];
            for j in i + 1..n {
                s -= self.lu[i][j] * x[j];
            }
            x[i] = s / self.lu[i][i];
        }
        *b = x;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dim::Const;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn solves_random_diagonally_dominant_systems(
            m in proptest::array::uniform4(proptest::array::uniform4(-1.0f64..1.0)),
            x in proptest::array::uniform4(-10.0f64..10.0),
        ) {
            let mut a = m;
            for (i, row) in a.iter_mut().enumerate() {
                row[i] += 5.0;
            }
            let mut b = [0.0; 4];
            for i in 0..4 {
                for j in 0..4 {
                    b[i] += a[i][j] * x[j];
                }
            }
            Lu::<Const<_>>::new(a).unwrap().solve(&mut b);
            for i in 0..4 {
                prop_assert!((b[i] - x[i]).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn singular_matrix_is_reported() {
        let a = [[1.0, 2.0], [2.0, 4.0]];
        assert!(Lu::<Const<_>>::new(a).is_err());
        // Pivoting handles a zero in the corner.
        let mut b = [2.0, 3.0];
        Lu::<Const<_>>::new([[0.0, 1.0], [1.0, 0.0]])
            .unwrap()
            .solve(&mut b);
        assert_eq!(b, [3.0, 2.0]);
    }
}
