//! A mass on a spring dragged by a belt through Coulomb friction: stick-slip, written with
//! modes and events, solved and checked against the closed form.
//!
//! Stuck, the mass moves with the belt (`v = vb`) until the spring force `k x` exceeds static
//! friction `mu_s m g`: from rest at `x = 0` that is at `t1 = mu_s m g / (k vb)`. Slipping, it
//! oscillates with `omega = sqrt(k/m)` about `x0 = mu_k m g / k` (kinetic friction pushes it
//! along the belt) from `x0 + C`, `C = (mu_s - mu_k) m g / k`, with velocity `vb`; it sticks
//! when its velocity is `vb` again, after `2 (pi - atan(C omega / vb)) / omega`, at
//! `x0 - C`; carried by the belt for `2 C / vb`, it slips again at the same place: a cycle.
//!
//! The same model, as text, is `stick_slip.dsl` beside this file (`eulerdisk model solve
//! model-macros/examples/stick_slip.dsl --t-end 10`); a test holds the two to the same tokens.
//!
//! ```text
//! cargo run -p model-macros --example stick_slip
//! ```

use model_runtime::Const;
use model_runtime::{run_switched, Dop853, HybridOptions, SwitchedRun, Tolerance};

model_macros::model! {
    /// A mass on a spring, dragged by a belt through Coulomb friction: it sticks to the belt until
    /// the spring's pull exceeds static friction, slips back under kinetic friction, and sticks
    /// again once it matches the belt's speed.
    mod stick_slip {
        params {
            /// Mass (kg).
            m = 1.0,
            /// Spring stiffness (N/m); the spring's other end is fixed at x = 0.
            k = 10.0,
            /// Belt speed (m/s).
            vb = 0.5,
            /// Static friction coefficient.
            mu_s = 0.6,
            /// Kinetic friction coefficient.
            mu_k = 0.4,
            /// Gravity (m/s^2).
            g = 9.81,
        }
        states {
            /// Position (m).
            x = 0.0,
            /// Velocity (m/s).
            v = 0.5,
            /// Direction of the slip, the sign of v - vb while slipping (0 while stuck).
            s = 0.0,
        }

        outputs {
            /// The spring's force on the mass (N).
            spring = -k * x;
        }

        /// Carried by the belt: static friction holds the mass as long as it can.
        mode stuck {
            equations { der(x) = vb; der(v) = 0; der(s) = 0; }
            /// The spring pulls back harder than static friction holds: the mass slips back.
            when slip_back: k * x > mu_s * m * g -> slipping { s = -1; }
            /// The spring pushes ahead harder than static friction holds.
            when slip_ahead: k * x < -mu_s * m * g -> slipping { s = 1; }
        }

        /// Sliding on the belt under kinetic friction.
        mode slipping {
            equations {
                der(x) = v;
                m * der(v) = -k * x - mu_k * m * g * s;
                der(s) = 0;
            }
            /// The mass matches the belt's speed again: it sticks.
            when stick: s * (v - vb) < 0 -> stuck { v = vb; s = 0; }
        }
    }
}

/// The belt from its initial state, sampled every 10 ms.
fn run(t_end: f64) -> SwitchedRun<Const<3>> {
    let options = HybridOptions {
        sample_rate: Some(100.0),
        ..HybridOptions::default()
    };
    let tolerance = Tolerance::scalar(1e-11, 1e-13);
    let start = (0.0, stick_slip::INITIAL);
    let model = stick_slip::Model::default();
    run_switched(model, Dop853::new(), tolerance, options, start, t_end).expect("the belt runs")
}

fn main() {
    let run = run(10.0);
    println!("event,t_s,x,v");
    for event in &run.events {
        let [x, v, _] = event.y;
        println!("{},{:.12},{x},{v}", event.event, event.t);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn every_slip_and_stick_at_its_closed_form_time() {
        let p = stick_slip::Params::default();
        let omega = (p.k / p.m).sqrt();
        let c = (p.mu_s - p.mu_k) * p.m * p.g / p.k;
        let x0 = p.mu_k * p.m * p.g / p.k;
        let slipping = 2.0 * (PI - (c * omega / p.vb).atan()) / omega;
        let stuck = 2.0 * c / p.vb;
        let run = run(20.0);
        let mut t = p.mu_s * p.m * p.g / (p.k * p.vb);
        let mut expected = Vec::new();
        while t < 20.0 {
            expected.push(("slip_back", t, x0 + c));
            t += slipping;
            if t < 20.0 {
                expected.push(("stick", t, x0 - c));
            }
            t += stuck;
        }
        assert!(expected.len() >= 16, "{}", expected.len());
        let found: Vec<(&str, f64, f64)> = (run.events.iter())
            .map(|e| (e.event.as_str(), e.t, e.y[0]))
            .collect();
        assert_eq!(found.len(), expected.len(), "{found:?}");
        for ((name, t, x), (want_name, want_t, want_x)) in found.iter().zip(&expected) {
            assert_eq!(name, want_name);
            assert!(
                (t - want_t).abs() < 1e-9,
                "{name} at {t}, closed form {want_t}"
            );
            assert!(
                (x - want_x).abs() < 1e-9,
                "{name} at x = {x}, closed form {want_x}"
            );
        }
        // Stuck, the mass moves with the belt exactly; the friction it needs stays within mu_s m g.
        for (t, mode, y) in &run.samples {
            if mode == "stuck" {
                assert_eq!(y[1], p.vb, "at t = {t}");
                assert!(
                    p.k * y[0].abs() <= p.mu_s * p.m * p.g * (1.0 + 1e-12),
                    "at t = {t}"
                );
            }
        }
    }

    #[test]
    fn the_dsl_file_holds_the_same_model() {
        let source = model_dsl::Source::new("stick_slip.dsl", include_str!("stick_slip.dsl"));
        let this = model_dsl::Source::rust("stick_slip.rs", include_str!("stick_slip.rs"));
        assert_eq!(
            this.tokens().unwrap().to_string(),
            source.tokens().unwrap().to_string()
        );
    }
}
