//! The paper's closed forms, each by name.
//!
//! These are the numbers a reader can check by hand: the normal force of eqs. (13)–(16), the
//! energy balance, the steady motions and the rolling-consistent initial velocities (Box 2).
//! The tests hold every model to them, so they are written directly from the paper and
//! docs/physics.md (§3, §5, §8, §9), not derived from any model in this crate.

use crate::DiskParams;
use nalgebra::Vector3;

/// Angular velocity of the disk in the moving frame `(e_x, e_y, e_z)` (rad/s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyRates {
    /// About the diameter through the contact point.
    pub omega_x: f64,
    /// About the horizontal diameter (`= θ̇`).
    pub omega_y: f64,
    /// About the disk normal.
    pub omega_z: f64,
}

/// Why a closed form has no value at the given arguments.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum FormulaError {
    /// The inclination makes the formula divide by `sin θ = 0` (or leaves `(0, π)`).
    #[error("inclination theta = {theta} is outside (0, pi): the formula divides by sin(theta)")]
    FlatDisk {
        /// The inclination given.
        theta: f64,
    },
    /// A steady circle needs a nonzero precession rate.
    #[error("precession rate p = {precession} must be nonzero for a steady circle")]
    ZeroPrecession {
        /// The precession rate given.
        precession: f64,
    },
    /// Spinning in place needs gravity pulling down.
    #[error("spinning in place needs g > 0, got g = {g}")]
    NoGravity {
        /// The gravitational acceleration.
        g: f64,
    },
}

fn sin_theta_checked(theta: f64) -> Result<f64, FormulaError> {
    let s = theta.sin();
    if theta > 0.0 && theta < std::f64::consts::PI && s > 0.0 {
        Ok(s)
    } else {
        Err(FormulaError::FlatDisk { theta })
    }
}

/// Eq. (14), rolling: `α1 = a cos θ [(C + m a²) Ω_x Ω_z - m g a cos θ] / (g (m a² + A))
/// - a Ω_y² sin θ / g + 1`.
pub fn alpha1(p: &DiskParams, theta: f64, w: &BodyRates) -> f64 {
    let (s, c) = theta.sin_cos();
    let ma2 = p.m * p.a * p.a;
    p.a * c / (p.g * (ma2 + p.A())) * ((p.C() + ma2) * w.omega_x * w.omega_z - p.m * p.g * p.a * c)
        - p.a * w.omega_y * w.omega_y * s / p.g
        + 1.0
}

/// Eq. (14), rolling: `α2 = a A Ω_x² cos² θ / (g (m a² + A))`.
pub fn alpha2(p: &DiskParams, theta: f64, w: &BodyRates) -> f64 {
    let c = theta.cos();
    p.a * p.A() * w.omega_x * w.omega_x * c * c / (p.g * (p.m * p.a * p.a + p.A()))
}

/// Eq. (16): `β0 = m a² cos θ [μ_d cos(α - ψ) sin θ + cos θ] + A`, the pivot of the sliding
/// solve (it vanishes only in the Painlevé-type regime).
pub fn beta0(p: &DiskParams, theta: f64, alpha_minus_psi: f64) -> f64 {
    let (s, c) = theta.sin_cos();
    p.m * p.a * p.a * c * (p.mu_d * alpha_minus_psi.cos() * s + c) + p.A()
}

/// Eq. (16), sliding: `α3 = A/β0 [1 - a Ω_y² sin θ / g] + a C Ω_x Ω_z cos θ / (g β0)`.
pub fn alpha3(p: &DiskParams, theta: f64, alpha_minus_psi: f64, w: &BodyRates) -> f64 {
    let (s, c) = theta.sin_cos();
    let b = beta0(p, theta, alpha_minus_psi);
    p.A() / b * (1.0 - p.a * w.omega_y * w.omega_y * s / p.g)
        + p.a * p.C() * w.omega_x * w.omega_z * c / (p.g * b)
}

/// Eq. (16), sliding: `α4 = a A Ω_x² cos² θ / (g β0)`.
pub fn alpha4(p: &DiskParams, theta: f64, alpha_minus_psi: f64, w: &BodyRates) -> f64 {
    let c = theta.cos();
    p.a * p.A() * w.omega_x * w.omega_x * c * c / (p.g * beta0(p, theta, alpha_minus_psi))
}

