//! The centre of pressure at an angle of attack (docs/physics.md §20.6), as OpenRocket's extended
//! Barrowman method gives it (Niskanen 2009, §3.2.3, after Galejs 1999, "Wind instability — what
//! Barrowman left out"): besides the linear Barrowman terms, every segment of the body adds a
//! normal force from its planform,
//!
//! `C_N,lift = K · (A_plan / A_ref) · sin² α`,   K = 1.1,
//!
//! acting at the planform's centroid, where `A_plan = ∫ 2 r dx` is the body's silhouette.
//! The rocket's CP is the mean of the component CPs weighted by `C_N / α`: the fin sets by
//! their `C_Nα`, nose cones and transitions by their Barrowman `C_Nα · sin α / α`, and each
//! body segment by `K (A_plan / A_ref) sin α · sin α / α`. At α → 0 the lift term vanishes
//! and the CP is Barrowman's; at a few degrees it moves the CP forward by a few percent of
//! the body length on a short rocket. Below Mach 0.05 and above 45° OpenRocket scales the
//! lift term by `(M / 0.05)²` (a turning rocket near apogee); that is kept.
//!
//! karman's flight model keeps the linear CP (RocketPy's convention); this is the CP the
//! estimate reports, for comparing with OpenRocket and for reading the design at rod exit.

use std::f64::consts::{FRAC_PI_4, PI};

use super::DragGeometry;
use super::shape::segment_radius;
use crate::Rocket;
use crate::surfaces::Geometry;

/// Galejs' body-lift coefficient K (Niskanen 2009, eq. 3.26).
pub const BODY_LIFT_K: f64 = 1.1;

/// Strips of the planform integration per segment.
const PLANFORM_DIVISIONS: usize = 200;

/// The planform of the body, precomputed per segment.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyLift {
    reference_area: f64,
    /// Per segment: planform area (m²) and its centroid aft of the nose tip (m).
    planforms: Vec<[f64; 2]>,
}

impl BodyLift {
    /// The planforms of `geometry`'s body segments, laid end to end from the nose tip.
    #[must_use]
    pub fn new(geometry: &DragGeometry) -> BodyLift {
        let mut start = 0.0;
        let mut planforms = Vec::with_capacity(geometry.body.len());
        for s in &geometry.body {
            let [area, moment] = planform(s.profile, s.fore_radius, s.aft_radius, s.length);
            if area > 0.0 {
                planforms.push([area, start + moment / area]);
            }
            start += s.length;
        }
        // Each pod's planform counts once per pod (OpenRocket sums the body lift of every
        // instance), at its own axial place.
        for pod in &geometry.pods {
            let mut start = pod.position;
            for s in &pod.body {
                let [area, moment] = planform(s.profile, s.fore_radius, s.aft_radius, s.length);
                if area > 0.0 {
                    planforms.push([area * f64::from(pod.count), start + moment / area]);
                }
                start += s.length;
            }
        }
        BodyLift {
            reference_area: PI * geometry.reference_radius * geometry.reference_radius,
            planforms,
        }
    }

    /// The body's silhouette area (m²) and its centroid aft of the nose tip (m).
    #[must_use]
    pub fn planform(&self) -> [f64; 2] {
        let area: f64 = self.planforms.iter().map(|p| p[0]).sum();
        let moment: f64 = self.planforms.iter().map(|p| p[0] * p[1]).sum();
        [area, if area > 0.0 { moment / area } else { 0.0 }]
    }

    /// `(Σ C_N/α, Σ (C_N/α) · x)` of the body lift at angle of attack `alpha` (rad) and
    /// `mach`, on the reference area of the geometry, x aft of the nose tip.
    #[must_use]
    pub fn weights(&self, alpha: f64, mach: f64) -> [f64; 2] {
        let mul = if mach < 0.05 && alpha > FRAC_PI_4 {
            (mach / 0.05).powi(2)
        } else {
            1.0
        };
        let sin = alpha.sin();
        let per_area = mul * BODY_LIFT_K * sin * sinc(alpha) / self.reference_area;
        self.planforms.iter().fold([0.0, 0.0], |[w, m], &[a, x]| {
            [w + per_area * a, m + per_area * a * x]
        })
    }

    /// OpenRocket's CP of `rocket` at angle of attack `alpha` (rad) and `mach`, aft of the
    /// nose tip (m), the tip being at `tip` in the rocket's user coordinates, with the flow's
    /// lateral component at roll angle `roll` (rad, in the fins' angular positions): the
    /// surfaces' Barrowman terms (nose cones and tails times `sin α / α`, fin sets of one or
    /// two fins times their [`FinAerodynamics::roll_factor`]) with the body lift, all on the
    /// rocket's reference area (the geometry's reference radius is the rocket's).
    ///
    /// [`FinAerodynamics::roll_factor`]: crate::FinAerodynamics::roll_factor
    #[must_use]
    pub fn cp_at_angle(&self, rocket: &Rocket, tip: f64, alpha: f64, mach: f64, roll: f64) -> f64 {
        let csys = rocket.csys();
        let area = rocket.reference_area();
        let [mut weight, mut moment] = self.weights(alpha, mach);
        for s in rocket.surfaces() {
            let body = matches!(s.geometry, Geometry::Nose { .. } | Geometry::Tail { .. });
            let k = s.reference_area / area * if body { sinc(alpha) } else { 1.0 };
            let roll_factor = s.fin_aerodynamics().map_or(1.0, |f| match s.pod {
                None => f.roll_factor(roll),
                Some(pod) => pod.mean_roll_factor(f, roll),
            });
            let w = k * roll_factor * s.cn_alpha(mach);
            weight += w;
            moment += w * csys * (tip - s.cp_user(csys));
        }
        moment / weight
    }

