//! Generic motor: the propellant is a solid cylinder filling the combustion chamber
//! (docs/physics.md §6.5; RocketPy `GenericMotor`, rocketpy/motors/motor.py).
//!
//! Reproduces RocketPy's sampling exactly:
//! - `m_p(t) = m_p0 + ∫ ṁ dt` with `ṁ = −T/v̄_e`, sampled at 100 equally spaced times over the
//!   thrust-curve nodes (`Function.integral_function`) and interpolated with a natural cubic
//!   spline, constant outside;
//! - `I11_p = m_p (3R_c² + H_c²)/12`, `I33_p = m_p R_c²/2` (solid cylinder), evaluated on the
//!   thrust-curve nodes from that spline and themselves interpolated by a natural cubic spline
//!   (`set_discrete_based_on_model` keeps the spline of the product), constant outside;
//! - the propellant centre of mass is the chamber position.

use karman_math::{Extrapolation, Interpolation, PhysicalConstants, Table1, linspace};

use crate::propellant::{finite, positive};
use crate::{PropellantModel, PropellantTables, PropulsionError, ThrustCurve};

/// Samples of RocketPy's `Function.integral_function` (its default `datapoints`).
const MASS_SAMPLES: usize = 100;

/// The cylindrical chamber of a generic motor (RocketPy `GenericMotor` arguments).
#[derive(Debug, Clone, PartialEq)]
pub struct CylindricalChamber {
    /// Chamber radius `R_c`, m.
    pub radius: f64,
    /// Chamber height `H_c`, m.
    pub height: f64,
    /// Chamber centre, m, motor coordinates (the propellant centre of mass).
    pub position: f64,
    /// Initial propellant mass `m_p0`, kg.
    pub propellant_initial_mass: f64,
}

impl PropellantModel for CylindricalChamber {
    fn initial_mass(&self) -> f64 {
        self.propellant_initial_mass
    }

    fn validate(&self) -> Result<(), PropulsionError> {
        positive("chamber_radius", self.radius)?;
        positive("chamber_height", self.height)?;
        finite("chamber_position", self.position)?;
        positive("propellant_initial_mass", self.propellant_initial_mass)
    }

    fn tables(
        &self,
        thrust: &ThrustCurve,
        exhaust_velocity: f64,
        _constants: &PhysicalConstants,
    ) -> Result<PropellantTables, PropulsionError> {
        let curve = thrust.table();
        let (start, end) = curve.domain();
        let times = linspace(start, end, MASS_SAMPLES);
        let masses = times
            .iter()
            .map(|&t| self.propellant_initial_mass - curve.integral(start, t) / exhaust_velocity)
            .collect();
        let mass = Table1::new(
            times,
            masses,
            Interpolation::Spline,
            Extrapolation::Constant,
        )
        .map_err(PropulsionError::table("propellant mass"))?;
        // A repeated time (a step of the thrust) is one node of the mass tables.
        let mut nodes = curve.xs().to_vec();
        nodes.dedup_by(|later, earlier| *later <= *earlier);
        let on_nodes = |what, factor: f64| {
            let ys = nodes.iter().map(|&t| mass.eval(t) * factor).collect();
            Table1::new(
                nodes.clone(),
                ys,
                Interpolation::Spline,
                Extrapolation::Constant,
            )
            .map_err(PropulsionError::table(what))
        };
        let r2 = self.radius * self.radius;
        let i11 = on_nodes(
            "propellant I11",
            (3.0 * r2 + self.height * self.height) / 12.0,
        )?;
        let i33 = on_nodes("propellant I33", r2 / 2.0)?;
        let center_of_mass = Table1::new(
            nodes.clone(),
            vec![self.position; nodes.len()],
            Interpolation::Linear,
            Extrapolation::Constant,
        )
        .map_err(PropulsionError::table("propellant centre of mass"))?;
        Ok(PropellantTables {
            mass,
            center_of_mass,
            i11,
            i33,
            parts: Vec::new(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ThrustData, ThrustFormat, ThrustOptions, ThrustSource};

    #[test]
    fn samples_as_rocketpy() {
        let data = ThrustData {
            source_name: "test".into(),
            format: ThrustFormat::Inline,
            times: vec![0.0, 0.5, 2.0],
            thrusts: vec![0.0, 1000.0, 0.0],
            header: None,
            warnings: Vec::new(),
        };
        let curve = ThrustCurve::new(
            &ThrustSource::Data(Box::new(data)),
            &ThrustOptions::default(),
        )
        .unwrap();
        let chamber = CylindricalChamber {
            radius: 0.05,
            height: 0.5,
            position: 0.3,
            propellant_initial_mass: 2.0,
        };
        let ve = curve.total_impulse() / 2.0;
        let t = chamber.tables(&curve, ve, &PhysicalConstants::SI).unwrap();
        assert_eq!(t.mass.xs().len(), MASS_SAMPLES);
        assert_eq!(t.mass.interpolation(), Interpolation::Spline);
        assert_eq!(t.i11.xs(), curve.table().xs());
        // Burnt out at the end; I11 = m (3R² + H²)/12 at the nodes.
        assert!(t.mass.eval(2.0).abs() < 1e-12 && t.mass.eval(9.0).abs() < 1e-12);
        let k = (3.0 * 0.0025 + 0.25) / 12.0;
        assert!((t.i11.eval(0.5) - t.mass.eval(0.5) * k).abs() < 1e-15);
        assert!((t.center_of_mass.eval(1.0) - 0.3).abs() < 1e-15);
    }
}
