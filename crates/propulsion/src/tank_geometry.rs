//! Tank geometry (docs/physics.md §15.1; RocketPy `TankGeometry`, `CylindricalTank`,
//! `SphericalTank`, rocketpy/motors/tank_geometry.py).
//!
//! A tank is a solid of revolution about its height axis `h`, described by its radius `r(h)`.
//! RocketPy tabulates every derived quantity, and the tables — not the continuous formulas —
//! are what the motor's figures are made of, so they are reproduced here node for node:
//!
//! 1. each geometry piece `(h_lo, h_hi) → r` is sampled at 100 points, pieces joined in height
//!    order with a shared end point kept once;
//! 2. the cross-section `A(h)` is the natural spline through `π r_i²`, zero outside;
//! 3. the volume `V(h) = ∫_bottom^h A` is the exact integral of that spline at 100 equally
//!    spaced heights, itself a spline (zero outside); its inverse `h(V)` is the spline through
//!    the swapped pairs, extended by its end cubics;
//! 4. the volume moment `M(h) = ∫_lo^h h' A dh'` integrates the linear interpolant of the node
//!    products `h_i A_i`, and the inertia volume `I_x(h) = ∫_lo^h A (h'² + r²/4) dh'` (thin
//!    discs about the transverse axis through `h = 0`) the spline through
//!    `A_i (h_i² + r_i²/4)`; both exactly, sampled at 100 heights on `[lo, up]` and splined,
//!    constant outside.
//!
//! For a cylinder the spline of a constant area is that constant, so the volume and moment
//! tables equal the closed forms `πR²(h − h_0)` and `πR²(h² − h_0²)/2` at their nodes, and the
//! inertia table `πR²[(h³ − h_0³)/3 + R²(h − h_0)/4]` to the accuracy of the natural spline
//! through the quadratic integrand (about 1e-6 relative); other shapes are exact to the
//! splines' accuracy.

use karman_math::{Extrapolation, Interpolation, PhysicalConstants, Table1, linspace};

use crate::PropulsionError;
use crate::propellant::positive;

/// Samples per geometry piece and of every derived table (RocketPy's defaults).
const SAMPLES: usize = 100;

/// The shape of a tank, in its own height coordinate.
#[derive(Debug, Clone, PartialEq)]
pub enum TankShape {
    /// A cylinder of `radius` from `−height/2` to `+height/2`; with `spherical_caps` two
    /// hemispheres of the same radius close it inside that height (RocketPy `CylindricalTank`).
    Cylindrical {
        /// Radius, m.
        radius: f64,
        /// Total height, m.
        height: f64,
        /// Whether hemispherical caps close the ends.
        spherical_caps: bool,
    },
    /// A sphere of `radius` from `−radius` to `+radius` (RocketPy `SphericalTank`).
    Spherical {
        /// Radius, m.
        radius: f64,
    },
    /// Radius as a table of height (m → m), linear between its points; its first and last
    /// heights are the tank's bottom and top (RocketPy `TankGeometry({(h0, h1): radius})`).
    Custom {
        /// Heights, m, strictly increasing.
        heights: Vec<f64>,
        /// Radii, m.
        radii: Vec<f64>,
    },
}

/// A tank geometry with its tables, built once.
#[derive(Debug, Clone, PartialEq)]
pub struct TankGeometry {
    shape: TankShape,
    /// Radius nodes `h_i`.
    heights: Vec<f64>,
    /// Radii `r_i` at the nodes.
    radii: Vec<f64>,
    area: Table1,
    volume: Table1,
    inverse_volume: Table1,
    /// A moment-table range shorter than this is widened by `degenerate_widening`
    /// (RocketPy's guard for an empty fluid column; lengths of the unit system).
    degenerate_range: f64,
    degenerate_widening: f64,
}

