//! Which way a guard crosses zero, and which ways fire it: the vocabulary the tracker and its
//! screening interval ([`super::quiet`]) share, kept in a leaf so that neither depends on the
//! other through it.

/// Which crossings of zero fire a guard.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Direction {
    /// From negative to non-negative.
    Up,
    /// From positive to non-positive.
    Down,
    /// Either.
    Both,
}

/// The direction of an actual crossing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Crossed {
    /// Negative before, non-negative at the event.
    Up,
    /// Positive before, non-positive at the event.
    Down,
}

impl Direction {
    /// Whether a crossing in direction `c` fires a guard with this filter.
    pub fn admits(self, c: Crossed) -> bool {
        matches!(
            (self, c),
            (Direction::Both, _) | (Direction::Up, Crossed::Up) | (Direction::Down, Crossed::Down)
        )
    }
}

/// The crossing of a single reference sign by a new value, if any.
#[inline]
pub(crate) fn crossing(reference: f64, value: f64) -> Option<Crossed> {
    if reference < 0.0 && value >= 0.0 {
        Some(Crossed::Up)
    } else if reference > 0.0 && value <= 0.0 {
        Some(Crossed::Down)
    } else {
        None
    }
}