    /// The flow's roll angle (rad) at which `rocket`'s CP lies furthest forward, OpenRocket's
    /// "worst" CP (its `getWorstCP`: Barrowman's CP at α = 0 and Mach 0.3 over the roll angles
    /// `2π k / 360`, the first of the most forward). OpenRocket's launch code means to roll
    /// the rocket on the rod so that the wind comes from this angle (24.12 starts it at 0
    /// instead: `karman_openrocket::StoredFlight::rod_exit_roll`); it differs from 0 only when a set of
    /// one or two fins makes the CP depend on the roll angle. Angles whose CPs differ by no
    /// more than rounding (a billionth of the CP) are a tie, kept at the first: a
    /// symmetric set (two canards at 90° and 270°) has its worst CP at 0 and at π exactly,
    /// and which of the two the last bits favour must not decide the roll.
    #[must_use]
    pub fn worst_roll_angle(&self, rocket: &Rocket, tip: f64) -> f64 {
        let mut worst = (f64::INFINITY, 0.0);
        for k in 0..WORST_ROLL_DIVISIONS {
            let roll = 2.0 * PI * f64::from(k) / f64::from(WORST_ROLL_DIVISIONS);
            let cp = self.cp_at_angle(rocket, tip, 0.0, WORST_ROLL_MACH, roll);
            if cp < worst.0 - WORST_ROLL_TIE * worst.0.abs().max(1.0) {
                worst = (cp, roll);
            }
        }
        worst.1
    }
}

/// CPs (m) closer than this share of their value are the same worst CP (rounding).
const WORST_ROLL_TIE: f64 = 1e-9;

/// Roll angles OpenRocket tries for its worst CP.
const WORST_ROLL_DIVISIONS: u32 = 360;

/// Mach number of OpenRocket's default flight conditions, at which it looks for the worst CP.
const WORST_ROLL_MACH: f64 = 0.3;

/// `sin x / x`, 1 at 0.
fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-6 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}

/// `[∫ 2 r dx, ∫ 2 r x dx]` over a segment (x aft of its forward end), by the midpoint rule.
fn planform(profile: super::Profile, fore: f64, aft: f64, length: f64) -> [f64; 2] {
    if length <= 0.0 {
        return [0.0, 0.0];
    }
    let dx = length / PLANFORM_DIVISIONS as f64;
    (0..PLANFORM_DIVISIONS).fold([0.0, 0.0], |[a, m], i| {
        let x = (i as f64 + 0.5) * dx;
        let strip = 2.0 * segment_radius(profile, x, fore, aft, length) * dx;
        [a + strip, m + strip * x]
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drag::{BodySegment, Profile};

    fn segment(length: f64, fore: f64, aft: f64, profile: Profile) -> BodySegment {
        BodySegment {
            name: "s".into(),
            length,
            fore_radius: fore,
            aft_radius: aft,
            profile,
            roughness: 0.0,
            drag_override: None,
        }
    }

    #[test]
    fn cone_and_tube_planforms_are_exact() {
        let geometry = DragGeometry {
            reference_radius: 0.05,
            body: vec![
                segment(0.3, 0.0, 0.05, Profile::Conical),
                segment(1.0, 0.05, 0.05, Profile::Conical),
            ],
            fins: Vec::new(),
            tube_fins: Vec::new(),
            launch_lugs: Vec::new(),
            rail_buttons: None,
            nozzle_exit_radius: 0.0,
            pods: Vec::new(),
        };
        let lift = BodyLift::new(&geometry);
        // Triangle 0.3 × 0.1 (centroid 2/3 of the way aft) and rectangle 1.0 × 0.1.
        let [a, x] = lift.planform();
        let exact_a = 0.5 * 0.3 * 0.1 + 0.1;
        let exact_x = (0.015 * 0.2 + 0.1 * 0.8) / exact_a;
        assert!((a - exact_a).abs() < 1e-9, "{a}");
        assert!((x - exact_x).abs() < 1e-6, "{x}");
        // The lift grows as sin² α: C_N = α · weight.
        let area = PI * 0.05 * 0.05;
        let alpha: f64 = 0.1;
        let [w, m] = lift.weights(alpha, 0.3);
        assert!((w * alpha - BODY_LIFT_K * exact_a / area * alpha.sin().powi(2)).abs() < 1e-9);
        assert!((m / w - exact_x).abs() < 1e-6);
        let [w0, m0] = lift.weights(0.0, 0.3);
        assert!(w0.abs() < 1e-15 && m0.abs() < 1e-15, "{w0} {m0}");
        // Two pods, each a 0.2 m tube of radius 0.01 starting 0.5 m aft of the tip: twice
        // its rectangle, centred at 0.6 m.
        let mut podded = geometry.clone();
        podded.pods.push(crate::drag::PodDrag {
            name: "pods".into(),
            count: 2,
            position: 0.5,
            body: vec![segment(0.2, 0.01, 0.01, Profile::Conical)],
        });
        let [pa, px] = BodyLift::new(&podded).planform();
        let pod_area = 2.0 * 0.2 * 0.02;
        assert!((pa - (exact_a + pod_area)).abs() < 1e-9, "{pa}");
        assert!((px - (exact_a * exact_x + pod_area * 0.6) / (exact_a + pod_area)).abs() < 1e-6);
        // Turning slowly (M < 0.05, α > 45°) the lift is scaled by (M / 0.05)².
        let [slow, _] = lift.weights(1.0, 0.025);
        let [fast, _] = lift.weights(1.0, 0.05);
        assert!((slow - 0.25 * fast).abs() < 1e-12);
    }
}
