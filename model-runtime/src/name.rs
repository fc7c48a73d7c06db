//! Names of models, states, pivots and quantities: borrowed when compiled, owned when read.
//!
//! A model compiled by `model!` knows its names at compile time, so they are `static` strings
//! that cost nothing to carry into an error. A model read from a file at run time (the DSL
//! interpreter's, or a Python session's) knows them only then; were they `&'static str` too,
//! every model solved would leak its names, which a long-lived process cannot afford. A
//! [`Name`] is either, with one type for both, and a list of [`Names`] likewise: a compiled
//! model's lists are its `static` arrays, an interpreted model's are owned and dropped with it.
//!
//! A leaf of the crate, like the errors that carry these names.

use std::borrow::Cow;
use std::ops::Index;

/// One name: `static` for a compiled model, owned for a model read at run time.
pub type Name = Cow<'static, str>;

/// Names in index order (states, parameters, outputs, pivots): a compiled model's `static`
/// array, or the owned names of a model read at run time.
///
/// ```
/// use model_runtime::Names;
/// const STATES: Names = Names::Static(&["x", "v"]);
/// let read: Names = ["x".to_string(), "v".to_string()].into_iter().collect();
/// assert_eq!(STATES, read);
/// assert_eq!(&read[1], "v");
/// assert_eq!(STATES.position("v"), Some(1));
/// assert_eq!(read.iter().collect::<Vec<_>>(), ["x", "v"]);
/// ```
#[derive(Clone, Debug)]
pub enum Names {
    /// Names known at compile time.
    Static(&'static [&'static str]),
    /// Names read at run time.
    Owned(Vec<String>),
}

impl Names {
    /// No names.
    pub const EMPTY: Names = Names::Static(&[]);

    /// How many names there are.
    pub fn len(&self) -> usize {
        match self {
            Names::Static(names) => names.len(),
            Names::Owned(names) => names.len(),
        }
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The name at `index`, if there is one.
    pub fn get(&self, index: usize) -> Option<&str> {
        match self {
            Names::Static(names) => names.get(index).copied(),
            Names::Owned(names) => names.get(index).map(String::as_str),
        }
    }

    /// The name at `index` as a [`Name`] to keep (an error's): borrowed when it is `static`.
    pub fn name(&self, index: usize) -> Option<Name> {
        match self {
            Names::Static(names) => names.get(index).map(|&name| Name::Borrowed(name)),
            Names::Owned(names) => names.get(index).map(|name| Name::Owned(name.clone())),
        }
    }

    /// Whether `name` is one of these.
    pub fn contains(&self, name: &str) -> bool {
        self.position(name).is_some()
    }

    /// The index of `name`, if it is one of these.
    pub fn position(&self, name: &str) -> Option<usize> {
        self.iter().position(|n| n == name)
    }

    /// The names in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = &str> + Clone + '_ {
        (0..self.len()).map(|index| &self[index])
    }
}

impl Index<usize> for Names {
    type Output = str;

    fn index(&self, index: usize) -> &str {
        match self {
            Names::Static(names) => names[index],
            Names::Owned(names) => &names[index],
        }
    }
}

impl PartialEq for Names {
    fn eq(&self, other: &Names) -> bool {
        self.iter().eq(other.iter())
    }
}

impl Eq for Names {}

impl<const K: usize> PartialEq<[&str; K]> for Names {
    fn eq(&self, other: &[&str; K]) -> bool {
        self.iter().eq(other.iter().copied())
    }
}

impl FromIterator<String> for Names {
    fn from_iter<I: IntoIterator<Item = String>>(names: I) -> Self {
        Names::Owned(names.into_iter().collect())
    }
}
