//! `time_scale = EXPR;`: a switched model's clock in regularised time, declared in the model.
//! The ball slowed near the floor keeps its closed-form impacts when `Regularised` integrates
//! it with the declared clock; a mode's own clock overrides the model's.

use model_runtime::Const;
use model_runtime::{
    AccumulationRule, Clocked, Dop853, HybridOptions, HybridSolver, Observer, PhysicalTime,
    Regularised, StopReason, Switched, SwitchedModel, SwitchedNote, Tolerance, TransitionRecord,
};
use model_runtime::{EventId, ModeId};

model_macros::model! {
    /// A ball whose clock slows near the floor; resting, it keeps its own (unit) clock.
    mod slow_ball {
        params { g = 9.81, e = 0.8 }
        states { h = 1.0, v = 0.0 }
        time_scale = 0.2 + abs(h);
        mode flying {
            equations { der(h) = v; der(v) = -g; }
            when impact: h < 0 { v = -e * v; }
        }
        mode resting {
            equations { der(h) = 0; der(v) = 0; }
            time_scale = 1;
        }
    }
}

/// The times of the transitions a run reports, in physical time.
#[derive(Default)]
struct Impacts(Vec<f64>);

impl Observer<Const<2>, ModeId, EventId, SwitchedNote> for Impacts {
    fn on_transition(
        &mut self,
        record: TransitionRecord<Const<2>, ModeId, EventId, SwitchedNote>,
    ) -> model_runtime::Observed {
        self.0.push(record.hit.t);
        Ok(())
    }
}

#[test]
fn the_declared_clock_is_the_model_s_time_scale_and_a_mode_may_override_it() {
    let ball = slow_ball::Model::default();
    assert_eq!(ball.time_scale(slow_ball::mode::flying, &[0.5, -3.0]), 0.7);
    assert_eq!(
        ball.time_scale(slow_ball::mode::flying, &[-0.25, 1.0]),
        0.45
    );
    assert_eq!(ball.time_scale(slow_ball::mode::resting, &[0.5, 0.0]), 1.0);
    assert!(
        slow_ball::SWITCHING_MARKDOWN.contains("`s = 0.2 + abs(h)`"),
        "{}",
        slow_ball::SWITCHING_MARKDOWN
    );
}

#[test]
fn in_regularised_time_the_impacts_keep_their_closed_form() {
    let (g, e, h0) = (9.81f64, 0.8f64, 1.0f64);
    let mut system = Switched::new(slow_ball::Model::default(), AccumulationRule::default())
        .expect("the default rule is valid");
    let modes: Vec<ModeId> = system.model().graph().ids().collect();
    let flying = modes[slow_ball::mode::flying];
    let t_end = 3.0;
    let mut clocked = Regularised::<_, 2, 3>::new(&mut system, &modes, 0.0, t_end);
    let tol = clocked.tolerance(&Tolerance::scalar(1e-11, 1e-13), (1e-11, 1e-13));
    let mut solver = HybridSolver::new(Dop853::new(), tol, HybridOptions::default()).unwrap();
    let mut impacts = Impacts::default();
    let mut physical = PhysicalTime::<_, 2, 3>::new(&mut impacts, 0.0, None);
    let z0 = Regularised::<Switched<slow_ball::Model>, 2, 3>::start(&[h0, 0.0]);
    let out = solver
        .run(&mut clocked, flying, 0.0, &z0, f64::MAX, &mut physical)
        .unwrap();
    assert_eq!(out.stop, StopReason::User(Clocked::EndTime));
    // t1 = sqrt(2 h0 / g), then t_{k+1} = t_k + 2 e^k v1 / g.
    let v1 = (2.0 * g * h0).sqrt();
    let mut want = (2.0 * h0 / g).sqrt();
    assert_eq!(impacts.0.len(), 6, "{:?}", impacts.0);
    for (k, t) in impacts.0.iter().enumerate() {
        assert!((t - want).abs() < 1e-9, "impact {k}: {t} vs {want}");
        want += 2.0 * e.powi(k as i32 + 1) * v1 / g;
    }
}
