//! Parasitic drag of protuberances (Niskanen 2009, §3.4.5, and OpenRocket's later models;
//! docs/physics.md §20.5).
//!
//! - Launch lug (a short open tube beside the body): 0.7 (C_stag + C_base) on its annular
//!   frontal area (Niskanen eq. 3.96, after Hoerner ch. 16 for a tube in a boundary layer),
//!   plus the internal pipe-flow loss of its bore, C = f l / d from the Darcy–Weisbach
//!   pressure drop with the Swamee & Jain (1976) friction factor
//!   f = 0.25 / log₁₀²(ε/(3.7 d) + 5.74 / Re_d^0.9). No skin friction.
//! - Rail button: the drag of a cylinder normal to the flow on its side area (height times
//!   outer diameter, less the notch), at the mean speed over its height in the turbulent
//!   boundary layer of thickness δ = 0.37 x / Re_x^0.2 (Schlichting) at its position x, and
//!   referred to the free stream; the cylinder's coefficient is Hoerner's (ch. 3 and 16) as a
//!   function of Mach, times the stagnation coefficient.

use super::pressure::{base_coefficient, stagnation_coefficient};

/// A launch lug.
#[derive(Debug, Clone, PartialEq)]
pub struct LaunchLug {
    /// Its name, for error messages.
    pub name: String,
    /// Outer radius (m).
    pub outer_radius: f64,
    /// Inner radius (m), 0 for a solid guide.
    pub inner_radius: f64,
    /// Length (m).
    pub length: f64,
    /// Number of lugs.
    pub count: u32,
    /// Sand roughness of the bore (m).
    pub roughness: f64,
}

/// A set of rail buttons of one size.
#[derive(Debug, Clone, PartialEq)]
pub struct RailButtonDrag {
    /// Outer diameter (m).
    pub outer_diameter: f64,
    /// Diameter of the notch the rail slides in (m).
    pub inner_diameter: f64,
    /// Height above the body surface (m).
    pub height: f64,
    /// Height of the notch (m).
    pub inner_height: f64,
    /// Distance of each button aft of the nose tip (m).
    pub positions: Vec<f64>,
}

/// Cylinder-in-crossflow drag coefficient against the Mach number at the button.
const BUTTON_MACH: [f64; 12] = [0.0, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 1.0, 1.6, 2.0, 2.8, 100.0];
const BUTTON_CD: [f64; 12] = [
    1.2, 1.22, 1.25, 1.3, 1.4, 1.5, 1.6, 2.1, 1.5, 1.45, 1.33, 1.33,
];

fn button_cd(mach: f64) -> f64 {
    let i = BUTTON_MACH
        .partition_point(|m| *m <= mach)
        .clamp(1, BUTTON_MACH.len() - 1);
    let (m0, m1) = (BUTTON_MACH[i - 1], BUTTON_MACH[i]);
    let (c0, c1) = (BUTTON_CD[i - 1], BUTTON_CD[i]);
    c0 + (mach.clamp(m0, m1) - m0) / (m1 - m0) * (c1 - c0)
}

/// Pressure drag of `lug` at Mach `mach` and airspeed `speed` in air of kinematic viscosity
/// `nu`, referred to `reference_area`.
pub(crate) fn launch_lug(
    lug: &LaunchLug,
    mach: f64,
    speed: f64,
    nu: f64,
    reference_area: f64,
) -> f64 {
    f64::from(lug.count)
        * open_tube(
            lug.outer_radius,
            lug.inner_radius,
            lug.length,
            lug.roughness,
            mach,
            speed,
            nu,
        )
        / reference_area
}

/// `C_D A` (m²) of one open tube of radii `outer` / `inner`, `length` long, its bore of sand
/// roughness `roughness`: the bore's pipe-flow loss and 0.7 (C_stag + C_base) on the face.
pub(crate) fn open_tube(
    outer: f64,
    inner: f64,
    length: f64,
    roughness: f64,
    mach: f64,
    speed: f64,
    nu: f64,
) -> f64 {
    use std::f64::consts::PI;
    if speed <= 0.0 {
        return 0.0;
    }
    let inner_area = PI * inner * inner;
    let frontal = PI * outer * outer - inner_area;
    let bore = if inner > 0.0 {
        let d = 2.0 * inner;
        let re = speed * d / nu;
        let f = 0.25
            / (roughness / (3.7 * d) + 5.74 / re.powf(0.9))
                .log10()
                .powi(2);
        f * length / d
    } else {
        0.0
    };
    bore * inner_area + 0.7 * (stagnation_coefficient(mach) + base_coefficient(mach)) * frontal
}

/// Pressure drag of the rail buttons at Mach `mach` and airspeed `speed`.
pub(crate) fn rail_buttons(
    buttons: &RailButtonDrag,
    mach: f64,
    speed: f64,
    nu: f64,
    reference_area: f64,
) -> f64 {
    let h = buttons.height;
    let side = h * buttons.outer_diameter
        - (buttons.outer_diameter - buttons.inner_diameter) * buttons.inner_height;
    if buttons.positions.is_empty() || mach <= 0.0 || speed <= 0.0 {
        return 0.0;
    }
    let mut sum = 0.0;
    for &x in &buttons.positions {
        let re_x = speed * x / nu;
        let delta = if re_x > 0.0 {
            0.37 * x / re_x.powf(0.2)
        } else {
            0.0
        };
        let local = if h > delta {
            (h - 0.5 * delta) * mach / h
        } else {
            0.5 * h / delta * mach
        };
        sum += button_cd(local) * (local / mach).powi(2);
    }
    sum * stagnation_coefficient(mach) * side / reference_area
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cylinder_table_ends() {
        assert!((button_cd(0.0) - 1.2).abs() < 1e-15);
        assert!((button_cd(1.0) - 2.1).abs() < 1e-15);
        assert!((button_cd(500.0) - 1.33).abs() < 1e-15);
    }

    #[test]
    fn solid_lug_is_frontal_drag_only() {
        let lug = LaunchLug {
            name: "lug".into(),
            outer_radius: 0.005,
            inner_radius: 0.0,
            length: 0.03,
            count: 1,
            roughness: 60e-6,
        };
        let a = std::f64::consts::PI * 0.005 * 0.005;
        let cd = launch_lug(&lug, 0.0, 1.0, 1.5e-5, a);
        assert!((cd - 0.7 * (0.85 + 0.12)).abs() < 1e-12);
    }
}
