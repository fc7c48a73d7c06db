//! A heavy symmetric top in Euler angles, solved to a trajectory and checked.
//!
//! Precession `phi`, nutation `theta`, spin `psi` (z–x–z), with their rates as states. The two
//! conserved momenta are written the way a mechanics text states them, as `der(p) = 0` of the
//! momentum's expression, and the compiler applies the chain rule and solves the coupled
//! block for the accelerations (dividing by `sin(theta)`, a checked pivot).
//!
//! Check against an independent derivation: with `u = cos(theta)`, the nutation obeys
//! `u'^2 = f(u) = (1 - u^2)(alpha - beta u) - (b - a u)^2`, a cubic whose two roots in
//! [-1, 1] bound the nutation. Its turning points (events where `w_theta = 0`) must lie exactly
//! at those roots, found here by bisection of the cubic, with no integration involved. The
//! energy and both momenta, outputs of the model, must stay constant.
//!
//! The same model, as text, is `heavy_top.dsl` beside this file: `eulerdisk model show|eval|solve`
//! read it without compiling Rust, and a test here holds the two to the same tokens and the
//! same numbers.
//!
//! ```text
//! cargo run -p model-macros --example heavy_top [-- OUT.csv]
//! ```

use model_runtime::Const;
use model_runtime::{Direction, Event, Method, Output, Problem, Trajectory};
use std::error::Error;
use std::path::PathBuf;

model_macros::model! {
    /// A symmetric top spinning on a fixed tip; `l` is the tip-to-centre-of-mass distance,
    /// `I1` the moment of inertia about a transverse axis through the tip, `I3` about the
    /// symmetry axis.
    pub mod heavy_top {
        params { m = 0.5, g = 9.81, l = 0.04, I1 = 0.0012, I3 = 0.0009 }
        // A sound start (the top tilted, spinning fast, precessing slowly), not the singular
        // point theta = 0 of the Euler angles.
        states { phi, theta = 0.3, psi, w_phi = 2, w_theta, w_psi = 150 }

        // The spin about the symmetry axis, and the momenta conjugate to phi and psi.
        let omega3 = w_psi + w_phi * cos(theta);
        let p_psi = I3 * omega3;
        let p_phi = I1 * w_phi * sin(theta)^2 + p_psi * cos(theta);

        equations {
            der(phi) = w_phi;
            der(theta) = w_theta;
            der(psi) = w_psi;
            precession: der(p_phi) = 0;
            spin: der(p_psi) = 0;
            nutation: I1 * der(w_theta) = I1 * w_phi^2 * sin(theta) * cos(theta)
                - I3 * omega3 * w_phi * sin(theta) + m * g * l * sin(theta);
        }

        outputs {
            energy = I1 / 2 * (w_theta^2 + w_phi^2 * sin(theta)^2) + I3 / 2 * omega3^2
                + m * g * l * cos(theta);
            momentum_phi = p_phi;
            momentum_psi = p_psi;
        }
    }
}

use heavy_top::{Params, State};

/// The initial state: tilted 30° from the vertical, spinning fast, no precession yet.
fn initial() -> State {
    State {
        phi: 0.0,
        theta: 30f64.to_radians(),
        psi: 0.0,
        w_phi: 0.0,
        w_theta: 0.0,
        w_psi: 150.0,
    }
}

