//! Box 1 of the paper: the rolling disk (docs/physics.md §3.1, rows R1–R12).
//!
//! The rows are in `box1_rolling.dsl`, beside this file: the disk's mode graph
//! (`crate::hybrid::switching`) includes the same file for its mode `rolling`, so a fix to a
//! row is made there once. This model takes the disk's parameters, moments of inertia and the
//! air's drag coefficients from `disk.dsl` (the mode graph sets the air's terms to zero
//! instead), and adds the contact force and the checks as outputs and the pruned variant in
//! still air. The contact force is eliminated with the linear-momentum balance and
//! the no-slip conditions are written in differential form, exactly as the paper does; the
//! compiler applies the chain rule and solves for the derivatives.

model_macros::model! {
    /// Euler's disk rolling without slipping on a rough plane (paper's Box 1).
    ///
    /// States: centre position and velocity, 3–2–3 Euler angles `psi, theta, phi`, and the
    /// angular velocity in the frame that precesses and nutates with the disk.
    pub mod rolling {
        // The parameters, the moments of inertia `A, C` and the air's `k_F, k_M`.
        include "disk.dsl";
        states { X, Y, Z, V_X, V_Y, V_Z, psi, theta, phi, Omega_x, Omega_y, Omega_z }

        // Rows R1–R12, said once for this model and the mode graph's `rolling`.
        include "box1_rolling.dsl";

        outputs {
            R_X = m*der(V_X) + k_F*(v_z - w_z)*sin(theta)*cos(psi);
            R_Y = m*der(V_Y) + k_F*(v_z - w_z)*sin(theta)*sin(psi);
            N = m*(der(V_Z) + g) + k_F*(v_z - w_z)*cos(theta);
            T = sqrt(R_X^2 + R_Y^2);
            nu = T/N;
            alpha_r = atan2(R_Y, R_X);
            energy = m/2*(V_X^2 + V_Y^2 + V_Z^2) + A/2*(Omega_x^2 + Omega_y^2) + C/2*Omega_z^2 + m*g*Z;
            z_residual = Z - a*sin(theta);
            vz_residual = V_Z - a*Omega_y*cos(theta);
            vx_residual = V_X - a*(Omega_y*cos(psi)*sin(theta) + Omega_z*sin(psi));
            vy_residual = V_Y - a*(Omega_y*sin(psi)*sin(theta) - Omega_z*cos(psi));
        }

        /// What the mode switching needs, in still air: the inclination, the contact force
        /// and the friction direction rolling requires. `X`, `Y` and `phi` drop out.
        variant pruned {
            keep { theta, N, T, nu, alpha_r }
            fix { mu_a = 0.0, w_z = 0.0 }
        }

        /// Every state, in still air: the air's terms vanish at compile time. Runs of a disk in
        /// still air integrate this (`crate::hybrid::GeneratedModels`), as the mode graph does.
        variant still {
            keep { X, Y, Z, V_X, V_Y, V_Z, psi, theta, phi, Omega_x, Omega_y, Omega_z }
            fix { mu_a = 0.0, w_z = 0.0 }
        }
    }
}
