//! The sign printed in the paper's Box 3, eq. (8), `+μ_d m a sin(α-ψ) V̇_Z + C Ω̇_z = …`, is a
//! misprint (docs/physics.md §12): with it, sliding would not lose energy to friction. This model
//! is Box 3 with the printed sign; the same energy test that the real models pass must fail on
//! it, and it must disagree with the reference. Both checks can therefore fail.

use crate::common;
use crate::common::dual::{energy_rate, Chart};
use crate::common::subject::{eval, Family, SlidingRef, SLIDING_OUTPUTS};
use crate::common::{scales, Agreement, Reach, Rng};
use equations::reference::sliding_polar;
use equations::DiskParams;

model_macros::model! {
    /// Box 3 as printed: the sign of the `der(V_Z)` term in row 8 flipped.
    pub mod printed_box3 {
        // The disk and Box 3's outputs as the real model has them (`k_F = 0` in still air,
        // the only air these tests use); only row 8's sign differs.
        include "../../src/models/disk.dsl";
        states { X, Y, Z, v_C, alpha, V_Z, psi, theta, phi, Omega_x, Omega_y, Omega_z }

        let S = sin(alpha - psi);
        let K = cos(alpha - psi);
        let k = mu_d*K*sin(theta) + cos(theta);

        equations {
            S1: der(X) = -v_C*cos(alpha) + a*(Omega_y*cos(psi)*sin(theta) + Omega_z*sin(psi));
            S2: der(Y) = -v_C*sin(alpha) + a*(Omega_y*sin(psi)*sin(theta) - Omega_z*cos(psi));
            S3: der(Z) = V_Z;
            S4: m*v_C*der(alpha) + m*a*(-Omega_y*K*sin(theta) + Omega_z*S)*der(psi)
                + m*a*Omega_y*S*cos(theta)*der(theta) + m*a*S*sin(theta)*der(Omega_y)
                + m*a*K*der(Omega_z) = 0;
            S5: -m*der(v_C) - mu_d*m*der(V_Z) + m*a*(Omega_y*S*sin(theta) + Omega_z*K)*der(psi)
                + m*a*Omega_y*K*cos(theta)*der(theta) + m*a*K*sin(theta)*der(Omega_y)
                - m*a*S*der(Omega_z) = mu_d*m*g;
            S6: A*Omega_y*der(phi) + A*der(Omega_x) = (A - C)*Omega_y*Omega_z;
            S7: m*a*k*der(V_Z) - A*Omega_x*der(phi) + A*der(Omega_y) = (C - A)*Omega_x*Omega_z - m*g*a*k;
            S8: C*der(Omega_z) + mu_d*m*a*S*der(V_Z) = mu_d*m*g*a*S;
            S9: sin(theta)*der(psi) = -Omega_x;
            S10: der(theta) = Omega_y;
            S11: cos(theta)*der(psi) + der(phi) = Omega_z;
            S12: der(V_Z) + a*(Omega_y*sin(theta)*der(theta) - cos(theta)*der(Omega_y)) = 0;
        }

        // Normal velocity of the centre, V·e_z (which the outputs' air terms read).
        let v_z = -v_C*sin(theta)*K + a*Omega_y*sin(theta)^2 + V_Z*cos(theta);
        include "../../src/models/box3_outputs.dsl";
    }
}

struct Printed;
impl Family<SLIDING_OUTPUTS> for Printed {
    type Model = printed_box3::Model;
    const NAME: &'static str = "Box 3 as printed";
    fn build(p: &DiskParams) -> Self::Model {
        printed_box3::Model::new(p.to_array())
    }
}

/// Worst violation of `dE/dt = -T v_C` over random still-air sliding states on the contact
/// manifold, in units of the 1e-12 tolerance the real models meet.
fn energy_balance<F: Family<SLIDING_OUTPUTS>>() -> Agreement {
    let mut rng = Rng::new(81);
    let mut agreement = Agreement::default();
    for _ in 0..500 {
        let p = DiskParams {
            mu_a: 0.0,
            ..common::some_params(&mut rng)
        };
        let y = common::sliding_consistent_state(&mut rng, &p, Reach::Typical);
        let e = eval(&F::build(&p), &y).unwrap();
        let row = scales::sliding_polar_full(&p, &y);
        let rate = energy_rate(&p, Chart::SlidingPolar, &y, &e.dy, &row);
        let expected = -e.out[sliding_polar::output::T] * y[3];
        agreement.check(rate.rate, expected, rate.scale, || {
            format!("dE/dt at {y:?}")
        });
    }
    agreement
}

#[test]
fn the_printed_sign_breaks_the_energy_balance() {
    energy_balance::<SlidingRef>().assert_within("reference");
    let printed = energy_balance::<Printed>();
    assert!(
        printed.worst > 1e6,
        "the printed sign should violate dE/dt = -T v_C, worst only {} × tolerance",
        printed.worst
    );
}

#[test]
fn the_printed_sign_disagrees_with_the_reference() {
    let p = DiskParams::paper();
    let y = [
        0.0, 0.0, 0.02, 0.1, 2.0, 0.01, 0.3, 0.6, 0.0, 3.0, -1.0, 20.0,
    ];
    let printed = eval(&Printed::build(&p), &y).unwrap();
    let reference = eval(&SlidingRef::build(&p), &y).unwrap();
    let i = sliding_polar::state::Omega_z;
    let gap = (printed.dy[i] - reference.dy[i]).abs();
    assert!(
        gap > 1e-3 * reference.dy[i].abs(),
        "{} vs {}",
        printed.dy[i],
        reference.dy[i]
    );
}
