//! A chart: the harmonic oscillator in polar coordinates, from the Cartesian rows.

use model_runtime::{Model, WithOutputs};

model_macros::model! {
    /// A harmonic oscillator.
    pub mod oscillator {
        params { w = 2.0 }
        states { x, v }
        equations { der(x) = v; der(v) = -w^2 * x; }
        outputs { energy = (v^2 + w^2 * x^2) / 2; }
        variant speed { keep { v } }
        /// The same oscillator in amplitude and phase (`x = r cos phi`, `v = -w r sin phi`).
        chart polar {
            states { r, phi } replace { x, v }
            let x = r * cos(phi);
            let v = -w * r * sin(phi);
            outputs after energy { amplitude = r; }
        }
    }
}

fn main() {
    let model = polar::Model::default();
    let y = [1.5, 0.3];
    let mut dy = [0.0; 2];
    model.rhs(0.0, &y, &mut dy).unwrap();
    // In polar coordinates the oscillator turns at constant amplitude and speed w.
    assert!(dy[polar::state::r].abs() < 1e-14, "{dy:?}");
    assert!((dy[polar::state::phi] - 2.0).abs() < 1e-14, "{dy:?}");
    let mut out = [0.0; polar::N_OUTPUTS];
    model.outputs(0.0, &y, &dy, &mut out).unwrap();
    assert_eq!(polar::OUTPUT_NAMES, ["energy", "amplitude"]);
    assert!((out[polar::output::energy] - 2.0 * 1.5 * 1.5).abs() < 1e-14);
    // The variant keeping `v` keeps both new states in the chart.
    assert_eq!(polar::speed::STATE_NAMES, ["r", "phi"]);
    assert_eq!(oscillator::speed::STATE_NAMES, ["x", "v"]);
    let _ = oscillator::Model::default();
}
