//! Tube fins: `n` open tubes side by side around the body (OpenRocket's tube fin set;
//! docs/physics.md §21.1).
//!
//! Each tube's normal-force slope is Ribner's ring airfoil (1947, "The ring airfoil in
//! nonaxial flow", J. Aero. Sci. 14(9), eq. 5), as OpenRocket applies it to one tube,
//! `C_Nα A = 2 π² r_i l · A′ / (1 + A′)` with `A′ = 2 A_R / π` and `A_R = 2 r_i / l`, so that
//! the set's slope on the reference area π r_b² of the body radius is
//! `CNα = n · C_Nα A / (π r_b²)`, constant in Mach, at the quarter length aft of the tubes'
//! forward end (OpenRocket's subsonic CP). No roll forcing (tubes have no cant) and, as for
//! noses and tails, no roll damping. Their drag is [`crate::drag::tube_fins`].

use std::f64::consts::PI;

use crate::drag::tube_fins::cn_alpha_area;
use crate::error::{AirframeError, positive};

/// A tube fin set.
#[derive(Debug, Clone, PartialEq)]
pub struct TubeFinsSpec {
    /// Number of tubes.
    pub n: u32,
    /// Tube length (m).
    pub length: f64,
    /// Outer radius of a tube (m).
    pub outer_radius: f64,
    /// Inner radius of a tube (m).
    pub inner_radius: f64,
    /// Body radius at the tubes (m); `None` = the rocket radius.
    pub radius: Option<f64>,
}

/// A resolved tube fin set: `(body radius, CNα on π r_b², CP aft of the forward end)`.
pub(crate) fn build(
    name: &str,
    spec: &TubeFinsSpec,
    rocket_radius: f64,
) -> Result<(f64, f64, f64), AirframeError> {
    let length = positive(name, "length", spec.length)?;
    let outer = positive(name, "outer_radius", spec.outer_radius)?;
    let inner = positive(name, "inner_radius", spec.inner_radius)?;
    let body = positive(name, "radius", spec.radius.unwrap_or(rocket_radius))?;
    if spec.n == 0 {
        return Err(AirframeError::Geometry {
            component: name.to_owned(),
            reason: "a tube fin set needs at least one tube".to_owned(),
        });
    }
    if inner >= outer {
        return Err(AirframeError::Geometry {
            component: name.to_owned(),
            reason: format!(
                "inner radius {inner} m is not smaller than the outer radius {outer} m"
            ),
        });
    }
    let cn_alpha = f64::from(spec.n) * cn_alpha_area(length, inner) / (PI * body * body);
    Ok((body, cn_alpha, 0.25 * length))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn six_tubes_on_the_body_reference_area() {
        let spec = TubeFinsSpec {
            n: 6,
            length: 0.08,
            outer_radius: 0.012,
            inner_radius: 0.0115,
            radius: None,
        };
        let (body, cn_alpha, cp) = build("tubes", &spec, 0.012).expect("valid");
        assert!((body - 0.012).abs() < 1e-15);
        assert!((cp - 0.02).abs() < 1e-15);
        let per_tube = cn_alpha_area(0.08, 0.0115);
        assert!((cn_alpha - 6.0 * per_tube / (PI * 0.012 * 0.012)).abs() < 1e-12);
        let solid = TubeFinsSpec {
            inner_radius: 0.012,
            ..spec
        };
        assert!(build("tubes", &solid, 0.012).is_err());
    }
}
