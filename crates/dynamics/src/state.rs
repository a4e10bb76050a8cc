//! The 13-component flight state and the small fixed-size linear algebra the equations of
//! motion need (docs/physics.md §2–§3).
//!
//! `u = [x, y, z, vx, vy, vz, e0, e1, e2, e3, ω1, ω2, ω3]`: position and velocity of the centre
//! of dry mass in the East-North-Up launch frame (z above sea level), the scalar-first attitude
//! quaternion (body → inertial, never renormalised in the state) and the body-frame angular
//! velocity.

/// The flight state vector (docs/physics.md §3); its components are named by [`X`]…[`W3`].
pub type State = [f64; 13];

/// Index of the position's east component `x`, m, in a [`State`].
pub const X: usize = 0;
/// Index of the position's north component `y`, m.
pub const Y: usize = 1;
/// Index of the height `z`, m above sea level.
pub const Z: usize = 2;
/// Index of the velocity's east component `v_x`, m/s.
pub const VX: usize = 3;
/// Index of the velocity's north component `v_y`, m/s.
pub const VY: usize = 4;
/// Index of the vertical velocity `v_z`, m/s.
pub const VZ: usize = 5;
/// Index of the attitude quaternion's scalar part `e0` (`e1`…`e3` follow).
pub const E0: usize = 6;
/// Index of the body-frame angular velocity's first component `ω1`, rad/s (`ω2`, `ω3`
/// follow).
pub const W1: usize = 10;
/// Index of the body-frame angular velocity's third component `ω3` (roll), rad/s.
pub const W3: usize = 12;

/// The position `(x, y, z)` of a state, m.
#[inline]
#[must_use]
pub fn position(u: &State) -> Vec3 {
    [u[X], u[Y], u[Z]]
}

/// The velocity `(v_x, v_y, v_z)` of a state, m/s.
#[inline]
#[must_use]
pub fn velocity(u: &State) -> Vec3 {
    [u[VX], u[VY], u[VZ]]
}

/// The body-frame angular velocity `(ω1, ω2, ω3)` of a state, rad/s.
#[inline]
#[must_use]
pub fn angular_velocity(u: &State) -> Vec3 {
    [u[W1], u[W1 + 1], u[W3]]
}

/// A state derivative from its parts: the velocity (the position's rate), the acceleration,
/// the quaternion's rate and the angular acceleration.
#[inline]
#[must_use]
pub fn derivative(v: Vec3, v_dot: Vec3, e_dot: [f64; 4], w_dot: Vec3) -> State {
    [
        v[0], v[1], v[2], v_dot[0], v_dot[1], v_dot[2], e_dot[0], e_dot[1], e_dot[2], e_dot[3],
        w_dot[0], w_dot[1], w_dot[2],
    ]
}

/// A 3-vector.
pub type Vec3 = [f64; 3];

/// A 3×3 matrix, row-major.
pub type Mat3 = [[f64; 3]; 3];

/// A 3-vector with the operators of the equations of motion: `+`, `−`, scaling by `f64`
/// (`s * a`), [`Vector::cross`], and a matrix product ([`Vector::by`], [`Vector::by_t`]).
/// Each operator performs exactly the floating-point operations of the function of the same
/// name ([`add`], [`sub`], [`scale`], [`cross`], [`mat_vec`], [`mat_t_vec`]), in the same
/// order: an expression written with them gives the same bits.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(transparent)]
pub struct Vector(pub Vec3);

impl Vector {
    /// Cross product `self × b`.
    #[inline]
    #[must_use]
    pub fn cross(self, b: Self) -> Self {
        Self(cross(self.0, b.0))
    }

    /// The product `M self`.
    #[inline]
    #[must_use]
    pub fn by(self, m: &Mat3) -> Self {
        Self(mat_vec(m, self.0))
    }

    /// The product `Mᵀ self`.
    #[inline]
    #[must_use]
    pub fn by_t(self, m: &Mat3) -> Self {
        Self(mat_t_vec(m, self.0))
    }
}

