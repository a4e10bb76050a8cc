//! Tank fluids (docs/physics.md §15.2; RocketPy `Fluid`, rocketpy/motors/fluid.py): a name and a
//! density, either constant or a function of temperature and pressure.
//!
//! RocketPy 1.13 builds `Fluid(density=f(T, p))` from `[T, p, ρ]` rows as a two-variable
//! `Function(interpolation="linear", extrapolation="natural")`: linear on the Delaunay
//! triangulation of the `(T, p)` points inside their convex hull, the thin-plate spline
//! through all rows outside it — here [`TriangulatedTable`], which also refuses what RocketPy
//! refuses (fewer than three rows, rows all on one line of the `(T, p)` plane, a repeated
//! `(T, p)`). A tank evaluates it at its own temperature and pressure (docs/physics.md §15.2).

use karman_math::TriangulatedTable;

use crate::PropulsionError;
use crate::propellant::positive;

/// A fluid's density.
#[derive(Debug, Clone, PartialEq)]
pub enum Density {
    /// Constant density, kg/m³.
    Constant(f64),
    /// Density of `(temperature K, pressure Pa)`, kg/m³: linear between the given rows on
    /// their Delaunay triangulation, a thin-plate spline outside their hull.
    Table(TriangulatedTable),
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
    /// [`PropulsionError::Table`] (naming `what`, e.g. `"liquid density"`) for fewer than
    /// three rows, a non-finite number, a repeated `(T, p)` or all `(T, p)` on one line.
    pub fn tabulated(
        name: &str,
        rows: &[[f64; 3]],
        what: &'static str,
    ) -> Result<Fluid, PropulsionError> {
        let points = rows.iter().map(|r| [r[0], r[1]]).collect();
        let values = rows.iter().map(|r| r[2]).collect();
        let table = TriangulatedTable::new(points, values).map_err(PropulsionError::table(what))?;
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
            Density::Table(table) => table.eval(temperature, pressure),
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
    fn constant_density() {
        let water = Fluid::constant("water", 1000.0);
        assert!((water.density_at(300.0, 2e5) - 1000.0).abs() < 1e-12);
        assert!(Fluid::constant("bad", -1.0).validate("density").is_err());
    }

    /// Ten scattered `[T, p, ρ]` rows and RocketPy 1.13.0's `Fluid("N2O", rows)
    /// .density_function.get_value(T, p)` at ten points (rocketpy==1.13.0, scipy 1.17.1,
    /// printed with `repr`): inside the hull (linear on the Delaunay triangles, a row itself),
    /// inside the bounding box but outside the hull, and outside the box (thin-plate spline).
    #[test]
    fn tabulated_density_as_rocketpy() {
        let rows = [
            [250.0, 1.0e5, 2.1],
            [262.0, 2.2e6, 48.0],
            [275.0, 4.1e6, 95.0],
            [290.0, 6.0e6, 131.0],
            [305.0, 1.5e6, 27.5],
            [318.0, 3.3e6, 58.0],
            [320.0, 5.6e6, 101.0],
            [284.0, 0.8e6, 15.2],
            [258.0, 5.1e6, 128.0],
            [300.0, 2.9e6, 55.0],
        ];
        let fluid = Fluid::tabulated("N2O", &rows, "liquid density").unwrap();
        let expected = [
            (280.0, 2.0e6, 41.190_476_190_476_19),
            (300.0, 4.0e6, 80.474_626_865_671_64),
            (262.0, 2.2e6, 48.0),
            (310.0, 1.0e6, 10.556_214_143_021_656),
            (260.0, 1.0e5, -2.774_611_271_473_190_8),
            (319.0, 5.9e6, 112.687_248_914_743_63),
            (340.0, 3.0e6, 38.886_032_266_099_825),
            (273.15, 101_325.0, -9.131_794_939_302_068),
            (300.0, 7.0e6, 157.414_658_667_522_36),
            (240.0, 5.0e6, 135.229_054_208_258_9),
        ];
        for (t, p, rho) in expected {
            let got = fluid.density_at(t, p);
            assert!(
                (got - rho).abs() < 1e-9 * rho.abs().max(1.0),
                "rho({t}, {p}) = {got}, RocketPy {rho}"
            );
        }
    }

    #[test]
    fn refuses_tables_rocketpy_refuses() {
        let two = [[280.0, 1e5, 10.0], [300.0, 1e5, 20.0]];
        let line = [[280.0, 1e5, 10.0], [300.0, 1e5, 20.0], [320.0, 1e5, 30.0]];
        let repeated = [
            [280.0, 1e5, 10.0],
            [300.0, 1e5, 20.0],
            [300.0, 3e5, 30.0],
            [300.0, 3e5, 31.0],
        ];
        for rows in [&two[..], &line, &repeated] {
            let err = Fluid::tabulated("gas", rows, "gas density").unwrap_err();
            assert!(err.to_string().contains("gas density"), "{err}");
        }
    }
}
