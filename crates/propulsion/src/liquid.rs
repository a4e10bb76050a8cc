//! Liquid motor: the propellant is the contents of its tanks (docs/physics.md §15.3; RocketPy
//! `LiquidMotor`, rocketpy/motors/liquid_motor.py).
//!
//! With tank `i` at `position_i` (motor coordinates of its height origin; a tank height adds
//! with a plus sign whatever the motor's coordinate system):
//!
//! ```text
//! m_p(t)  = Σ m_i(t)
//! z_pc(t) = Σ m_i (position_i + c_i) / Σ m_i
//! I11_p   = Σ [ I_i + m_i (position_i + c_i − z_pc)² ],   I33_p = 0
//! ```
//!
//! RocketPy forms these with `Function` arithmetic: tanks on one time grid (same flux time
//! and `discretize`, or the same points without resampling) give node-wise sums with the
//! first tank's interpolation and extrapolation (its mass table's for the mass and the centre
//! of mass, its inertia table's interpolation, held constant, for the inertia), reproduced
//! exactly here. On different grids RocketPy evaluates the sums pointwise — except that each
//! tank's moment `m_i (position_i + c_i)` is first its own node-wise table — and so does the
//! rocket, from the tanks' own tables ([`crate::Motor::propellant_parts`]); the motor's
//! propellant tables then tabulate the same sums on the union of the grids, linear between
//! its nodes, for reports.
//!
//! The motor's mass flow in the equations of motion is still `−T/v̄_e` with
//! `v̄_e = I_tot/m_p(burn start)` ([`crate::Motor::mass_flow_rate`]), not the tanks' flow.

use karman_math::{Extrapolation, Interpolation, PhysicalConstants, Table1};

use crate::propellant::{finite, propellant_part};
use crate::{PropellantModel, PropellantTables, PropulsionError, Tank, ThrustCurve};

/// A tank placed in the motor (RocketPy `add_tank(tank, position)`).
#[derive(Debug, Clone, PartialEq)]
pub struct PositionedTank {
    /// The tank with its tables.
    pub tank: Tank,
    /// Motor coordinate of the tank's height origin, m.
    pub position: f64,
}

impl PositionedTank {
    /// The tank's centre of mass in motor coordinates, `position + c(t)`: RocketPy's
    /// `tank_position + tank.center_of_mass`, the node values shifted on the tank's grid with
    /// its interpolation.
    ///
    /// # Errors
    /// [`PropulsionError::Table`] when the shift overflows.
    pub fn center_of_mass_in_motor(&self) -> Result<Table1, PropulsionError> {
        let c = self.tank.center_of_mass();
        let ys = c.ys().iter().map(|&z| self.position + z).collect();
        Table1::on_same_abscissae(c, ys, c.interpolation(), c.extrapolation())
            .map_err(PropulsionError::table("tank centre of mass"))
    }
}

/// Whether the tanks' tables share one time grid (RocketPy's node-wise `Function`
/// arithmetic), rather than being summed pointwise.
pub(crate) fn on_one_grid(tanks: &[PositionedTank]) -> bool {
    tanks.first().is_none_or(|first| {
        let xs = first.tank.mass().xs();
        tanks.iter().all(|p| p.tank.mass().xs() == xs)
    })
}

/// The tanks' combined mass, centre of mass and inertia at one instant, pointwise.
pub(crate) fn tanks_at(tanks: &[PositionedTank], t: f64) -> (f64, f64, f64) {
    let mut mass = 0.0;
    let mut moment = 0.0;
    for p in tanks {
        let m = p.tank.mass().eval(t);
        mass += m;
        moment += m * (p.position + p.tank.center_of_mass().eval(t));
    }
    let center = if mass != 0.0 {
        moment / mass
    } else {
        tanks.first().map_or(0.0, |p| p.position)
    };
    let inertia = tanks
        .iter()
        .map(|p| {
            let m = p.tank.mass().eval(t);
            let d = p.position + p.tank.center_of_mass().eval(t) - center;
            p.tank.inertia().eval(t) + m * d * d
        })
        .sum();
    (mass, center, inertia)
}

/// The sorted union of the tanks' time grids.
pub(crate) fn union_grid(grids: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut times: Vec<f64> = grids.collect();
    times.sort_by(f64::total_cmp);
    times.dedup();
    times
}

/// The tanks of a liquid motor as its propellant model.
pub(crate) struct LiquidPropellant<'a> {
    pub tanks: &'a [PositionedTank],
    /// Burn start, s: the initial propellant mass is the tanks' mass then.
    pub burn_start: f64,
}

impl PropellantModel for LiquidPropellant<'_> {
    fn initial_mass(&self) -> f64 {
        tanks_at(self.tanks, self.burn_start).0
    }

    fn validate(&self) -> Result<(), PropulsionError> {
        if self.tanks.is_empty() {
            return Err(PropulsionError::InvalidParameter {
                name: "tanks",
                value: 0.0,
                reason: "a liquid or hybrid motor needs at least one tank",
            });
        }
        for p in self.tanks {
            finite("tank position", p.position)?;
        }
        Ok(())
    }

    fn tables(
        &self,
        _thrust: &ThrustCurve,
        _exhaust_velocity: f64,
        _constants: &PhysicalConstants,
    ) -> Result<PropellantTables, PropulsionError> {
        let first = self.tanks[0].tank.mass();
        let hold = Extrapolation::Constant;
        let one_grid = on_one_grid(self.tanks);
        let mut parts = Vec::new();
        if !one_grid {
            for p in self.tanks {
                parts.push(propellant_part(
                    p.tank.mass().clone(),
                    p.center_of_mass_in_motor()?,
                    p.tank.inertia().clone(),
                )?);
            }
        }
        let (times, interpolation, extrapolation, inertia_interpolation) = if one_grid {
            (
                first.xs().to_vec(),
                first.interpolation(),
                first.extrapolation(),
                self.tanks[0].tank.inertia().interpolation(),
            )
        } else {
            let all = self
                .tanks
                .iter()
                .flat_map(|p| p.tank.mass().xs().iter().copied());
            (
                union_grid(all),
                Interpolation::Linear,
                hold,
                Interpolation::Linear,
            )
        };
        // On one grid the tank tables' ordinates are the node values; elsewhere the tables are
        // evaluated.
        let (mut mass, mut center, mut inertia) = (
            Vec::with_capacity(times.len()),
            Vec::with_capacity(times.len()),
            Vec::with_capacity(times.len()),
        );
        for &t in &times {
            let (m, c, i) = tanks_at(self.tanks, t);
            mass.push(m);
            center.push(c);
            inertia.push(i);
        }
        let mass = Table1::new(times, mass, interpolation, extrapolation)
            .map_err(PropulsionError::table("propellant mass"))?;
        let like = |ys, interpolation, extrapolation, what| {
            Table1::on_same_abscissae(&mass, ys, interpolation, extrapolation)
                .map_err(PropulsionError::table(what))
        };
        Ok(PropellantTables {
            center_of_mass: like(
                center,
                interpolation,
                extrapolation,
                "propellant centre of mass",
            )?,
            i11: like(inertia, inertia_interpolation, hold, "propellant I11")?,
            i33: like(
                vec![0.0; mass.xs().len()],
                Interpolation::Linear,
                hold,
                "propellant I33",
            )?,
            mass,
            parts,
        })
    }
}
