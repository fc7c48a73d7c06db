//! The bridge: the exact straight line that carries the slip between zero and the stick
//! threshold, where neither sliding chart can be evaluated (module docs of [`crate::hybrid`]).
//! Planning it is the one place where a constant derivative stands in for the model, so its
//! limits ([`MAX_BRIDGE`]) live here with it.

use super::{DiskGuard, DiskNote, DiskSystem, DiskTransition, Halt, Phase};
use crate::hybrid::onset::OnsetError;
use crate::hybrid::StopReason;
use crate::modes::layout::{ALPHA, U_X, U_Y, V_C};
use crate::modes::{ContactForce, Mode, PhysicalState, Slip, SlipChart, DIM};
use model_runtime::Const;
use model_runtime::{EvalError, EventHit, Model, Transition};

/// The longest bridge (s). A bridge moves the state along a constant derivative, so it is exact
/// only while the state barely changes; its duration is `2δ / |v̇_C|`, about `2e-9` s at the
/// usual accelerations. When the slip's acceleration is small (static friction barely above
/// dynamic friction) the duration runs away — at `μ_st − μ_d = 1e-9` it would be seconds, during
/// which the disk would fly on a straight line with no other guard. Beyond this bound, and at an
/// onset of second order (`v̇_C = 0`, docs/physics.md §7.1), sliding starts at once with the
/// slip `2δ`, an error of `2δ` in the slip speed: the size the stick threshold already accepts.
const MAX_BRIDGE: f64 = 1e-6;

/// What happens when a bridge ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum AfterBridge {
    /// The slip has reached zero: the rolling equations decide.
    StickDecision,
    /// The slip has grown to the stick threshold's double: sliding proper starts with it.
    StartSliding { slip: Slip },
}

/// A planned bridge: when it ends, its constant derivative, and what follows it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BridgePlan {
    pub(crate) t_end: f64,
    pub(crate) slope: [f64; DIM],
    pub(crate) then: AfterBridge,
}

/// Where a segment starts: its phase and state, and on a bridge the slip it starts from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Entry {
    pub phase: Phase,
    pub y: [f64; DIM],
    pub bridge: Option<Slip>,
}

/// Where sliding starts — the bridge's first state, or sliding proper when the bridge would
/// be shorter than an ulp of `t` — or why the run must stop instead (no consistent direction,
/// or a sliding disk that the floor would have to pull).
pub(crate) type BridgeStart = Result<Entry, Halt>;

impl<R: Model<DIM>, S: Model<DIM>> DiskSystem<'_, R, S> {
    /// Plans a bridge from zero slip to `|v_C| = 2δ` along `e_s(direction)`, the slip speed
    /// signed like `along` (its rate), and returns the bridge's first state. A rate of `+0.0`
    /// (an onset of second order) starts sliding proper at once with the slip `+2δ`.
    pub(super) fn bridge_into_sliding(
        &mut self,
        t: f64,
        state: &PhysicalState,
        direction: f64,
        along: f64,
    ) -> Result<BridgeStart, EvalError> {
        if !along.is_finite() {
            return Ok(Err(Halt::Onset {
                t,
                source: OnsetError::NoConsistentDirection { guess: direction },
            }));
        }
        let (_, dy) = self.models.probe_onset(t, state, direction)?;
        let zero = Slip {
            speed: 0.0,
            direction,
        };
        let mut start_state = *state;
        start_state.slip = zero;
        let normal = ContactForce::sliding(&self.models.params, &start_state, &dy).normal;
        if normal <= 0.0 || normal.is_nan() {
            // Rolling was not admissible and sliding would need the floor to pull.
            return Ok(Err(Halt::Stop(StopReason::ContactLost {
                t,
                mode: Mode::Sliding,
            })));
        }
        let target = Slip {
            speed: 2.0 * self.settings.stick * along.signum(),
            direction,
        };
        let duration = 2.0 * self.settings.stick / along.abs();
        let start = state.sliding_vector(self.models.chart, zero);
        let end = state.sliding_vector(self.models.chart, target);
        if t + duration <= t || duration > MAX_BRIDGE {
            // Shorter than an ulp of t (a bridge guard would start at exactly zero and never
            // arm), or too long to be a straight line ([`MAX_BRIDGE`]): sliding starts at once.
            return Ok(Ok(Entry {
                phase: Phase::Sliding,
                y: self.start_sliding(&end, target),
                bridge: None,
            }));
        }
        let mut slope = dy;
        for i in [U_X, U_Y] {
            // U_X/U_Y and V_C/ALPHA share indices 3 and 4: a straight line in either chart.
            slope[i] = (end[i] - start[i]) / duration;
        }
        self.bridge = BridgePlan {
            t_end: t + duration,
            slope,
            then: AfterBridge::StartSliding { slip: target },
        };
        Ok(Ok(Entry {
            phase: Phase::Bridge,
            y: start,
            bridge: Some(zero),
        }))
    }

    /// The slip reached the stick threshold: bridge it to its exact zero.
    pub(super) fn bridge_to_stop(
        &mut self,
        hit: &EventHit<Const<DIM>, DiskGuard>,
    ) -> Result<DiskTransition, EvalError> {
        let (y, dy) = (&hit.y, &hit.dy);
        let duration = match self.models.chart {
            SlipChart::Cartesian => {
                let (u, du) = ([y[U_X], y[U_Y]], [dy[U_X], dy[U_Y]]);
                -(u[0] * du[0] + u[1] * du[1]) / (du[0] * du[0] + du[1] * du[1])
            }
            SlipChart::Polar => -y[V_C] / dy[V_C],
        };
        if !(duration.is_finite() && hit.t + duration > hit.t) || duration > MAX_BRIDGE {
            // Already at the zero to within an ulp of t (or receding from it), or approaching
            // it too slowly for a straight line ([`MAX_BRIDGE`]): decide here.
            return self.decide_at_stop(hit.t, y);
        }
        let mut slope = *dy;
        if self.models.chart == SlipChart::Polar {
            // α̇ = w / v_C is not followed through zero: the slip direction is held.
            slope[ALPHA] = 0.0;
        }
        self.bridge = BridgePlan {
            t_end: hit.t + duration,
            slope,
            then: AfterBridge::StickDecision,
        };
        Ok(Transition::Switch {
            to: Phase::Bridge,
            y: *y,
            note: DiskNote {
                decision: None,
                bridge: Some(self.models.sliding_state(y).slip),
            },
        })
    }
}