impl TankGeometry {
    /// Builds the tables of `shape`, lengths in the unit system of `constants` (which holds the
    /// moment tables' degenerate-range guard).
    ///
    /// # Errors
    /// [`PropulsionError::InvalidParameter`] for a non-positive radius or height, caps that do
    /// not fit (`height < 2·radius`), or a custom profile with fewer than two points, negative
    /// radii or heights that do not increase; [`PropulsionError::Table`] when a table cannot
    /// be built.
    pub fn new(
        shape: TankShape,
        constants: &PhysicalConstants,
    ) -> Result<TankGeometry, PropulsionError> {
        let pieces = pieces(&shape)?;
        let mut heights: Vec<f64> = Vec::with_capacity(pieces.len() * SAMPLES);
        let mut radii: Vec<f64> = Vec::with_capacity(pieces.len() * SAMPLES);
        for (lo, hi, radius) in &pieces {
            for h in linspace(*lo, *hi, SAMPLES) {
                if heights.last().is_some_and(|&last| h <= last) {
                    continue;
                }
                heights.push(h);
                radii.push(radius(h));
            }
        }
        let (spline, zero) = (Interpolation::Spline, Extrapolation::Zero);
        let areas = radii.iter().map(|r| std::f64::consts::PI * r * r).collect();
        let area = Table1::new(heights.clone(), areas, spline, zero)
            .map_err(PropulsionError::table("tank area"))?;
        let (bottom, top) = (heights[0], heights[heights.len() - 1]);
        let levels = linspace(bottom, top, SAMPLES);
        let volumes: Vec<f64> = levels.iter().map(|&h| area.integral(bottom, h)).collect();
        let volume = Table1::new(levels.clone(), volumes.clone(), spline, zero)
            .map_err(PropulsionError::table("tank volume"))?;
        let inverse_volume = Table1::new(volumes, levels, spline, Extrapolation::Natural)
            .map_err(PropulsionError::table("tank inverse volume"))?;
        Ok(TankGeometry {
            shape,
            heights,
            radii,
            area,
            volume,
            inverse_volume,
            degenerate_range: constants.tank_degenerate_range,
            degenerate_widening: constants.tank_degenerate_widening,
        })
    }

    /// The shape this geometry was built from.
    #[must_use]
    pub fn shape(&self) -> &TankShape {
        &self.shape
    }
    /// Lowest height, m.
    #[must_use]
    pub fn bottom(&self) -> f64 {
        self.heights[0]
    }
    /// Highest height, m.
    #[must_use]
    pub fn top(&self) -> f64 {
        self.heights[self.heights.len() - 1]
    }
    /// Total inner volume, m³.
    #[must_use]
    pub fn total_volume(&self) -> f64 {
        self.volume.eval(self.top())
    }
    /// Cross-section `A(h)`, m².
    #[must_use]
    pub fn area(&self, h: f64) -> f64 {
        self.area.eval(h)
    }
    /// Volume below height `h`, m³.
    #[must_use]
    pub fn volume(&self, h: f64) -> f64 {
        self.volume.eval(h)
    }
    /// The height below which the tank holds `volume` m³ (the inverse-volume spline).
    #[must_use]
    pub fn height_of_volume(&self, volume: f64) -> f64 {
        self.inverse_volume.eval(volume)
    }
    /// Radius nodes `(h_i, r_i)` of the profile.
    #[must_use]
    pub fn profile(&self) -> (&[f64], &[f64]) {
        (&self.heights, &self.radii)
    }

    /// The volume-moment table `M(h) = ∫_lo^h h' A(h') dh'` on `[lo, up]` (m⁴).
    pub(crate) fn volume_moment(&self, lo: f64, up: f64) -> Result<Table1, PropulsionError> {
        let products = self
            .heights
            .iter()
            .zip(self.area.ys())
            .map(|(h, a)| h * a)
            .collect();
        let integrand = Table1::new(
            self.heights.clone(),
            products,
            Interpolation::Linear,
            Extrapolation::Natural,
        )
        .map_err(PropulsionError::table("tank volume moment"))?;
        self.integral_table(&integrand, lo, up, "tank volume moment")
    }

