//! The natural scale of each derivative: the size of the terms of the implicit row that
//! defines it (EQUATIONS.md §3 rows R1–R12, §4 rows S1–S12), divided by the size of its own
//! coefficient.
//!
//! Why this scale: any implementation that solves the implicit system (the reference by LU,
//! the generated code by symbolic elimination) inherits its sensitivity. A derivative defined
//! by a row whose terms cancel can only be known to ε times those terms. Example: rolling
//! `C Ω̇_z = -m a (sin ψ V̇_X - cos ψ V̇_Y)`, where near a flat disk `V̇_X, V̇_Y ~ a Ω_z Ω_x /
//! sin θ` are huge and cancel to `O(Ω_x Ω_y)`: a rounding of `V̇_X` by ε moves `Ω̇_z` by
//! `ε m a |V̇_X| / C`. The scale is evaluated at the explicit solution, so it does not depend
//! on either implementation under test.

/// Row scales of the rolling derivatives at `y` with derivatives `dy` (EQUATIONS.md §3).
#[allow(non_snake_case)]
pub fn rolling(p: &equations::DiskParams, y: &[f64; 12], dy: &[f64; 12]) -> [f64; 12] {
    let [_, _, _, V_X, V_Y, V_Z, psi, theta, _, Ox, Oy, Oz] = *y;
    let [_, _, _, VX_d, VY_d, VZ_d, psi_d, th_d, _, _, Oy_d, Oz_d] = *dy;
    let (s, c) = theta.sin_cos();
    let (sp, cp) = psi.sin_cos();
    let (a, m, g) = (p.a, p.m, p.g);
    let (ai, ci, kf, km) = (p.A(), p.C(), p.k_F(), p.k_M());
    let v_z = (V_X * cp + V_Y * sp) * s + V_Z * c;
    [
        V_X.abs(),
        V_Y.abs(),
        V_Z.abs(),
        a * ((s * cp * Oy_d).abs()
            + (sp * Oz_d).abs()
            + (c * cp * Oy * th_d).abs()
            + ((Oz * cp).abs() + (Oy * s * sp).abs()) * psi_d.abs()),
        a * ((s * sp * Oy_d).abs()
            + (cp * Oz_d).abs()
            + (c * sp * Oy * th_d).abs()
            + ((Oy * s * cp).abs() + (Oz * sp).abs()) * psi_d.abs()),
        a * ((c * Oy_d).abs() + (s * Oy * th_d).abs()),
        Ox.abs() / s.abs(),
        Oy.abs(),
        (c * psi_d).abs() + Oz.abs(),
        ((ai * Oy * c * psi_d).abs() + (ci * Oy * Oz).abs() + (km * Ox).abs()) / ai,
        ((ai * Ox * c * psi_d).abs()
            + m * a * ((s * cp * VX_d).abs() + (s * sp * VY_d).abs() + (c * VZ_d).abs())
            + (ci * Ox * Oz).abs()
            + (m * g * a * c).abs()
            + (kf * a * (v_z - p.w_z)).abs()
            + (km * Oy).abs())
            / ai,
        m * a * ((sp * VX_d).abs() + (cp * VY_d).abs()) / ci,
    ]
}

/// Row scales of the polar sliding derivatives (EQUATIONS.md §4; `dy` holds `α̇`).
#[allow(non_snake_case)]
pub fn sliding_polar(p: &equations::DiskParams, y: &[f64; 12], dy: &[f64; 12]) -> [f64; 12] {
    let [_, _, _, v_C, alpha, V_Z, psi, theta, _, Ox, Oy, Oz] = *y;
    let [_, _, _, _, _, VZ_d, psi_d, th_d, _, _, Oy_d, Oz_d] = *dy;
    let (s, c) = theta.sin_cos();
    let (sp, cp) = psi.sin_cos();
    let (S, K) = (alpha - psi).sin_cos();
    let k = p.mu_d * K * s + c;
    let (a, m, g, mu) = (p.a, p.m, p.g, p.mu_d);
    let (ai, ci, kf, km) = (p.A(), p.C(), p.k_F(), p.k_M());
    let v_z = -v_C * s * K + a * Oy * s * s + V_Z * c;
    let air = (kf * (v_z - p.w_z)).abs();
    // S4 divided by m v_C: the terms of w = v_C α̇, over |v_C|.
    let w_terms = a
        * (((Oy * K * s).abs() + (Oz * S).abs()) * psi_d.abs()
            + (Oy * S * c * th_d).abs()
            + (S * s * Oy_d).abs()
            + (K * Oz_d).abs())
        + air / m * (s * S).abs();
    [
        (v_C * alpha.cos()).abs() + a * ((Oy * cp * s).abs() + (Oz * sp).abs()),
        (v_C * alpha.sin()).abs() + a * ((Oy * sp * s).abs() + (Oz * cp).abs()),
        V_Z.abs(),
        mu * VZ_d.abs()
            + a * (((Oy * S * s).abs() + (Oz * K).abs()) * psi_d.abs()
                + (Oy * K * c * th_d).abs()
                + (K * s * Oy_d).abs()
                + (S * Oz_d).abs())
            + mu * g
            + air / m * (mu * c.abs() + (K * s).abs()),
        w_terms / v_C.abs(),
        a * ((Oy * s * th_d).abs() + (c * Oy_d).abs()),
        Ox.abs() / s.abs(),
        Oy.abs(),
        (c * psi_d).abs() + Oz.abs(),
        ((ai * Oy * c * psi_d).abs() + (ci * Oy * Oz).abs() + (km * Ox).abs()) / ai,
        ((m * a * k * VZ_d).abs()
            + (ai * Ox * c * psi_d).abs()
            + (ci * Ox * Oz).abs()
            + (m * g * a * k).abs()
            + a * air * (c * k).abs()
            + (km * Oy).abs())
            / ai,
        mu * a * ((m * S * VZ_d).abs() + (m * g * S).abs() + air * (c * S).abs()) / ci,
    ]
}

/// Row scales of the Cartesian sliding derivatives at the Cartesian state `y`: the polar
/// scales mapped through `u̇ = v̇_C e_s + v_C α̇ e_s⊥` (`polar_y`, `polar_dy` are the same
/// state and derivatives in the polar chart).
pub fn sliding_cartesian(
    p: &equations::DiskParams,
    polar_y: &[f64; 12],
    polar_dy: &[f64; 12],
) -> [f64; 12] {
    let mut s = sliding_polar(p, polar_y, polar_dy);
    let pair = s[3] + polar_y[3].abs() * s[4];
    s[3] = pair;
    s[4] = pair;
    s
}
