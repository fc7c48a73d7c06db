//! The reduced explicit forms of docs/physics.md (§3.2 for rolling, §4.2 lines 1–8 for sliding),
//! transcribed as printed: a third implementation, independent of the reference's vector
//! assembly and of the generated code's symbolic solve.

use super::tracked::Scalar;
use equations::DiskParams;

/// Parameters lifted into the arithmetic `T`.
#[allow(non_snake_case)]
struct P<T> {
    m: T,
    a: T,
    g: T,
    mu_d: T,
    w_z: T,
    A: T,
    C: T,
    k_F: T,
    k_M: T,
    ma2: T,
}

#[allow(non_snake_case)]
fn lift<T: Scalar>(p: &DiskParams) -> P<T> {
    let (m, a) = (T::exact(p.m), T::exact(p.a));
    let mu_a = T::exact(p.mu_a);
    let pi = T::exact(std::f64::consts::PI);
    P {
        m,
        a,
        g: T::exact(p.g),
        mu_d: T::exact(p.mu_d),
        w_z: T::exact(p.w_z),
        A: T::exact(0.25) * m * a * a,
        C: T::exact(0.5) * m * a * a,
        k_F: mu_a * pi * a * a,
        k_M: T::exact(0.25) * mu_a * pi * a * a * a * a,
        ma2: m * a * a,
    }
}

/// The state in the arithmetic `T`: `ψ`, `φ` and (polar sliding) `α` as angles, the rest exact.
fn lift_state<T: Scalar>(y: &[f64; 12], polar_slip: bool) -> [T; 12] {
    std::array::from_fn(|i| match i {
        6 | 8 => T::angle(y[i]),
        4 if polar_slip => T::angle(y[i]),
        _ => T::exact(y[i]),
    })
}

/// Derivatives and contact forces of one mode, by name.
pub struct Explicit<T> {
    pub dy: [T; 12],
    pub n: T,
    pub r_x: T,
    pub r_y: T,
    pub v_x: T,
    pub v_y: T,
}

/// docs/physics.md §3.2, reduced explicit form, then R4–R6 and the secondary outputs.
#[allow(non_snake_case)]
pub fn rolling<T: Scalar>(p: &DiskParams, y: &[f64; 12]) -> Explicit<T> {
    let q = lift::<T>(p);
    let y = lift_state::<T>(y, false);
    let [_X, _Y, _Z, V_X, V_Y, V_Z, psi, theta, _phi, Ox, Oy, Oz] = y;
    let (s, c) = (theta.sin(), theta.cos());
    let (sp, cp) = (psi.sin(), psi.cos());
    let v_z = (V_X * cp + V_Y * sp) * s + V_Z * c;
    let psi_d = -Ox / s;
    let th_d = Oy;
    let phi_d = Oz + Ox * c / s;
    let Ox_d = -Ox * Oy * c / s - q.C / q.A * Oy * Oz - q.k_M / q.A * Ox;
    let Oy_d = (q.A * Ox * Ox * c / s + (q.C + q.ma2) * Ox * Oz
        - q.m * q.g * q.a * c
        - q.k_F * q.a * (v_z - q.w_z)
        - q.k_M * Oy)
        / (q.A + q.ma2);
    let Oz_d = -q.ma2 * Ox * Oy / (q.C + q.ma2);
    let VX_d =
        q.a * (s * cp * Oy_d + sp * Oz_d + c * cp * Oy * th_d + (Oz * cp - Oy * s * sp) * psi_d);
    let VY_d =
        q.a * (s * sp * Oy_d - cp * Oz_d + c * sp * Oy * th_d + (Oy * s * cp + Oz * sp) * psi_d);
    let VZ_d = q.a * (c * Oy_d - s * Oy * th_d);
    let air = q.k_F * (v_z - q.w_z);
    Explicit {
        dy: [
            V_X, V_Y, V_Z, VX_d, VY_d, VZ_d, psi_d, th_d, phi_d, Ox_d, Oy_d, Oz_d,
        ],
        n: q.m * (VZ_d + q.g) + air * c,
        r_x: q.m * VX_d + air * s * cp,
        r_y: q.m * VY_d + air * s * sp,
        v_x: V_X,
        v_y: V_Y,
    }
}

