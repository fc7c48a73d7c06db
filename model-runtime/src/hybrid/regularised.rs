//! Regularised time: a hybrid system integrated in a fictitious time `τ` with `dt = s(y) dτ`.
//!
//! Near a singular or non-analytic point of a right-hand side, an explicit method's steps are
//! set by the distance to that point, not by the motion: a field that behaves like `u/|u|`
//! near `u = 0` needs a geometric run of ever smaller steps into the origin and out of it.
//! Sundman's transformation, used for close encounters in celestial mechanics, integrates
//! `dy/dτ = s(y) f(y)` instead, with a scale `s` that vanishes at the bad point like its
//! distance: the scaled field is smooth there, so the steps in `τ` stay long while the steps
//! in `t = ∫ s dτ` shrink by themselves.
//!
//! Physical time becomes a state, and because a relative tolerance needs a small magnitude to
//! mean anything, the clock holds the time since the segment started: the state is
//! `z = (y, t − t_seg)`, `N + 1` components, the last one the clock. [`Regularised`] presents
//! a system `H` with a [`TimeScale`] as a hybrid system in `τ` that the unchanged driver runs:
//!
//! * its right-hand side is `dz/dτ = (s f, s)`;
//! * its guards are `H`'s, evaluated in physical terms (`t = t_seg + z_N`,
//!   `dy/dt = (dz/dτ) / s`, where `s` is the clock's own rate), plus one more, the end time
//!   `t − t_end`, so the run ends at the physical end time located like any event;
//! * a transition of `H` restarts the clock at zero for the next segment.
//!
//! [`crate::PhysicalTime`] turns what the driver reports in `τ` back into physical time for an
//! observer of `H`: samples at `t_first + k / rate` (found on each step's dense output as the
//! roots of the clock), steps and transitions with physical times and derivatives. The
//! driver's own sampling must stay off (its grid would be in `τ`).

use super::{HybridError, HybridOutcome, HybridSystem, StopReason, Transition};
use crate::dim::Const;
use crate::error::EvalError;
use crate::events::{Direction, EventHit, GuardInputs, GuardSpec};
use crate::stepper::Components;
use crate::tolerance::{LimitingComponent, Tolerance};

/// A hybrid system's time transformation `dt = s dτ`, per mode.
pub trait TimeScale<const N: usize>: HybridSystem<Const<N>> {
    /// `s(y) > 0` in `mode`: how much physical time one unit of `τ` is at `y`. It should
    /// vanish like the distance to the points where the right-hand side is not smooth, and
    /// be 1 (or close) away from them.
    fn time_scale(&self, mode: Self::Mode, y: &[f64; N]) -> f64;
}

/// A guard of a [`Regularised`] system: one of the inner system's, or the end time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ClockGuard<G> {
    /// The inner system's guard.
    Inner(G),
    /// Physical time reached the end time.
    EndTime,
}

/// Why a [`Regularised`] run stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum Clocked<R> {
    /// The inner system's transition map stopped it.
    Inner(R),
    /// Physical time reached the end time.
    EndTime,
}

