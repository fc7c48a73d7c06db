//! Test problems with known solutions, shared by the integration tests.
#![allow(dead_code)]

pub mod ball;
pub mod log;

use model_runtime::Const;
use model_runtime::{
    Direction, EvalError, EventHit, GuardSpec, HybridSystem, Model, ModelInfo, Transition,
};

/// A `ModelInfo` for a hand-written test model.
pub const fn info(name: &'static str, states: &'static [&'static str]) -> ModelInfo {
    ModelInfo::of(name, states, &[], &[])
}

/// x' = v, v' = -x, z' = cos(t) z: an oscillator plus a non-autonomous component.
/// From (1, 0, 1) at t = 0: (cos t, -sin t, exp(sin t)).
pub struct Forced;
static FORCED: ModelInfo = info("forced", &["x", "v", "z"]);
impl Model<3> for Forced {
    fn info(&self) -> &'static ModelInfo {
        &FORCED
    }
    fn rhs(&self, t: f64, y: &[f64; 3], dy: &mut [f64; 3]) -> Result<(), EvalError> {
        *dy = [y[1], -y[0], t.cos() * y[2]];
        Ok(())
    }
    fn jacobian(&self, t: f64, _y: &[f64; 3], jac: &mut [[f64; 3]; 3]) -> Result<(), EvalError> {
        *jac = [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, t.cos()]];
        Ok(())
    }
}
impl Forced {
    pub const Y0: [f64; 3] = [1.0, 0.0, 1.0];
    pub fn exact(t: f64) -> [f64; 3] {
        [t.cos(), -t.sin(), t.sin().exp()]
    }
}

/// A clock: y' = 1.
pub struct Ramp;
static RAMP: ModelInfo = info("ramp", &["y"]);
impl Model<1> for Ramp {
    fn info(&self) -> &'static ModelInfo {
        &RAMP
    }
    fn rhs(&self, _t: f64, _y: &[f64; 1], dy: &mut [f64; 1]) -> Result<(), EvalError> {
        dy[0] = 1.0;
        Ok(())
    }
}

/// Harmonic oscillator x' = v, v' = -x.
pub struct Harmonic;
static HARMONIC: ModelInfo = info("harmonic", &["x", "v"]);
impl Model<2> for Harmonic {
    fn info(&self) -> &'static ModelInfo {
        &HARMONIC
    }
    fn rhs(&self, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
        *dy = [y[1], -y[0]];
        Ok(())
    }
}

/// The Kepler problem with GM = 1: (x, y, vx, vy).
pub struct Kepler;
static KEPLER: ModelInfo = info("kepler", &["x", "y", "vx", "vy"]);
impl Model<4> for Kepler {
    fn info(&self) -> &'static ModelInfo {
        &KEPLER
    }
    fn rhs(&self, _t: f64, y: &[f64; 4], dy: &mut [f64; 4]) -> Result<(), EvalError> {
        let r2 = y[0] * y[0] + y[1] * y[1];
        let r3 = r2 * r2.sqrt();
        *dy = [y[2], y[3], -y[0] / r3, -y[1] / r3];
        Ok(())
    }
}
impl Kepler {
    /// Periapsis of the orbit with semi-major axis 1 and eccentricity `e`.
    pub fn periapsis(e: f64) -> [f64; 4] {
        [1.0 - e, 0.0, 0.0, ((1.0 + e) / (1.0 - e)).sqrt()]
    }
    /// The exact state at `t` (period 2π), from Kepler's equation.
    pub fn exact(e: f64, t: f64) -> [f64; 4] {
        let m = t;
        let mut ea = if e > 0.8 { std::f64::consts::PI } else { m };
        for _ in 0..60 {
            let d = (ea - e * ea.sin() - m) / (1.0 - e * ea.cos());
            ea -= d;
            if d.abs() < 1e-16 {
                break;
            }
        }
        let b = (1.0 - e * e).sqrt();
        let den = 1.0 - e * ea.cos();
        [
            ea.cos() - e,
            b * ea.sin(),
            -ea.sin() / den,
            b * ea.cos() / den,
        ]
    }
}

/// Van der Pol: y1' = y2, y2' = mu (1 - y1²) y2 - y1.
pub struct VanDerPol {
    pub mu: f64,
}
static VDP: ModelInfo = info("van_der_pol", &["y1", "y2"]);
impl Model<2> for VanDerPol {
    fn info(&self) -> &'static ModelInfo {
        &VDP
    }
    fn rhs(&self, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
        *dy = [y[1], self.mu * (1.0 - y[0] * y[0]) * y[1] - y[0]];
        Ok(())
    }
    fn jacobian(&self, _t: f64, y: &[f64; 2], jac: &mut [[f64; 2]; 2]) -> Result<(), EvalError> {
        *jac = [
            [0.0, 1.0],
            [
                -2.0 * self.mu * y[0] * y[1] - 1.0,
                self.mu * (1.0 - y[0] * y[0]),
            ],
        ];
        Ok(())
    }
}

/// y' = y², y(0) = 1: blows up at t = 1.
pub struct Blowup;
static BLOWUP: ModelInfo = info("blowup", &["y"]);
impl Model<1> for Blowup {
    fn info(&self) -> &'static ModelInfo {
        &BLOWUP
    }
    fn rhs(&self, _t: f64, y: &[f64; 1], dy: &mut [f64; 1]) -> Result<(), EvalError> {
        dy[0] = y[0] * y[0];
        Ok(())
    }
}