/// `cos(theta)` at the two turning points of the nutation, from the cubic alone (`None` if it
/// does not have two roots in [-1, 1]).
fn nutation_bounds(p: &Params, y: &State) -> Option<[f64; 2]> {
    let u0 = y.theta.cos();
    let omega3 = y.w_psi + y.w_phi * u0;
    let p_psi = p.I3 * omega3;
    let p_phi = p.I1 * y.w_phi * (1.0 - u0 * u0) + p_psi * u0;
    let reduced_energy =
        p.I1 / 2.0 * (y.w_theta.powi(2) + (y.w_phi * y.theta.sin()).powi(2)) + p.m * p.g * p.l * u0;
    let (a, b) = (p_psi / p.I1, p_phi / p.I1);
    let alpha = 2.0 * reduced_energy / p.I1;
    let beta = 2.0 * p.m * p.g * p.l / p.I1;
    let f = |u: f64| (1.0 - u * u) * (alpha - beta * u) - (b - a * u).powi(2);
    // f(±1) = -(b ± a)^2 <= 0 and f >= 0 between the turning points: scan for the two sign
    // changes, then bisect each to the last bit.
    let bisect = |mut lo: f64, mut hi: f64| {
        let positive_lo = f(lo) > 0.0;
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if (f(mid) > 0.0) == positive_lo {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    let n = 200_000;
    let mut roots = Vec::new();
    let mut previous = -1.0;
    for k in 1..=n {
        let u = -1.0 + 2.0 * k as f64 / n as f64;
        if (f(u) > 0.0) != (f(previous) > 0.0) {
            roots.push(bisect(previous, u));
        }
        previous = u;
    }
    match roots[..] {
        [low, high] => Some([low, high]),
        _ => None,
    }
}

fn solve() -> Result<Trajectory<Const<6>, 3>, Box<dyn Error>> {
    let model = heavy_top::Model::default();
    let times = (0..=1000).map(|k| 0.001 * k as f64).collect();
    let trajectory = Problem::new(&model, initial().to_array(), (0.0, 1.0))
        .method(Method::Dop853)
        .tolerances(1e-12, 1e-12)
        .output(Output::Times(times))
        .event(
            Event::new("deepest", |_t, y, _dy| y[heavy_top::state::w_theta])
                .direction(Direction::Down),
        )
        .event(
            Event::new("highest", |_t, y, _dy| y[heavy_top::state::w_theta])
                .direction(Direction::Up),
        )
        .solve()?;
    Ok(trajectory)
}

/// The largest relative change of each conserved output along the trajectory.
fn drifts(trajectory: &Trajectory<Const<6>, 3>) -> Vec<(&'static str, f64)> {
    ["energy", "momentum_phi", "momentum_psi"]
        .into_iter()
        .map(|name| {
            let values = trajectory.column(name).unwrap_or_default();
            let scale = values[0].abs().max(f64::MIN_POSITIVE);
            let drift = values
                .iter()
                .map(|v| (v - values[0]).abs())
                .fold(0.0, f64::max);
            (name, drift / scale)
        })
        .collect()
}

/// The largest distance of a turning point's `cos(theta)` from the cubic's root it should sit
/// on (events `deepest` at the larger `theta`, `highest` at the smaller).
fn turning_point_error(trajectory: &Trajectory<Const<6>, 3>) -> f64 {
    let Some([low, high]) = nutation_bounds(&heavy_top::Params::default(), &initial()) else {
        return f64::INFINITY;
    };
    trajectory
        .events
        .iter()
        .map(|event| {
            let u = event.y[heavy_top::state::theta].cos();
            let root = if event.name == "deepest" { low } else { high };
            (u - root).abs()
        })
        .fold(0.0, f64::max)
}

fn main() -> Result<(), Box<dyn Error>> {
    let out = std::env::args()
        .nth(1)
        .map_or_else(|| std::env::temp_dir().join("heavy_top.csv"), PathBuf::from);
    let trajectory = solve()?;
    trajectory.write_csv(std::io::BufWriter::new(std::fs::File::create(&out)?))?;
    let [low, high] = nutation_bounds(&heavy_top::Params::default(), &initial())
        .ok_or("the nutation cubic does not have two roots in [-1, 1]")?;
    println!(
        "nutation between {:.6}° and {:.6}° (cubic); {} turning points, largest miss in cos(theta) {:.1e}",
        high.acos().to_degrees(),
        low.acos().to_degrees(),
        trajectory.events.len(),
        turning_point_error(&trajectory)
    );
    for (name, drift) in drifts(&trajectory) {
        println!("{name}: relative drift {drift:.1e}");
    }
    println!("wrote {}", out.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turning_points_sit_on_the_roots_of_the_cubic() {
        let trajectory = solve().unwrap();
        let deepest = trajectory
            .events
            .iter()
            .filter(|e| e.name == "deepest")
            .count();
        let highest = trajectory
            .events
            .iter()
            .filter(|e| e.name == "highest")
            .count();
        // A fast top nods many times a second: both kinds of turning point, alternating.
        assert!(deepest >= 5 && highest >= 5, "{deepest} {highest}");
        assert!(deepest.abs_diff(highest) <= 1);
        let error = turning_point_error(&trajectory);
        assert!(error < 1e-9, "{error:e}");
        // The nutation is small but not zero: the two roots differ.
        let [low, high] = nutation_bounds(&heavy_top::Params::default(), &initial()).unwrap();
        assert!(high - low > 1e-5, "{low} {high}");
        // The start (w_theta = 0) is the highest point.
        assert!((high - initial().theta.cos()).abs() < 1e-12);
    }

    /// The `model!` body of this file and `heavy_top.dsl` are the same tokens, and the
    /// interpreter running the file's compilation gives the compiled model's derivatives and
    /// outputs to round-off at pseudo-random states and parameters.
    #[test]
    fn the_dsl_file_interpreted_agrees_with_the_compiled_model() {
        use model_runtime::WithOutputs as _;
        let source = model_dsl::Source::new("heavy_top.dsl", include_str!("heavy_top.dsl"));
        let this = model_dsl::Source::rust("heavy_top.rs", include_str!("heavy_top.rs"));
        let body = this.tokens().unwrap().to_string();
        assert_eq!(body, source.tokens().unwrap().to_string());
        let models = source.compile().unwrap();
        let interpreted = &models[0].compiled;
        // A small linear congruential sequence: reproducible, spread over each range.
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut uniform = |lo: f64, hi: f64| {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            lo + (hi - lo) * (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..200 {
            let p = heavy_top::Params {
                m: uniform(0.1, 2.0),
                g: uniform(1.0, 20.0),
                l: uniform(0.01, 0.2),
                I1: uniform(1e-4, 1e-2),
                I3: uniform(1e-4, 1e-2),
            };
            let y: [f64; 6] = std::array::from_fn(|k| match k {
                1 => uniform(0.1, 3.0),
                _ => uniform(-50.0, 50.0),
            });
            let t = uniform(0.0, 10.0);
            let compiled = heavy_top::Model::from_params(p).evaluate(t, &y).unwrap();
            let params = p.to_array();
            let der = interpreted.derivatives(t, &y, &params).unwrap();
            let out = interpreted.outputs_at(t, &y, &der, &params).unwrap();
            for (got, want) in der
                .iter()
                .zip(&compiled.der)
                .chain(out.iter().zip(&compiled.outputs))
            {
                assert!(
                    (got - want).abs() <= 1e-13 * want.abs().max(1.0),
                    "{got} vs {want} at {y:?}"
                );
            }
        }
    }

    #[test]
    fn energy_and_momenta_are_conserved() {
        for (name, drift) in drifts(&solve().unwrap()) {
            assert!(drift < 1e-9, "{name}: {drift:e}");
        }
    }
}