/// Eq. (13): `N / (m g) = α1 + α2 / sin θ` while rolling (`μ_a = 0`).
pub fn rolling_normal_force_ratio(
    p: &DiskParams,
    theta: f64,
    w: &BodyRates,
) -> Result<f64, FormulaError> {
    let s = sin_theta_checked(theta)?;
    Ok(alpha1(p, theta, w) + alpha2(p, theta, w) / s)
}

/// Eq. (15): `N / (m g) = α3 + α4 / sin θ` while sliding (`μ_a = 0`).
pub fn sliding_normal_force_ratio(
    p: &DiskParams,
    theta: f64,
    alpha_minus_psi: f64,
    w: &BodyRates,
) -> Result<f64, FormulaError> {
    let s = sin_theta_checked(theta)?;
    Ok(alpha3(p, theta, alpha_minus_psi, w) + alpha4(p, theta, alpha_minus_psi, w) / s)
}

/// Total energy `½ m |V|² + ½ A (Ω_x² + Ω_y²) + ½ C Ω_z² + m g Z` (J).
pub fn total_energy(p: &DiskParams, centre_velocity: &Vector3<f64>, w: &BodyRates, z: f64) -> f64 {
    0.5 * p.m * centre_velocity.norm_squared()
        + 0.5 * p.A() * (w.omega_x * w.omega_x + w.omega_y * w.omega_y)
        + 0.5 * p.C() * w.omega_z * w.omega_z
        + p.m * p.g * z
}

/// Power of the friction force while sliding, `P_f = -T v_C` (W); zero while rolling.
pub fn friction_power(friction: f64, slip_speed: f64) -> f64 {
    -friction * slip_speed
}

/// Normal velocity of the centre, `v_z = V · e_z` with
/// `e_z = (cos ψ sin θ, sin ψ sin θ, cos θ)` (m/s).
pub fn normal_velocity(psi: f64, theta: f64, centre_velocity: &Vector3<f64>) -> f64 {
    let (sp, cp) = psi.sin_cos();
    let (st, ct) = theta.sin_cos();
    (centre_velocity.x * cp + centre_velocity.y * sp) * st + centre_velocity.z * ct
}

/// Power of the air loads of one face,
/// `P_a = -k_F (v_z - w_z) v_z - k_M (Ω_x² + Ω_y²)` (W).
pub fn air_power(p: &DiskParams, normal_velocity: f64, w: &BodyRates) -> f64 {
    -p.k_F() * (normal_velocity - p.w_z) * normal_velocity
        - p.k_M() * (w.omega_x * w.omega_x + w.omega_y * w.omega_y)
}

/// Precession rate `|p|` of a disk spinning in place (centre fixed, `Ω_z = 0`) at inclination
/// `θ0`: `p² = m g a / (A sin θ0)` (rad/s). Both signs of `p` are steady.
pub fn spinning_in_place_rate(p: &DiskParams, theta0: f64) -> Result<f64, FormulaError> {
    let s = sin_theta_checked(theta0)?;
    if p.g.is_nan() || p.g <= 0.0 {
        return Err(FormulaError::NoGravity { g: p.g });
    }
    Ok((p.m * p.g * p.a / (p.A() * s)).sqrt())
}

/// Spin `Ω_z` of steady rolling on a circle at inclination `θ0` and precession rate `p`:
/// `Ω_z = (A p² cos θ0 - m g a cot θ0) / (p (C + m a²))` (rad/s).
pub fn steady_circle_spin(
    p: &DiskParams,
    theta0: f64,
    precession: f64,
) -> Result<f64, FormulaError> {
    let s = sin_theta_checked(theta0)?;
    if precession == 0.0 || !precession.is_finite() {
        return Err(FormulaError::ZeroPrecession { precession });
    }
    let c = theta0.cos();
    Ok(
        (p.A() * precession * precession * c - p.m * p.g * p.a * c / s)
            / (precession * (p.C() + p.m * p.a * p.a)),
    )
}

