// Box 1 of the paper, rows R1–R12: the disk rolling without slipping (docs/physics.md §3.1).
//
// Said once, here, and included where it is needed: by the smooth model `rolling`
// (box1_rolling.rs) and by the mode `rolling` of the disk's mode graph (../hybrid/switching.rs).
// The contact force is eliminated with the linear-momentum balance and the no-slip conditions
// are written in differential form, exactly as the paper does; the compiler applies the chain
// rule and solves for the derivatives.
//
// The rows read the including model's parameters `m, a, g`, its moments of inertia `A, C`,
// and the air's drag coefficients `k_F, k_M` and vertical speed `w_z`: lets of the model,
// which in still air are zero (`let k_F = 0;`), so that the air's terms vanish before the
// solve.

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
