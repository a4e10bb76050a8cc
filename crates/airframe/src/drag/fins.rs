//! Fin-set drag terms (Niskanen 2009, §3.4.1 and §3.4.3, after Hoerner 1965 ch. 6 and 16;
//! docs/physics.md §20.4):
//! the planform quantities of one fin from its outline, and the pressure drag of its leading
//! and trailing edges.
//!
//! Leading edge, per unit frontal area t·s of one fin and times cos²Λ_L (Λ_L the leading-edge
//! sweep): rounded (and airfoil) edges (1 − M²)^−0.417 − 1 below Mach 0.9,
//! 1 − 1.785 (M − 0.9) to Mach 1, 1.214 − 0.502/M² + 0.1095/M⁴ above (Niskanen eq. 3.89);
//! a square edge takes the stagnation coefficient. Trailing edge: a square edge takes the base
//! coefficient, a rounded edge half of it, an airfoil none.

use super::pressure::{base_coefficient, stagnation_coefficient};

/// Cross-section of a fin (the shape of its leading and trailing edges).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FinCrossSection {
    /// Flat plate with square edges (OpenRocket's default).
    #[default]
    Square,
    /// Flat plate with rounded edges.
    Rounded,
    /// Airfoil: rounded leading edge, sharp trailing edge.
    Airfoil,
}

/// Number of spanwise strips of the mean-chord and sweep integrals.
const STRIPS: usize = 200;

/// Planform quantities of one fin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Planform {
    /// Planform area of one fin (m²).
    pub area: f64,
    /// Span (m).
    pub span: f64,
    /// Mean aerodynamic chord ∫c² dy / ∫c dy (m).
    pub mean_chord: f64,
    /// Spanwise mean of cos Λ of the leading edge.
    pub cos_leading_sweep: f64,
    /// Largest x of the outline, aft of the root leading edge (m).
    pub aft_extent: f64,
}

/// The planform of a fin outline `(x aft of the root leading edge, y outward from the
/// root)`, a closed polygon with its root on y = 0.
pub(crate) fn planform(outline: &[[f64; 2]]) -> Planform {
    let n = outline.len();
    let mut area = 0.0;
    for i in 0..n {
        let (a, b) = (outline[i], outline[(i + 1) % n]);
        area += a[0] * b[1] - b[0] * a[1];
    }
    let area = 0.5 * area.abs();
    let span = outline.iter().map(|p| p[1]).fold(0.0, f64::max);
    let aft_extent = outline.iter().map(|p| p[0]).fold(0.0, f64::max);
    if span <= 0.0 || area <= 0.0 {
        return Planform {
            area: 0.0,
            span,
            mean_chord: 0.0,
            cos_leading_sweep: 1.0,
            aft_extent,
        };
    }
    // Chord edges at each strip height: the extreme intersections of the outline with y.
    let chord_at = |y: f64| {
        let (mut lead, mut trail) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..n {
            let (a, b) = (outline[i], outline[(i + 1) % n]);
            let (lo, hi) = (a[1].min(b[1]), a[1].max(b[1]));
            if y < lo || y > hi {
                continue;
            }
            let xs = if hi - lo <= 0.0 {
                [a[0], b[0]]
            } else {
                let x = a[0] + (y - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
                [x, x]
            };
            for x in xs {
                lead = lead.min(x);
                trail = trail.max(x);
            }
        }
        if lead.is_finite() {
            (lead, trail)
        } else {
            (0.0, 0.0)
        }
    };
    let dy = span / STRIPS as f64;
    let (mut c_sum, mut c2_sum, mut cos_sum) = (0.0, 0.0, 0.0);
    let mut previous: Option<(f64, f64)> = None;
    for i in 0..=STRIPS {
        // Strip centres stay inside the outline; the end strips use half a step inward.
        let y = (i as f64 * dy).clamp(0.5 * dy * 1e-3, span * (1.0 - 1e-9));
        let (lead, trail) = chord_at(y);
        let c = trail - lead;
        let w = if i == 0 || i == STRIPS { 0.5 } else { 1.0 };
        c_sum += w * c;
        c2_sum += w * c * c;
        if let Some((y0, lead0)) = previous {
            cos_sum += (y - y0) / (lead - lead0).hypot(y - y0);
        }
        previous = Some((y, lead));
    }
    Planform {
        area,
        span,
        mean_chord: if c_sum > 0.0 { c2_sum / c_sum } else { 0.0 },
        cos_leading_sweep: cos_sum / STRIPS as f64,
        aft_extent,
    }
}

/// Pressure drag coefficient of one fin's edges on its frontal area t·s, at Mach `mach`.
#[must_use]
pub fn edge_coefficient(cross_section: FinCrossSection, cos_leading_sweep: f64, mach: f64) -> f64 {
    let leading = match cross_section {
        FinCrossSection::Rounded | FinCrossSection::Airfoil => {
            if mach < 0.9 {
                (1.0 - mach * mach).powf(-0.417) - 1.0
            } else if mach < 1.0 {
                1.0 - 1.785 * (mach - 0.9)
            } else {
                let m2 = mach * mach;
                1.214 - 0.502 / m2 + 0.1095 / (m2 * m2)
            }
        }
        FinCrossSection::Square => stagnation_coefficient(mach),
    };
    let trailing = match cross_section {
        FinCrossSection::Square => base_coefficient(mach),
        FinCrossSection::Rounded => 0.5 * base_coefficient(mach),
        FinCrossSection::Airfoil => 0.0,
    };
    leading * cos_leading_sweep * cos_leading_sweep + trailing
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trapezoid_planform() {
        // Root 0.1, tip 0.05, span 0.06, leading-edge sweep 0.03.
        let p = planform(&[[0.0, 0.0], [0.03, 0.06], [0.08, 0.06], [0.1, 0.0]]);
        assert!((p.area - 0.5 * (0.1 + 0.05) * 0.06).abs() < 1e-12);
        let (cr, ct) = (0.1f64, 0.05f64);
        let mac = 2.0 / 3.0 * (cr + ct - cr * ct / (cr + ct));
        assert!((p.mean_chord - mac).abs() < 1e-4, "{} {mac}", p.mean_chord);
        let cos = 0.06 / 0.03f64.hypot(0.06);
        assert!((p.cos_leading_sweep - cos).abs() < 1e-9);
    }

    #[test]
    fn edges_at_low_speed() {
        assert!(edge_coefficient(FinCrossSection::Airfoil, 1.0, 0.0).abs() < 1e-15);
        assert!((edge_coefficient(FinCrossSection::Rounded, 1.0, 0.0) - 0.06).abs() < 1e-15);
        assert!((edge_coefficient(FinCrossSection::Square, 1.0, 0.0) - 0.97).abs() < 1e-15);
    }
}
