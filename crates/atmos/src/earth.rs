//! Earth models: reference ellipsoids (datums) and the local radius they give, Somigliana
//! normal gravity with a free-air height correction, and Earth's rotation vector.
//!
//! Sources: NIMA TR8350.2 (2000), Moritz (1980) "Geodetic Reference System 1980"; RocketPy
//! 1.13 `Environment.somigliana_gravity`, `calculate_earth_radius` and
//! `__set_earth_rotation_vector` (docs/physics.md §4.3, §4.5, §4.6).

use crate::AtmosError;
use karman_math::PhysicalConstants;

/// A geodetic datum: only its reference ellipsoid matters here.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Datum {
    /// SIRGAS 2000 (GRS 80 / WGS-84 ellipsoid), RocketPy's default.
    #[default]
    Sirgas2000,
    /// WGS 84.
    Wgs84,
    /// South American Datum 1969.
    Sad69,
    /// North American Datum 1983 (GRS 80 ellipsoid).
    Nad83,
}

impl Datum {
    /// Every datum with its canonical name.
    pub const ALL: [(Datum, &'static str); 4] = [
        (Datum::Sirgas2000, "SIRGAS2000"),
        (Datum::Wgs84, "WGS84"),
        (Datum::Sad69, "SAD69"),
        (Datum::Nad83, "NAD83"),
    ];

    /// Parses a datum name, ignoring case, spaces, dashes and underscores.
    ///
    /// # Errors
    /// [`AtmosError::UnknownName`] listing the accepted names.
    pub fn from_name(name: &str) -> Result<Datum, AtmosError> {
        let key: String = name
            .chars()
            .filter(|c| c.is_ascii_alphanumeric())
            .map(|c| c.to_ascii_uppercase())
            .collect();
        Datum::ALL
            .iter()
            .find(|(_, n)| *n == key)
            .map(|(d, _)| *d)
            .ok_or_else(|| AtmosError::UnknownName {
                what: "datum".into(),
                name: name.into(),
                known: Datum::ALL
                    .iter()
                    .map(|(_, n)| *n)
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }

    /// Semi-major axis `a` (m) and flattening `f` of the datum's ellipsoid.
    #[must_use]
    pub fn ellipsoid(self, c: &PhysicalConstants) -> (f64, f64) {
        match self {
            Datum::Sirgas2000 | Datum::Wgs84 => (c.wgs84_semi_major_axis, c.wgs84_flattening),
            Datum::Sad69 => (c.sad69_semi_major_axis, c.sad69_flattening),
            Datum::Nad83 => (c.wgs84_semi_major_axis, c.nad83_flattening),
        }
    }

    /// Geocentric radius of the ellipsoid at latitude `latitude_deg` (docs/physics.md §4.6):
    /// `R = √(((a² cos φ)² + (b² sin φ)²) / ((a cos φ)² + (b sin φ)²))`, `b = a (1 − f)`.
    #[must_use]
    pub fn radius(self, latitude_deg: f64, c: &PhysicalConstants) -> f64 {
        let (a, f) = self.ellipsoid(c);
        let b = a * (1.0 - f);
        let phi = latitude_deg.to_radians();
        let (s, co) = phi.sin_cos();
        (((co * a * a).powi(2) + (s * b * b).powi(2)) / ((co * a).powi(2) + (s * b).powi(2))).sqrt()
    }
}

/// Somigliana normal gravity (m/s²) at latitude `latitude_deg` and height `h` (m) with the
/// second-order free-air correction (NIMA TR8350.2 eq. 4-1 and 4-3; docs/physics.md §4.3):
/// `g = g_e (1 + k sin²φ)/√(1 − e² sin²φ) · [1 − (2h/a)(1 + f + m − 2f sin²φ) + 3h²/a²]`.
#[must_use]
pub fn somigliana_gravity(latitude_deg: f64, h: f64, c: &PhysicalConstants) -> f64 {
    let s2 = (latitude_deg.to_radians()).sin().powi(2);
    let g_surface = c.wgs84_equatorial_gravity * (1.0 + c.wgs84_somigliana_k * s2)
        / (1.0 - c.wgs84_eccentricity_squared * s2).sqrt();
    let a = c.wgs84_semi_major_axis;
    let f = c.wgs84_flattening;
    let correction =
        1.0 - h * 2.0 / a * (1.0 + f + c.wgs84_m - 2.0 * f * s2) + 3.0 * h * h / (a * a);
    correction * g_surface
}

/// Earth's rotation vector in the launch ENU frame, `Ω (0, cos φ, sin φ)` (docs/physics.md §4.5).
#[must_use]
pub fn earth_rotation_enu(latitude_deg: f64, c: &PhysicalConstants) -> [f64; 3] {
    let (s, co) = latitude_deg.to_radians().sin_cos();
    let w = c.earth_rotation_rate;
    [0.0, w * co, w * s]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn somigliana_matches_rocketpy_anchor() {
        // docs/physics.md §13: g(1400 m, lat 32.990254) = 9.7913331 (RocketPy 1.13).
        let g = somigliana_gravity(32.990254, 1400.0, &PhysicalConstants::SI);
        assert!((g - 9.791_333_1).abs() < 1e-7, "{g}");
    }

    #[test]
    fn rotation_matches_rocketpy_anchor() {
        // docs/physics.md §13: Ω_A = (0, 6.1163577e-05, 3.9705302e-05) at lat 32.990254.
        let w = earth_rotation_enu(32.990254, &PhysicalConstants::SI);
        assert!(w[0].abs() < 1e-20);
        assert!((w[1] - 6.116_357_7e-5).abs() < 1e-12);
        assert!((w[2] - 3.970_530_2e-5).abs() < 1e-12);
    }

    #[test]
    fn radius_spans_the_ellipsoid() {
        let c = PhysicalConstants::SI;
        let eq = Datum::Wgs84.radius(0.0, &c);
        let pole = Datum::Wgs84.radius(90.0, &c);
        assert!((eq - 6_378_137.0).abs() < 1e-6);
        assert!((pole - 6_356_752.314_245).abs() < 1e-3);
        assert!(Datum::Sad69.radius(0.0, &c) > eq);
    }

    #[test]
    fn datum_names_are_lenient() {
        assert_eq!(Datum::from_name("wgs-84").ok(), Some(Datum::Wgs84));
        assert_eq!(
            Datum::from_name("Sirgas 2000").ok(),
            Some(Datum::Sirgas2000)
        );
        assert!(Datum::from_name("ED50").is_err());
    }
}
