//! A switched model given by tables ([`SwitchedModel`], run as [`Switched`]): a bouncing ball
//! whose impacts, apexes and accumulation point have closed forms.

use crate::common::ball::{Ball, Flights, G};
use crate::common::log::RunLog;
use model_runtime::Const;
use model_runtime::{
    AccumulationAction, AccumulationRule, Direction, Dop853, EvalError, EventAction, EventDecl,
    EventId, GraphError, HybridError, HybridOptions, HybridOutcome, HybridSolver, ModeDecl,
    ModeGraph, ModeId, StopReason, Switched, SwitchedModel, SwitchedNote, SwitchedStop, Tolerance,
    TransitionKind,
};

/// The ball's restitution here.
const E: f64 = 0.8;
/// It is dropped from this height, at rest.
const H0: f64 = 1.0;

/// What the tests vary in the ball's tables.
#[derive(Clone, Copy)]
struct Tables {
    /// The impact's action.
    impact: EventAction,
    /// What an accumulation of impacts does.
    on_accumulation: Option<AccumulationAction>,
    /// Whether the apex (`v` crossing down) is recorded.
    apex: bool,
}

/// The tables of a ball that comes to rest: impacts reset `v = -e v`, their accumulation
/// switches to `resting` with `h = v = 0`.
const RESTS: Tables = Tables {
    impact: EventAction::Reset {
        to: None,
        reset: true,
    },
    on_accumulation: Some(AccumulationAction {
        to: Some(1),
        reset: true,
    }),
    apex: false,
};

/// y = (h, v): mode `flying` (0), `h' = v, v' = -g`, with the event `impact` (h crossing down)
/// and perhaps `apex`; mode `resting` (1), everything still.
struct SwitchedBall {
    graph: ModeGraph,
    /// A reset that assigns NaN, to test the error.
    broken: bool,
    /// The mode a decided impact names (with the reset `v = -e v`); `None`: none.
    decides: Option<usize>,
}

impl SwitchedBall {
    fn new(tables: Tables) -> SwitchedBall {
        let event = |name: &str, direction, action, on_accumulation| EventDecl {
            name: name.to_owned(),
            direction,
            action,
            on_accumulation,
        };
        let mut flying = vec![event(
            "impact",
            Direction::Down,
            tables.impact,
            tables.on_accumulation,
        )];
        if tables.apex {
            flying.push(event("apex", Direction::Down, EventAction::Record, None));
        }
        let mode = |name: &str, events| ModeDecl {
            name: name.to_owned(),
            events,
        };
        let graph = ModeGraph::new(vec![mode("flying", flying), mode("resting", Vec::new())]);
        SwitchedBall {
            graph: graph.unwrap(),
            broken: false,
            decides: None,
        }
    }
}

impl SwitchedModel<Const<2>> for SwitchedBall {
    fn graph(&self) -> &ModeGraph {
        &self.graph
    }
    fn rhs(&self, mode: usize, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
        *dy = if mode == 0 { [y[1], -G] } else { [0.0, 0.0] };
        Ok(())
    }
    fn event_values(
        &self,
        _mode: usize,
        _t: f64,
        y: &[f64; 2],
        _dy: &[f64; 2],
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        // `flying` has the impact (h) and perhaps the apex (v); `resting` has no event.
        for (value, y) in values.iter_mut().zip(y) {
            *value = *y;
        }
        Ok(())
    }
    fn reset(
        &mut self,
        _mode: usize,
        _event: usize,
        accumulation: bool,
        _t: f64,
        y: &[f64; 2],
        _dy: &[f64; 2],
        out: &mut [f64; 2],
    ) -> Result<(), EvalError> {
        if accumulation {
            *out = [0.0, 0.0];
        } else {
            out[1] = if self.broken { f64::NAN } else { -E * y[1] };
        }
        Ok(())
    }
    fn decide(
        &mut self,
        mode: usize,
        event: usize,
        t: f64,
        y: &[f64; 2],
        dy: &[f64; 2],
        out: &mut [f64; 2],
    ) -> Result<Option<usize>, EvalError> {
        self.reset(mode, event, false, t, y, dy, out)?;
        Ok(self.decides)
    }
}

