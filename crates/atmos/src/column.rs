//! The air column: every height-dependent table of an [`crate::Environment`] re-cut on the
//! union of their heights, so that one located search finds the pieces of all of them.
//!
//! Pressure, temperature, gravity and the node-wise derived quantities live on different
//! heights (the ISA pressure on 100 even samples, its temperature on the 9 layer bases,
//! Somigliana gravity on its own samples, a sounding on its levels). Between two consecutive
//! heights of their union every table is a single piece (a cubic, or a held end value), and
//! [`karman_math::Piece`] evaluates that piece bit for bit as its table does, so a query is
//! one search with a cursor and a polynomial per quantity (docs/performance.md, "Atmosphere").

use karman_math::{Cursor, Extrapolation, Interpolation, Location, Piece, Table1};

/// The pieces of the environment's tables on one interval of the union heights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct AirRow {
    pub pressure: Piece,
    pub temperature: Piece,
    /// The node-wise density table's piece (unused when the density is pointwise).
    pub density: Piece,
    /// The node-wise speed-of-sound table's piece (unused when it is pointwise).
    pub speed_of_sound: Piece,
    /// The node-wise viscosity table's piece (unused when it is pointwise).
    pub viscosity: Piece,
    pub gravity: Piece,
}

/// The tables an [`AirColumn`] gathers; `None` for a quantity computed pointwise.
pub(crate) struct ColumnTables<'a> {
    pub pressure: &'a Table1,
    pub temperature: &'a Table1,
    pub density: Option<&'a Table1>,
    pub speed_of_sound: Option<&'a Table1>,
    pub viscosity: Option<&'a Table1>,
    pub gravity: &'a Table1,
}

/// [`AirRow`]s on the union of the tables' heights.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct AirColumn {
    /// The union heights (the values are unused): the located search.
    heights: Table1,
    /// Below the first height, then one row per interval, then above the last height.
    rows: Vec<AirRow>,
}

impl AirColumn {
    /// Gathers the tables; `None` if one of them is not made of pieces (a single polynomial)
    /// or zeroes its ends (its first sample would then differ from the piece below it).
    pub fn new(tables: &ColumnTables<'_>) -> Option<Self> {
        let all: Vec<&Table1> = [tables.pressure, tables.temperature, tables.gravity]
            .into_iter()
            .chain(tables.density)
            .chain(tables.speed_of_sound)
            .chain(tables.viscosity)
            .collect();
        if all.iter().any(|t| t.extrapolation() == Extrapolation::Zero) {
            return None;
        }
        let mut zs: Vec<f64> = all.iter().flat_map(|t| t.xs().iter().copied()).collect();
        zs.sort_by(f64::total_cmp);
        zs.dedup_by(|a, b| a.to_bits() == b.to_bits());
        if zs.len() == 1 {
            // Only one-sample tables: their pieces are constants, any second height will do.
            zs.push(zs[0] + 1.0);
        }
        let row = |at: &dyn Fn(&Table1) -> Location| -> Option<AirRow> {
            let piece = |t: &Table1| t.piece(at(t));
            let derived = |t: Option<&Table1>| match t {
                Some(t) => piece(t),
                None => Some(Piece::constant(f64::NAN)),
            };
            Some(AirRow {
                pressure: piece(tables.pressure)?,
                temperature: piece(tables.temperature)?,
                density: derived(tables.density)?,
                speed_of_sound: derived(tables.speed_of_sound)?,
                viscosity: derived(tables.viscosity)?,
                gravity: piece(tables.gravity)?,
            })
        };
        let mut rows = Vec::with_capacity(zs.len() + 1);
        rows.push(row(&|_| Location::Below)?);
        for w in zs.windows(2) {
            // Every table is one piece on the open interval (its heights are among the
            // union's), so the piece at the midpoint is the piece at every inner point. At
            // the ends the tables' choice agrees with the union's (a sample belongs to the
            // interval on its left), but at a table's first sample, where the table begins
            // its first piece while the union may still hold the table's end value below
            // it: the two agree there for a held or natural end (the piece's constant term
            // is the sample), which is why zeroed ends are refused above.
            let mid = 0.5 * (w[0] + w[1]);
            rows.push(row(&|t| t.locate(mid))?);
        }
        rows.push(row(&|_| Location::Above)?);
        let values = vec![0.0; zs.len()];
        let heights =
            Table1::new(zs, values, Interpolation::Linear, Extrapolation::Constant).ok()?;
        Some(Self { heights, rows })
    }

    /// The row of height `z`, located from `cursor` (and updating it).
    #[inline(always)]
    pub fn row_near(&self, z: f64, cursor: &mut Cursor) -> &AirRow {
        let index = match self.heights.locate_with(z, cursor) {
            Location::Below => 0,
            Location::Interval(i) => i + 1,
            Location::Above => self.rows.len() - 1,
        };
        &self.rows[index]
    }
}
