// Box 3 of the paper, rows S1–S12: the disk sliding on a rough plane, in the polar slip
// variables `(v_C, alpha)` (docs/physics.md §4.1, with the sign of row 8 corrected: §12).
//
// Said once, here, and included where it is needed: by the smooth model `sliding` and its
// Cartesian chart (box3_sliding.rs) and by the mode `sliding` of the disk's mode graph
// (../hybrid/switching.rs). `alpha` is the direction of the friction force; the slip velocity
// of the contact point is `-v_C (cos alpha, sin alpha)`. Where the slip is carried as
// `(u_X, u_Y)`, `v_C` and `alpha` are lets of the including model or mode and the compiler's
// chain rule turns `der(v_C)` and `der(alpha)` into derivatives of `u`.
//
// The rows read the including model's parameters `m, a, g, mu_d`, its moments of inertia
// `A, C`, and the air's drag coefficients `k_F, k_M` and vertical speed `w_z`: lets of the
// model, which in still air are zero (`let k_F = 0;`), so that the air's terms vanish before
// the solve.

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
