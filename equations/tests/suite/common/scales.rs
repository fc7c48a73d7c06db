//! The natural scale of each derivative: how far rounding can move it in any solve of the
//! paper's implicit system (docs/physics.md §3.1 rows R1–R12, §4.1 rows S1–S12).
//!
//! Why this scale: the reference (by LU) and the generated code (by symbolic elimination) both
//! solve `M ẏ = f`. A solve that is exact for rows perturbed by ε relative to the size of
//! their terms (componentwise backward stable) is off by at most, to first order,
//! `ε · |M⁻¹| (|M|·|ẏ| + |f|)`, componentwise (Skeel's bound), where `|M|` and `|f|` hold the
//! sums of the absolute values of the terms of each entry. Example: rolling
//! `C Ω̇_z = -m a (sin ψ V̇_X - cos ψ V̇_Y)`, where near a flat disk `V̇_X, V̇_Y ~ a Ω_z Ω_x /
//! sin θ` are huge and cancel to `O(Ω_x Ω_y)`: a rounding of `V̇_X` by ε moves `Ω̇_z` by
//! `ε m a |V̇_X| / C`, and the bound says so. It is evaluated at the explicit solution with the
//! row tables written out here, so it depends on neither implementation under test.

use equations::DiskParams;
use nalgebra::{SMatrix, SVector};

type Mat = SMatrix<f64, 12, 12>;
type Vec12 = SVector<f64, 12>;

/// One implicit system: coefficients, their term sizes, and the right-hand side's term sizes.
struct Rows {
    m: Mat,
    m_abs: Mat,
    f_abs: Vec12,
}

impl Rows {
    fn new() -> Self {
        Rows {
            m: Mat::zeros(),
            m_abs: Mat::zeros(),
            f_abs: Vec12::zeros(),
        }
    }

    /// Coefficient of derivative `j` in row `i`, and the size of its terms.
    fn coef(&mut self, i: usize, j: usize, value: f64, size: f64) {
        self.m[(i, j)] = value;
        self.m_abs[(i, j)] = size;
    }

    /// A coefficient that is a single term.
    fn term(&mut self, i: usize, j: usize, value: f64) {
        self.coef(i, j, value, value.abs());
    }

    /// Skeel's bound `|M⁻¹| (|M| |ẏ| + |f|)`.
    fn bound(&self, dy: &[f64; 12]) -> [f64; 12] {
        let inverse = self.m.try_inverse().expect("the row table is regular here");
        let residual = self.m_abs * Vec12::from(dy.map(f64::abs)) + self.f_abs;
        let b = inverse.abs() * residual;
        std::array::from_fn(|i| b[i])
    }
}