/// y' = 1 with a "singular pivot" once y exceeds 2: a model error to propagate.
pub struct Fragile;
static FRAGILE: ModelInfo = info("fragile", &["y"]);
impl Model<1> for Fragile {
    fn info(&self) -> &'static ModelInfo {
        &FRAGILE
    }
    fn rhs(&self, _t: f64, y: &[f64; 1], dy: &mut [f64; 1]) -> Result<(), EvalError> {
        if y[0] > 2.0 {
            return Err(EvalError::SingularPivot {
                model: "fragile".into(),
                pivot: "2 - y".into(),
                value: 2.0 - y[0],
            });
        }
        dy[0] = 1.0;
        Ok(())
    }
}

/// Max-norm distance.
pub fn dist<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// A one-mode hybrid system around `model` with one upward guard `guard(y, dy)`; `on_event`
/// decides what a crossing does. The test systems of the hybrid driver are all of this shape.
pub struct OneGuard<M, G, E> {
    /// The model integrated.
    pub model: M,
    /// The guard's value at a state and its derivative.
    pub guard: G,
    /// The transition when the guard fires.
    pub on_event: E,
}

/// The transition map of a [`OneGuard`] system of dimension `N`.
pub type EventMap<const N: usize> = fn(&EventHit<Const<N>, ()>) -> Transition<Const<N>, (), ()>;

/// Restarts in place: events that leave the solution unchanged.
pub fn continue_in_place<const N: usize>(
    hit: &EventHit<Const<N>, ()>,
) -> Transition<Const<N>, (), ()> {
    Transition::Continue { y: hit.y, note: () }
}

/// Stops the run.
pub fn stop<const N: usize>(_: &EventHit<Const<N>, ()>) -> Transition<Const<N>, (), ()> {
    Transition::Stop(())
}

/// The system whose guard is `y[component]` crossing upwards, restarting in place (periapsis
/// passages of an orbit, zero crossings of an oscillator).
pub fn up_crossings<M: Model<N>, const N: usize>(
    model: M,
    component: usize,
) -> OneGuard<M, impl Fn(&[f64; N], &[f64; N]) -> f64, EventMap<N>> {
    OneGuard {
        model,
        guard: move |y: &[f64; N], _: &[f64; N]| y[component],
        on_event: continue_in_place,
    }
}

const UP: [GuardSpec<()>; 1] = [GuardSpec {
    id: (),
    direction: Direction::Up,
}];

impl<M, G, E, const N: usize> HybridSystem<Const<N>> for OneGuard<M, G, E>
where
    M: Model<N>,
    G: Fn(&[f64; N], &[f64; N]) -> f64,
    E: FnMut(&EventHit<Const<N>, ()>) -> Transition<Const<N>, (), ()>,
{
    type Mode = ();
    type Guard = ();
    type Stop = ();
    type Note = ();
    fn rhs(&self, _: (), t: f64, y: &[f64; N], dy: &mut [f64; N]) -> Result<(), EvalError> {
        self.model.rhs(t, y, dy)
    }
    fn guards(&self, _: ()) -> &[GuardSpec<()>] {
        &UP
    }
    fn guard_values(
        &self,
        _: (),
        _t: f64,
        y: &[f64; N],
        dy: &[f64; N],
        g: &mut [f64],
    ) -> Result<(), EvalError> {
        g[0] = (self.guard)(y, dy);
        Ok(())
    }
    fn on_event(
        &mut self,
        _: (),
        hit: &EventHit<Const<N>, ()>,
    ) -> Result<Transition<Const<N>, (), ()>, EvalError> {
        Ok((self.on_event)(hit))
    }
}

/// A clock `x' = 1` with several guards `value(i, x)`; the first that fires stops the run and
/// names itself. The guard semantics (earliest wins, ties, direction filters, excursions) are
/// tested on it.
pub struct ClockGuards<G> {
    /// The guards, identified by their index.
    pub specs: Vec<GuardSpec<usize>>,
    /// Guard `i`'s value at `x`.
    pub value: G,
}

impl<G: Fn(usize, f64) -> f64> HybridSystem<Const<1>> for ClockGuards<G> {
    type Mode = ();
    type Guard = usize;
    type Stop = usize;
    type Note = ();
    fn rhs(&self, _: (), _t: f64, _y: &[f64; 1], dy: &mut [f64; 1]) -> Result<(), EvalError> {
        dy[0] = 1.0;
        Ok(())
    }
    fn guards(&self, _: ()) -> &[GuardSpec<usize>] {
        &self.specs
    }
    fn guard_values(
        &self,
        _: (),
        _t: f64,
        y: &[f64; 1],
        _dy: &[f64; 1],
        g: &mut [f64],
    ) -> Result<(), EvalError> {
        for (i, v) in g.iter_mut().enumerate() {
            *v = (self.value)(i, y[0]);
        }
        Ok(())
    }
    fn on_event(
        &mut self,
        _: (),
        hit: &EventHit<Const<1>, usize>,
    ) -> Result<Transition<Const<1>, (), usize>, EvalError> {
        Ok(Transition::Stop(hit.guard))
    }
}