    /// The inertia-volume table `I_x(h) = ∫_lo^h A (h'² + r²/4) dh'` on `[lo, up]` (m⁵).
    pub(crate) fn inertia_volume(&self, lo: f64, up: f64) -> Result<Table1, PropulsionError> {
        let values = self
            .heights
            .iter()
            .zip(&self.radii)
            .zip(self.area.ys())
            .map(|((h, r), a)| a * (h * h + r * r / 4.0))
            .collect();
        let integrand = Table1::new(
            self.heights.clone(),
            values,
            Interpolation::Spline,
            Extrapolation::Zero,
        )
        .map_err(PropulsionError::table("tank inertia volume"))?;
        self.integral_table(&integrand, lo, up, "tank inertia volume")
    }

    /// The spline through `∫_lo^x f` at 100 heights of `[lo, up]`, constant outside
    /// (RocketPy `Function.integral_function(lo, up)`).
    fn integral_table(
        &self,
        integrand: &Table1,
        lo: f64,
        up: f64,
        what: &'static str,
    ) -> Result<Table1, PropulsionError> {
        let up = if up - lo < self.degenerate_range {
            up + self.degenerate_widening
        } else {
            up
        };
        let xs = linspace(lo, up, SAMPLES);
        let ys = xs.iter().map(|&x| integrand.integral(lo, x)).collect();
        Table1::new(xs, ys, Interpolation::Spline, Extrapolation::Constant)
            .map_err(PropulsionError::table(what))
    }
}

type Piece = (f64, f64, Box<dyn Fn(f64) -> f64>);

