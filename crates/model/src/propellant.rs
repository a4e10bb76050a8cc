//! A motor's propellant handed over in parts: the one piece of plain data that the motor crate
//! (karman-propulsion) produces and the vehicle crate (karman-airframe) consumes, defined here
//! because neither may depend on the other.

use karman_math::{MathError, Table1};

/// One part of a motor's propellant on a time grid of its own (a tank of a liquid motor, a
/// hybrid's grain or its tanks together), which the vehicle sums pointwise with the others as
/// RocketPy 1.13 does (docs/physics.md §15.3–15.4). Tables of time (s) from the thrust curve's
/// origin; positions in the motor's own coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct PropellantPart {
    /// Mass `m_i(t)`, kg.
    pub mass: Table1,
    /// Centre of mass `z_i(t)`, m (for a tank, its position plus its fluids' centre of mass).
    pub center_of_mass: Table1,
    /// Mass moment `m_i z_i`, kg·m: the node-wise products on the part's grid, interpolated
    /// and extrapolated as its mass (RocketPy multiplies the two tables node by node before
    /// summing the parts pointwise).
    pub moment: Table1,
    /// `I11_i(t)` (= `I22_i`) about `z_i`, kg·m²; the axial inertia is carried by the
    /// propellant's summed I33 table.
    pub i11: Table1,
}

impl PropellantPart {
    /// The part whose mass, centre of mass and `I11` are these tables, its moment the
    /// node-wise products of the first two (on the mass's grid, with its interpolation and
    /// extrapolation; the centre of mass must be tabulated on that grid).
    ///
    /// # Errors
    /// [`Table1::on_same_abscissae`]'s for the products: fewer of them than nodes (a centre of
    /// mass on a shorter grid), or one that is not finite.
    pub fn from_tables(
        mass: Table1,
        center_of_mass: Table1,
        i11: Table1,
    ) -> Result<PropellantPart, MathError> {
        let products = mass
            .ys()
            .iter()
            .zip(center_of_mass.ys())
            .map(|(m, z)| m * z)
            .collect();
        let moment =
            Table1::on_same_abscissae(&mass, products, mass.interpolation(), mass.extrapolation())?;
        Ok(PropellantPart {
            mass,
            center_of_mass,
            moment,
            i11,
        })
    }
}
