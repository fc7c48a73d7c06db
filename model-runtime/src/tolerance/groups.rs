//! Components that are one physical vector, for the error norm.
//!
//! A relative tolerance applied component by component depends on the frame a vector is
//! written in: a component that happens to be small gets a tight scale, though its error is
//! as large a part of the vector as any other component's. When the frame turns quickly (an
//! angular velocity in a precessing body frame) that small component sets the step for no
//! physical reason. Declaring the vector's components as a group gives all of them the
//! vector's magnitude as the relative part of their scale, which does not depend on the frame.

use crate::dim::{Const, Dim};
use crate::error::{GroupProblem, InputError};
use std::ops::Range;

/// A run of consecutive state components that form one vector: `start..end`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ComponentGroup {
    /// First component.
    pub start: usize,
    /// One past the last component.
    pub end: usize,
}

impl ComponentGroup {
    /// The components as a range.
    pub fn range(&self) -> Range<usize> {
        self.start..self.end
    }

    /// The Euclidean length of the group's part of `y`.
    #[inline]
    pub fn magnitude(&self, y: &[f64]) -> f64 {
        y[self.range()].iter().map(|v| v * v).sum::<f64>().sqrt()
    }
}

impl From<Range<usize>> for ComponentGroup {
    fn from(r: Range<usize>) -> Self {
        ComponentGroup {
            start: r.start,
            end: r.end,
        }
    }
}

/// Disjoint groups of components of an `N`-vector (none by default).
///
/// Groups are added only through [`VectorGroups::push`], which checks them, so a value always
/// holds non-empty, in-range, disjoint groups; there can be at most `N` of them, which is the
/// storage reserved (for a [`crate::Const`] size, an array: no allocation).
#[derive(Clone, Debug, PartialEq)]
pub struct VectorGroups<D: Dim> {
    slots: D::Array<ComponentGroup>,
    len: usize,
}

impl<const N: usize> Copy for VectorGroups<Const<N>> {}

impl<const N: usize> Default for VectorGroups<Const<N>> {
    fn default() -> Self {
        Self::none(Const)
    }
}

impl<D: Dim> VectorGroups<D> {
    /// No group, in a vector of size `dim`.
    pub fn none(dim: D) -> Self {
        VectorGroups {
            slots: dim.filled(ComponentGroup { start: 0, end: 0 }),
            len: 0,
        }
    }

    /// Adds the components `range` as the next group. A group that is empty, reaches past
    /// the last component or shares a component with an earlier group is refused with an
    /// [`InputError::ComponentGroup`] naming it (its position in the order of declaration)
    /// and what is wrong with it.
    pub fn push(&mut self, range: Range<usize>) -> Result<(), InputError> {
        let group = ComponentGroup::from(range);
        let fail = |problem| InputError::ComponentGroup {
            group: self.len,
            start: group.start,
            end: group.end,
            problem,
        };
        if group.start >= group.end {
            return Err(fail(GroupProblem::Empty));
        }
        let dim = self.slots.as_ref().len();
        if group.end > dim {
            return Err(fail(GroupProblem::OutOfRange { dim }));
        }
        if let Some(other) = self
            .iter()
            .position(|g| g.start < group.end && group.start < g.end)
        {
            return Err(fail(GroupProblem::Overlaps { other }));
        }
        // Disjoint, non-empty and in range: at most `N` groups get here.
        self.slots[self.len] = group;
        self.len += 1;
        Ok(())
    }

    /// Whether no group is declared.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The groups, in the order declared.
    pub fn iter(&self) -> impl Iterator<Item = ComponentGroup> + '_ {
        self.slots.as_ref()[..self.len].iter().copied()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dim::Const;

    /// Declares `groups` in order; the first refusal.
    fn declare(groups: &[Range<usize>]) -> Result<VectorGroups<Const<6>>, InputError> {
        let mut out = VectorGroups::default();
        for g in groups {
            out.push(g.clone())?;
        }
        Ok(out)
    }

    #[test]
    fn each_problem_names_its_group() {
        let problem = |groups: &[Range<usize>]| match declare(groups) {
            Err(InputError::ComponentGroup { group, problem, .. }) => (group, problem),
            other => panic!("{other:?}"),
        };
        assert_eq!(problem(&[0..2, 3..3]), (1, GroupProblem::Empty));
        let (start, end) = (4, 2);
        assert_eq!(problem(&[3..5, start..end]), (1, GroupProblem::Empty));
        assert_eq!(
            problem(&[0..2, 4..7]),
            (1, GroupProblem::OutOfRange { dim: 6 })
        );
        assert_eq!(
            problem(&[0..2, 3..5, 4..6]),
            (2, GroupProblem::Overlaps { other: 1 })
        );
        assert_eq!(
            problem(&[0..3, 2..3]),
            (1, GroupProblem::Overlaps { other: 0 })
        );
        let ok = declare(&[3..6, 0..1, 1..3]).unwrap();
        let ranges: Vec<_> = ok.iter().map(|g| g.range()).collect();
        assert_eq!(ranges, [3..6, 0..1, 1..3]);
    }

    #[test]
    fn the_message_names_group_and_components() {
        let e = declare(&[0..2, 1..3]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "component group 1 (components 1..3) overlaps group 0"
        );
    }
}
