//! Tube fins: a ring of open tubes along the body (OpenRocket's tube fin set; Niskanen's method
//! extended in OpenRocket 23.09, `TubeFinSetCalc`; docs/physics.md §21.2), each tube
//!
//! - a normal-force slope from Ribner (1947), "The ring airfoil in nonaxial flow", J. Aero.
//!   Sci. 14(9), eq. 5: `C_Nα A = 2 π² r_i l · A′ / (1 + A′)`, `A′ = 2 A_R / π`, aspect ratio
//!   `A_R = 2 r_i / l`, acting at the quarter length (subsonic);
//! - skin friction on its outer surface outside the interstice it closes with the body, less
//!   the body surface it covers;
//! - the pressure drag of an open tube (as a launch lug, [`super::parasitic`]: the bore's
//!   Darcy–Weisbach loss and 0.7 (C_stag + C_base) on the annular face), plus
//!   (C_stag + C_base) on the interstice, the gap between the tube, its neighbour and the body
//!   seen from ahead.
//!
//! The interstice of one tube of outer radius `r_o` touching a body of radius `r_b`: with
//! `d = √((r_b + r_o)² − r_o²)` the tangent length from the body's axis, `θ₁ = acos(r_o /
//! (r_o + r_b))` and `θ₂ = π/2 − θ₁`, its area is `d r_o − r_o² θ₁ − r_b² θ₂` (the kite of
//! the two tangents less the tube's and the body's sectors).

use std::f64::consts::PI;

use super::parasitic::open_tube;
use super::pressure::{base_coefficient, stagnation_coefficient};

/// A tube fin set, for the drag estimate.
#[derive(Debug, Clone, PartialEq)]
pub struct TubeFinSetDrag {
    /// Its name, for error messages.
    pub name: String,
    /// Number of tubes.
    pub count: u32,
    /// Tube length (m).
    pub length: f64,
    /// Outer radius of a tube (m).
    pub outer_radius: f64,
    /// Inner radius of a tube (m).
    pub inner_radius: f64,
    /// Radius of the body the tubes sit on (m).
    pub body_radius: f64,
    /// Distance of the tubes' forward end aft of the nose tip (m).
    pub position: f64,
    /// Sand roughness of the tubes (m).
    pub roughness: f64,
}

/// Areas of one tube: `[interstice, wetted]` (m²).
#[must_use]
pub fn areas(t: &TubeFinSetDrag) -> [f64; 2] {
    let (ro, rb) = (t.outer_radius, t.body_radius);
    if ro <= 0.0 {
        return [0.0, 0.0];
    }
    let d = ((rb + ro).powi(2) - ro * ro).max(0.0).sqrt();
    let theta1 = (ro / (ro + rb)).clamp(-1.0, 1.0).acos();
    let theta2 = 0.5 * PI - theta1;
    let interstice = d * ro - ro * ro * theta1 - rb * rb * theta2;
    let outer = t.length * 2.0 * (PI - theta1) * ro;
    let masked = t.length * 2.0 * theta2 * rb;
    [interstice.max(0.0), (outer - masked).max(0.0)]
}

/// Normal-force slope of one tube times the area it refers to, `C_Nα A` (m² per rad).
#[must_use]
pub fn cn_alpha_area(length: f64, inner_radius: f64) -> f64 {
    if length <= 0.0 || inner_radius <= 0.0 {
        return 0.0;
    }
    let aspect = 2.0 * inner_radius / length;
    let a = 2.0 * aspect / PI;
    2.0 * (a / (1.0 + a)) * PI * PI * inner_radius * length
}

/// `C_D A` (m²) of the pressure drag of one tube of `t` whose interstice is `interstice`
/// (m²), at Mach `mach` and airspeed `speed` in air of kinematic viscosity `nu`.
pub(crate) fn pressure(t: &TubeFinSetDrag, interstice: f64, mach: f64, speed: f64, nu: f64) -> f64 {
    if speed <= 0.0 {
        return 0.0;
    }
    open_tube(
        t.outer_radius,
        t.inner_radius,
        t.length,
        t.roughness,
        mach,
        speed,
        nu,
    ) + (stagnation_coefficient(mach) + base_coefficient(mach)) * interstice
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interstice_closes_between_body_and_tube() {
        // Equal radii: tangents from the body's axis at 30° to the centre line.
        let t = TubeFinSetDrag {
            name: "tubes".into(),
            count: 6,
            length: 0.1,
            outer_radius: 0.01,
            inner_radius: 0.009,
            body_radius: 0.01,
            position: 0.5,
            roughness: 60e-6,
        };
        let [interstice, wetted] = areas(&t);
        let (r, d) = (0.01_f64, 0.01 * 3.0_f64.sqrt());
        let exact = d * r - r * r * (PI / 3.0) - r * r * (PI / 6.0);
        assert!((interstice - exact).abs() < 1e-15, "{interstice} {exact}");
        let outer = 0.1 * 2.0 * (PI - PI / 3.0) * r;
        let masked = 0.1 * 2.0 * (PI / 6.0) * r;
        assert!((wetted - (outer - masked)).abs() < 1e-15);
        // Ribner's ring: A_R = 2 r_i / l.
        let a = 2.0 * (2.0 * 0.009 / 0.1) / PI;
        let expected = 2.0 * a / (1.0 + a) * PI * PI * 0.009 * 0.1;
        assert!((cn_alpha_area(0.1, 0.009) - expected).abs() < 1e-15);
        assert!(pressure(&t, interstice, 0.3, 100.0, 1.5e-5) > 0.0);
    }
}
