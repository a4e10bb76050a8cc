//! Air brakes (RocketPy's `AirBrakes`, docs/physics.md §16.1–§16.3): a drag coefficient of the
//! deployment level and the Mach number, its reference area, whether it replaces the rocket's
//! drag, and the clamp applied to every level written.
//!
//! While the level is **> 0** the brakes give the axial force
//! `−½ ρ V² · A_ab · Cd_ab(level, Mach)` along the body axis, added to the rocket's drag or
//! replacing it (`override_rocket_drag`); at level 0 or below they do nothing. The curve is
//! RocketPy's default 2-D `Function`: Shepard inverse-distance weighting with weights `d⁻³` in
//! raw (level, Mach) units, rows in file order, the first exactly matching row's value at a
//! node, no clamping outside the table (docs/physics.md §16.2).

use crate::error::{AirframeError, finite, positive};
use karman_math::ScatteredTable;

/// The control input of the vehicle's [`karman_model::Configuration`] that carries the
/// deployment level.
pub const AIR_BRAKES_CONTROL: usize = 0;

/// RocketPy's Shepard power: weights `d^{-3}`.
const SHEPARD_POWER: f64 = 3.0;

/// The drag-coefficient curve of the air brakes.
#[derive(Debug, Clone, PartialEq)]
pub enum AirBrakesDrag {
    /// The same coefficient at every level and Mach number.
    Constant(f64),
    /// Rows `[level, Mach, Cd]` in file order.
    Table(Vec<[f64; 3]>),
}

/// What defines the air brakes.
#[derive(Debug, Clone, PartialEq)]
pub struct AirBrakesSpec {
    /// The user's name for them.
    pub name: String,
    /// `Cd(level, Mach)`.
    pub drag: AirBrakesDrag,
    /// Reference area of the curve, m².
    pub reference_area: f64,
    /// Clip every level written to `[0, 1]`.
    pub clamp: bool,
    /// While deployed, the curve is the whole rocket's drag (not an increment).
    pub override_rocket_drag: bool,
    /// The level at `t = 0`.
    pub initial_level: f64,
}

#[derive(Debug, Clone, PartialEq)]
enum Curve {
    Constant(f64),
    Shepard(ScatteredTable),
}

/// Air brakes ready for the equations of motion.
#[derive(Debug, Clone, PartialEq)]
pub struct AirBrakes {
    name: String,
    curve: Curve,
    reference_area: f64,
    clamp: bool,
    override_rocket_drag: bool,
    initial_level: f64,
}

impl AirBrakes {
    /// Checks `spec` and builds the curve.
    ///
    /// # Errors
    /// [`AirframeError`] for a non-finite number, a reference area that is not > 0, or a
    /// table without rows.
    pub fn new(spec: &AirBrakesSpec) -> Result<Self, AirframeError> {
        let name = spec.name.as_str();
        positive(name, "reference_area", spec.reference_area)?;
        finite(name, "deployment_level", spec.initial_level)?;
        let curve = match &spec.drag {
            AirBrakesDrag::Constant(cd) => Curve::Constant(finite(name, "drag_coefficient", *cd)?),
            AirBrakesDrag::Table(rows) => {
                let nodes = rows.iter().flat_map(|r| [r[0], r[1]]).collect();
                let values = rows.iter().map(|r| r[2]).collect();
                Curve::Shepard(
                    ScatteredTable::new(2, nodes, values, SHEPARD_POWER).map_err(|source| {
                        AirframeError::Table {
                            component: spec.name.clone(),
                            quantity: "drag_coefficient_curve",
                            error: source,
                        }
                    })?,
                )
            }
        };
        Ok(AirBrakes {
            name: spec.name.clone(),
            curve,
            reference_area: spec.reference_area,
            clamp: spec.clamp,
            override_rocket_drag: spec.override_rocket_drag,
            initial_level: spec.initial_level,
        })
    }

    /// The user's name.
    #[must_use]
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Reference area, m².
    #[must_use]
    pub fn reference_area(&self) -> f64 {
        self.reference_area
    }

    /// Whether levels are clipped to `[0, 1]`.
    #[must_use]
    pub fn clamp(&self) -> bool {
        self.clamp
    }

    /// Whether the curve replaces the rocket's drag while deployed.
    #[must_use]
    pub fn override_rocket_drag(&self) -> bool {
        self.override_rocket_drag
    }

    /// The level at `t = 0` as the mission gives it. The level belongs to the controller's
    /// store (karman-script), which clips this value as it clips every write when the brakes
    /// clamp (docs/physics.md §16.3): one clamp, one owner.
    #[must_use]
    pub fn initial_level(&self) -> f64 {
        self.initial_level
    }

    /// The curve's `Cd(level, Mach)`, whatever the level.
    #[inline]
    #[must_use]
    pub fn drag_coefficient(&self, level: f64, mach: f64) -> f64 {
        match &self.curve {
            Curve::Constant(cd) => *cd,
            Curve::Shepard(table) => table.eval(&[level, mach]),
        }
    }

