//! The motor as the airframe sees it: plain tabulated data.
//!
//! karman-airframe may not depend on karman-propulsion (layering rule), so the mission layer
//! converts a `karman_propulsion::Motor` into [`MotorProperties`]. Positions are in the
//! MOTOR's own coordinate system (orientation [`MotorProperties::coordinate_system_sign`]),
//! times in s from the thrust curve's time origin (RocketPy `Motor`, docs/physics.md §5.2, §6).

use karman_math::Table1;
use karman_model::PropellantPart;

use crate::error::{AirframeError, finite, non_negative, positive};

/// Tabulated properties of one motor (RocketPy `Motor` attributes, docs/physics.md §6).
///
/// The tables must be built exactly as RocketPy builds them (sample points and
/// interpolation), because the rocket's time tables are formed node by node from them when
/// they share their abscissae, exactly as RocketPy's `Function` arithmetic does.
#[derive(Debug, Clone, PartialEq)]
pub struct MotorProperties {
    /// Raw thrust T(t) in N: linear, zero extrapolation, clipped to the burn interval (§6.1).
    pub thrust: Table1,
    /// Burn start time t_b0 (s).
    pub burn_start: f64,
    /// Burn-out time t_b1 (s).
    pub burn_out: f64,
    /// Average exhaust velocity v̄_e = I_tot / m_p0 (m/s), §6.2.
    pub exhaust_velocity: f64,
    /// Propellant mass m_p(t) (kg).
    pub propellant_mass: Table1,
    /// Signed mass-flow rate `dm_p/dt` (kg/s) consistent with `propellant_mass`, for a motor
    /// whose mass comes from elsewhere than its thrust (tanks); `None`: the derivative of
    /// `propellant_mass` (the `standard` equations, [`karman_model::MassFlowLaw`]).
    pub mass_flow: Option<Table1>,
    /// Propellant centre of mass z_pc(t) in motor coordinates (m).
    pub propellant_center_of_mass: Table1,
    /// Propellant I11 about the propellant centre of mass (kg·m²); I22 is taken equal.
    pub propellant_i11: Table1,
    /// Propellant I33 about the propellant centre of mass (kg·m²).
    pub propellant_i33: Table1,
    /// The propellant as parts on time grids of their own, summed pointwise (a liquid motor
    /// whose tanks are on different time grids, a hybrid motor's grain and tanks: RocketPy
    /// evaluates those motors' sums pointwise, docs/physics.md §15.3–15.4); the propellant tables
    /// above then only tabulate the sums (for reports) and the I33. Empty for a motor whose
    /// propellant is those tables.
    pub propellant_parts: Vec<PropellantPart>,
    /// Motor dry mass (kg).
    pub dry_mass: f64,
    /// Motor dry centre of mass, motor coordinates (m).
    pub center_of_dry_mass: f64,
    /// Motor dry inertia about its dry CM `(I11, I22, I33, I12, I13, I23)` (kg·m²).
    pub dry_inertia: [f64; 6],
    /// Nozzle exit position, motor coordinates (m).
    pub nozzle_position: f64,
    /// Nozzle exit radius r_n (m).
    pub nozzle_radius: f64,
    /// csys_m: +1 for `nozzle_to_combustion_chamber`, −1 otherwise.
    pub coordinate_system_sign: f64,
    /// Reference (test-stand) pressure of the thrust curve for the pressure-thrust
    /// correction (Pa), if any (§6.3).
    pub reference_pressure: Option<f64>,
}

impl MotorProperties {
    /// Checks the scalar data (finite values, non-negative masses, a ±1 orientation).
    pub(crate) fn validate(&self) -> Result<(), AirframeError> {
        const C: &str = "motor";
        finite(C, "burn_start", self.burn_start)?;
        finite(C, "burn_out", self.burn_out)?;
        if self.burn_out < self.burn_start {
            return Err(AirframeError::Geometry {
                component: C.to_owned(),
                reason: format!(
                    "burn-out time {} s is before the burn start {} s",
                    self.burn_out, self.burn_start
                ),
            });
        }
        non_negative(C, "dry_mass", self.dry_mass)?;
        finite(C, "center_of_dry_mass", self.center_of_dry_mass)?;
        for (i, v) in self.dry_inertia.iter().enumerate() {
            finite(C, INERTIA_NAMES[i], *v)?;
        }
        for v in &self.dry_inertia[..3] {
            non_negative(C, "dry_inertia", *v)?;
        }
        finite(C, "nozzle_position", self.nozzle_position)?;
        non_negative(C, "nozzle_radius", self.nozzle_radius)?;
        if let Some(p) = self.reference_pressure {
            positive(C, "reference_pressure", p)?;
        }
        if (self.coordinate_system_sign.abs() - 1.0).abs() > 1e-12 {
            return Err(AirframeError::OutOfRange {
                component: C.to_owned(),
                quantity: "coordinate_system_sign",
                value: self.coordinate_system_sign,
                min: -1.0,
                max: 1.0,
            });
        }
        Ok(())
    }
}

/// Names of the six inertia components, in the `(I11, I22, I33, I12, I13, I23)` order.
pub(crate) const INERTIA_NAMES: [&str; 6] = ["I11", "I22", "I33", "I12", "I13", "I23"];
