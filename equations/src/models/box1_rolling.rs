//! Box 1 of the paper: the rolling disk (docs/physics.md §3.1, rows R1–R12).
//!
//! The contact force is eliminated with the linear-momentum balance and the no-slip
//! conditions are written in differential form, exactly as the paper does; the compiler
//! applies the chain rule and solves for the derivatives.

model_macros::model! {
    /// Euler's disk rolling without slipping on a rough plane (paper's Box 1).
    ///
    /// States: centre position and velocity, 3–2–3 Euler angles `psi, theta, phi`, and the
    /// angular velocity in the frame that precesses and nutates with the disk.
    pub mod rolling {
        params { m = 0.4387, a = 0.03755, g = 9.81, mu_d = 0.115, mu_st = 0.2, mu_a = 0.0, w_z = 0.0 }
        states { X, Y, Z, V_X, V_Y, V_Z, psi, theta, phi, Omega_x, Omega_y, Omega_z }

        let A = m*a^2/4;
        let C = m*a^2/2;
        let k_F = mu_a*pi*a^2;
        let k_M = mu_a*pi*a^4/4;
        // Normal velocity of the centre, V·e_z (air drag acts along the disk normal).
        let v_z = (V_X*cos(psi) + V_Y*sin(psi))*sin(theta) + V_Z*cos(theta);

        equations {
            R1: der(X) = V_X;
            R2: der(Y) = V_Y;
            R3: der(Z) = V_Z;
            R4: der(V_X - a*(Omega_y*cos(psi)*sin(theta) + Omega_z*sin(psi))) = 0;
            R5: der(V_Y - a*(Omega_y*sin(psi)*sin(theta) - Omega_z*cos(psi))) = 0;
            R6: der(V_Z - a*Omega_y*cos(theta)) = 0;
            R7: A*der(Omega_x) - A*Omega_y*cos(theta)*der(psi) = -C*Omega_y*Omega_z - k_M*Omega_x;
            R8: A*der(Omega_y) + A*Omega_x*cos(theta)*der(psi)
                + m*a*(sin(theta)*(cos(psi)*der(V_X) + sin(psi)*der(V_Y)) + cos(theta)*der(V_Z))
                = C*Omega_x*Omega_z - m*g*a*cos(theta) - k_F*a*(v_z - w_z) - k_M*Omega_y;
            R9: C*der(Omega_z) + m*a*(sin(psi)*der(V_X) - cos(psi)*der(V_Y)) = 0;
            R10: sin(theta)*der(psi) = -Omega_x;
            R11: der(theta) = Omega_y;
            R12: cos(theta)*der(psi) + der(phi) = Omega_z;
        }

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
    }
}
