//! A switched model in regularised time: the ball of `switched.rs` with a time scale that
//! slows the clock near the floor keeps its closed-form impacts, through `Regularised`.

use crate::common::ball::{Ball, Flights, G};
use crate::common::log::RunLog;
use model_runtime::Const;
use model_runtime::{
    AccumulationRule, Clocked, Direction, Dop853, EvalError, EventAction, EventDecl, EventId,
    HybridOptions, HybridSolver, ModeDecl, ModeGraph, ModeId, PhysicalTime, Regularised,
    StopReason, Switched, SwitchedModel, SwitchedNote, Tolerance,
};

const E: f64 = 0.8;
const H0: f64 = 1.0;

/// y = (h, v), one mode with the impact `h` crossing down, reset `v = -e v`; the clock runs at
/// `s = 0.2 + h` (slow near the floor).
struct SlowNearTheFloor {
    graph: ModeGraph,
}

impl SwitchedModel<Const<2>> for SlowNearTheFloor {
    fn graph(&self) -> &ModeGraph {
        &self.graph
    }
    fn rhs(&self, _: usize, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
        *dy = [y[1], -G];
        Ok(())
    }
    fn event_values(
        &self,
        _: usize,
        _t: f64,
        y: &[f64; 2],
        _dy: &[f64; 2],
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        values[0] = y[0];
        Ok(())
    }
    fn reset(
        &mut self,
        _: usize,
        _: usize,
        _: bool,
        _t: f64,
        y: &[f64; 2],
        _dy: &[f64; 2],
        out: &mut [f64; 2],
    ) -> Result<(), EvalError> {
        out[1] = -E * y[1];
        Ok(())
    }
    fn time_scale(&self, _: usize, y: &[f64; 2]) -> f64 {
        0.2 + y[0].abs()
    }
}

#[test]
fn a_switched_model_runs_in_regularised_time_with_its_time_scale() {
    let impact = EventDecl {
        name: "impact".into(),
        direction: Direction::Down,
        action: EventAction::Reset {
            to: None,
            reset: true,
        },
        on_accumulation: None,
    };
    let graph = ModeGraph::new(vec![ModeDecl {
        name: "flying".into(),
        events: vec![impact],
    }])
    .unwrap();
    let mut system =
        Switched::new(SlowNearTheFloor { graph }, AccumulationRule::default()).unwrap();
    let flying: ModeId = system.model().graph().first();
    let t_end = 3.0;
    let mut clocked = Regularised::<_, 2, 3>::new(&mut system, &[flying], 0.0, t_end);
    let tol = clocked.tolerance(&Tolerance::scalar(1e-11, 1e-13), (1e-11, 1e-13));
    let mut solver = HybridSolver::new(Dop853::new(), tol, HybridOptions::default()).unwrap();
    let mut log: RunLog<2, ModeId, EventId, SwitchedNote> = RunLog::new();
    let mut physical = PhysicalTime::<_, 2, 3>::new(&mut log, 0.0, None);
    let z0 = Regularised::<Switched<SlowNearTheFloor>, 2, 3>::start(&[H0, 0.0]);
    let out = (solver.run(&mut clocked, flying, 0.0, &z0, f64::MAX, &mut physical)).unwrap();
    assert_eq!(out.stop, StopReason::User(Clocked::EndTime));
    let expected = Flights::of(&Ball::new(G, E), H0, 0.0).impact_times(6);
    let impacts: Vec<f64> = log.records.iter().map(|r| r.hit.t).collect();
    assert_eq!(impacts.len(), 6, "{impacts:?}");
    for (t, want) in impacts.iter().zip(&expected) {
        assert!((t - want).abs() < 1e-9, "{t} vs {want}");
    }
}
