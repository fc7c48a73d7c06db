//! A rocking block: a reset at every impact, a mode change when the impacts accumulate,
//! checked against the closed form of the linearised (Housner) equations.
//!
//! Rocking about a corner, `theta'' = p^2 (theta - alpha sign(theta))`. Released from rest at
//! `theta0`, the block lands after `t1 = acosh(alpha / (alpha - theta0)) / p` with angular
//! speed `w1 = p sqrt(alpha^2 - (alpha - theta0)^2)`; each impact multiplies the speed by `r`,
//! and a rock that leaves the floor with speed `w` lands again after
//! `(2 / p) atanh(w / (p alpha))`, with the same speed. The rocks accumulate at
//! `t1 + sum_k (2 / p) atanh(r^k w1 / (p alpha))`, after which the block stands.
//!
//! The same model, as text, is `rocking_block.dsl` beside this file (`eulerdisk model solve
//! model-macros/examples/rocking_block.dsl --t-end 10`); a test holds the two to the same
//! tokens.
//!
//! ```text
//! cargo run -p model-macros --example rocking_block
//! ```

use model_runtime::Const;
use model_runtime::{run_switched, Dop853, HybridOptions, SwitchedRun, Tolerance};

model_macros::model! {
    /// A slender rigid block rocking on a hard floor (Housner's model, for small angles): it tips
    /// about one bottom corner, hits the floor with the other, loses angular velocity at each
    /// impact, and comes to stand once its ever shorter rocks accumulate.
    mod rocking_block {
        params {
            /// Frequency parameter sqrt(3 g / (4 R)) (1/s), R the half-diagonal.
            p = 2.0,
            /// Slenderness: the angle between the diagonal and the vertical (rad).
            alpha = 0.2,
            /// Ratio of the angular velocities after and before an impact.
            r = 0.7,
        }
        states {
            /// Tilt (rad), positive when the block rocks on its right corner.
            theta = 0.1,
            /// Angular velocity (rad/s).
            omega = 0.0,
        }

        mode rocking {
            equations {
                der(theta) = omega;
                // Gravity's torque about the corner in contact, linearised: it pulls the block back
                // upright as long as |theta| < alpha.
                der(omega) = p^2 * (theta - alpha * sign(theta));
            }
            /// The block lands flat and tips over onto its other corner, losing angular velocity.
            when impact: theta == 0 { omega = r * omega; }
            /// The rocks accumulate: the block stands.
            when impact accumulates -> standing { theta = 0; omega = 0; }
            /// Past its corner the block falls over.
            when overturns: abs(theta) > alpha -> stop;
        }

        /// Standing upright on the floor.
        mode standing {
            equations { der(theta) = 0; der(omega) = 0; }
        }
    }
}

/// The block from its initial state, sampled every millisecond.
fn run(params: rocking_block::Params, t_end: f64) -> SwitchedRun<Const<2>> {
    let options = HybridOptions {
        sample_rate: Some(1000.0),
        ..HybridOptions::default()
    };
    let tolerance = Tolerance::scalar(1e-12, 1e-15);
    let start = (0.0, rocking_block::INITIAL);
    let model = rocking_block::Model::from_params(params);
    run_switched(model, Dop853::new(), tolerance, options, start, t_end).expect("the block runs")
}

fn main() {
    let run = run(rocking_block::Params::default(), 10.0);
    println!("event,t_s,theta,omega");
    for event in &run.events {
        let [theta, omega] = event.y;
        println!("{},{:.12},{theta},{omega}", event.event, event.t);
    }
    eprintln!("run ended at t = {} s in mode {}", run.t, run.mode);
}

#[cfg(test)]
mod tests {
    use super::*;
    use model_runtime::Fired;

    #[test]
    fn impacts_at_their_closed_form_times_then_the_block_stands() {
        let params = rocking_block::Params::default();
        let (p, alpha, r) = (params.p, params.alpha, params.r);
        let theta0 = rocking_block::INITIAL[rocking_block::state::theta];
        let t1 = (alpha / (alpha - theta0)).acosh() / p;
        let w1 = p * (alpha * alpha - (alpha - theta0).powi(2)).sqrt();
        let rock = |k: i32| 2.0 / p * (r.powi(k) * w1 / (p * alpha)).atanh();
        let run = run(params, 10.0);
        let impacts = run.times("impact", Fired::Reset);
        assert!(impacts.len() > 30, "{} impacts", impacts.len());
        let mut expected = t1;
        for (k, &t) in impacts.iter().enumerate() {
            assert!(
                (t - expected).abs() < 1e-9,
                "impact {}: {t} vs {expected}",
                k + 1
            );
            expected += rock(k as i32 + 1);
        }
        let t_inf = t1 + (1..400).map(rock).sum::<f64>();
        let stands = run.times("impact", Fired::Accumulated);
        assert_eq!(stands.len(), 1, "{stands:?}");
        assert!((stands[0] - t_inf).abs() < 1e-9, "{} vs {t_inf}", stands[0]);
        assert_eq!(
            (run.t, run.mode.as_str(), run.y),
            (10.0, "standing", [0.0, 0.0])
        );
        // Between impacts the tilt keeps its sign: the sign of omega flips at no other time.
        for (t, _, y) in &run.samples {
            assert!(y[0].abs() < alpha, "tilt {} at t = {t}", y[0]);
        }
    }

    #[test]
    fn pushed_hard_enough_the_block_falls_over_at_its_closed_form_time() {
        let params = rocking_block::Params::default();
        let (p, alpha) = (params.p, params.alpha);
        let (theta0, omega0) = (0.1, 0.3); // omega0 > p (alpha - theta0): past the corner
        let model = rocking_block::Model::from_params(params);
        let tolerance = Tolerance::scalar(1e-12, 1e-15);
        let start = (0.0, [theta0, omega0]);
        let run = run_switched(
            model,
            Dop853::new(),
            tolerance,
            HybridOptions::default(),
            start,
            10.0,
        )
        .unwrap();
        assert_eq!(run.stopped_by.as_deref(), Some("overturns"));
        let fall = ((alpha - theta0) * p / omega0).atanh() / p;
        assert_eq!(run.times("overturns", Fired::Stopped).len(), 1);
        assert!((run.t - fall).abs() < 1e-9, "{} vs {fall}", run.t);
        assert!((run.y[0] - alpha).abs() < 1e-9, "{}", run.y[0]);
    }

    #[test]
    fn the_dsl_file_holds_the_same_model() {
        let source = model_dsl::Source::new("rocking_block.dsl", include_str!("rocking_block.dsl"));
        let this = model_dsl::Source::rust("rocking_block.rs", include_str!("rocking_block.rs"));
        assert_eq!(
            this.tokens().unwrap().to_string(),
            source.tokens().unwrap().to_string()
        );
    }
}