/// Scales of the rolling derivatives at `y` with derivatives `dy` (rows R1–R12).
///
/// R4–R6 are taken along the frame (`V̇·e_x, V̇·e_y, V̇·e_z` as unknowns, the projections the
/// paper's R8 and R9 are written in): an orthogonal change of unknowns that leaves the physics
/// alone but keeps `Ω̇_z` (set by `V̇·e_y`) from inheriting the size of `V̇_X` and `V̇_Y`, which
/// near a flat disk are huge and cancel in that projection. The spatial `V̇` is then the frame
/// one rotated, and its scale follows through the rotation.
#[allow(non_snake_case)]
pub fn rolling(p: &DiskParams, y: &[f64; 12], dy: &[f64; 12]) -> [f64; 12] {
    let [_, _, _, V_X, V_Y, V_Z, psi, theta, _, Ox, Oy, Oz] = *y;
    let (s, c) = theta.sin_cos();
    let (sp, cp) = psi.sin_cos();
    let (a, m, g) = (p.a, p.m, p.g);
    let (ai, ci, kf, km) = (p.A(), p.C(), p.k_F(), p.k_M());
    let v_z_size = ((V_X * cp).abs() + (V_Y * sp).abs()) * s.abs() + (V_Z * c).abs();
    // Frame vectors (columns) in spatial components, docs/physics.md §1.
    let frame = nalgebra::Matrix3::new(cp * c, -sp, cp * s, sp * c, cp, sp * s, -s, 0.0, c);
    let accel = frame.transpose() * nalgebra::Vector3::new(dy[3], dy[4], dy[5]);
    let mut frame_dy = *dy;
    frame_dy[3..6].copy_from_slice(accel.as_slice());
    let mut r = Rows::new();
    // R1–R3: der(X) = V_X, ...
    for (i, v) in [V_X, V_Y, V_Z].into_iter().enumerate() {
        r.term(i, i, 1.0);
        r.f_abs[i] = v.abs();
    }
    // R4–R6 along e_x, e_y, e_z: V̇ + Ω̇ × a e_x + ω × (Ω × a e_x) = 0.
    r.term(3, 3, 1.0);
    r.term(3, 7, -a * Oy);
    r.term(3, 6, -a * c * Oz);
    r.term(4, 4, 1.0);
    r.term(4, 11, a);
    r.term(4, 6, -a * s * Oy);
    r.term(5, 5, 1.0);
    r.term(5, 10, -a);
    r.term(5, 6, -a * s * Oz);
    // R7
    r.term(6, 9, ai);
    r.term(6, 6, -ai * Oy * c);
    r.f_abs[6] = (ci * Oy * Oz).abs() + (km * Ox).abs();
    // R8: m a (V̇·e_z) is its bracket.
    r.term(7, 10, ai);
    r.term(7, 6, ai * Ox * c);
    r.term(7, 5, m * a);
    r.f_abs[7] = (ci * Ox * Oz).abs()
        + (m * g * a * c).abs()
        + kf * a * (v_z_size + p.w_z.abs())
        + (km * Oy).abs();
    // R9: its bracket is -(V̇·e_y).
    r.term(8, 11, ci);
    r.term(8, 4, -m * a);
    // R10–R12
    r.term(9, 6, s);
    r.f_abs[9] = Ox.abs();
    r.term(10, 7, 1.0);
    r.f_abs[10] = Oy.abs();
    r.term(11, 6, c);
    r.term(11, 8, 1.0);
    r.f_abs[11] = Oz.abs();
    let mut b = r.bound(&frame_dy);
    // Rotate the frame accelerations' scales back to V̇_X, V̇_Y, V̇_Z (plus the rotation's own
    // rounding, the size of its terms).
    let sizes = nalgebra::Vector3::new(
        b[3] + accel.x.abs(),
        b[4] + accel.y.abs(),
        b[5] + accel.z.abs(),
    );
    let spatial = frame.abs() * sizes;
    b[3..6].copy_from_slice(spatial.as_slice());
    b
}