/// A system `H` in `N` states, integrated in `τ` with the clock as state `N` (`M = N + 1`).
///
/// Its right-hand side is `dz/dτ = (s f, s)`; its guards are `H`'s in physical terms plus the
/// end time; a transition of `H` restarts the clock. [`crate::PhysicalTime`] feeds an observer
/// of `H` from the run (the driver's own sampling must stay off: its grid would be in `τ`).
///
/// ```
/// use model_runtime::{
///     Const, Clocked, Dop853, Direction, EvalError, EventHit, GuardSpec, HybridOptions, HybridSolver,
///     HybridSystem, PhysicalTime, Recorder, Regularised, StopReason, TimeScale, Tolerance,
///     Transition,
/// };
///
/// /// y' = -1, stopped when y reaches 0.45 (at t = 0.55), integrated with s = y.
/// struct Drain;
/// const GUARDS: [GuardSpec<&str>; 1] = [GuardSpec { id: "half", direction: Direction::Down }];
/// impl HybridSystem<Const<1>> for Drain {
///     type Mode = ();
///     type Guard = &'static str;
///     type Stop = f64;
///     type Note = ();
///     fn rhs(&self, _: (), _t: f64, _y: &[f64; 1], dy: &mut [f64; 1]) -> Result<(), EvalError> {
///         dy[0] = -1.0;
///         Ok(())
///     }
///     fn guards(&self, _: ()) -> &[GuardSpec<&'static str>] { &GUARDS }
///     fn guard_values(&self, _: (), _t: f64, y: &[f64; 1], _dy: &[f64; 1], g: &mut [f64])
///         -> Result<(), EvalError> { g[0] = y[0] - 0.45; Ok(()) }
///     fn on_event(&mut self, _: (), hit: &EventHit<Const<1>, &'static str>)
///         -> Result<Transition<Const<1>, (), f64>, EvalError> { Ok(Transition::Stop(hit.t)) }
/// }
/// impl TimeScale<1> for Drain {
///     fn time_scale(&self, _: (), y: &[f64; 1]) -> f64 { y[0] }
/// }
///
/// let mut sys = Drain;
/// let mut clocked = Regularised::<_, 1, 2>::new(&mut sys, &[()], 0.0, 10.0);
/// let tol = clocked.tolerance(&Tolerance::scalar(1e-10, 1e-12), (1e-10, 1e-12));
/// let mut solver = HybridSolver::new(Dop853::new(), tol, HybridOptions::default()).unwrap();
/// let mut seen = Recorder::new();
/// let mut observer = PhysicalTime::<_, 1, 2>::new(&mut seen, 0.0, Some(10.0));
/// let out = solver.run(&mut clocked, (), 0.0, &Regularised::<Drain, 1, 2>::start(&[1.0]),
///                      f64::MAX, &mut observer).unwrap();
/// let StopReason::User(Clocked::Inner(t)) = out.stop else { panic!() };
/// assert!((t - 0.55).abs() < 1e-9);
/// // Samples at t = 0, 0.1, ..., 0.5 in physical time: y = 1 - t.
/// assert_eq!(seen.samples.len(), 6);
/// assert!((seen.samples[3].2[0] - 0.7).abs() < 1e-9);
/// ```
pub struct Regularised<'a, H: HybridSystem<Const<N>>, const N: usize, const M: usize> {
    inner: &'a mut H,
    /// Physical time at the start of the current segment.
    t_seg: f64,
    t_end: f64,
    /// The physical time of the latest evaluation: where a failure happened.
    latest: std::cell::Cell<f64>,
    /// Each mode's guards: the inner ones, then the end time.
    guards: Vec<ModeGuards<H::Mode, H::Guard>>,
}

/// One mode's guard list in a [`Regularised`] system.
type ModeGuards<Md, G> = (Md, Vec<GuardSpec<ClockGuard<G>>>);

/// The first `N` components of `z`.
#[inline]
pub(super) fn head<const N: usize, const M: usize>(z: &[f64; M]) -> [f64; N] {
    std::array::from_fn(|i| z[i])
}

/// The first `N` components of `z`, in place.
#[inline]
fn head_ref<const N: usize, const M: usize>(z: &[f64; M]) -> &[f64; N] {
    z[..N]
        .try_into()
        .expect("the clocked state has N + 1 components")
}

/// The first `N` components of `z`, in place and writable.
#[inline]
fn head_mut<const N: usize, const M: usize>(z: &mut [f64; M]) -> &mut [f64; N] {
    (&mut z[..N])
        .try_into()
        .expect("the clocked state has N + 1 components")
}

/// `y` with the clock `c` appended.
#[inline]
fn with_clock<const N: usize, const M: usize>(y: &[f64; N], c: f64) -> [f64; M] {
    std::array::from_fn(|i| if i < N { y[i] } else { c })
}

/// The physical rate `dy/dt` from the rate in `τ`, whose clock component is `s`.
#[inline]
pub(super) fn physical_rate<const N: usize, const M: usize>(dz: &[f64; M]) -> [f64; N] {
    let per_s = 1.0 / dz[N];
    std::array::from_fn(|i| dz[i] * per_s)
}

