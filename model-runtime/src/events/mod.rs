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
/// value. A guard with filter [`Direction::Down`] *holds* where `g <= 0`, one with
/// [`Direction::Up`] where `g >= 0`: the side its admitted crossings lead to. A
/// [`Direction::Both`] guard has no such side.
///
/// * **Crossing.** A guard with reference sign `-` crosses *up* in a step when its value at the
///   step end is `>= 0`; with reference sign `+` it crosses *down* when the value is `<= 0`.
///   A value exactly zero at a step end therefore counts as a crossing, located at (or before)
///   that end.
/// * **Direction filter.** [`Direction::Up`] guards fire only on up-crossings,
///   [`Direction::Down`] only on down-crossings, [`Direction::Both`] on either. A filtered
///   crossing fires nothing but still updates the reference sign.
/// * **A guard on its surface where a segment starts** (after a switch or a restart: exactly
///   zero, or closer to zero than it moves in `h 2^-30`, the first probe's time, so within
///   the rounding an event located on a surface leaves; and the guard whose event restarted
///   the mode, whatever rounding left in its value) takes its reference from its
///   *departure*: its value just after the start, probed on the first step's dense output at
///   `t0 + h 2^-k` for `k` = 30, 24, 18, 12, 6, from the nearest out (the nearest ones may
///   still be in the rounding of its surface, the farther ones past a short excursion).
///   - A departure in a direction the filter admits is an event at the segment's start: the
///     new mode was entered on its own switching surface heading out through it (an immediate
///     switch back, a sliding-mode relay that must chatter), visible instead of silently
///     continuing in an inconsistent mode. The guard that restarted its mode is the exception:
///     it has fired, and moves on from whichever side it leaves to.
///   - Otherwise the departure's side becomes the reference, with the probe as the guard's
///     last check point: an excursion that leaves the surface and comes back through it within
///     the same step (a bounce whose next flight is shorter than the step after it) is a
///     crossing, located between the probe and the step's end, after the excursion's turning
///     point, at the time of the return.
///   
///   At the start of a run departures are quiet (never fire; no transition led there: a run
///   may well start on a surface, an orbit at its periapsis), and a guard still exactly zero
///   at every probe stays pending until its first nonzero value.
/// * **A guard that holds on entry.** For a system whose [`crate::HybridSystem::fires_on_entry`]
///   is true (every [`crate::Switched`] model, so every model of the model language), a guard
///   that holds strictly (not on its surface) where a segment starts fires there at once, at
///   the segment's start, in the direction that leads to its holding side: an instantaneous
///   transition, as in a hybrid automaton. This holds at the start of a run as well as after a
///   switch or a restart (for the guards other than the one that restarted the mode); the first
///   such guard in priority order fires first. A model whose modes keep enabling each other
///   ends with [`crate::HybridError::Chattering`], never a loop. Other systems (the default)
///   take such a guard's side as its reference: it fires after it has left and crossed back.
/// * **The invariant.** After every accepted step in which nothing fired, no guard of the
///   current mode is on its holding side without having fired. The exceptions, where a guard
///   holds legitimately: one that fired and passed ([`crate::Transition::Pass`]) or restarted
///   its mode; one that left its surface at the start of a run; one that holds after a
///   projection ([`crate::HybridSystem::project`]: a projection that pushes a guard across zero
///   is not an event); and, for systems that do not fire on entry, one that held where its
///   segment started. A violation ends the run with [`crate::SolveError::GuardHolds`] naming
///   the guard, never a silent continuation.
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
/// * **Interior checks.** Away from a segment's start, a guard is compared at the step ends:
///   a guard that changes sign and changes back inside one ordinary step leaves no trace
///   there (it is on the same side at both ends, so the invariant holds too). Where a model
///   can do that (a thin obstacle, an oscillation faster than the steps), set
///   [`crate::HybridOptions::guard_checks`] to sample the guards at interior points of
///   each step on the dense output ([`InteriorChecks`]). [`InteriorChecks::Screened`] samples
///   cost no model evaluation: the
///   guards see the interpolant and its derivative, and only a sample that shows an admitted
///   crossing (or a non-finite value) is evaluated exactly, so estimates can trigger a check
///   but never decide an event or move a reference sign. An estimate interpolates only the
///   components the mode's guards declare they read ([`GuardInputs`]) and is NaN in all
///   others, so a guard that reads an undeclared one gets a non-finite estimate: an exact
///   check, never a wrong answer. Most steps need only two estimates:
///   with the exact end values they fit a cubic per guard, and when every cubic keeps its sign
///   with a margin, the other sample points are skipped. When they do not, each third of the
///   step is tested the same way (two more estimates each), and only the sample points of the
///   thirds that do not clear are screened one by one.
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