/// The pieces of the sliding solve that are regular at `v_C = 0`.
pub struct SlidingExplicit<T> {
    /// Derivatives, with `w = v_C α̇` in the `alpha` slot.
    pub with_w: Explicit<T>,
    /// `w = v_C α̇`.
    pub w: T,
}

/// docs/physics.md §4.2, lines 1–8 (polar chart), with `w` kept apart.
#[allow(non_snake_case)]
pub fn sliding<T: Scalar>(p: &DiskParams, y: &[f64; 12]) -> SlidingExplicit<T> {
    let q = lift::<T>(p);
    let y = lift_state::<T>(y, true);
    let [_X, _Y, _Z, v_C, alpha, V_Z, psi, theta, _phi, Ox, Oy, Oz] = y;
    let (s, c) = (theta.sin(), theta.cos());
    let (sp, cp) = (psi.sin(), psi.cos());
    let (S, K) = ((alpha - psi).sin(), (alpha - psi).cos());
    let k = q.mu_d * K * s + c;
    let V_X = -v_C * alpha.cos() + q.a * (Oy * cp * s + Oz * sp);
    let V_Y = -v_C * alpha.sin() + q.a * (Oy * sp * s - Oz * cp);
    // docs/physics.md §4.1: the normal velocity of the centre while sliding.
    let v_z = -v_C * s * K + q.a * Oy * s * s + V_Z * c;
    let air = q.k_F * (v_z - q.w_z);
    // 1.
    let psi_d = -Ox / s;
    let th_d = Oy;
    let phi_d = Oz + Ox * c / s;
    // 2.
    let Ox_d = -Ox * Oy * c / s - q.C / q.A * Oy * Oz - q.k_M / q.A * Ox;
    // 3.
    let beta0 = q.A + q.ma2 * c * k;
    let Oy_d = (q.A * Ox * Ox * c / s + q.C * Ox * Oz
        - q.m * q.g * q.a * k
        - q.a * air * c * k
        - q.k_M * Oy
        + q.ma2 * k * s * Oy * Oy)
        / beta0;
    // 4.
    let VZ_d = q.a * (c * Oy_d - s * Oy * Oy);
    let n = q.m * (VZ_d + q.g) + air * c;
    // 5.
    let Oz_d = q.a * q.mu_d * n * S / q.C;
    // 6.
    let vC_d = -q.mu_d * n / q.m
        + q.a * ((Oy * S * s + Oz * K) * psi_d + Oy * Oy * K * c + K * s * Oy_d - S * Oz_d)
        + air / q.m * K * s;
    // 7.
    let w = -q.a * ((-Oy * K * s + Oz * S) * psi_d + Oy * Oy * S * c + S * s * Oy_d + K * Oz_d)
        - air / q.m * s * S;
    // 8.
    let t = q.mu_d * n;
    SlidingExplicit {
        with_w: Explicit {
            dy: [
                V_X, V_Y, V_Z, vC_d, w, VZ_d, psi_d, th_d, phi_d, Ox_d, Oy_d, Oz_d,
            ],
            n,
            r_x: t * alpha.cos(),
            r_y: t * alpha.sin(),
            v_x: V_X,
            v_y: V_Y,
        },
        w,
    }
}

/// The polar sliding derivatives (`α̇ = w / v_C`).
pub fn sliding_polar<T: Scalar>(p: &DiskParams, y: &[f64; 12]) -> Explicit<T> {
    let SlidingExplicit { mut with_w, w } = sliding::<T>(p, y);
    with_w.dy[4] = w / T::exact(y[3]);
    with_w
}

/// The Cartesian sliding derivatives at a Cartesian state, through the polar chart:
/// `u̇ = v̇_C e_s + w e_s⊥` with `e_s = -(cos α, sin α)`, `e_s⊥ = (sin α, -cos α)`.
pub fn sliding_cartesian<T: Scalar>(p: &DiskParams, y: &[f64; 12]) -> Explicit<T> {
    let (ux, uy) = (y[3], y[4]);
    let mut polar = *y;
    polar[3] = ux.hypot(uy);
    polar[4] = (-uy).atan2(-ux);
    let alpha = T::angle(polar[4]);
    let SlidingExplicit { mut with_w, w } = sliding::<T>(p, &polar);
    let vc_d = with_w.dy[3];
    let (sa, ca) = (alpha.sin(), alpha.cos());
    with_w.dy[3] = -vc_d * ca + w * sa;
    with_w.dy[4] = -vc_d * sa - w * ca;
    with_w
}