type Log = RunLog<2, ModeId, EventId, SwitchedNote>;
type Outcome = HybridOutcome<Const<2>, ModeId, SwitchedStop>;

/// DOP853 at rtol 1e-10, atol 1e-12, 100 samples per second, from `(H0, 0)` in `flying` to 10;
/// `ball` is a [`SwitchedBall`], owned or borrowed.
fn drop(ball: impl SwitchedModel<Const<2>>) -> (Result<Outcome, HybridError<ModeId>>, Log) {
    let options = HybridOptions {
        sample_rate: Some(100.0),
        ..HybridOptions::default()
    };
    let mut solver =
        HybridSolver::new(Dop853::new(), Tolerance::scalar(1e-10, 1e-12), options).unwrap();
    let flying = ball.graph().mode_id("flying").unwrap();
    let mut system = Switched::new(ball, AccumulationRule::default()).unwrap();
    let mut log = RunLog::new();
    let out = solver.run(&mut system, flying, 0.0, &[H0, 0.0], 10.0, &mut log);
    (out, log)
}

/// The closed form: impact times `t1 = sqrt(2 h0 / g)`, `t_{k+1} = t_k + 2 e^k v1 / g`.
fn flights() -> Flights {
    Flights::of(&Ball::new(G, E), H0, 0.0)
}

/// The accumulation point `t1 + 2 e v1 / (g (1 - e))`.
fn accumulation_point() -> f64 {
    let f = flights();
    f.t1 + 2.0 * E * f.v1 / (G * (1.0 - E))
}

/// Every impact in `log` is a restart by `impact` at its closed-form time; returns them.
fn check_impacts(log: &Log) -> Vec<f64> {
    let impacts: Vec<_> = log.records.iter().filter(|r| r.hit.index == 0).collect();
    let expected = flights().impact_times(impacts.len());
    for (k, (r, t)) in impacts.iter().zip(&expected).enumerate() {
        assert!(
            (r.hit.t - t).abs() < 1e-9,
            "impact {k}: {} against {t}",
            r.hit.t
        );
    }
    impacts.iter().map(|r| r.hit.t).collect()
}

#[test]
fn a_bouncing_ball_comes_to_rest_at_its_accumulation_point() {
    let (out, log) = drop(SwitchedBall::new(RESTS));
    let out = out.unwrap();
    let (flying, resting) = (log.records[0].from, out.mode);
    assert_eq!(out.stop, StopReason::EndTime);
    assert_eq!((out.t, out.y), (10.0, [0.0, 0.0]));
    let impacts = check_impacts(&log);
    // Dozens of bounces before the tail is below the rule's 1e-9 s.
    assert!(impacts.len() > 50, "{}", impacts.len());
    let (last, restarts) = log.records.split_last().unwrap();
    let impact = EventId {
        mode: flying,
        event: 0,
    };
    for r in restarts {
        assert_eq!(
            (r.kind, r.note),
            (TransitionKind::Continue, SwitchedNote::Reset(impact))
        );
        assert_eq!(r.y_after, [r.hit.y[0], -E * r.hit.y[1]]);
    }
    assert_eq!(last.kind, TransitionKind::Switch { to: resting });
    assert_eq!(last.y_after, [0.0, 0.0]);
    let SwitchedNote::Accumulated {
        event,
        accumulation,
    } = last.note
    else {
        panic!("{:?}", last.note);
    };
    assert_eq!(event, impact);
    assert!(
        (accumulation.t_inf - accumulation_point()).abs() < 1e-9,
        "{accumulation:?}"
    );
    assert!((accumulation.ratio - E).abs() < 1e-3, "{accumulation:?}");
    assert!(accumulation.t_inf - last.hit.t <= AccumulationRule::default().tail);
    // The samples: never below the ground, at rest after the accumulation, all the way.
    assert_eq!(log.samples.len(), 1001);
    assert!(log.samples.iter().all(|(_, y)| y[0] >= -1e-12));
    let after = log
        .samples
        .iter()
        .filter(|(t, _)| *t > accumulation_point());
    assert!(after.clone().count() > 500 && after.clone().all(|(_, y)| *y == [0.0, 0.0]));
    assert_eq!(out.transitions, log.records.len() as u64);
}