impl From<Vec3> for Vector {
    #[inline]
    fn from(a: Vec3) -> Self {
        Self(a)
    }
}

impl std::ops::Add for Vector {
    type Output = Self;
    #[inline]
    fn add(self, b: Self) -> Self {
        Self(add(self.0, b.0))
    }
}

impl std::ops::Sub for Vector {
    type Output = Self;
    #[inline]
    fn sub(self, b: Self) -> Self {
        Self(sub(self.0, b.0))
    }
}

impl std::ops::Mul<Vector> for f64 {
    type Output = Vector;
    #[inline]
    fn mul(self, a: Vector) -> Vector {
        Vector(scale(self, a.0))
    }
}

/// Cross product `a × b`.
#[inline]
#[must_use]
pub fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Dot product.
#[inline]
#[must_use]
pub fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Euclidean norm.
#[inline]
#[must_use]
pub fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}

/// `a + b`.
#[inline]
#[must_use]
pub fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a − b`.
#[inline]
#[must_use]
pub fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `s · a`.
#[inline]
#[must_use]
pub fn scale(s: f64, a: Vec3) -> Vec3 {
    [s * a[0], s * a[1], s * a[2]]
}

/// Matrix–vector product `M v`.
#[inline]
#[must_use]
pub fn mat_vec(m: &Mat3, v: Vec3) -> Vec3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}

/// Transposed product `Mᵀ v`.
#[inline]
#[must_use]
pub fn mat_t_vec(m: &Mat3, v: Vec3) -> Vec3 {
    [
        m[0][0] * v[0] + m[1][0] * v[1] + m[2][0] * v[2],
        m[0][1] * v[0] + m[1][1] * v[1] + m[2][1] * v[2],
        m[0][2] * v[0] + m[1][2] * v[1] + m[2][2] * v[2],
    ]
}

/// Symmetric tensor from RocketPy's component order `(I11, I22, I33, I12, I13, I23)`.
#[inline]
#[must_use]
pub fn tensor(c: [f64; 6]) -> Mat3 {
    [[c[0], c[3], c[4]], [c[3], c[1], c[5]], [c[4], c[5], c[2]]]
}

/// Inverse of a 3×3 matrix by the adjugate formula (as RocketPy's `Matrix.inverse`);
/// `None` when singular.
#[inline]
#[must_use]
pub fn inverse(m: &Mat3) -> Option<Mat3> {
    let [[a, b, c], [d, e, f], [g, h, i]] = *m;
    let co00 = e * i - f * h;
    let co01 = f * g - d * i;
    let co02 = d * h - e * g;
    let det = a * co00 + b * co01 + c * co02;
    if det.abs() <= f64::MIN_POSITIVE || !det.is_finite() {
        return None;
    }
    let r = 1.0 / det;
    Some([
        [co00 * r, (c * h - b * i) * r, (b * f - c * e) * r],
        [co01 * r, (a * i - c * g) * r, (c * d - a * f) * r],
        [co02 * r, (b * g - a * h) * r, (a * e - b * d) * r],
    ])
}

/// Rotation matrix body → inertial of the normalised quaternion `ê = e/|e|` (docs/physics.md §2.3).
/// Every entry is quadratic in `ê`, `êi·êj = ei·ej/|e|²`, so the matrix is formed from the raw
/// components with the one factor `2/|e|²`: no square root, one division.
#[inline]
#[must_use]
pub fn rotation(e: [f64; 4]) -> Mat3 {
    let [e0, e1, e2, e3] = e;
    let s = 2.0 / ((e0 * e0 + e1 * e1) + (e2 * e2 + e3 * e3));
    [
        [
            1.0 - s * (e2 * e2 + e3 * e3),
            s * (e1 * e2 - e0 * e3),
            s * (e1 * e3 + e0 * e2),
        ],
        [
            s * (e1 * e2 + e0 * e3),
            1.0 - s * (e1 * e1 + e3 * e3),
            s * (e2 * e3 - e0 * e1),
        ],
        [
            s * (e1 * e3 - e0 * e2),
            s * (e2 * e3 + e0 * e1),
            1.0 - s * (e1 * e1 + e2 * e2),
        ],
    ]
}

/// Quaternion kinematics `ė = ½ e ⊗ (0, ω)` with the raw (unnormalised) quaternion
/// (docs/physics.md §2.3; Baruh, *Analytical Dynamics*, §7.7).
#[inline]
#[must_use]
pub fn quaternion_rate(e: [f64; 4], w: Vec3) -> [f64; 4] {
    [
        0.5 * (-w[0] * e[1] - w[1] * e[2] - w[2] * e[3]),
        0.5 * (w[0] * e[0] + w[2] * e[2] - w[1] * e[3]),
        0.5 * (w[1] * e[0] - w[2] * e[1] + w[0] * e[3]),
        0.5 * (w[2] * e[0] + w[1] * e[1] - w[0] * e[2]),
    ]
}

/// Quaternion of the 3-1-3 Euler sequence (precession `psi`, nutation `theta`, spin `phi`,
/// radians), scalar first (docs/physics.md §2.4).
#[must_use]
pub fn euler313_to_quaternion(phi: f64, theta: f64, psi: f64) -> [f64; 4] {
    let (st, ct) = (0.5 * theta).sin_cos();
    [
        ct * (0.5 * (phi + psi)).cos(),
        st * (0.5 * (phi - psi)).cos(),
        st * (0.5 * (psi - phi)).sin(),
        ct * (0.5 * (phi + psi)).sin(),
    ]
}

/// Splits a state into its quaternion.
#[inline]
#[must_use]
pub fn quaternion(u: &State) -> [f64; 4] {
    [u[6], u[7], u[8], u[9]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn initial_attitude_matches_physics_example() {
        // docs/physics.md §2.4: i = 85°, h = 0°, rail-button angle 45° (measured in RocketPy).
        let e = euler313_to_quaternion(45f64.to_radians(), -5f64.to_radians(), 0.0);
        let expected = [0.9230002, -0.0402991, 0.0166924, 0.3823192];
        for (a, b) in e.iter().zip(expected) {
            assert!((a - b).abs() < 1e-7, "{e:?}");
        }
        let k = rotation(e);
        // Rocket axis = third column = (cos i sin h, cos i cos h, sin i).
        assert!(k[0][2].abs() < 1e-12);
        assert!((k[1][2] - 5f64.to_radians().sin()).abs() < 1e-12);
        assert!((k[2][2] - 85f64.to_radians().sin()).abs() < 1e-12);
    }

    #[test]
    fn rotation_is_orthonormal_even_for_unnormalised_quaternions() {
        let k = rotation([1.3, -0.2, 0.5, 0.7]);
        for i in 0..3 {
            for j in 0..3 {
                let d = dot([k[0][i], k[1][i], k[2][i]], [k[0][j], k[1][j], k[2][j]]);
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((d - expected).abs() < 1e-14);
            }
        }
        let v = [0.3, -1.2, 2.0];
        let back = mat_t_vec(&k, mat_vec(&k, v));
        assert!(norm(sub(back, v)) < 1e-14);
    }

    #[test]
    #[allow(clippy::needless_range_loop)] // column extraction reads clearer with indices
    fn inverse_times_matrix_is_identity() {
        let m = tensor([9.6, 9.6, 0.038, 0.01, -0.02, 0.003]);
        let inv = inverse(&m).unwrap();
        for i in 0..3 {
            let col = mat_vec(&inv, [m[0][i], m[1][i], m[2][i]]);
            for (j, c) in col.iter().enumerate() {
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((c - expected).abs() < 1e-12);
            }
        }
        assert!(inverse(&[[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]]).is_none());
    }

    #[test]
    fn quaternion_rate_preserves_norm() {
        let e = [0.9, 0.1, -0.3, 0.2];
        let de = quaternion_rate(e, [0.4, -1.0, 3.0]);
        let d_norm2: f64 = e.iter().zip(de).map(|(a, b)| a * b).sum();
        assert!(d_norm2.abs() < 1e-15);
    }
}