/// Scales of the polar sliding derivatives (rows S1–S12; `dy` holds `α̇`).
#[allow(non_snake_case)]
pub fn sliding_polar(p: &DiskParams, y: &[f64; 12], dy: &[f64; 12]) -> [f64; 12] {
    let [_, _, _, v_C, alpha, V_Z, psi, theta, _, Ox, Oy, Oz] = *y;
    let (s, c) = theta.sin_cos();
    let (sp, cp) = psi.sin_cos();
    let (S, K) = (alpha - psi).sin_cos();
    let (sa, ca) = alpha.sin_cos();
    let (a, m, g, mu) = (p.a, p.m, p.g, p.mu_d);
    let (ai, ci, kf, km) = (p.A(), p.C(), p.k_F(), p.k_M());
    let k = mu * K * s + c;
    let k_size = (mu * K * s).abs() + c.abs();
    let v_z_size = (v_C * s * K).abs() + (a * Oy * s * s).abs() + (V_Z * c).abs();
    let air = kf * (v_z_size + p.w_z.abs());
    let mut r = Rows::new();
    // S1–S3
    r.term(0, 0, 1.0);
    r.f_abs[0] = (v_C * ca).abs() + a * ((Oy * cp * s).abs() + (Oz * sp).abs());
    r.term(1, 1, 1.0);
    r.f_abs[1] = (v_C * sa).abs() + a * ((Oy * sp * s).abs() + (Oz * cp).abs());
    r.term(2, 2, 1.0);
    r.f_abs[2] = V_Z.abs();
    // S4
    r.term(3, 4, m * v_C);
    r.coef(
        3,
        6,
        m * a * (-Oy * K * s + Oz * S),
        m * a * ((Oy * K * s).abs() + (Oz * S).abs()),
    );
    r.term(3, 7, m * a * Oy * S * c);
    r.term(3, 10, m * a * S * s);
    r.term(3, 11, m * a * K);
    r.f_abs[3] = air * (s * S).abs();
    // S5
    r.term(4, 3, -m);
    r.term(4, 5, -mu * m);
    r.coef(
        4,
        6,
        m * a * (Oy * S * s + Oz * K),
        m * a * ((Oy * S * s).abs() + (Oz * K).abs()),
    );
    r.term(4, 7, m * a * Oy * K * c);
    r.term(4, 10, m * a * K * s);
    r.term(4, 11, -m * a * S);
    r.f_abs[4] = mu * m * g.abs() + air * ((mu * c).abs() + (K * s).abs());
    // S6 (table form, with der(psi))
    r.term(5, 9, ai);
    r.term(5, 6, -ai * Oy * c);
    r.f_abs[5] = (ci * Oy * Oz).abs() + (km * Ox).abs();
    // S7
    r.coef(6, 5, m * a * k, m * a * k_size);
    r.term(6, 10, ai);
    r.term(6, 6, ai * Ox * c);
    r.f_abs[6] = (ci * Ox * Oz).abs()
        + m * g.abs() * a * k_size
        + a * air * (c * k_size).abs()
        + (km * Oy).abs();
    // S8
    r.term(7, 11, ci);
    r.term(7, 5, -mu * m * a * S);
    r.f_abs[7] = mu * a * (m * g.abs() + air * c.abs()) * S.abs();
    // S9–S11
    r.term(8, 6, s);
    r.f_abs[8] = Ox.abs();
    r.term(9, 7, 1.0);
    r.f_abs[9] = Oy.abs();
    r.term(10, 6, c);
    r.term(10, 8, 1.0);
    r.f_abs[10] = Oz.abs();
    // S12
    r.term(11, 5, 1.0);
    r.term(11, 7, a * Oy * s);
    r.term(11, 10, -a * c);
    r.bound(dy)
}

/// Scales of the Cartesian sliding derivatives: the polar scales mapped through
/// `u̇ = v̇_C e_s + v_C α̇ e_s⊥` (`polar_y`, `polar_dy` are the same state and derivatives in
/// the polar chart).
pub fn sliding_cartesian(p: &DiskParams, polar_y: &[f64; 12], polar_dy: &[f64; 12]) -> [f64; 12] {
    let mut s = sliding_polar(p, polar_y, polar_dy);
    let pair = s[3] + polar_y[3].abs() * s[4];
    s[3] = pair;
    s[4] = pair;
    s
}

/// The scale each comparison uses: the larger of the row bound above and the running rounding
/// bound of the explicit form (which carries the rounding of the inputs, e.g. of
/// `cos(α - ψ)` when it multiplies a large rate).
pub fn rolling_full(p: &DiskParams, y: &[f64; 12]) -> [f64; 12] {
    let e = super::explicit::rolling::<super::tracked::Tracked>(p, y);
    let rows = rolling(p, y, &e.dy.map(|x| x.v));
    std::array::from_fn(|i| rows[i].max(e.dy[i].scale))
}

/// As [`rolling_full`], polar sliding.
pub fn sliding_polar_full(p: &DiskParams, y: &[f64; 12]) -> [f64; 12] {
    let e = super::explicit::sliding_polar::<super::tracked::Tracked>(p, y);
    let rows = sliding_polar(p, y, &e.dy.map(|x| x.v));
    std::array::from_fn(|i| rows[i].max(e.dy[i].scale))
}

/// As [`rolling_full`], Cartesian sliding, at the Cartesian state `y`.
pub fn sliding_cartesian_full(p: &DiskParams, y: &[f64; 12]) -> [f64; 12] {
    let e = super::explicit::sliding_cartesian::<super::tracked::Tracked>(p, y);
    let polar_y = super::cartesian_to_polar(y);
    let polar_dy = super::explicit::sliding_polar::<f64>(p, &polar_y).dy;
    let rows = sliding_cartesian(p, &polar_y, &polar_dy);
    std::array::from_fn(|i| rows[i].max(e.dy[i].scale))
}