/// An event of the clocked run (dated in `τ`) as the inner system sees it: at physical time
/// `t`, its state without the clock, its rate in physical time, the inner `guard`.
pub(super) fn physical_hit<G, const N: usize, const M: usize>(
    hit: &EventHit<Const<M>, ClockGuard<G>>,
    guard: G,
    t: f64,
) -> EventHit<Const<N>, G> {
    EventHit {
        guard,
        index: hit.index,
        t,
        // The bracket's width in τ, converted at the clock's rate.
        before: t - (hit.t - hit.before) * hit.dy[N],
        y: head(&hit.y),
        dy: physical_rate(&hit.dy),
        value: hit.value,
        direction: hit.direction,
    }
}

impl<'a, H: TimeScale<N>, const N: usize, const M: usize> Regularised<'a, H, N, M> {
    const CLOCK_IS_LAST: () = assert!(M == N + 1, "the clocked state has one more component");

    /// `inner` in regularised time, starting at physical time `t0` and ending at `t_end`.
    /// `modes` lists every mode the run may enter (their guard lists are built here).
    pub fn new(inner: &'a mut H, modes: &[H::Mode], t0: f64, t_end: f64) -> Self {
        let () = Self::CLOCK_IS_LAST;
        let guards = modes
            .iter()
            .map(|&mode| {
                let mut list: Vec<_> = inner
                    .guards(mode)
                    .iter()
                    .map(|g| GuardSpec {
                        id: ClockGuard::Inner(g.id),
                        direction: g.direction,
                    })
                    .collect();
                list.push(GuardSpec {
                    id: ClockGuard::EndTime,
                    direction: Direction::Up,
                });
                (mode, list)
            })
            .collect();
        Regularised {
            inner,
            t_seg: t0,
            t_end,
            latest: std::cell::Cell::new(t0),
            guards,
        }
    }

    /// The clocked state a run starts from: `y` with the clock at zero.
    pub fn start(y: &[f64; N]) -> [f64; M] {
        with_clock(y, 0.0)
    }

    /// The physical time of the clocked state `z` (in the current segment).
    pub fn time_of(&self, z: &[f64; M]) -> f64 {
        self.t_seg + z[N]
    }

    /// The physical state of the clocked state `z`.
    pub fn state_of(z: &[f64; M]) -> [f64; N] {
        head(z)
    }

    /// The physical time of the latest evaluation of the right-hand side or the guards: a
    /// failure's time in physical terms (the driver dates it in `τ`).
    pub fn latest_time(&self) -> f64 {
        self.latest.get()
    }

    /// A run's outcome in physical terms: where it ended in physical time (the end time
    /// exactly when the clock's guard ended it) and state, and why, the clock's end being
    /// [`StopReason::EndTime`] and the inner system's stops its own.
    pub fn physical_outcome(
        &self,
        out: HybridOutcome<Const<M>, H::Mode, Clocked<H::Stop>>,
    ) -> HybridOutcome<Const<N>, H::Mode, H::Stop> {
        let (t, stop) = match out.stop {
            StopReason::User(Clocked::EndTime) => (self.t_end, StopReason::EndTime),
            StopReason::User(Clocked::Inner(stop)) => {
                (self.time_of(&out.y), StopReason::User(stop))
            }
            StopReason::EndTime => (self.time_of(&out.y), StopReason::EndTime),
            StopReason::Observer => (self.time_of(&out.y), StopReason::Observer),
        };
        HybridOutcome {
            t,
            y: head(&out.y),
            mode: out.mode,
            stop,
            stats: out.stats,
            transitions: out.transitions,
            passes: out.passes,
        }
    }

    /// A run's failure dated in physical time: the driver dates its own failures in `τ`, so
    /// they get the physical time of the latest evaluation ([`Regularised::latest_time`]); an
    /// observer's failure keeps the time the observer gave it (physical, behind
    /// [`crate::PhysicalTime`]).
    pub fn physical_error(&self, error: HybridError<H::Mode>) -> HybridError<H::Mode> {
        let at = self.latest_time();
        match error {
            HybridError::Solve { mode, error } => HybridError::Solve {
                mode,
                error: error.at_time(at),
            },
            mut other => {
                if let HybridError::Transition { t, .. } | HybridError::Chattering { t, .. } =
                    &mut other
                {
                    *t = at;
                }
                other
            }
        }
    }

