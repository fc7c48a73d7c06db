//! A ball bouncing on the ground: the hybrid system whose event times, speeds and notes have
//! closed forms, shared by the event, property and note tests.

use model_runtime::Const;
use model_runtime::{Direction, EvalError, EventHit, GuardSpec, HybridSystem, Transition};

/// Gravity of the ball tests (m/s²).
pub const G: f64 = 9.81;
/// The restitution of the ball dropped in most tests.
pub const RESTITUTION: f64 = 0.9;

/// The ball's one guard.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BallGuard {
    /// The height reaching zero from above.
    Ground,
}
const GROUND: [GuardSpec<BallGuard>; 1] = [GuardSpec {
    id: BallGuard::Ground,
    direction: Direction::Down,
}];

/// y = (height, velocity) under gravity `g`; at the ground the velocity is reversed and
/// scaled by the restitution `e`.
pub struct Ball {
    /// Gravity (m/s²).
    pub g: f64,
    /// Restitution.
    pub e: f64,
    /// Impacts so far.
    pub impacts: u32,
}

impl Ball {
    /// A ball under gravity `g` with restitution `e`.
    pub fn new(g: f64, e: f64) -> Ball {
        Ball { g, e, impacts: 0 }
    }

    /// The ball most tests drop: [`G`], [`RESTITUTION`].
    pub fn dropped() -> Ball {
        Ball::new(G, RESTITUTION)
    }
}

/// What the transition map tells the observer about an impact.
#[derive(Clone, Debug, PartialEq)]
pub struct Impact {
    /// 1 for the first impact.
    pub number: u32,
    /// The speed just before it (m/s), read from the event state.
    pub speed: f64,
    /// A label built at the impact: a note need not be `Copy`.
    pub label: String,
}

impl HybridSystem<Const<2>> for Ball {
    type Mode = ();
    type Guard = BallGuard;
    type Stop = ();
    type Note = Impact;
    fn rhs(&self, _: (), _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
        *dy = [y[1], -self.g];
        Ok(())
    }
    fn jacobian(
        &self,
        _: (),
        _t: f64,
        _y: &[f64; 2],
        j: &mut [[f64; 2]; 2],
    ) -> Result<(), EvalError> {
        *j = [[0.0, 1.0], [0.0, 0.0]];
        Ok(())
    }
    fn guards(&self, _: ()) -> &[GuardSpec<BallGuard>] {
        &GROUND
    }
    fn guard_values(
        &self,
        _: (),
        _t: f64,
        y: &[f64; 2],
        _dy: &[f64; 2],
        g: &mut [f64],
    ) -> Result<(), EvalError> {
        g[0] = y[0];
        Ok(())
    }
    fn on_event(
        &mut self,
        _: (),
        hit: &EventHit<Const<2>, BallGuard>,
    ) -> Result<Transition<Const<2>, (), (), Impact>, EvalError> {
        self.impacts += 1;
        Ok(Transition::Continue {
            y: [0.0, -self.e * hit.y[1]],
            note: Impact {
                number: self.impacts,
                speed: -hit.y[1],
                label: format!("impact {} at t = {:.3}", self.impacts, hit.t),
            },
        })
    }
}

/// The closed form of a ball thrown from height `h0` upwards at `v0`.
pub struct Flights {
    /// Gravity.
    pub g: f64,
    /// Restitution.
    pub e: f64,
    /// The first impact's time.
    pub t1: f64,
    /// The speed just before the first impact.
    pub v1: f64,
}

impl Flights {
    /// The flights of `ball` from height `h0`, thrown upwards at `v0`.
    pub fn of(ball: &Ball, h0: f64, v0: f64) -> Flights {
        let g = ball.g;
        // First impact: h0 + v0 t - g t²/2 = 0.
        let t1 = (v0 + (v0 * v0 + 2.0 * g * h0).sqrt()) / g;
        Flights {
            g,
            e: ball.e,
            t1,
            v1: g * t1 - v0,
        }
    }

    /// The speed just before impact `k` (from 1).
    pub fn speed(&self, k: u32) -> f64 {
        self.v1 * self.e.powi(k as i32 - 1)
    }

    /// The times of the first `count` impacts.
    pub fn impact_times(&self, count: usize) -> Vec<f64> {
        let mut times = vec![self.t1];
        for k in 1..count {
            let last = times[k - 1];
            times.push(last + 2.0 * self.e.powi(k as i32) * self.v1 / self.g);
        }
        times
    }
}
