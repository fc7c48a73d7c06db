//! Where a run starts: a time, the mode the state is given in, and the state with its slip.
//!
//! The slip is carried explicitly, never folded into the centre's velocity for the run to
//! read back: a sliding start is the rolling variables plus the slip `(v_C, α)`, and the
//! sliding chart's vector is built from that slip directly ([`PhysicalState::sliding_vector`]).
//! A start given by the centre's velocity (a scene's `V_X`, `V_Y`) is read into that form
//! once, by [`InitialState::from_velocity`].

use crate::issue::{Checks, Issue};
use crate::modes::layout::{THETA, V_X, V_Y};
use crate::modes::{no_slip_velocity, Mode, PhysicalState, Slip, DIM};
use crate::params::DiskParams;
use std::f64::consts::PI;

/// The scene's names of the state components, in the rolling layout's order
/// (`crate::modes::layout`); an issue about component `i` has the key `initial.{NAMES[i]}`.
pub const STATE_NAMES: [&str; DIM] = [
    "X", "Y", "Z", "V_X", "V_Y", "V_Z", "psi", "theta", "phi", "Omega_x", "Omega_y", "Omega_z",
];

/// A given value agrees with the value a constraint requires when `|given − required| <=
/// CONSTRAINT_TOL · (1 + |required|)` in SI units; a velocity this close to the no-slip one
/// is a start without slip.
pub const CONSTRAINT_TOL: f64 = 1e-9;

/// Where a run starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InitialState {
    /// Start time (s).
    pub t: f64,
    /// [`Mode::Sliding`]: the contact particle slips with `state.slip`, and the run starts
    /// sliding (if the slip exceeds the stick threshold). [`Mode::Rolling`]: it is at rest; the
    /// run puts the state on the rolling constraints and starts rolling if static friction can
    /// hold it, else sliding from zero slip in the consistent direction.
    pub mode: Mode,
    /// The state in rolling variables (`V_X, V_Y` the centre's velocity, slip included) and
    /// the slip.
    pub state: PhysicalState,
}

impl InitialState {
    /// A start without slip from the rolling variables `y` (`V_X, V_Y` are replaced by the
    /// no-slip velocity when the run projects onto the constraints).
    pub fn rolling(t: f64, y: [f64; DIM]) -> Self {
        InitialState {
            t,
            mode: Mode::Rolling,
            state: PhysicalState::from_rolling(&y, 0.0),
        }
    }

    /// A sliding start: the rolling variables `y` with the contact particle slipping with
    /// `slip`; `V_X, V_Y` are set to the no-slip velocity plus the slip.
    pub fn sliding(p: &DiskParams, t: f64, y: [f64; DIM], slip: Slip) -> Self {
        let mut state = PhysicalState { y, slip };
        let roll = no_slip_velocity(p, &y);
        let u = slip.vector();
        state.y[V_X] = roll[0] + u[0];
        state.y[V_Y] = roll[1] + u[1];
        InitialState {
            t,
            mode: Mode::Sliding,
            state,
        }
    }

    /// A start given by the centre's velocity: the slip is `V_hor − V_no-slip`, a sliding
    /// start unless it is within [`CONSTRAINT_TOL`] of zero (relative to the no-slip speed).
    pub fn from_velocity(p: &DiskParams, t: f64, y: [f64; DIM]) -> Self {
        let rolling = PhysicalState::from_rolling(&y, 0.0);
        let u = rolling.velocity_slip(p);
        let roll = no_slip_velocity(p, &y);
        let slip = Slip::from_vector(u);
        if slip.speed <= CONSTRAINT_TOL * (1.0 + roll[0].hypot(roll[1])) || !slip.speed.is_finite()
        {
            let mut y = y;
            if slip.speed.is_finite() {
                y[V_X] = roll[0];
                y[V_Y] = roll[1];
            }
            InitialState::rolling(t, y)
        } else {
            InitialState {
                t,
                mode: Mode::Sliding,
                state: PhysicalState { y, slip },
            }
        }
    }

    /// The paper's start (docs/physics.md §11): centre above the origin at rest, `ψ = φ = 0`,
    /// `θ0 = π/2 − 1`, `Ω = (1, 0, 0)` rad/s, on the rolling constraints.
    pub fn paper(params: &DiskParams) -> Self {
        let theta0 = std::f64::consts::FRAC_PI_2 - 1.0;
        let mut y = [0.0; DIM];
        y[crate::modes::layout::Z] = params.a * theta0.sin();
        y[THETA] = theta0;
        y[crate::modes::layout::OMEGA_X] = 1.0;
        InitialState::rolling(0.0, y)
    }

    /// Every rule the start breaks, keyed `initial.<name>` (`initial.t` for the time,
    /// `initial.v_C` and `initial.alpha` for the slip): every number finite, `θ` in `(0, π)`.
    pub fn issues(&self) -> Vec<Issue> {
        let mut c = Checks::default();
        c.finite("initial.t", self.t);
        for (name, value) in STATE_NAMES.iter().zip(self.state.y) {
            let key = format!("initial.{name}");
            if c.finite(&key, value) && *name == "theta" {
                c.in_range(&key, value, 0.0, PI, true);
            }
        }
        if self.mode == Mode::Sliding {
            c.finite("initial.v_C", self.state.slip.speed);
            c.finite("initial.alpha", self.state.slip.direction);
        }
        c.issues
    }
}
