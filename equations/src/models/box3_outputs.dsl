// The outputs of Box 3 in the polar slip variables (docs/physics.md §4.1): the contact force,
// the centre's velocity, the energy and its loss to friction, and the residuals of the
// contact. Included by the smooth model `sliding` (box3_sliding.rs) and by the test model of
// the paper's misprinted row 8, which must be held to the same outputs.
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
