//! Profiles of the body's segments of revolution: radius along the axis, wetted area, the
//! slope at the aft end and the fineness ratio the pressure-drag tables need (docs/physics.md
//! §20.1).
//!
//! The families and their shape parameters are those of Niskanen (2009), §3.1.2 (OpenRocket's
//! "transition shapes"): conical; secant/tangent ogive (parameter 0…1, 1 = tangent);
//! ellipsoid; power series x^k (0…1); parabolic series (0…1, 1 = full parabola); Haack
//! series (0 = Von Kármán, 1/3 = LV-Haack).

use std::f64::consts::PI;

/// Profile family of a nose cone or transition (Niskanen 2009, §3.1.2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Profile {
    /// Straight cone or frustum.
    Conical,
    /// Circular-arc ogive; the parameter (0…1) is 1 for a tangent ogive, less for a secant
    /// ogive, 0 for a cone.
    Ogive(f64),
    /// Half ellipse (ellipsoid of revolution).
    Ellipsoid,
    /// Power series r ∝ (x/L)^k, parameter k in 0…1.
    Power(f64),
    /// Parabolic series r ∝ (2x/L − K (x/L)²)/(2 − K), parameter K in 0…1.
    Parabolic(f64),
    /// Haack series, parameter C: 0 Von Kármán (LD-Haack), 1/3 LV-Haack.
    Haack(f64),
}

impl Profile {
    /// The shape parameter and its admissible range, for validation.
    pub(crate) fn parameter(self) -> Option<(f64, f64, f64)> {
        match self {
            Profile::Conical | Profile::Ellipsoid => None,
            Profile::Ogive(p) | Profile::Power(p) | Profile::Parabolic(p) => Some((p, 0.0, 1.0)),
            Profile::Haack(c) => Some((c, 0.0, 1.0 / 3.0)),
        }
    }

    /// Radius at distance `x` from the pointed end of a shape of length `length` growing to
    /// `radius` (0 ≤ x ≤ length).
    #[must_use]
    pub fn radius(self, x: f64, radius: f64, length: f64) -> f64 {
        let x = x.clamp(0.0, length);
        match self {
            Profile::Conical => radius * x / length,
            Profile::Ogive(p) => {
                // A circle through the tip and the base point; for a length shorter than the
                // radius the profile is scaled from the length-equals-radius ogive.
                let (x, length) = if length < radius {
                    (x * radius / length, radius)
                } else {
                    (x, length)
                };
                if p <= 0.0 {
                    return radius * x / length;
                }
                let rho2 = (length * length + radius * radius)
                    * (((2.0 - p) * length).powi(2) + (p * radius).powi(2))
                    / (4.0 * (p * radius).powi(2));
                let centre = length / p;
                let y0 = (rho2 - centre * centre).max(0.0).sqrt();
                (rho2 - (centre - x).powi(2)).max(0.0).sqrt() - y0
            }
            Profile::Ellipsoid => {
                let s = x * radius / length;
                (2.0 * radius * s - s * s).max(0.0).sqrt()
            }
            Profile::Power(k) => {
                if k <= 0.0 {
                    if x > 0.0 { radius } else { 0.0 }
                } else {
                    radius * (x / length).powf(k)
                }
            }
            Profile::Parabolic(k) => {
                let u = x / length;
                radius * (2.0 * u - k * u * u) / (2.0 - k)
            }
            Profile::Haack(c) => {
                let theta = (1.0 - 2.0 * x / length).clamp(-1.0, 1.0).acos();
                let s = theta.sin();
                radius
                    * ((theta - 0.5 * (2.0 * theta).sin() + c * s * s * s) / PI)
                        .max(0.0)
                        .sqrt()
            }
        }
    }
}

/// Number of frustums of the wetted-area integration.
const AREA_DIVISIONS: usize = 400;

/// Radius of a segment `length` long from `fore` to `aft` at `x` aft of its forward end: the
/// profile grows from the smaller to the larger end (a nose cone when `fore` is 0, a tail
/// cone when `aft` is 0).
pub(crate) fn segment_radius(profile: Profile, x: f64, fore: f64, aft: f64, length: f64) -> f64 {
    if length <= 0.0 {
        return fore.max(aft);
    }
    if aft >= fore {
        fore + profile.radius(x, aft - fore, length)
    } else {
        aft + profile.radius(length - x, fore - aft, length)
    }
}

/// Lateral (wetted) area ∫ 2π r √(1 + r′²) dx of a segment, summed over frustums.
pub(crate) fn wetted_area(profile: Profile, fore: f64, aft: f64, length: f64) -> f64 {
    if length <= 0.0 {
        return 0.0;
    }
    let dx = length / AREA_DIVISIONS as f64;
    let mut area = 0.0;
    let mut r0 = segment_radius(profile, 0.0, fore, aft, length);
    for i in 1..=AREA_DIVISIONS {
        let r1 = segment_radius(profile, i as f64 * dx, fore, aft, length);
        area += PI * (r0 + r1) * dx.hypot(r1 - r0);
        r0 = r1;
    }
    area
}

/// Sine of the profile's angle to the axis at the aft end of a growing segment, taken over
/// the last hundredth of its length (Niskanen 2009, §3.4.2: the nose-cone angle φ of the
/// subsonic pressure-drag fit).
pub(crate) fn aft_slope_sine(profile: Profile, fore: f64, aft: f64, length: f64) -> f64 {
    let r = segment_radius(profile, 0.99 * length, fore, aft, length);
    let dr = aft - r;
    let h = dr.hypot(0.01 * length);
    if h > 0.0 { dr / h } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profiles_reach_the_base_radius() {
        for p in [
            Profile::Conical,
            Profile::Ogive(1.0),
            Profile::Ogive(0.5),
            Profile::Ellipsoid,
            Profile::Power(0.5),
            Profile::Parabolic(1.0),
            Profile::Haack(0.0),
            Profile::Haack(1.0 / 3.0),
        ] {
            assert!(p.radius(0.0, 0.05, 0.3).abs() < 1e-12, "{p:?} tip");
            assert!((p.radius(0.3, 0.05, 0.3) - 0.05).abs() < 1e-9, "{p:?} base");
        }
    }

    #[test]
    fn cone_wetted_area_is_exact() {
        let (r, l) = (0.05, 0.3);
        let exact = PI * r * r.hypot(l);
        assert!((wetted_area(Profile::Conical, 0.0, r, l) - exact).abs() < 1e-12);
        let cylinder = wetted_area(Profile::Conical, r, r, l);
        assert!((cylinder - 2.0 * PI * r * l).abs() < 1e-12);
    }

    #[test]
    fn tangent_ogive_meets_the_body_smoothly() {
        let s = aft_slope_sine(Profile::Ogive(1.0), 0.0, 0.0125, 0.1);
        assert!(s.abs() < 2e-3, "{s}");
        let cone = aft_slope_sine(Profile::Conical, 0.0, 0.05, 0.2);
        assert!((cone - 0.05 / 0.05f64.hypot(0.2)).abs() < 1e-12);
    }
}
