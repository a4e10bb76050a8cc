//! The pluggable propellant model: what a motor type must provide besides its thrust curve.
//!
//! Every motor type turns the processed thrust curve into four tables of time — propellant
//! mass, propellant centre of mass (motor coordinates) and the propellant's transverse and
//! axial moments of inertia about its own centre of mass — which is all RocketPy's `Motor`
//! base class needs to derive the motor's total mass, centre of mass and inertia
//! (rocketpy/motors/motor.py). Solid ([`crate::BatesGrains`]) and generic
//! ([`crate::CylindricalChamber`]) models exist; hybrid and liquid models plug in the same way.

use karman_math::{PhysicalConstants, Table1};
use karman_model::PropellantPart;

use crate::{PropulsionError, ThrustCurve};

/// Propellant tables of time (s), built once per motor.
#[derive(Debug, Clone, PartialEq)]
pub struct PropellantTables {
    /// Propellant mass `m_p(t)`, kg.
    pub mass: Table1,
    /// Propellant centre of mass `z_p(t)`, m, motor coordinates.
    pub center_of_mass: Table1,
    /// `I11_p(t)` (= `I22_p`) about the propellant centre of mass, kg·m².
    pub i11: Table1,
    /// `I33_p(t)` about the propellant centre of mass, kg·m².
    pub i33: Table1,
    /// The parts whose pointwise sum the propellant is, when RocketPy sums them pointwise (a
    /// liquid motor's tanks on different time grids, docs/physics.md §15.3; a hybrid motor's grain
    /// and tanks, §15.4); the tables above then tabulate that sum for reports (and hold the
    /// I33). Empty when the tables are the propellant exactly.
    pub parts: Vec<PropellantPart>,
}

/// The propellant part whose mass, centre of mass (motor coordinates) and `I11` are these
/// tables ([`PropellantPart::from_tables`]).
///
/// # Errors
/// [`PropulsionError::Table`] when the grids differ or a product overflows.
pub(crate) fn propellant_part(
    mass: Table1,
    center_of_mass: Table1,
    i11: Table1,
) -> Result<PropellantPart, PropulsionError> {
    PropellantPart::from_tables(mass, center_of_mass, i11)
        .map_err(PropulsionError::table("propellant mass moment"))
}

/// A motor type's propellant bookkeeping.
pub trait PropellantModel {
    /// Initial propellant mass `m_p0`, kg.
    fn initial_mass(&self) -> f64;

    /// Checks the model's parameters.
    ///
    /// # Errors
    /// [`PropulsionError::InvalidParameter`] naming the offending parameter.
    fn validate(&self) -> Result<(), PropulsionError>;

    /// Builds the propellant tables for `thrust`, given the average exhaust velocity
    /// `v̄_e = I_tot / m_p0` (so the mass flow is `ṁ = −T / v̄_e`, docs/physics.md §6.2), in the
    /// unit system of `constants` (which holds the numerical time steps of the tables).
    ///
    /// # Errors
    /// [`PropulsionError::Table`] when a table cannot be built.
    fn tables(
        &self,
        thrust: &ThrustCurve,
        exhaust_velocity: f64,
        constants: &PhysicalConstants,
    ) -> Result<PropellantTables, PropulsionError>;
}

/// Requires `value` to be finite and strictly positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<(), PropulsionError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(PropulsionError::InvalidParameter {
            name,
            value,
            reason: "must be a positive number",
        })
    }
}

/// Requires `value` to be finite and not negative.
pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<(), PropulsionError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(PropulsionError::InvalidParameter {
            name,
            value,
            reason: "must be zero or a positive number",
        })
    }
}

/// Requires `value` to be finite.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<(), PropulsionError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(PropulsionError::InvalidParameter {
            name,
            value,
            reason: "must be finite",
        })
    }
}
