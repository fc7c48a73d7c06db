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
//! fast when the slip passes near zero; only `u = 0` itself is singular. Both models come from
//! one text, so a fix to a row of Box 3 is made here once.

model_macros::model! {
    /// Euler's disk sliding on a rough plane, polar slip chart (paper's Box 3).
    pub mod sliding {
        params { m = 0.4387, a = 0.03755, g = 9.81, mu_d = 0.115, mu_st = 0.2, mu_a = 0.0, w_z = 0.0 }
        states { X, Y, Z, v_C, alpha, V_Z, psi, theta, phi, Omega_x, Omega_y, Omega_z }

        let A = m*a^2/4;
        let C = m*a^2/2;
        let k_F = mu_a*pi*a^2;
        let k_M = mu_a*pi*a^4/4;
        let S = sin(alpha - psi);
        let K = cos(alpha - psi);
        let k = mu_d*K*sin(theta) + cos(theta);
        // Normal velocity of the centre, V·e_z.
        let v_z = -v_C*sin(theta)*K + a*Omega_y*sin(theta)^2 + V_Z*cos(theta);

        equations {
            S1: der(X) = -v_C*cos(alpha) + a*(Omega_y*cos(psi)*sin(theta) + Omega_z*sin(psi));
            S2: der(Y) = -v_C*sin(alpha) + a*(Omega_y*sin(psi)*sin(theta) - Omega_z*cos(psi));
            S3: der(Z) = V_Z;
            S4: m*v_C*der(alpha) + m*a*(-Omega_y*K*sin(theta) + Omega_z*S)*der(psi)
                + m*a*Omega_y*S*cos(theta)*der(theta) + m*a*S*sin(theta)*der(Omega_y)
                + m*a*K*der(Omega_z)
                = -k_F*(v_z - w_z)*sin(theta)*S;
            S5: -m*der(v_C) - mu_d*m*der(V_Z) + m*a*(Omega_y*S*sin(theta) + Omega_z*K)*der(psi)
                + m*a*Omega_y*K*cos(theta)*der(theta) + m*a*K*sin(theta)*der(Omega_y)
                - m*a*S*der(Omega_z)
                = mu_d*m*g + k_F*(v_z - w_z)*(mu_d*cos(theta) - K*sin(theta));
            S6: A*Omega_y*der(phi) + A*der(Omega_x) = (A - C)*Omega_y*Omega_z - k_M*Omega_x;
            S7: m*a*k*der(V_Z) - A*Omega_x*der(phi) + A*der(Omega_y)
                = (C - A)*Omega_x*Omega_z - m*g*a*k - k_F*a*(v_z - w_z)*cos(theta)*k - k_M*Omega_y;
            S8: C*der(Omega_z) - mu_d*m*a*S*der(V_Z) = mu_d*m*g*a*S + mu_d*k_F*a*(v_z - w_z)*cos(theta)*S;
            S9: sin(theta)*der(psi) = -Omega_x;
            S10: der(theta) = Omega_y;
            S11: cos(theta)*der(psi) + der(phi) = Omega_z;
            S12: der(V_Z) + a*(Omega_y*sin(theta)*der(theta) - cos(theta)*der(Omega_y)) = 0;
        }

        outputs {
            N = m*(der(V_Z) + g) + k_F*(v_z - w_z)*cos(theta);
            T = mu_d*N;
            R_X = T*cos(alpha);
            R_Y = T*sin(alpha);
            nu = T/N;
            V_X = -v_C*cos(alpha) + a*(Omega_y*cos(psi)*sin(theta) + Omega_z*sin(psi));
            V_Y = -v_C*sin(alpha) + a*(Omega_y*sin(psi)*sin(theta) - Omega_z*cos(psi));
            energy = m/2*(V_X^2 + V_Y^2 + V_Z^2) + A/2*(Omega_x^2 + Omega_y^2) + C/2*Omega_z^2 + m*g*Z;
            friction_power = -T*v_C;
            z_residual = Z - a*sin(theta);
            vz_residual = V_Z - a*Omega_y*cos(theta);
        }

        /// What the mode switching needs, in still air: the inclination, the contact force
        /// and the slip. `X`, `Y` and `phi` drop out.
        variant pruned {
            keep { theta, v_C, alpha, N, T, nu }
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