#[test]
fn without_an_accumulation_action_the_run_stops_at_the_accumulation() {
    let (out, log) = drop(SwitchedBall::new(Tables {
        on_accumulation: None,
        ..RESTS
    }));
    let out = out.unwrap();
    let StopReason::User(SwitchedStop::Accumulation { mode, event, t_inf }) = out.stop else {
        panic!("{:?}", out.stop);
    };
    assert_eq!((mode, event), (out.mode, 0));
    assert!((t_inf - accumulation_point()).abs() < 1e-9, "{t_inf}");
    // It ends at the firing that showed the accumulation, just before the point.
    assert!(out.t < t_inf && t_inf - out.t <= AccumulationRule::default().tail);
    let impacts = check_impacts(&log);
    assert_eq!(out.transitions, impacts.len() as u64);
    assert!(out.t > *impacts.last().unwrap());
}

#[test]
fn a_recorded_apex_passes_at_its_closed_form_times_and_changes_no_step() {
    let (plain, plain_log) = drop(SwitchedBall::new(RESTS));
    let (out, log) = drop(SwitchedBall::new(Tables {
        apex: true,
        ..RESTS
    }));
    let (plain, out) = (plain.unwrap(), out.unwrap());
    assert_eq!(log.steps, plain_log.steps);
    assert_eq!(log.samples, plain_log.samples);
    assert_eq!(
        (out.t, out.y, out.transitions),
        (plain.t, plain.y, plain.transitions)
    );
    let apexes: Vec<_> = log.records.iter().filter(|r| r.hit.index == 1).collect();
    assert_eq!(out.passes, apexes.len() as u64);
    // One apex per flight after the first (the drop starts at its apex: a quiet start).
    assert_eq!(apexes.len() + 1, check_impacts(&log).len());
    let f = flights();
    let impacts = f.impact_times(apexes.len());
    for (k, r) in apexes.iter().enumerate() {
        let t = impacts[k] + E.powi(k as i32 + 1) * f.v1 / G;
        assert!(
            (r.hit.t - t).abs() < 1e-9,
            "apex {k}: {} against {t}",
            r.hit.t
        );
        assert_eq!(r.kind, TransitionKind::Pass);
        assert!(matches!(r.note, SwitchedNote::Recorded(e) if e.event == 1));
    }
}

#[test]
fn a_terminal_event_ends_the_run_with_its_name() {
    let mut ball = SwitchedBall::new(Tables {
        impact: EventAction::Stop,
        on_accumulation: None,
        ..RESTS
    });
    let (out, log) = drop(&mut ball);
    let out = out.unwrap();
    let StopReason::User(stop) = out.stop else {
        panic!("{:?}", out.stop);
    };
    assert!(matches!(stop, SwitchedStop::Event { event: 0, t, .. } if t == out.t));
    assert_eq!(ball.graph.event_name(stop.event()), "flying.impact");
    assert!((out.t - flights().t1).abs() < 1e-9 && log.records.is_empty());
}

#[test]
fn a_reset_that_is_not_finite_is_an_error_naming_the_event() {
    let mut ball = SwitchedBall::new(RESTS);
    ball.broken = true;
    let (out, _) = drop(ball);
    let Err(HybridError::Transition { t, source, .. }) = out else {
        panic!("{out:?}");
    };
    assert!((t - flights().t1).abs() < 1e-9);
    let EvalError::ResetNotFinite {
        ref event,
        component,
        ..
    } = source
    else {
        panic!("{source:?}");
    };
    assert_eq!((event.as_str(), component), ("flying.impact", 1));
    assert!(source.to_string().contains("flying.impact"), "{source}");
}