/// The geometry pieces `(h_lo, h_hi, r(h))` of a shape, in height order.
fn pieces(shape: &TankShape) -> Result<Vec<Piece>, PropulsionError> {
    Ok(match shape {
        TankShape::Cylindrical {
            radius,
            height,
            spherical_caps,
        } => {
            let (r, h) = (*radius, *height);
            positive("tank radius", r)?;
            positive("tank height", h)?;
            if !spherical_caps {
                vec![(-h / 2.0, h / 2.0, Box::new(move |_| r))]
            } else {
                if h < 2.0 * r {
                    return Err(PropulsionError::InvalidParameter {
                        name: "tank height",
                        value: h,
                        reason: "must be at least twice the radius to hold spherical caps",
                    });
                }
                let (lo, hi) = (-h / 2.0 + r, h / 2.0 - r);
                vec![
                    (
                        -h / 2.0,
                        lo,
                        Box::new(move |x: f64| (r * r - (x - lo).powi(2)).abs().sqrt()),
                    ),
                    (lo, hi, Box::new(move |_| r)),
                    (
                        hi,
                        h / 2.0,
                        Box::new(move |x: f64| (r * r - (x - hi).powi(2)).abs().sqrt()),
                    ),
                ]
            }
        }
        TankShape::Spherical { radius } => {
            let r = *radius;
            positive("tank radius", r)?;
            vec![(-r, r, Box::new(move |x: f64| (r * r - x * x).abs().sqrt()))]
        }
        TankShape::Custom { heights, radii } => {
            if heights.len() < 2 || heights.len() != radii.len() {
                return Err(PropulsionError::InvalidParameter {
                    name: "tank radius",
                    value: heights.len() as f64,
                    reason: "a custom profile needs at least two (height, radius) points",
                });
            }
            if let Some(&r) = radii.iter().find(|r| !(r.is_finite() && **r >= 0.0)) {
                return Err(PropulsionError::InvalidParameter {
                    name: "tank radius",
                    value: r,
                    reason: "must be zero or a positive number",
                });
            }
            let table = Table1::linear(heights.clone(), radii.clone())
                .map_err(PropulsionError::table("tank radius"))?;
            let (lo, hi) = (heights[0], heights[heights.len() - 1]);
            vec![(lo, hi, Box::new(move |x: f64| table.eval(x)))]
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1e-300)
    }

    #[test]
    fn cylinder_tables_equal_the_closed_forms() {
        let (r, h) = (0.07, 0.32);
        let g = TankGeometry::new(
            TankShape::Cylindrical {
                radius: r,
                height: h,
                spherical_caps: false,
            },
            &PhysicalConstants::SI,
        )
        .unwrap();
        assert_eq!(g.profile().0.len(), 100);
        let a = PI * r * r;
        assert!(close(g.total_volume(), a * h, 1e-14));
        // docs/physics.md §15.5: Halcyon's tank volume.
        assert!((g.total_volume() - 0.004_926_017_280_828_808_5).abs() < 1e-17);
        for x in [-0.16, -0.1, 0.0, 0.05, 0.16] {
            assert!(
                (g.volume(x) - a * (x + h / 2.0)).abs() < 1e-14 * a * h,
                "{x}"
            );
        }
        // The inverse at a tabulated volume returns its height.
        assert!(g.height_of_volume(a * h / 2.0).abs() < 1e-9);
        let moment = g.volume_moment(-h / 2.0, h / 2.0).unwrap();
        let inertia = g.inertia_volume(-h / 2.0, h / 2.0).unwrap();
        let h0 = -h / 2.0;
        for x in linspace(h0, h / 2.0, 100) {
            let m = a * (x * x - h0 * h0) / 2.0;
            assert!((moment.eval(x) - m).abs() < 1e-15, "{x}");
            let i = a * ((x.powi(3) - h0.powi(3)) / 3.0 + r * r * (x - h0) / 4.0);
            // The natural spline through the quadratic integrand departs from it near the ends.
            assert!(
                (inertia.eval(x) - i).abs() < 2e-6 * inertia.eval(h / 2.0),
                "{x}"
            );
        }
    }

    #[test]
    fn capped_cylinder_and_sphere_volumes() {
        let (r, h) = (0.0575, 0.573);
        let g = TankGeometry::new(
            TankShape::Cylindrical {
                radius: r,
                height: h,
                spherical_caps: true,
            },
            &PhysicalConstants::SI,
        )
        .unwrap();
        assert_eq!(g.profile().0.len(), 298);
        let exact = PI * r * r * (h - 2.0 * r) + 4.0 / 3.0 * PI * r.powi(3);
        assert!(close(g.total_volume(), exact, 1e-4), "{}", g.total_volume());
        // docs/physics.md §15.5: Hedy's capped tank volume.
        assert!((g.total_volume() - 0.005_553_527_460_220_63).abs() < 1e-15);
        let s = TankGeometry::new(TankShape::Spherical { radius: 0.1 }, &PhysicalConstants::SI)
            .unwrap();
        assert!(close(s.total_volume(), 4.0 / 3.0 * PI * 1e-3, 1e-4));
        // Half the sphere's volume lies below its centre (symmetry of the samples).
        assert!(close(s.volume(0.0), s.total_volume() / 2.0, 1e-3));
        let m = s.volume_moment(-0.1, 0.1).unwrap();
        assert!(m.eval(0.1).abs() < 1e-9, "centroid at the centre");
        let i = s.inertia_volume(-0.1, 0.1).unwrap();
        // A solid sphere: I = (2/5) m r² → per unit density (8/15) π r⁵.
        assert!(close(i.eval(0.1), 8.0 / 15.0 * PI * 1e-5, 1e-3));
    }

    #[test]
    fn custom_profiles_and_bad_shapes() {
        let cone = TankGeometry::new(
            TankShape::Custom {
                heights: vec![0.0, 1.0],
                radii: vec![0.0, 0.1],
            },
            &PhysicalConstants::SI,
        )
        .unwrap();
        assert!(close(cone.total_volume(), PI * 0.01 / 3.0, 1e-3));
        assert!((cone.bottom()).abs() < 1e-300 && (cone.top() - 1.0).abs() < 1e-15);
        let bad = [
            TankShape::Cylindrical {
                radius: 0.1,
                height: 0.1,
                spherical_caps: true,
            },
            TankShape::Spherical { radius: -1.0 },
            TankShape::Custom {
                heights: vec![0.0],
                radii: vec![0.1],
            },
            TankShape::Custom {
                heights: vec![0.0, 1.0],
                radii: vec![0.1, -0.1],
            },
            TankShape::Custom {
                heights: vec![1.0, 0.0],
                radii: vec![0.1, 0.1],
            },
        ];
        for shape in bad {
            assert!(TankGeometry::new(shape, &PhysicalConstants::SI).is_err());
        }
    }
}
