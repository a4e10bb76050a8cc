//! The mass properties of a rigid part on the rocket's axis, and how parts add up: one
//! definition of the parallel-axis theorem (Steiner) for every place that lumps parts
//! together — the copies of a motor cluster, the dry masses of several motors, the stages of
//! a stack, an imported design's components (docs/physics.md §5.3, §24.1).
//!
//! A part is its mass `m`, the axial position `z` of its centre of mass and its inertia
//! tensor `I = (I11, I22, I33, I12, I13, I23)` about that centre (`I11`, `I22` lateral, `I33`
//! about the rocket's axis). Moved along the axis by `d`, the lateral inertias gain `m d²` and
//! the rest is unchanged; moved off the axis to a ring of `n` copies at radius `r`, each copy
//! gains `m r²` about the axis and, on the mean of the two lateral axes, `m r²/2` (exact for
//! three or more copies evenly on the ring; two copies sit on one lateral axis, whose mean the
//! axisymmetric rocket flies).

/// Mass (kg), axial centre of mass (m, in the frame of whoever holds it) and inertia about
/// that centre (kg·m², `(I11, I22, I33, I12, I13, I23)`) of a rigid part.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RigidMass {
    /// Mass, kg.
    pub mass: f64,
    /// Axial position of the centre of mass, m.
    pub center: f64,
    /// Inertia about the centre of mass, `(I11, I22, I33, I12, I13, I23)`, kg·m².
    pub inertia: [f64; 6],
}

impl RigidMass {
    /// A part of `mass` at `center` with `inertia` about another point `about` of the axis:
    /// its inertia moved to its own centre (`I11`, `I22` less `m d²`, `d = center − about`).
    #[must_use]
    pub fn with_inertia_about(mass: f64, center: f64, inertia: [f64; 6], about: f64) -> Self {
        let d = center - about;
        let mut own = inertia;
        own[0] -= mass * d * d;
        own[1] -= mass * d * d;
        Self {
            mass,
            center,
            inertia: own,
        }
    }

    /// The inertia about the point `about` of the axis: `I11`, `I22` plus `m (z − about)²`.
    #[must_use]
    pub fn inertia_about(&self, about: f64) -> [f64; 6] {
        let shift = self.steiner(about);
        let mut inertia = self.inertia;
        inertia[0] += shift;
        inertia[1] += shift;
        inertia
    }

    /// The parallel-axis term `m d²` of the part about the point `about` of the axis.
    fn steiner(&self, about: f64) -> f64 {
        let d = self.center - about;
        self.mass * d * d
    }

    /// Two parts as one: [`RigidMass::gathered`] of the two.
    #[must_use]
    pub fn combined(self, other: RigidMass) -> RigidMass {
        RigidMass::gathered(&[self, other], 0.0)
    }

    /// Many parts as one: the masses summed, the centre their mass-weighted mean `Σ m z / Σ m`,
    /// the inertia about it the sum of the parts' own inertias plus, on the lateral axes, the
    /// sum of their parallel-axis terms `Σ m (z − z̄)²` (each sum in the order given). Parts
    /// of no mass in all sit at `massless_center`, their inertias summed.
    #[must_use]
    pub fn gathered(parts: &[RigidMass], massless_center: f64) -> RigidMass {
        let mass: f64 = parts.iter().map(|p| p.mass).sum();
        let center = if mass > 0.0 {
            parts.iter().map(|p| p.mass * p.center).sum::<f64>() / mass
        } else {
            massless_center
        };
        let mut inertia = [0.0; 6];
        let mut axial = 0.0;
        for part in parts {
            for (total, value) in inertia.iter_mut().zip(part.inertia) {
                *total += value;
            }
            axial += part.steiner(center);
        }
        inertia[0] += axial;
        inertia[1] += axial;
        RigidMass {
            mass,
            center,
            inertia,
        }
    }

    /// `count` copies of the part, their axes on a ring of `radius` about the rocket's axis:
    /// mass and the products of inertia times `count`, the centre unchanged, per copy `m r²`
    /// added about the axis and `m r²/2` about each lateral axis.
    #[must_use]
    pub fn ring(self, count: u32, radius: f64) -> RigidMass {
        let n = f64::from(count);
        let arm2 = radius * radius;
        let i = self.inertia;
        let m = self.mass;
        RigidMass {
            mass: n * m,
            center: self.center,
            inertia: [
                n * (i[0] + 0.5 * m * arm2),
                n * (i[1] + 0.5 * m * arm2),
                n * (i[2] + m * arm2),
                n * i[3],
                n * i[4],
                n * i[5],
            ],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(mass: f64, center: f64) -> RigidMass {
        RigidMass {
            mass,
            center,
            inertia: [0.0; 6],
        }
    }

    #[test]
    fn two_points_follow_the_parallel_axis_theorem() {
        let two = point(1.0, -1.0).combined(point(3.0, 1.0));
        assert!((two.mass - 4.0).abs() < 1e-15 && (two.center - 0.5).abs() < 1e-15);
        // 1·1.5² + 3·0.5² about the common centre, nothing about the axis.
        assert!((two.inertia[0] - 3.0).abs() < 1e-15 && (two.inertia[1] - 3.0).abs() < 1e-15);
        assert!(two.inertia[2].abs() < 1e-15);
        let many = RigidMass::gathered(&[point(1.0, -1.0), point(3.0, 1.0)], 0.0);
        assert_eq!(many, two, "two parts gathered are two parts combined");
    }

    #[test]
    fn a_massless_part_changes_nothing() {
        let body = RigidMass {
            mass: 3.55,
            center: 0.973,
            inertia: [0.8, 0.8, 0.003, 0.0, 0.0, 0.0],
        };
        assert_eq!(body.combined(point(0.0, 2.0)), body);
        assert_eq!(RigidMass::gathered(&[body, point(0.0, 7.0)], 0.0), body);
        assert_eq!(
            point(0.0, 1.0).combined(point(0.0, 2.0)),
            RigidMass::default()
        );
        assert_eq!(
            RigidMass::gathered(&[point(0.0, 1.0)], 0.25),
            point(0.0, 0.25)
        );
    }

    #[test]
    fn moving_the_reference_point_is_reversible() {
        let part = RigidMass {
            mass: 2.0,
            center: 0.4,
            inertia: [0.3, 0.3, 0.01, 0.0, 0.0, 0.0],
        };
        let about_tip = part.inertia_about(1.4);
        // 0.3 + 2·1² about a point 1 m away.
        assert!((about_tip[0] - 2.3).abs() < 1e-15);
        let back = RigidMass::with_inertia_about(2.0, 0.4, about_tip, 1.4);
        for (a, b) in back.inertia.iter().zip(part.inertia) {
            assert!((a - b).abs() < 1e-15);
        }
    }

    #[test]
    fn a_ring_of_three_is_the_sum_of_its_copies() {
        let one = RigidMass {
            mass: 0.5,
            center: 0.2,
            inertia: [0.02, 0.02, 0.001, 0.0, 0.0, 0.0],
        };
        let r: f64 = 0.05;
        let ring = one.ring(3, r);
        // Copies at 0°, 120°, 240°: Σ y² = Σ z² = 3 r²/2, Σ (y² + z²) = 3 r².
        assert!((ring.mass - 1.5).abs() < 1e-15);
        assert!((ring.inertia[2] - 3.0 * (0.001 + 0.5 * r * r)).abs() < 1e-15);
        assert!((ring.inertia[0] - 3.0 * (0.02 + 0.5 * 0.5 * r * r)).abs() < 1e-15);
        assert_eq!(one.ring(1, 0.0), one);
    }
}