    /// Tolerances for the clocked state: `tol` for the states (its vector groups kept), and
    /// `clock.0` (relative), `clock.1` (absolute) for the clock.
    pub fn tolerance(&self, tol: &Tolerance<Const<N>>, clock: (f64, f64)) -> Tolerance<Const<M>> {
        let rtol = with_clock(&tol.rtol, clock.0);
        let atol = with_clock(&tol.atol, clock.1);
        let mut out = Tolerance::per_component(rtol, atol);
        for g in tol.groups().iter() {
            out = out
                .with_group(g.range())
                .expect("a group valid for N states is valid for N + 1");
        }
        match tol.limiting() {
            LimitingComponent::Tracked => out.tracking_limiting(),
            LimitingComponent::Untracked => out,
        }
    }

    fn mode_guards(&self, mode: H::Mode) -> &[GuardSpec<ClockGuard<H::Guard>>] {
        self.guards
            .iter()
            .find(|(m, _)| *m == mode)
            .map(|(_, g)| g.as_slice())
            .expect("Regularised::new lists every mode the run enters")
    }
}

impl<H: TimeScale<N>, const N: usize, const M: usize> HybridSystem<Const<M>>
    for Regularised<'_, H, N, M>
{
    type Mode = H::Mode;
    type Guard = ClockGuard<H::Guard>;
    type Stop = Clocked<H::Stop>;
    type Note = H::Note;

    #[inline]
    fn rhs(
        &self,
        mode: H::Mode,
        _tau: f64,
        z: &[f64; M],
        dz: &mut [f64; M],
    ) -> Result<(), EvalError> {
        let y = head_ref(z);
        let t = self.t_seg + z[N];
        self.latest.set(t);
        let s = self.inner.time_scale(mode, y);
        let dy = head_mut(dz);
        self.inner.rhs(mode, t, y, dy)?;
        for v in dy.iter_mut() {
            *v *= s;
        }
        dz[N] = s;
        Ok(())
    }

    fn guards(&self, mode: H::Mode) -> &[GuardSpec<Self::Guard>] {
        self.mode_guards(mode)
    }

    /// The inner guards' inputs, and the clock with its rate (the physical time and `s`).
    fn guard_inputs(&self, mode: H::Mode) -> Option<GuardInputs<Const<M>>> {
        let inner = self.inner.guard_inputs(mode)?;
        let lift = |c: &Components<Const<N>>| {
            let mut list: Vec<usize> = c.indices().to_vec();
            list.push(N);
            list
        };
        Some(GuardInputs::of(&lift(&inner.state), &lift(&inner.rates)))
    }

    fn guard_values(
        &self,
        mode: H::Mode,
        _tau: f64,
        z: &[f64; M],
        dz: &[f64; M],
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        let (last, inner) = values.split_last_mut().expect("the end-time guard is last");
        let t = self.t_seg + z[N];
        self.inner
            .guard_values(mode, t, head_ref(z), &physical_rate(dz), inner)?;
        *last = t - self.t_end;
        Ok(())
    }

    fn on_event(
        &mut self,
        mode: H::Mode,
        hit: &EventHit<Const<M>, Self::Guard>,
    ) -> Result<Transition<Const<M>, H::Mode, Self::Stop, H::Note>, EvalError> {
        let ClockGuard::Inner(guard) = hit.guard else {
            return Ok(Transition::Stop(Clocked::EndTime));
        };
        let t = self.time_of(&hit.y);
        self.latest.set(t);
        let physical = physical_hit(hit, guard, t);
        Ok(match self.inner.on_event(mode, &physical)? {
            Transition::Stop(r) => Transition::Stop(Clocked::Inner(r)),
            // The segment goes on: the clock keeps its origin.
            Transition::Pass { note } => Transition::Pass { note },
            Transition::Switch { to, y, note } => {
                self.t_seg = t;
                Transition::Switch {
                    to,
                    y: with_clock(&y, 0.0),
                    note,
                }
            }
            Transition::Continue { y, note } => {
                self.t_seg = t;
                Transition::Continue {
                    y: with_clock(&y, 0.0),
                    note,
                }
            }
        })
    }

    /// The inner system's first step in physical time, as a step in `τ`.
    fn first_step(&self, mode: H::Mode, _tau: f64, z: &[f64; M]) -> Option<f64> {
        let y = head(z);
        let h = self.inner.first_step(mode, self.t_seg + z[N], &y)?;
        Some(h / self.inner.time_scale(mode, &y))
    }

    fn fires_on_entry(&self) -> bool {
        self.inner.fires_on_entry()
    }

    fn project(&self, mode: H::Mode, _tau: f64, z: &mut [f64; M]) -> bool {
        let mut y = head(z);
        let changed = self.inner.project(mode, self.t_seg + z[N], &mut y);
        z[..N].copy_from_slice(&y);
        changed
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dop853::Dop853;
    use crate::dopri5::Dopri5;
    use crate::hybrid::physical_time::PhysicalTime;
    use crate::hybrid::run::HybridSolver;
    use crate::hybrid::{HybridOptions, StopReason};
    use crate::observer::{Observer, Recorder, Sample};

    /// `y' = -1/(2y)`: `y = sqrt(1 - t)`, whose derivative blows up as `y → 0` (at `t = 1`);
    /// the guard fires at `y = Y_STOP`, i.e. `t = 1 - Y_STOP²`. With `s = y` the clocked field
    /// is `(-1/2, y)`: a straight line in `τ`.
    struct Root;
    const Y_STOP: f64 = 1e-4;
    const LOW: [GuardSpec<&str>; 1] = [GuardSpec {
        id: "low",
        direction: Direction::Down,
    }];

    impl HybridSystem<Const<1>> for Root {
        type Mode = ();
        type Guard = &'static str;
        type Stop = f64;
        type Note = ();
        fn rhs(&self, _: (), _t: f64, y: &[f64; 1], dy: &mut [f64; 1]) -> Result<(), EvalError> {
            dy[0] = -0.5 / y[0];
            Ok(())
        }
        fn guards(&self, _: ()) -> &[GuardSpec<&'static str>] {
            &LOW
        }
        fn guard_values(
            &self,
            _: (),
            _t: f64,
            y: &[f64; 1],
            _dy: &[f64; 1],
            g: &mut [f64],
        ) -> Result<(), EvalError> {
            g[0] = y[0] - Y_STOP;
            Ok(())
        }
        fn on_event(
            &mut self,
            _: (),
            hit: &EventHit<Const<1>, &'static str>,
        ) -> Result<Transition<Const<1>, (), f64>, EvalError> {
            Ok(Transition::Stop(hit.t))
        }
    }

    impl TimeScale<1> for Root {
        fn time_scale(&self, _: (), y: &[f64; 1]) -> f64 {
            y[0]
        }
    }

    fn tol() -> Tolerance<Const<1>> {
        Tolerance::scalar(1e-10, 1e-12)
    }

    /// A regularised run's outcome, its physical stop time and its samples.
    type ClockedRun = (
        crate::hybrid::HybridOutcome<Const<2>, (), Clocked<f64>>,
        f64,
        Recorder<Const<1>, (), &'static str>,
    );

    /// Runs `Root` in regularised time to `t_end`; returns the outcome, the physical stop
    /// time and the samples at `rate`.
    fn clocked_run(t_end: f64, rate: f64) -> ClockedRun {
        let mut sys = Root;
        let mut clocked = Regularised::<_, 1, 2>::new(&mut sys, &[()], 0.0, t_end);
        let tol = clocked.tolerance(&tol(), (1e-10, 1e-12));
        let mut solver = HybridSolver::new(Dop853::new(), tol, HybridOptions::default()).unwrap();
        let mut seen = Recorder::new();
        let mut observer = PhysicalTime::<_, 1, 2>::new(&mut seen, 0.0, Some(rate));
        let z0 = Regularised::<Root, 1, 2>::start(&[1.0]);
        let out = solver
            .run(&mut clocked, (), 0.0, &z0, f64::MAX, &mut observer)
            .unwrap();
        let t = clocked.time_of(&out.y);
        (out, t, seen)
    }

    #[test]
    fn a_singular_approach_takes_few_steps_in_regularised_time() {
        let (out, t, _) = clocked_run(10.0, 10.0);
        let StopReason::User(Clocked::Inner(t_hit)) = out.stop else {
            panic!("{:?}", out.stop)
        };
        let exact = 1.0 - Y_STOP * Y_STOP;
        assert!((t_hit - exact).abs() < 1e-9, "{t_hit} against {exact}");
        assert_eq!(t, t_hit);
        assert!(out.stats.steps < 30, "{} steps", out.stats.steps);
        // The same approach in physical time: the steps shrink with y.
        let mut physical =
            HybridSolver::new(Dop853::new(), tol(), HybridOptions::default()).unwrap();
        let direct = physical
            .run(&mut Root, (), 0.0, &[1.0], 10.0, &mut ())
            .unwrap();
        assert_eq!(direct.stop, StopReason::User(direct.t));
        assert!((direct.t - exact).abs() < 1e-9);
        assert!(
            direct.stats.steps > 3 * out.stats.steps,
            "{} physical steps against {} regularised",
            direct.stats.steps,
            out.stats.steps
        );
    }

    /// Refuses the sample at `at` (in its own time), keeping every other one.
    struct Refuses {
        at: f64,
        seen: Vec<f64>,
    }
    impl Observer<Const<1>, (), &'static str> for Refuses {
        fn on_sample(&mut self, s: &Sample<'_, Const<1>, ()>) -> crate::observer::Observed {
            if s.t == self.at {
                let source = EvalError::non_finite("refuses", "y", s.y[0]);
                return Err(crate::observer::ObserverError { t: s.t, source });
            }
            self.seen.push(s.t);
            Ok(())
        }
    }

    #[test]
    fn an_observer_that_fails_ends_the_run_there_in_either_time() {
        let options = HybridOptions {
            sample_rate: Some(8.0),
            ..HybridOptions::default()
        };
        // Physical time: the driver's own samples.
        let mut refuses = Refuses {
            at: 0.5,
            seen: Vec::new(),
        };
        let mut solver = HybridSolver::new(Dop853::new(), tol(), options).unwrap();
        let error = solver
            .run(&mut Root, (), 0.0, &[1.0], 0.75, &mut refuses)
            .unwrap_err();
        let HybridError::Observer { t, source, .. } = &error else {
            panic!("{error:?}")
        };
        assert_eq!(*t, 0.5);
        assert!(matches!(source, EvalError::NonFinite { .. }), "{source:?}");
        assert_eq!(refuses.seen, [0.0, 0.125, 0.25, 0.375]);
        let physical_steps = solver.stats().steps;
        assert!(physical_steps > 0);
        // Regularised time: the samples come from `PhysicalTime`, and the failure keeps the
        // physical time the observer gave it.
        let mut refuses = Refuses {
            at: 0.5,
            seen: Vec::new(),
        };
        let mut sys = Root;
        let mut clocked = Regularised::<_, 1, 2>::new(&mut sys, &[()], 0.0, 0.75);
        let tol = clocked.tolerance(&tol(), (1e-10, 1e-12));
        let mut solver = HybridSolver::new(Dop853::new(), tol, HybridOptions::default()).unwrap();
        let mut observer = PhysicalTime::<_, 1, 2>::new(&mut refuses, 0.0, Some(8.0));
        let z0 = Regularised::<Root, 1, 2>::start(&[1.0]);
        let error = solver
            .run(&mut clocked, (), 0.0, &z0, f64::MAX, &mut observer)
            .unwrap_err();
        let error = clocked.physical_error(error);
        assert!(
            matches!(error, HybridError::Observer { t, .. } if t == 0.5),
            "{error:?}"
        );
        assert_eq!(refuses.seen, [0.0, 0.125, 0.25, 0.375]);
        assert!(solver.stats().steps > 0);
        // The run ended at the failure, not at its end time: fewer steps than the whole run.
        let (whole, ..) = clocked_run(0.75, 8.0);
        assert!(solver.stats().steps < whole.stats.steps);
    }

    #[test]
    fn a_clocked_outcome_reads_in_physical_terms() {
        let mut sys = Root;
        let mut clocked = Regularised::<_, 1, 2>::new(&mut sys, &[()], 0.0, 0.75);
        let clock_tol = clocked.tolerance(&tol(), (1e-10, 1e-12));
        let mut solver =
            HybridSolver::new(Dop853::new(), clock_tol, HybridOptions::default()).unwrap();
        let z0 = Regularised::<Root, 1, 2>::start(&[1.0]);
        let out = solver
            .run(&mut clocked, (), 0.0, &z0, f64::MAX, &mut ())
            .unwrap();
        let (steps, z) = (out.stats.steps, out.y);
        let physical = clocked.physical_outcome(out);
        // The clock's guard ended it: the end time exactly, as the end time.
        assert_eq!(physical.stop, StopReason::EndTime);
        assert_eq!(physical.t, 0.75);
        assert_eq!(physical.y, [z[0]]);
        assert!((physical.y[0] - 0.5).abs() < 1e-9, "{}", physical.y[0]);
        assert_eq!(physical.stats.steps, steps);
        // The inner system's stop keeps its own reason and time.
        let mut sys = Root;
        let mut clocked = Regularised::<_, 1, 2>::new(&mut sys, &[()], 0.0, 10.0);
        let clock_tol = clocked.tolerance(&tol(), (1e-10, 1e-12));
        let mut solver =
            HybridSolver::new(Dop853::new(), clock_tol, HybridOptions::default()).unwrap();
        let out = solver
            .run(&mut clocked, (), 0.0, &z0, f64::MAX, &mut ())
            .unwrap();
        let physical = clocked.physical_outcome(out);
        let StopReason::User(t_hit) = physical.stop else {
            panic!("{:?}", physical.stop)
        };
        assert_eq!(physical.t, t_hit);
        assert!((physical.y[0] - Y_STOP).abs() < 1e-12, "{}", physical.y[0]);
    }

    #[test]
    fn samples_and_the_end_time_are_in_physical_time() {
        let (out, t, seen) = clocked_run(0.75, 8.0);
        assert!(matches!(out.stop, StopReason::User(Clocked::EndTime)));
        assert!((t - 0.75).abs() < 1e-12, "ended at t = {t}");
        // t = 0, 1/8, ..., 6/8: y = sqrt(1 - t) at each.
        assert_eq!(seen.samples.len(), 7);
        for (k, (ts, _, y)) in seen.samples.iter().enumerate() {
            assert_eq!(*ts, k as f64 / 8.0);
            assert!((y[0] - (1.0 - ts).sqrt()).abs() < 1e-9, "{ts}: {}", y[0]);
        }
    }

    /// Runs `Root` in regularised time to `t = 0.75` (DOP853, rtol 1e-10) with `seen`
    /// observing in physical time, without a sample grid.
    fn observe_clocked(seen: &mut impl Observer<Const<1>, (), &'static str>) {
        let mut sys = Root;
        let mut clocked = Regularised::<_, 1, 2>::new(&mut sys, &[()], 0.0, 0.75);
        let tol = clocked.tolerance(&tol(), (1e-10, 1e-12));
        let mut solver = HybridSolver::new(Dop853::new(), tol, HybridOptions::default()).unwrap();
        let mut observer = PhysicalTime::<_, 1, 2>::new(seen, 0.0, None);
        let z0 = Regularised::<Root, 1, 2>::start(&[1.0]);
        solver
            .run(&mut clocked, (), 0.0, &z0, f64::MAX, &mut observer)
            .unwrap();
    }

    #[test]
    fn steps_carry_their_dense_output_in_physical_time() {
        /// Checks the interpolant of every step against `y = sqrt(1 - t)` in physical time.
        struct Dense(usize, f64);
        impl Observer<Const<1>, (), &'static str> for Dense {
            fn wants_dense(&self) -> bool {
                true
            }
            fn on_step(
                &mut self,
                step: &crate::observer::StepView<'_, Const<1>, ()>,
            ) -> crate::observer::Observed {
                let dense = step.dense.expect("asked for");
                for k in 0..=4 {
                    let t = step.t0 + (step.t1 - step.t0) * k as f64 / 4.0;
                    let err = (dense.component_at(t, 0) - (1.0 - t).sqrt()).abs();
                    self.1 = self.1.max(err);
                }
                self.0 += 1;
                Ok(())
            }
        }
        let mut seen = Dense(0, 0.0);
        observe_clocked(&mut seen);
        assert!(seen.0 > 2, "{} steps", seen.0);
        // The interpolant's error at rtol 1e-10, and the clock's root to a few ulps.
        assert!(seen.1 < 1e-9, "largest error {:e}", seen.1);
    }

    #[test]
    fn a_steps_fractions_are_taken_in_tau() {
        /// Reads every step at fractions of its span: `y = 1 − τ/2` is a straight line in `τ`
        /// (and not in `t`), so the point a fraction `u` through the step in `τ` has `y` a
        /// fraction `u` of the way from `y0` to `y1`; its time is where `y = sqrt(1 − t)`.
        struct Fractions(usize, f64, f64);
        impl Observer<Const<1>, (), &'static str> for Fractions {
            fn wants_dense(&self) -> bool {
                true
            }
            fn on_step(
                &mut self,
                step: &crate::observer::StepView<'_, Const<1>, ()>,
            ) -> crate::observer::Observed {
                let dense = step.dense.expect("asked for");
                let span = (step.t0, step.t1);
                let mut y = [0.0];
                let mut before = f64::NEG_INFINITY;
                for k in 0..=8 {
                    let u = k as f64 / 8.0;
                    let t = dense.at_fraction(span, u, &mut y);
                    assert!(t > before, "time {t} after {before}");
                    before = t;
                    let line = step.y0[0] + u * (step.y1[0] - step.y0[0]);
                    self.1 = self.1.max((y[0] - line).abs());
                    self.2 = self.2.max((y[0] - (1.0 - t).sqrt()).abs());
                }
                assert_eq!(dense.at_fraction(span, 0.0, &mut y), step.t0);
                assert_eq!(dense.at_fraction(span, 1.0, &mut y), step.t1);
                self.0 += 1;
                Ok(())
            }
        }
        let mut seen = Fractions(0, 0.0, 0.0);
        observe_clocked(&mut seen);
        assert!(seen.0 > 2, "{} steps", seen.0);
        // On the line in τ to round-off; in t, sqrt(1 − t) to the interpolant's error.
        assert!(seen.1 < 1e-14, "off the line in τ by {:e}", seen.1);
        assert!(seen.2 < 1e-9, "off sqrt(1 − t) by {:e}", seen.2);
    }

    #[test]
    fn declined_samples_cost_nothing_and_are_not_delivered() {
        struct Even(Vec<f64>);
        impl Observer<Const<1>, (), &'static str> for Even {
            fn wants_sample(&self, t: f64) -> bool {
                (t * 4.0).round() as i64 % 2 == 0
            }
            fn on_sample(&mut self, s: &Sample<'_, Const<1>, ()>) -> crate::observer::Observed {
                self.0.push(s.t);
                Ok(())
            }
        }
        let mut even = Even(Vec::new());
        let options = HybridOptions {
            sample_rate: Some(4.0),
            ..HybridOptions::default()
        };
        let mut solver = HybridSolver::new(Dopri5::new(), tol(), options).unwrap();
        solver
            .run(&mut Root, (), 0.0, &[1.0], 0.9, &mut even)
            .unwrap();
        assert_eq!(even.0, vec![0.0, 0.5]);
    }

    #[test]
    fn an_observer_can_stop_the_run() {
        struct Budget(u32);
        impl Observer<Const<1>, (), &'static str> for Budget {
            fn proceed(&mut self) -> std::ops::ControlFlow<()> {
                self.0 -= 1;
                if self.0 == 0 {
                    std::ops::ControlFlow::Break(())
                } else {
                    std::ops::ControlFlow::Continue(())
                }
            }
        }
        let mut solver = HybridSolver::new(Dopri5::new(), tol(), HybridOptions::default()).unwrap();
        let out = solver
            .run(&mut Root, (), 0.0, &[1.0], 0.9, &mut Budget(3))
            .unwrap();
        assert_eq!(out.stop, StopReason::Observer);
        assert_eq!(out.stats.steps, 3);
        assert!(out.t > 0.0 && out.t < 0.9);
    }
}
