//! Tank fluids (physics.md §15.2; RocketPy `Fluid`, rocketpy/motors/fluid.py): a name and a
//! density, either constant or a function of temperature and pressure.
//!
//! RocketPy builds `Fluid(density=f(T, p))` from `[T, p, ρ]` rows as a two-variable `Function`,
//! whose default interpolation for scattered data is Shepard's inverse-distance weighting with
//! power 3 (Shepard 1968); here the same [`ScatteredTable`]. A tank evaluates it at its own
//! temperature and pressure at each node of its time grid.

use karman_math::ScatteredTable;

use crate::PropulsionError;
use crate::propellant::positive;

/// Shepard power of RocketPy's N-dimensional `Function` interpolation.
const SHEPARD_POWER: f64 = 3.0;

/// A fluid's density.
#[derive(Debug, Clone, PartialEq)]
pub enum Density {
    /// Constant density, kg/m³.
    Constant(f64),
    /// Density of `(temperature K, pressure Pa)`, kg/m³, interpolated by inverse-distance
    /// weighting between the given rows.
    Table(ScatteredTable),
}

/// A tank fluid (RocketPy `Fluid(name, density)`).
#[derive(Debug, Clone, PartialEq)]
pub struct Fluid {
    /// Name shown in reports.
    pub name: String,
    /// Density model.
    pub density: Density,
}

impl Fluid {
    /// A fluid of constant density `density` kg/m³.
    #[must_use]
    pub fn constant(name: &str, density: f64) -> Fluid {
        Fluid {
            name: name.to_owned(),
            density: Density::Constant(density),
        }
    }

    /// A fluid whose density is tabulated as `[temperature K, pressure Pa, density kg/m³]`
    /// rows.
    ///
    /// # Errors
    /// [`PropulsionError::Table`] for no rows or a non-finite number.
    pub fn tabulated(name: &str, rows: &[[f64; 3]]) -> Result<Fluid, PropulsionError> {
        let nodes = rows.iter().flat_map(|r| [r[0], r[1]]).collect();
        let values = rows.iter().map(|r| r[2]).collect();
        let table = ScatteredTable::new(2, nodes, values, SHEPARD_POWER)
            .map_err(PropulsionError::table("fluid density"))?;
        Ok(Fluid {
            name: name.to_owned(),
            density: Density::Table(table),
        })
    }

    /// Density at `temperature` (K) and `pressure` (Pa), kg/m³.
    #[must_use]
    pub fn density_at(&self, temperature: f64, pressure: f64) -> f64 {
        match &self.density {
            Density::Constant(rho) => *rho,
            Density::Table(table) => table.eval(&[temperature, pressure]),
        }
    }

    /// Checks a constant density (a tabulated one is checked where it is evaluated).
    pub(crate) fn validate(&self, name: &'static str) -> Result<(), PropulsionError> {
        match &self.density {
            Density::Constant(rho) => positive(name, *rho),
            Density::Table(_) => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_and_tabulated_densities() {
        let water = Fluid::constant("water", 1000.0);
        assert!((water.density_at(300.0, 2e5) - 1000.0).abs() < 1e-12);
        let rows = [[280.0, 1e5, 10.0], [300.0, 1e5, 20.0]];
        let gas = Fluid::tabulated("gas", &rows).unwrap();
        // At a node the table returns the node's value; halfway both weigh the same.
        assert!((gas.density_at(280.0, 1e5) - 10.0).abs() < 1e-12);
        assert!((gas.density_at(290.0, 1e5) - 15.0).abs() < 1e-12);
        assert!(Fluid::tabulated("none", &[]).is_err());
        assert!(Fluid::constant("bad", -1.0).validate("density").is_err());
    }
}