    /// `A_ab · Cd_ab(level, Mach)` of the brakes at `level`: 0 unless the level is > 0
    /// (docs/physics.md §16.1), m².
    #[inline]
    #[must_use]
    pub fn drag_area(&self, level: f64, mach: f64) -> f64 {
        if level > 0.0 {
            self.reference_area * self.drag_coefficient(level, mach)
        } else {
            0.0
        }
    }

    /// The axial force `R3` of rocket and brakes at `level`, N: `rocket_force` (the
    /// rocket's own `−½ ρ V² A Cd`) plus, or with `override_rocket_drag` replaced by,
    /// `minus_half_rho_v2 · A_ab · Cd_ab(level, Mach)` (`minus_half_rho_v2 = −½ ρ V²`, the
    /// product in RocketPy's order); `rocket_force` itself at level 0 or below.
    #[inline]
    #[must_use]
    pub fn axial_force(
        &self,
        level: f64,
        mach: f64,
        minus_half_rho_v2: f64,
        rocket_force: f64,
    ) -> f64 {
        if level > 0.0 {
            let brakes =
                minus_half_rho_v2 * self.reference_area * self.drag_coefficient(level, mach);
            if self.override_rocket_drag {
                brakes
            } else {
                rocket_force + brakes
            }
        } else {
            rocket_force
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brakes(clamp: bool, override_rocket_drag: bool) -> AirBrakes {
        AirBrakes::new(&AirBrakesSpec {
            name: "brakes".into(),
            drag: AirBrakesDrag::Table(vec![
                [0.0, 0.1, 0.0],
                [1.0, 0.1, 1.0],
                [0.0, 0.9, 0.0],
                [1.0, 0.9, 2.0],
            ]),
            reference_area: 0.01,
            clamp,
            override_rocket_drag,
            initial_level: 1.5,
        })
        .expect("valid")
    }

    #[test]
    fn shepard_is_exact_at_rows_and_pulled_by_all_rows() {
        let b = brakes(true, false);
        assert_eq!(b.drag_coefficient(1.0, 0.9).to_bits(), 2.0f64.to_bits());
        // The centre is equidistant from the four rows: their mean.
        let centre = b.drag_coefficient(0.5, 0.5);
        assert!((centre - 0.75).abs() < 1e-15, "{centre}");
        // Not bilinear: at (0.5, 0.1) the far rows pull towards their values.
        let d = |l: f64, m: f64| ((0.5 - l).powi(2) + (0.1 - m).powi(2)).powf(-1.5);
        let expected = (d(1.0, 0.1) * 1.0 + d(1.0, 0.9) * 2.0)
            / (d(0.0, 0.1) + d(1.0, 0.1) + d(0.0, 0.9) + d(1.0, 0.9));
        assert!((b.drag_coefficient(0.5, 0.1) - expected).abs() < 1e-15);
    }

    #[test]
    fn level_zero_does_nothing_and_override_replaces() {
        let added = brakes(true, false);
        let replaced = brakes(true, true);
        for b in [&added, &replaced] {
            assert_eq!(b.drag_area(0.0, 0.5).to_bits(), 0.0f64.to_bits());
            assert_eq!(
                b.axial_force(0.0, 0.5, -50.0, -4.0).to_bits(),
                (-4.0f64).to_bits()
            );
            assert_eq!(
                b.axial_force(-1.0, 0.5, -50.0, -4.0).to_bits(),
                (-4.0f64).to_bits()
            );
        }
        let brakes = -50.0 * 0.01 * added.drag_coefficient(1.0, 0.1);
        assert_eq!(
            added.axial_force(1.0, 0.1, -50.0, -4.0).to_bits(),
            (-4.0 + brakes).to_bits()
        );
        assert_eq!(
            replaced.axial_force(1.0, 0.1, -50.0, -4.0).to_bits(),
            brakes.to_bits()
        );
    }

    #[test]
    fn the_initial_level_is_kept_as_given_for_the_controller_to_clamp() {
        for clamp in [true, false] {
            let brakes = brakes(clamp, false);
            assert_eq!(brakes.initial_level().to_bits(), 1.5f64.to_bits());
            assert_eq!(brakes.clamp(), clamp);
        }
    }

    #[test]
    fn bad_inputs_are_named() {
        let mut spec = AirBrakesSpec {
            name: "ab".into(),
            drag: AirBrakesDrag::Table(Vec::new()),
            reference_area: 0.01,
            clamp: true,
            override_rocket_drag: false,
            initial_level: 0.0,
        };
        assert!(matches!(
            AirBrakes::new(&spec),
            Err(AirframeError::Table { .. })
        ));
        spec.drag = AirBrakesDrag::Constant(0.5);
        spec.reference_area = 0.0;
        assert!(matches!(
            AirBrakes::new(&spec),
            Err(AirframeError::NotPositive { .. })
        ));
    }
}
