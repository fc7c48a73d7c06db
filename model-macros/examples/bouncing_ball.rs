//! A ball dropped on a hard floor, written with modes and events, solved and checked against
//! the closed form.
//!
//! In flight the ball falls freely; at the floor its velocity reverses, scaled by the
//! coefficient of restitution `e`. The flights shrink geometrically, so infinitely many
//! impacts happen before a finite time (a Zeno point): from there the model says the ball
//! lies on the floor. With `v1 = sqrt(2 g h0)` the impacts are at `t1 = sqrt(2 h0 / g)` and
//! `t_{k+1} = t_k + 2 e^k v1 / g`, and they accumulate at `t1 + 2 e v1 / (g (1 - e))`.
//!
//! The same model, as text, is `bouncing_ball.dsl` beside this file:
//! `eulerdisk model solve model-macros/examples/bouncing_ball.dsl --t-end 10` runs it without
//! compiling Rust, and a test here holds the two to the same tokens.
//!
//! ```text
//! cargo run -p model-macros --example bouncing_ball
//! ```

use model_runtime::Const;
use model_runtime::{run_switched, Dop853, Fired, HybridOptions, SwitchedRun, Tolerance};

model_macros::model! {
    /// A ball dropped on a hard floor: free flight, an impact that reverses and scales its
    /// velocity, and rest once the bounces accumulate.
    mod bouncing_ball {
        params {
            /// Gravity (m/s^2).
            g = 9.81,
            /// Coefficient of restitution.
            e = 0.8,
        }
        states {
            /// Height above the floor (m).
            h = 1.0,
            /// Upward velocity (m/s).
            v = 0.0,
        }

        mode flying {
            equations { der(h) = v; der(v) = -g; }
            /// The ball reaches the floor: its velocity reverses, scaled by the restitution.
            when impact: h < 0 { v = -e * v; }
            /// Ever shorter bounces end at a finite time: from there the ball lies on the floor.
            when impact accumulates -> resting { h = 0; v = 0; }
        }

        /// On the floor: nothing moves.
        mode resting {
            equations { der(h) = 0; der(v) = 0; }
        }

        outputs {
            energy = g * h + v^2 / 2;
        }
    }
}

/// The ball from its initial state, sampled every millisecond.
fn run(t_end: f64) -> SwitchedRun<Const<2>> {
    let options = HybridOptions {
        sample_rate: Some(1000.0),
        ..HybridOptions::default()
    };
    let tolerance = Tolerance::scalar(1e-10, 1e-12);
    let start = (0.0, bouncing_ball::INITIAL);
    let model = bouncing_ball::Model::default();
    run_switched(model, Dop853::new(), tolerance, options, start, t_end).expect("the ball runs")
}

fn main() {
    let run = run(10.0);
    println!("event,t_s,h,v");
    for event in &run.events {
        let [h, v] = event.y_after;
        println!("{},{:.12},{h},{v}", event.event, event.t);
    }
    eprintln!(
        "{} impacts, at rest from t = {:?} s, run ended at t = {} s in mode {}",
        run.times("impact", Fired::Reset).len(),
        run.times("impact", Fired::Accumulated),
        run.t,
        run.mode
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = 9.81;
    const E: f64 = 0.8;
    const H0: f64 = 1.0;

    #[test]
    fn impacts_at_their_closed_form_times_then_rest_at_the_accumulation_point() {
        let run = run(10.0);
        let v1 = (2.0 * G * H0).sqrt();
        let mut expected = (2.0 * H0 / G).sqrt();
        let impacts = run.times("impact", Fired::Reset);
        assert!(impacts.len() > 50, "{} impacts", impacts.len());
        for (k, &t) in impacts.iter().enumerate() {
            assert!(
                (t - expected).abs() < 1e-9,
                "impact {}: {t} vs {expected}",
                k + 1
            );
            expected += 2.0 * E.powi(k as i32 + 1) * v1 / G;
        }
        let t_inf = (2.0 * H0 / G).sqrt() + 2.0 * E * v1 / (G * (1.0 - E));
        let rest = run.times("impact", Fired::Accumulated);
        assert_eq!(rest.len(), 1, "{rest:?}");
        assert!(
            (rest[0] - t_inf).abs() < 1e-9,
            "rest at {rest:?}, closed form {t_inf}"
        );
        assert_eq!((run.t, run.mode.as_str()), (10.0, "resting"));
        // Never through the floor; and at rest, exactly on it.
        for (t, _, y) in &run.samples {
            assert!(y[0] >= -1e-12, "h = {} at t = {t}", y[0]);
            if *t > t_inf + 1e-6 {
                assert_eq!(*y, [0.0, 0.0], "at t = {t}");
            }
        }
    }

    #[test]
    fn the_dsl_file_holds_the_same_model() {
        let source = model_dsl::Source::new("bouncing_ball.dsl", include_str!("bouncing_ball.dsl"));
        let this = model_dsl::Source::rust("bouncing_ball.rs", include_str!("bouncing_ball.rs"));
        assert_eq!(
            this.tokens().unwrap().to_string(),
            source.tokens().unwrap().to_string()
        );
    }
}
