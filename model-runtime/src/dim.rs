//! The size of a state, known when the program compiles or only when it runs.
//!
//! A model emitted by `model-macros` has a size fixed at compile time, and its states are
//! fixed-size arrays: a step allocates nothing and the compiler removes the bounds checks. A
//! model read from a file at run time (the DSL interpreter) has its size only then. Rather than
//! padding such a model to a fixed maximum, every integrator, tolerance, event locator and
//! driver is written once over a [`Dim`], as nalgebra does for matrices with `Const<N>` and
//! `Dyn`: [`Const<N>`] stores a state as `[f64; N]` (the compiled path, monomorphised to the
//! same code as before), [`Dyn`] as a `Vec<f64>` of the size it carries.
//!
//! Generic code makes a fresh vector from a size it already has ([`Dim::zeros`]) or from a
//! vector it holds ([`Dim::of`]), so a dimension value travels with the data and `Const<N>`
//! costs nothing: it is a zero-sized type whose `size` is the constant.

use std::fmt::Debug;
use std::hash::Hash;
use std::ops::{Index, IndexMut};

/// What an element of a [`Dim::Array`] must be.
pub trait Element: Clone + Debug + PartialEq + Send + Sync + 'static {}
impl<T: Clone + Debug + PartialEq + Send + Sync + 'static> Element for T {}

/// A sequence of [`Dim::size`] values of `T`: `[T; N]` or `Vec<T>`.
pub trait Array<T>:
    Clone
    + Debug
    + PartialEq
    + Send
    + Sync
    + AsRef<[T]>
    + AsMut<[T]>
    + Index<usize, Output = T>
    + IndexMut<usize>
    + 'static
{
    /// Copies `from` into `self` without allocating (both have the same size).
    #[inline]
    fn assign(&mut self, from: &Self)
    where
        T: Copy,
    {
        self.as_mut().copy_from_slice(from.as_ref());
    }
}

impl<T: Element, const N: usize> Array<T> for [T; N] {}
impl<T: Element> Array<T> for Vec<T> {}

/// The number of components of a state, at compile time ([`Const`]) or at run time ([`Dyn`]).
pub trait Dim: Copy + Debug + PartialEq + Eq + Hash + Send + Sync + 'static {
    /// `size` values of `T`.
    type Array<T: Element>: Array<T>;

    /// The number of components.
    fn size(self) -> usize;

    /// The size of `array` (for [`Const`], the constant).
    fn of<T: Element>(array: &Self::Array<T>) -> Self;

    /// `size` copies of `value`.
    fn filled<T: Element>(self, value: T) -> Self::Array<T>;

    /// `size` values `value(i)`.
    fn tabulate<T: Element>(self, value: impl FnMut(usize) -> T) -> Self::Array<T>;

    /// The zero vector.
    #[inline(always)]
    fn zeros(self) -> Vector<Self> {
        self.filled(0.0)
    }

    /// The zero matrix (`size` rows of `size`).
    #[inline(always)]
    fn zero_matrix(self) -> Matrix<Self> {
        self.filled(self.zeros())
    }

    /// The components of `slice` as a vector of this size, or `None` if its length differs.
    fn vector(self, slice: &[f64]) -> Option<Vector<Self>> {
        (slice.len() == self.size()).then(|| self.tabulate(|i| slice[i]))
    }
}

/// A state of a [`Dim`]: `[f64; N]` or `Vec<f64>`.
pub type Vector<D> = <D as Dim>::Array<f64>;

/// A square matrix of a [`Dim`], as rows (`m[i][j]`): `[[f64; N]; N]` or `Vec<Vec<f64>>`.
pub type Matrix<D> = <D as Dim>::Array<Vector<D>>;

/// A size known at compile time: states are `[f64; N]`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Const<const N: usize>;

impl<const N: usize> Dim for Const<N> {
    type Array<T: Element> = [T; N];

    #[inline(always)]
    fn size(self) -> usize {
        N
    }

    #[inline(always)]
    fn of<T: Element>(_: &[T; N]) -> Self {
        Const
    }

    #[inline(always)]
    fn filled<T: Element>(self, value: T) -> [T; N] {
        std::array::from_fn(|_| value.clone())
    }

    #[inline(always)]
    fn tabulate<T: Element>(self, value: impl FnMut(usize) -> T) -> [T; N] {
        std::array::from_fn(value)
    }

    #[inline(always)]
    fn zeros(self) -> [f64; N] {
        [0.0; N]
    }

    #[inline(always)]
    fn zero_matrix(self) -> [[f64; N]; N] {
        [[0.0; N]; N]
    }
}

/// A size known only at run time (a model read from a file): states are `Vec<f64>` of this
/// many components.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Dyn(pub usize);

impl Dim for Dyn {
    type Array<T: Element> = Vec<T>;

    #[inline]
    fn size(self) -> usize {
        self.0
    }

    #[inline]
    fn of<T: Element>(array: &Vec<T>) -> Self {
        Dyn(array.len())
    }

    fn filled<T: Element>(self, value: T) -> Vec<T> {
        vec![value; self.0]
    }

    fn tabulate<T: Element>(self, value: impl FnMut(usize) -> T) -> Vec<T> {
        (0..self.0).map(value).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same generic code on both kinds of size.
    fn sum_of_squares<D: Dim>(d: D) -> f64 {
        let v = d.tabulate(|i| i as f64);
        (0..d.size()).map(|i| v[i] * v[i]).sum()
    }

    #[test]
    fn const_and_dyn_agree() {
        assert_eq!(sum_of_squares(Const::<4>), 14.0);
        assert_eq!(sum_of_squares(Dyn(4)), 14.0);
        assert_eq!(Dyn::of(&Dyn(3).zeros()), Dyn(3));
        assert_eq!(Dyn(2).zero_matrix(), vec![vec![0.0; 2]; 2]);
        assert_eq!(Const::<2>.vector(&[1.0, 2.0]), Some([1.0, 2.0]));
        assert_eq!(Dyn(2).vector(&[1.0]), None);
    }
}