/// Upright rolling (`θ = π/2`, spin `n` about the normal) is stable iff
/// `n² > m g a A / (C (C + m a²))` (`= g / (3a)` for the thin disk); returns that bound on `n²`.
pub fn upright_stability_threshold(p: &DiskParams) -> f64 {
    let ma2 = p.m * p.a * p.a;
    ma2 * p.g / p.a * p.A() / (p.C() * (p.C() + ma2))
}

/// The centre's height and velocity that make a state rolling-consistent (Box 2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RollingConsistent {
    /// `Z = a sin θ` (m).
    pub z: f64,
    /// `V = (a(Ω_y cos ψ sin θ + Ω_z sin ψ), a(Ω_y sin ψ sin θ - Ω_z cos ψ), a Ω_y cos θ)` (m/s).
    pub velocity: Vector3<f64>,
}

/// Box 2: the contact point on the floor and at rest.
pub fn rolling_consistent(
    p: &DiskParams,
    psi: f64,
    theta: f64,
    w: &BodyRates,
) -> RollingConsistent {
    let (sp, cp) = psi.sin_cos();
    let (st, ct) = theta.sin_cos();
    RollingConsistent {
        z: p.a * st,
        velocity: Vector3::new(
            p.a * (w.omega_y * cp * st + w.omega_z * sp),
            p.a * (w.omega_y * sp * st - w.omega_z * cp),
            p.a * w.omega_y * ct,
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spinning_in_place_matches_the_table() {
        // docs/physics.md §9: |p| = 44.0, 102, 187 rad/s at θ0 = 0.57, 0.1, 0.03.
        let p = DiskParams::paper();
        for (theta0, expected, tol) in [(0.57, 44.0, 0.05), (0.1, 102.3, 0.05), (0.03, 186.7, 0.05)]
        {
            let rate = spinning_in_place_rate(&p, theta0).unwrap();
            assert!((rate - expected).abs() < tol, "{theta0}: {rate}");
        }
        assert_eq!(
            spinning_in_place_rate(&p, 0.0),
            Err(FormulaError::FlatDisk { theta: 0.0 })
        );
    }

    #[test]
    fn upright_threshold_is_g_over_3a_for_the_thin_disk() {
        let p = DiskParams::paper();
        let n2 = upright_stability_threshold(&p);
        assert!((n2 - p.g / (3.0 * p.a)).abs() < 1e-12 * n2);
        // docs/physics.md §9: n > 9.33 rad/s for the paper's disk.
        assert!((n2.sqrt() - 9.33).abs() < 5e-3);
    }

    #[test]
    fn steady_circle_reduces_to_spinning_in_place_when_spin_vanishes() {
        let p = DiskParams::paper();
        let theta0 = 0.4;
        let rate = spinning_in_place_rate(&p, theta0).unwrap();
        let spin = steady_circle_spin(&p, theta0, rate).unwrap();
        assert!(spin.abs() < 1e-12 * rate);
        assert!(matches!(
            steady_circle_spin(&p, theta0, 0.0),
            Err(FormulaError::ZeroPrecession { .. })
        ));
    }

    #[test]
    fn sliding_formulas_reduce_to_rolling_ones_without_friction_and_with_no_spin_coupling() {
        // With μ_d = 0, β0 = A + m a² cos² θ; α3 + α4/s and α1 + α2/s differ only through
        // the denominators, so at Ω = 0 both give N/mg = A / β0 resp. 1 - m a² c² / (m a² + A).
        let p = DiskParams {
            mu_d: 0.0,
            ..DiskParams::paper()
        };
        let w = BodyRates {
            omega_x: 0.0,
            omega_y: 0.0,
            omega_z: 0.0,
        };
        let theta: f64 = 0.7;
        let c = theta.cos();
        let ma2 = p.m * p.a * p.a;
        let rolling = rolling_normal_force_ratio(&p, theta, &w).unwrap();
        let sliding = sliding_normal_force_ratio(&p, theta, 1.0, &w).unwrap();
        assert!((rolling - (1.0 - ma2 * c * c / (ma2 + p.A()))).abs() < 1e-14);
        assert!((sliding - p.A() / (p.A() + ma2 * c * c)).abs() < 1e-14);
    }
}
