//! Guards, their semantics, and the search for the earliest crossing inside a step.
//!
//! The guard semantics themselves are documented where users meet them, on
//! [`GuardSpec`]; this module keeps one definition of what fires ([`GuardTracker`]) that the
//! step-end checks, the interior checks and screening all share.

use crate::dim::{Const, Dim, Vector};

mod direction;
mod inputs;
mod interior;
mod quiet;
mod tracker;

pub use direction::{Crossed, Direction};
pub use inputs::GuardInputs;
pub use interior::InteriorChecks;
pub(crate) use tracker::GuardTracker;

/// How guard values at a time are obtained.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Probe {
    /// From the state on the dense output and an exact model evaluation there.
    Exact,
    /// From the dense output and its derivative: an estimate, used only to screen.
    Estimate,
}

/// One guard of a mode: an identifier chosen by the user and its direction filter.
///
/// # Semantics
///
/// A guard is a scalar function `g(t, y, dy)` of the current mode. The driver evaluates all
/// guards of the mode at the start of a segment and after every accepted step (where `dy` is
/// already known), and tracks for each guard a *reference sign*: the sign of its last nonzero
/// value.
///
/// * **Crossing.** A guard with reference sign `-` crosses *up* in a step when its value at the
///   step end is `>= 0`; with reference sign `+` it crosses *down* when the value is `<= 0`.
///   A value exactly zero at a step end therefore counts as a crossing, located at (or before)
///   that end.
/// * **Direction filter.** [`Direction::Up`] guards fire only on up-crossings,
///   [`Direction::Down`] only on down-crossings, [`Direction::Both`] on either. A filtered
///   crossing fires nothing but still updates the reference sign.
/// * **Re-arming after a transition.** A guard exactly zero at the start of a segment
///   (typically because the transition put the state on that guard's surface) does not fire
///   there: it has no reference sign until it moves away from zero, and its first nonzero value
///   at a later check point decides what happens:
///   - if it left zero in a direction its filter *admits*, the new mode was entered on its own
///     switching surface heading out through it: that departure is an event, reported at the
///     last check point where the guard was still zero (normally the segment start, with the
///     exact start state). This is how an immediate switch back (or a sliding-mode relay that
///     must chatter) becomes visible instead of silently continuing in an inconsistent mode;
///   - otherwise the value becomes the reference sign and nothing fires.
///
///   Exceptions, where a departure is *quiet* (never fires; the guard fires again only after a
///   later genuine crossing): after [`crate::Transition::Continue`], the guard that
///   just fired (a reset such as a bounce leaves the state on the surface and moves on; that
///   is not a new event); and at the start of a run, every guard (no transition led there: a
///   run may well start on a surface, e.g. an orbit started at its periapsis).
/// * **Exact location.** A crossing is located on the step's dense output by a bracketing root
///   finder ([`crate::find_crossing`]) to a few ulps of `t`. The reported time is the first point found
///   on the *far* side of the crossing (or exactly on zero), so the event state is already
///   past the surface and a restart from it cannot detect the same crossing again.
/// * **Several guards in one step.** The earliest crossing wins; equal times go to the guard
///   listed first. The others are not reported (the segment ends at the event).
/// * **Passes.** An event whose transition is [`crate::Transition::Pass`] does not end the
///   segment, and it changes nothing for the other guards: the search of the step resumes
///   at the check point where the event was found, with the same check points, values and
///   brackets as if the guard that passed did not exist, so every later event is located
///   exactly where it would be without it (to the bit). Only the guard that passed moves on:
///   its reference becomes its sign at the event (the far side; exactly zero there, it is
///   pending with a quiet departure) and its next crossing is searched from the event time,
///   so it fires again only when it crosses back in a direction its filter admits. Events
///   after a pass are reported no earlier than it (a tie located a few ulps before it is
///   reported at its time), and every pass consumes one guard's crossing, so a step holds
///   finitely many.
/// * **Limitation: a sign change and back inside one step** is invisible at the step ends. Set
///   [`crate::HybridOptions::guard_checks`] to sample the guards at interior points of
///   each step on the dense output ([`InteriorChecks`]); a double crossing between two samples
///   still goes unseen. [`InteriorChecks::Screened`] samples cost no model evaluation: the
///   guards see the interpolant and its derivative, and only a sample that shows an admitted
///   crossing (or a non-finite value) is evaluated exactly, so estimates can trigger a check
///   but never decide an event or move a reference sign. An estimate interpolates only the
///   components the mode's guards declare they read ([`GuardInputs`]) and is NaN in all
///   others, so a guard that reads an undeclared one gets a non-finite estimate: an exact
///   check, never a wrong answer. Most steps need only two estimates:
///   with the exact end values they fit a cubic per guard, and when every cubic keeps its sign
///   with a margin, the other sample points are skipped. The same holds for an excursion shorter than a step right after a
///   `Continue` (e.g. the ever shorter flights of a bouncing ball near its accumulation
///   point): the quiet guard's first nonzero value is already back on the near side.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct GuardSpec<G> {
    /// The user's name for the guard (typically a fieldless enum).
    pub id: G,
    /// Which crossings fire it.
    pub direction: Direction,
}

/// A guard that fired: which one, exactly when, and the state there (from the dense output,
/// not the end of the step).
#[derive(Clone, Debug, PartialEq)]
pub struct EventHit<D: Dim, G> {
    /// The guard's identifier.
    pub guard: G,
    /// Its index in the mode's guard list.
    pub index: usize,
    /// The event time.
    pub t: f64,
    /// The last time found on the near side of the crossing (`t - before` is a few ulps).
    pub before: f64,
    /// The state at `t`, interpolated on the step's dense output.
    pub y: Vector<D>,
    /// `f(t, y)` in the mode in which the guard fired.
    pub dy: Vector<D>,
    /// The guard's value at `t` (zero or of the far sign, tiny).
    pub value: f64,
    /// How it crossed.
    pub direction: Crossed,
}

impl<const N: usize, G: Copy> Copy for EventHit<Const<N>, G> {}

/// How a segment's start reads its guards (see [`GuardSpec`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Quiet {
    /// After a switch: a guard that holds fires at once, a departure from zero in a
    /// direction the filter admits fires.
    None,
    /// After a restart in the same mode: as after a switch, and the guard that fired is on
    /// its surface, its departure deciding.
    Guard(usize),
    /// At the start of a run: a guard that holds fires at once; departures from zero are
    /// quiet.
    Start,
    /// After a projection: nothing fires; the values become the reference signs.
    All,
}

/// A crossing found and located in a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Found {
    pub index: usize,
    pub t: f64,
    pub before: f64,
    pub direction: Crossed,
}
