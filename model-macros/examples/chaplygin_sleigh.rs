//! The Chaplygin sleigh: a rigid body on a plane, resting on a knife edge that cannot slide
//! sideways, solved to a trajectory and checked.
//!
//! The no-side-slip condition is nonholonomic (not the derivative of any position
//! constraint), and it is written the way the Euler's-disk models write their no-slip
//! conditions, in differential form: `der(lateral velocity) = 0`. The reaction of the blade is
//! eliminated by hand: it acts sideways at the blade, so the centre of mass does not accelerate
//! along the blade, and the sideways momentum balance and the angular momentum balance about
//! the centre of mass share it (`I der(omega) = -a * lambda`).
//!
//! Check against an independent derivation: the reduced equations in the body frame,
//! `v' = a omega^2`, `omega' = -(m a / (I + m a^2)) v omega`, conserve
//! `m v^2 + (I + m a^2) omega^2 = m v_inf^2` and integrate in closed form,
//! `v(t) = v_inf tanh(k v_inf t + c0)`, `omega(t) = omega0 cosh(c0) / cosh(k v_inf t + c0)`
//! with `k = m a / (I + m a^2)`, `c0 = atanh(v0 / v_inf)`. A sleigh pushed backwards turns
//! round and ends up moving forwards: `v` passes through zero, an event, at
//! `t = -c0 / (k v_inf)`.
//!
//! ```text
//! cargo run -p model-macros --example chaplygin_sleigh [-- OUT.csv]
//! ```

use model_runtime::Const;
use model_runtime::{Direction, Event, Method, Output, Problem, Trajectory};
use std::error::Error;
use std::path::PathBuf;

model_macros::model! {
    /// The sleigh: blade at `(x, y)`, heading `phi`; the centre of mass sits `a` ahead of the
    /// blade along the heading; `I` is the moment of inertia about the centre of mass.
    pub mod sleigh {
        params { m = 2.0, I = 0.05, a = 0.3 }
        states { x, y, phi, vx, vy, omega }

        // The velocity of the centre of mass.
        let cvx = vx - a * sin(phi) * omega;
        let cvy = vy + a * cos(phi) * omega;

        equations {
            der(x) = vx;
            der(y) = vy;
            der(phi) = omega;
            // The blade's reaction is sideways: no acceleration of the centre along the heading.
            along: cos(phi) * der(cvx) + sin(phi) * der(cvy) = 0;
            // Sideways momentum m * n . c'' = lambda, and I * omega' = -a * lambda.
            turning: I * der(omega) + a * m * (-sin(phi) * der(cvx) + cos(phi) * der(cvy)) = 0;
            // No side slip, in differential form.
            blade: der(-sin(phi) * vx + cos(phi) * vy) = 0;
        }

        outputs {
            /// The blade's speed along the heading.
            v = cos(phi) * vx + sin(phi) * vy;
            /// The side slip, zero at the start: its drift measures the integration error.
            side_slip = -sin(phi) * vx + cos(phi) * vy;
            energy = m / 2 * (cvx^2 + cvy^2) + I / 2 * omega^2;
        }
    }
}

use sleigh::{Params, State};

/// Pushed backwards while turning.
fn initial() -> State {
    let (phi, v) = (0.4, -0.5);
    State {
        x: 0.0,
        y: 0.0,
        phi,
        vx: v * phi.cos(),
        vy: v * phi.sin(),
        omega: 1.5,
    }
}

/// The closed-form solution of the reduced equations: `(v, omega)` at `t`, and the time `v`
/// passes through zero.
struct ClosedForm {
    k: f64,
    v_inf: f64,
    c0: f64,
    omega0: f64,
}

impl ClosedForm {
    fn new(p: &Params, v0: f64, omega0: f64) -> Self {
        let inertia = p.I + p.m * p.a * p.a;
        let v_inf = ((p.m * v0 * v0 + inertia * omega0 * omega0) / p.m).sqrt();
        ClosedForm {
            k: p.m * p.a / inertia,
            v_inf,
            c0: (v0 / v_inf).atanh(),
            omega0,
        }
    }

