//! A double pendulum written in mass-matrix form, solved to a trajectory and checked.
//!
//! The two angular accelerations are coupled through the state-dependent mass matrix
//! `[[(m1 + m2) l1, m2 l2 cos Δ], [l1 cos Δ, l2]]` (Δ = θ1 − θ2); the compiler solves the
//! 2 × 2 block symbolically. Checks: the derivatives agree with the textbook explicit formulas
//! (derived independently, by eliminating the accelerations by hand), and the energy, an
//! output, stays constant along the trajectory. Every passage of the lower arm through the
//! vertical is located as an event.
//!
//! ```text
//! cargo run -p model-macros --example double_pendulum [-- OUT.csv]
//! ```

use model_runtime::Const;
use model_runtime::{Event, Method, Model as _, Output, Problem, Trajectory};
use std::error::Error;
use std::path::PathBuf;

model_macros::model! {
    /// Two point masses on massless rods; angles from the downward vertical.
    pub mod double_pendulum {
        params { m1 = 1.0, m2 = 0.5, l1 = 1.0, l2 = 0.7, g = 9.81 }
        states { th1, th2, w1, w2 }

        let d = th1 - th2;

        equations {
            der(th1) = w1;
            der(th2) = w2;
            upper: (m1 + m2) * l1 * der(w1) + m2 * l2 * cos(d) * der(w2)
                = -m2 * l2 * w2^2 * sin(d) - (m1 + m2) * g * sin(th1);
            lower: l2 * der(w2) + l1 * cos(d) * der(w1) = l1 * w1^2 * sin(d) - g * sin(th2);
        }

        outputs {
            kinetic = (m1 + m2) / 2 * l1^2 * w1^2 + m2 / 2 * l2^2 * w2^2
                + m2 * l1 * l2 * w1 * w2 * cos(d);
            potential = -(m1 + m2) * g * l1 * cos(th1) - m2 * g * l2 * cos(th2);
            energy = kinetic + potential;
        }
    }
}

use double_pendulum::{Params, State};

/// The textbook explicit accelerations (e.g. any classical-mechanics text), by hand.
fn textbook(p: &Params, y: &State) -> [f64; 2] {
    let Params { m1, m2, l1, l2, g } = *p;
    let (t1, t2, w1, w2) = (y.th1, y.th2, y.w1, y.w2);
    let den = 2.0 * m1 + m2 - m2 * (2.0 * t1 - 2.0 * t2).cos();
    let a1 = (-g * (2.0 * m1 + m2) * t1.sin()
        - m2 * g * (t1 - 2.0 * t2).sin()
        - 2.0 * (t1 - t2).sin() * m2 * (w2 * w2 * l2 + w1 * w1 * l1 * (t1 - t2).cos()))
        / (l1 * den);
    let a2 = 2.0
        * (t1 - t2).sin()
        * (w1 * w1 * l1 * (m1 + m2)
            + g * (m1 + m2) * t1.cos()
            + w2 * w2 * l2 * m2 * (t1 - t2).cos())
        / (l2 * den);
    [a1, a2]
}

/// Solves 20 s from a large swing; returns the trajectory.
fn solve() -> Result<Trajectory<Const<4>, 3>, Box<dyn Error>> {
    let model = double_pendulum::Model::default();
    let y0 = State {
        th1: 2.0,
        th2: -1.0,
        w1: 0.0,
        w2: 0.5,
    };
    let times = (0..=2000).map(|k| 0.01 * k as f64).collect();
    let trajectory = Problem::new(&model, y0.to_array(), (0.0, 20.0))
        .method(Method::Dop853)
        .tolerances(1e-11, 1e-11)
        .output(Output::Times(times))
        .event(Event::new("lower arm vertical", |_t, y, _dy| {
            y[double_pendulum::state::th2].sin()
        }))
        .solve()?;
    Ok(trajectory)
}

/// The largest relative difference between the compiled and the textbook accelerations over
/// the trajectory's states.
fn largest_disagreement(trajectory: &Trajectory<Const<4>, 3>) -> Result<f64, Box<dyn Error>> {
    let model = double_pendulum::Model::default();
    let p = model.named_params();
    let mut worst: f64 = 0.0;
    for y in &trajectory.y {
        let mut dy = [0.0; 4];
        model.rhs(0.0, y, &mut dy)?;
        let der = State::from(dy);
        let [a1, a2] = textbook(&p, &State::from(*y));
        worst = worst.max((der.w1 - a1).abs() / a1.abs().max(1.0));
        worst = worst.max((der.w2 - a2).abs() / a2.abs().max(1.0));
    }
    Ok(worst)
}

/// The largest change of the energy along the trajectory, relative to its size.
fn energy_drift(trajectory: &Trajectory<Const<4>, 3>) -> f64 {
    let energy = trajectory.column("energy").unwrap_or_default();
    let e0 = energy[0];
    energy.iter().map(|e| (e - e0).abs()).fold(0.0, f64::max) / e0.abs()
}

fn main() -> Result<(), Box<dyn Error>> {
    let out = std::env::args().nth(1).map_or_else(
        || std::env::temp_dir().join("double_pendulum.csv"),
        PathBuf::from,
    );
    let trajectory = solve()?;
    trajectory.write_csv(std::io::BufWriter::new(std::fs::File::create(&out)?))?;
    println!(
        "{} points, {} steps, {} events; energy drift {:.1e}, largest disagreement with the textbook {:.1e}; wrote {}",
        trajectory.t.len(),
        trajectory.stats.steps,
        trajectory.events.len(),
        energy_drift(&trajectory),
        largest_disagreement(&trajectory)?,
        out.display()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_textbook_and_conserves_energy() {
        let trajectory = solve().unwrap();
        assert_eq!(trajectory.t.len(), 2001);
        assert!(largest_disagreement(&trajectory).unwrap() < 1e-12);
        assert!(
            energy_drift(&trajectory) < 1e-8,
            "{}",
            energy_drift(&trajectory)
        );
        // The lower arm passes the vertical (up or down) many times in 20 s, each located
        // where sin(th2) = 0.
        assert!(trajectory.events.len() > 5);
        for event in &trajectory.events {
            assert!(event.y[double_pendulum::state::th2].sin().abs() < 1e-9);
        }
    }

    #[test]
    fn writes_a_csv_with_the_model_names() {
        let trajectory = solve().unwrap();
        let mut csv = Vec::new();
        trajectory.write_csv(&mut csv).unwrap();
        let text = String::from_utf8(csv).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next(),
            Some("t,th1,th2,w1,w2,kinetic,potential,energy")
        );
        assert_eq!(lines.count(), trajectory.t.len());
    }
}
