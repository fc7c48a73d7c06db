//! Box 3 of the paper: the sliding disk in the polar slip variables `(v_C, alpha)`
//! (docs/physics.md §4.1, rows S1–S12, with the sign of row 8 corrected: §12).
//!
//! `alpha` is the direction of the friction force; the slip velocity of the contact point is
//! `-v_C (cos alpha, sin alpha)`. The chart is singular at `v_C = 0` (the coefficient of
//! `der(alpha)` in S4 is `m v_C`).
//!
//! The same rows also give `sliding_cartesian`, Box 3 in the Cartesian slip chart of
//! docs/physics.md §6: its states carry the slip velocity `u = (u_X, u_Y) = v_C e_s` of the
//! contact point, `v_C` and `alpha` become expressions of `u`, and the compiler's chain rule
//! turns `der(v_C)` and `der(alpha)` into derivatives of `u`. Nothing there turns infinitely
//! fast when the slip passes near zero; only `u = 0` itself is singular.
//!
//! The rows are in `box3_sliding.dsl`, beside this file, which the disk's mode graph
//! (`crate::hybrid::switching`) includes too for its mode `sliding` (in the Cartesian slip
//! chart, carried in the slots of `V_X, V_Y`): both models here and the mode come from one
//! text, so a fix to a row of Box 3 is made there once. The parameters, moments of inertia
//! and the air's drag coefficients are `disk.dsl`'s, the outputs `box3_outputs.dsl`'s (which
//! the test of the paper's misprinted row 8 holds its model to as well).

model_macros::model! {
    /// Euler's disk sliding on a rough plane, polar slip chart (paper's Box 3).
    pub mod sliding {
        // The parameters, the moments of inertia `A, C` and the air's `k_F, k_M`.
        include "disk.dsl";
        states { X, Y, Z, v_C, alpha, V_Z, psi, theta, phi, Omega_x, Omega_y, Omega_z }

        // Rows S1–S12, said once for this model, its chart and the mode graph's `sliding`.
        include "box3_sliding.dsl";

        include "box3_outputs.dsl";

        /// What the mode switching needs, in still air: the inclination, the contact force
        /// and the slip. `X`, `Y` and `phi` drop out.
        variant pruned {
            keep { theta, v_C, alpha, N, T, nu }
            fix { mu_a = 0.0, w_z = 0.0 }
        }

        /// Every state, in still air: the air's terms vanish at compile time. Runs of a disk in
        /// still air integrate this (`crate::hybrid::GeneratedModels`), as the mode graph does.
        variant still {
            keep { X, Y, Z, v_C, alpha, V_Z, psi, theta, phi, Omega_x, Omega_y, Omega_z }
            fix { mu_a = 0.0, w_z = 0.0 }
        }

        /// Euler's disk sliding on a rough plane, Cartesian slip chart (paper's Box 3).
        chart sliding_cartesian {
            states { u_X, u_Y } replace { v_C, alpha }
            let v_C = sqrt(u_X^2 + u_Y^2);
            let alpha = atan2(-u_Y, -u_X);
            outputs after V_Y {
                slip_speed = v_C;
                slip_direction = alpha;
            }
        }
    }
}
