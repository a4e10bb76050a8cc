//! Conical tails and transitions (boat-tails, shoulders).
//!
//! `CNα = 2[(r_bottom/r_ref)² − (r_top/r_ref)²]` and the conical-frustum CP
//! `x_cp = (L/3)[1 + (1 − q)/(1 − q²)]`, `q = r_top/r_bottom` (Barrowman 1967, §3.2;
//! docs/physics.md §7.4). No Mach dependence, as in RocketPy.

use crate::error::{AirframeError, non_negative, positive};

/// A conical tail or transition (RocketPy `Rocket.add_tail`).
#[derive(Debug, Clone, PartialEq)]
pub struct TailSpec {
    /// Radius at the forward end (m).
    pub top_radius: f64,
    /// Radius at the aft end (m).
    pub bottom_radius: f64,
    /// Axial length (m).
    pub length: f64,
    /// Reference radius (m); `None` = the rocket radius.
    pub radius: Option<f64>,
}

/// A resolved tail.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Tail {
    pub top_radius: f64,
    pub bottom_radius: f64,
    pub length: f64,
    pub reference_radius: f64,
    pub cn_alpha: f64,
    pub cp_local: f64,
}

/// Builds a tail.
pub(crate) fn build(
    name: &str,
    spec: &TailSpec,
    rocket_radius: f64,
) -> Result<Tail, AirframeError> {
    let top = non_negative(name, "top_radius", spec.top_radius)?;
    // A bottom radius of 0 closes the tail to a point (a pod's tail cone).
    let bottom = non_negative(name, "bottom_radius", spec.bottom_radius)?;
    let length = positive(name, "length", spec.length)?;
    let reference_radius = positive(name, "radius", spec.radius.unwrap_or(rocket_radius))?;
    if top <= 0.0 && bottom <= 0.0 {
        return Err(AirframeError::Geometry {
            component: name.to_owned(),
            reason: "top and bottom radii are both 0".to_owned(),
        });
    }
    let q = top / bottom;
    if bottom > 0.0 && (1.0 - q).abs() < 1e-9 {
        return Err(AirframeError::Geometry {
            component: name.to_owned(),
            reason: format!(
                "top and bottom radii are equal ({top} m): a straight tube is not a tail"
            ),
        });
    }
    let cn_alpha = 2.0 * ((bottom / reference_radius).powi(2) - (top / reference_radius).powi(2));
    // A cone closing to a point (q → ∞): the frustum's limit L/3, Barrowman's
    // `(L A_aft − V)/(A_aft − A_fore)` with A_aft = 0.
    let cp_local = if bottom > 0.0 {
        (length / 3.0) * (1.0 + (1.0 - q) / (1.0 - q * q))
    } else {
        length / 3.0
    };
    Ok(Tail {
        top_radius: top,
        bottom_radius: bottom,
        length,
        reference_radius,
        cn_alpha,
        cp_local,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calisto_tail_matches_reference() {
        // validation/calisto/reference.json: tail cn_alpha_mach0 −1.061442122884246,
        // cp_m −1.2227868411214953 with the top at −1.194656 (tail_to_nose).
        let spec = TailSpec {
            top_radius: 0.0635,
            bottom_radius: 0.0435,
            length: 0.06,
            radius: None,
        };
        let t = build("tail", &spec, 0.0635).expect("valid tail");
        assert!((t.cn_alpha - (-1.061_442_122_884_246)).abs() < 1e-13);
        assert!((-1.194_656 - t.cp_local - (-1.222_786_841_121_495_3)).abs() < 1e-13);
    }

    #[test]
    fn straight_and_negative_tails_are_errors() {
        let ok = TailSpec {
            top_radius: 0.06,
            bottom_radius: 0.04,
            length: 0.1,
            radius: None,
        };
        let mut s = ok.clone();
        s.bottom_radius = 0.06;
        assert!(build("t", &s, 0.06).is_err());
        let mut s = ok.clone();
        s.length = -0.1;
        assert!(build("t", &s, 0.06).is_err());
        let mut s = ok.clone();
        s.top_radius = -0.01;
        assert!(build("t", &s, 0.06).is_err());
        let mut s = ok.clone();
        (s.top_radius, s.bottom_radius) = (0.0, 0.0);
        assert!(build("t", &s, 0.06).is_err());
        // A cone closing to a point: −2 (r/r_ref)², CP a third of its length aft.
        let mut s = ok;
        s.bottom_radius = 0.0;
        let t = build("t", &s, 0.06).expect("a closing cone");
        assert!((t.cn_alpha + 2.0).abs() < 1e-15);
        assert!((t.cp_local - 0.1 / 3.0).abs() < 1e-15);
    }
}
