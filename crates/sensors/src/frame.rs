//! The small amount of rotation algebra the sensors need, written as RocketPy 1.13's
//! `mathutils/vector_matrix.py` evaluates it (`Matrix.transformation` of a normalised
//! quaternion, `Matrix.transformation_euler_angles` of a 3-1-3 sequence, products in the same
//! order), so that a noise-free reading equals RocketPy's to round-off (docs/physics.md §2.3,
//! §29.2).

/// A 3-vector.
pub type Vec3 = [f64; 3];
/// A 3×3 matrix, rows first.
pub type Mat3 = [[f64; 3]; 3];

/// `a × b`.
#[inline]
pub(crate) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a + b`.
#[inline]
pub(crate) fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `m v`.
#[inline]
pub(crate) fn mul(m: &Mat3, v: Vec3) -> Vec3 {
    std::array::from_fn(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2])
}

/// `a b`.
#[inline]
pub(crate) fn matmul(a: &Mat3, b: &Mat3) -> Mat3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j])
    })
}

/// `mᵀ`.
#[inline]
pub(crate) fn transpose(m: &Mat3) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| m[j][i]))
}

/// The rotation matrix (body → inertial) of the quaternion `e = (e0, e1, e2, e3)`, normalised
/// first (a zero quaternion is the identity), as RocketPy's `Matrix.transformation`.
#[must_use]
pub fn rotation(e: [f64; 4]) -> Mat3 {
    let norm = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3]).sqrt();
    let [w, x, y, z] = if norm == 0.0 {
        [1.0, 0.0, 0.0, 0.0]
    } else {
        [e[0] / norm, e[1] / norm, e[2] / norm, e[3] / norm]
    };
    let (x2, y2, z2) = (x * x, y * y, z * z);
    let (wx, wy, wz) = (w * x, w * y, w * z);
    let (xy, xz, yz) = (x * y, x * z, y * z);
    [
        [1.0 - 2.0 * (y2 + z2), 2.0 * (xy - wz), 2.0 * (xz + wy)],
        [2.0 * (xy + wz), 1.0 - 2.0 * (x2 + z2), 2.0 * (yz - wx)],
        [2.0 * (xz - wy), 2.0 * (yz + wx), 1.0 - 2.0 * (x2 + y2)],
    ]
}

/// The quaternion of the intrinsic 3-1-3 Euler angles `(φ, θ, ψ)`, rad (RocketPy's
/// `tools.euler313_to_quaternions`).
#[must_use]
pub fn euler313_to_quaternion(phi: f64, theta: f64, psi: f64) -> [f64; 4] {
    let (sphi, cphi) = (phi / 2.0).sin_cos();
    let (stheta, ctheta) = (theta / 2.0).sin_cos();
    let (spsi, cpsi) = (psi / 2.0).sin_cos();
    [
        cphi * ctheta * cpsi - sphi * ctheta * spsi,
        cphi * cpsi * stheta + sphi * stheta * spsi,
        cphi * stheta * spsi - sphi * cpsi * stheta,
        cphi * ctheta * spsi + ctheta * cpsi * sphi,
    ]
}

/// `x` rounded to 12 decimals (RocketPy's `Matrix.round(12)` of a sensor's rotation, which
/// makes the matrices of right angles exact): `round(x·10¹²)/10¹²` with ties to even, as
/// Python's `round`; it can differ from Python's correctly rounded decimal result by one unit
/// in the last place.
#[inline]
fn round12(x: f64) -> f64 {
    (x * 1e12).round_ties_even() / 1e12
}

/// The sensor-to-body rotation of a sensor mounted with the 3-1-3 Euler angles
/// `orientation_deg` (roll, pitch, roll 2; degrees), as RocketPy's
/// `InertialSensor.rotation_sensor_to_body`.
#[must_use]
pub fn sensor_to_body(orientation_deg: [f64; 3]) -> Mat3 {
    let [a, b, c] = orientation_deg.map(f64::to_radians);
    rotation(euler313_to_quaternion(a, b, c)).map(|row| row.map(round12))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_zero_orientation_is_the_identity_and_right_angles_are_exact() {
        let bits = |m: Mat3| m.map(|row| row.map(f64::to_bits));
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert_eq!(bits(sensor_to_body([0.0; 3])), bits(identity));
        // 90° about z: x → y (−0 and 0 alike).
        let m = sensor_to_body([90.0, 0.0, 0.0]);
        let x = mul(&m, [1.0, 0.0, 0.0]).map(|v| v + 0.0);
        assert_eq!(x.map(f64::to_bits), [0.0, 1.0, 0.0].map(f64::to_bits));
    }

    #[test]
    fn rotations_are_orthonormal() {
        let m = rotation([0.3, -0.2, 0.5, 0.7]);
        let p = matmul(&m, &transpose(&m));
        for (i, row) in p.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((v - expected).abs() < 1e-15, "{p:?}");
            }
        }
        let z = cross([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert_eq!(z.map(f64::to_bits), [0.0, 0.0, 1.0].map(f64::to_bits));
    }
}