#[test]
fn a_mode_graph_names_what_is_wrong_with_it() {
    let event = |name: &str, action, to: Option<usize>| EventDecl {
        name: name.to_owned(),
        direction: Direction::Down,
        action,
        on_accumulation: to.map(|to| AccumulationAction {
            to: Some(to),
            reset: true,
        }),
    };
    let reset = |to| EventAction::Reset { to, reset: true };
    let mode = |name: &str, events| ModeDecl {
        name: name.to_owned(),
        events,
    };
    let problem = |modes| ModeGraph::new(modes).unwrap_err();
    assert_eq!(problem(Vec::new()), GraphError::NoModes);
    let e = problem(vec![mode("a", Vec::new()), mode("a", Vec::new())]);
    assert!(
        matches!(
            e,
            GraphError::DuplicateMode {
                first: 0,
                second: 1,
                ..
            }
        ),
        "{e}"
    );
    let twice = vec![event("x", EventAction::Stop, None); 2];
    let e = problem(vec![mode("a", twice)]);
    assert!(
        matches!(
            e,
            GraphError::DuplicateEvent {
                first: 0,
                second: 1,
                ..
            }
        ),
        "{e}"
    );
    let e = problem(vec![mode("a", vec![event("x", reset(Some(2)), None)])]);
    assert!(matches!(
        e,
        GraphError::TargetOutOfRange {
            what: "reset",
            to: 2,
            modes: 1,
            ..
        }
    ));
    assert!(e.to_string().contains("`a.x`"), "{e}");
    let e = problem(vec![mode("a", vec![event("x", reset(None), Some(1))])]);
    assert!(
        matches!(
            e,
            GraphError::TargetOutOfRange {
                what: "accumulation",
                ..
            }
        ),
        "{e}"
    );
    let e = problem(vec![mode(
        "a",
        vec![event("x", EventAction::Record, Some(0))],
    )]);
    assert!(
        matches!(e, GraphError::AccumulationWithoutReset { .. }),
        "{e}"
    );
    let graph = ModeGraph::new(vec![mode("a", vec![event("x", reset(None), Some(0))])]).unwrap();
    let a = graph.mode_id("a").unwrap();
    assert_eq!(
        (graph.id(0), graph.id(1), graph.mode_name(a)),
        (Some(a), None, "a")
    );
}

/// The ball whose impact is decided by the model, naming `decides`.
fn decided(decides: Option<usize>) -> SwitchedBall {
    let mut ball = SwitchedBall::new(Tables {
        impact: EventAction::Decide,
        on_accumulation: None,
        ..RESTS
    });
    ball.decides = decides;
    ball
}

#[test]
fn a_decided_restart_is_a_reset_and_its_accumulation_stops_the_run() {
    let (reset, reset_log) = drop(SwitchedBall::new(Tables {
        on_accumulation: None,
        ..RESTS
    }));
    let (decided, decided_log) = drop(decided(Some(0)));
    let (reset, decided) = (reset.unwrap(), decided.unwrap());
    // The same run: the decision restarts `flying` with the reset's state, bit for bit.
    assert_eq!(decided.stop, reset.stop);
    assert_eq!((decided.t, decided.y), (reset.t, reset.y));
    assert_eq!(check_impacts(&decided_log), check_impacts(&reset_log));
    assert!(matches!(
        decided.stop,
        StopReason::User(SwitchedStop::Accumulation { .. })
    ));
}

#[test]
fn a_decision_may_switch_stop_or_fail_naming_the_event() {
    // To `resting`: still from the first impact on (the decided state is the reset's).
    let (out, log) = drop(decided(Some(1)));
    let out = out.unwrap();
    assert_eq!(log.records.len(), 1);
    assert_eq!(log.records[0].kind, TransitionKind::Switch { to: out.mode });
    assert!((log.records[0].hit.t - flights().t1).abs() < 1e-9);
    // `None`: the run stops there, with the event as its reason.
    let (out, _) = drop(decided(None));
    let StopReason::User(SwitchedStop::Event { event, t, .. }) = out.unwrap().stop else {
        panic!("not stopped by the event");
    };
    assert_eq!(event, 0);
    assert!((t - flights().t1).abs() < 1e-9);
    // A mode the graph does not have.
    let (out, _) = drop(decided(Some(7)));
    let Err(HybridError::Transition { source, .. }) = out else {
        panic!("{out:?}");
    };
    assert_eq!(
        source,
        EvalError::Undecided {
            event: "flying.impact".to_string(),
            mode: Some(7)
        }
    );
    assert!(source.to_string().contains("mode 7"), "{source}");
}