    fn at(&self, t: f64) -> (f64, f64) {
        let s = self.k * self.v_inf * t + self.c0;
        (
            self.v_inf * s.tanh(),
            self.omega0 * self.c0.cosh() / s.cosh(),
        )
    }

    fn turnaround(&self) -> f64 {
        -self.c0 / (self.k * self.v_inf)
    }
}

fn closed_form() -> ClosedForm {
    let y0 = initial();
    let v0 = y0.vx * y0.phi.cos() + y0.vy * y0.phi.sin();
    ClosedForm::new(&Params::default(), v0, y0.omega)
}

fn solve() -> Result<Trajectory<Const<6>, 3>, Box<dyn Error>> {
    let model = sleigh::Model::default();
    let times = (0..=400).map(|k| 0.025 * k as f64).collect();
    let trajectory = Problem::new(&model, initial().to_array(), (0.0, 10.0))
        .method(Method::Dopri5)
        .tolerances(1e-11, 1e-12)
        .output(Output::Times(times))
        .event(
            Event::new("turned round", |_t, y, _dy| {
                let s = State::from(std::array::from_fn(|i| y[i]));
                s.vx * s.phi.cos() + s.vy * s.phi.sin()
            })
            .direction(Direction::Up),
        )
        .solve()?;
    Ok(trajectory)
}

/// The largest difference of `(v, omega)` from the closed form over the trajectory.
fn closed_form_error(trajectory: &Trajectory<Const<6>, 3>) -> f64 {
    let exact = closed_form();
    let v = trajectory.column("v").unwrap_or_default();
    let omega = trajectory.column("omega").unwrap_or_default();
    trajectory
        .t
        .iter()
        .zip(v.iter().zip(&omega))
        .map(|(&t, (v, omega))| {
            let (v_exact, omega_exact) = exact.at(t);
            (v - v_exact).abs().max((omega - omega_exact).abs())
        })
        .fold(0.0, f64::max)
}

fn main() -> Result<(), Box<dyn Error>> {
    let out = std::env::args().nth(1).map_or_else(
        || std::env::temp_dir().join("chaplygin_sleigh.csv"),
        PathBuf::from,
    );
    let trajectory = solve()?;
    trajectory.write_csv(std::io::BufWriter::new(std::fs::File::create(&out)?))?;
    let slip = trajectory.column("side_slip").unwrap_or_default();
    println!(
        "turned round at t = {:?} (closed form {:.12}); largest error against the closed form {:.1e}; largest side slip {:.1e}; wrote {}",
        trajectory.events.first().map(|e| e.t),
        closed_form().turnaround(),
        closed_form_error(&trajectory),
        slip.iter().map(|s| s.abs()).fold(0.0, f64::max),
        out.display()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn follows_the_closed_form_of_the_reduced_equations() {
        let trajectory = solve().unwrap();
        let error = closed_form_error(&trajectory);
        assert!(error < 1e-8, "{error:e}");
        // The sleigh ends up moving forwards, close to v_inf.
        let v = trajectory.column("v").unwrap();
        assert!(v[0] < 0.0 && *v.last().unwrap() > 0.9 * closed_form().v_inf);
    }

    #[test]
    fn turns_round_when_the_closed_form_says() {
        let trajectory = solve().unwrap();
        assert_eq!(trajectory.events.len(), 1);
        let event = &trajectory.events[0];
        assert!(
            (event.t - closed_form().turnaround()).abs() < 1e-8,
            "{}",
            event.t
        );
    }

    #[test]
    fn keeps_the_blade_from_slipping_and_the_energy_constant() {
        let trajectory = solve().unwrap();
        let slip = trajectory.column("side_slip").unwrap();
        assert!(slip.iter().all(|s| s.abs() < 1e-9));
        let energy = trajectory.column("energy").unwrap();
        assert!(energy
            .iter()
            .all(|e| (e - energy[0]).abs() < 1e-9 * energy[0]));
    }
}
