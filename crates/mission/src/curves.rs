//! Turning a mission [`Curve`] into points and tables: inline points are sorted stably by x,
//! files are read with karman-math's column reader (relative to the mission's directory), and
//! the table interpolates linearly and holds its end values unless told otherwise
//! (mission-format.md "Conventions").

use crate::error::{CurveError, ProblemKind};
use crate::schema::{AirBrakesCurve, Curve, ExtrapolationKind, InterpolationKind};
use karman_airframe::AirBrakesDrag;
use karman_math::{Extrapolation, Interpolation, PointOrder, Table1};
use std::path::Path;

/// The table interpolation of a mission `interpolation` key. `"akima"` is Akima's (1970)
/// method, as RocketPy 1.13's `"akima"` ([`Interpolation::Akima`]), so a RocketPy script
/// translates unchanged.
impl From<InterpolationKind> for Interpolation {
    fn from(kind: InterpolationKind) -> Self {
        match kind {
            InterpolationKind::Linear => Interpolation::Linear,
            InterpolationKind::Spline => Interpolation::Spline,
            InterpolationKind::Akima => Interpolation::Akima,
            InterpolationKind::Polynomial => Interpolation::Polynomial,
        }
    }
}

/// The table extrapolation of a mission `extrapolation` key.
impl From<ExtrapolationKind> for Extrapolation {
    fn from(kind: ExtrapolationKind) -> Self {
        match kind {
            ExtrapolationKind::Constant => Extrapolation::Constant,
            ExtrapolationKind::Natural => Extrapolation::Natural,
            ExtrapolationKind::Zero => Extrapolation::Zero,
        }
    }
}

impl AirBrakesCurve {
    /// The air-brake table as RocketPy builds it: rows `[level, Mach, Cd]` in file order, or
    /// a constant. Files are resolved against `mission_dir`.
    pub fn to_drag(&self, mission_dir: &Path) -> Result<AirBrakesDrag, CurveError> {
        Ok(match self {
            AirBrakesCurve::Constant(cd) => AirBrakesDrag::Constant(*cd),
            AirBrakesCurve::Rows(rows) => AirBrakesDrag::Table(rows.clone()),
            AirBrakesCurve::File(path) => AirBrakesDrag::Table(
                karman_math::read_rows(mission_dir.join(path), 3)?
                    .into_iter()
                    .map(|row| [row[0], row[1], row[2]])
                    .collect(),
            ),
        })
    }
}

impl Curve {
    /// The curve's points in their given order (file rows or inline points); a constant is
    /// the single point `[0, value]`. Files are resolved against `mission_dir`.
    pub fn points(&self, mission_dir: &Path) -> Result<Vec<[f64; 2]>, CurveError> {
        match self {
            Curve::Constant(value) => Ok(vec![[0.0, *value]]),
            Curve::Points(points) => Ok(points.clone()),
            Curve::File(path) => Ok(karman_math::read_curve(mission_dir.join(path))?),
        }
    }

    /// The curve as a table, its points sorted stably by x (a linear table keeps repeated x
    /// with RocketPy's semantics, [`Table1::linear_stepwise`]); a constant is a one-point
    /// table (its value everywhere with constant extrapolation).
    pub fn to_table(
        &self,
        mission_dir: &Path,
        interpolation: Interpolation,
        extrapolation: Extrapolation,
    ) -> Result<Table1, CurveError> {
        let points = self.points(mission_dir)?;
        Ok(Table1::from_points(
            &points,
            interpolation,
            extrapolation,
            PointOrder::SortStably,
        )?)
    }

    /// The curve as the format's default table: linear, end values held.
    pub fn to_linear_table(&self, mission_dir: &Path) -> Result<Table1, CurveError> {
        self.to_table(mission_dir, Interpolation::Linear, Extrapolation::Constant)
    }
}

/// Validation of a curve: its file exists and parses, and its points make a table of the
/// given kind.
pub(crate) fn check(
    curve: &Curve,
    mission_dir: &Path,
    interpolation: Interpolation,
    extrapolation: Extrapolation,
) -> Result<(), ProblemKind> {
    if let Some(path) = curve.file_path(mission_dir) {
        if let Err(source) = karman_math::files::check_data_file(&path) {
            return Err(ProblemKind::File { path, source });
        }
    }
    curve
        .to_table(mission_dir, interpolation, extrapolation)
        .map(drop)
        .map_err(|source| ProblemKind::Curve { source })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn fixtures() -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures")
    }

    #[test]
    fn constant_is_its_value_everywhere() {
        let table = Curve::Constant(0.44)
            .to_linear_table(&fixtures())
            .expect("one point");
        for mach in [-1.0, 0.0, 0.7, 25.0] {
            assert!((table.eval(mach) - 0.44).abs() < 1e-15, "mach {mach}");
        }
    }

    #[test]
    fn inline_points_are_sorted_and_linear() {
        let curve = Curve::Points(vec![[1.0, 3.0], [0.0, 1.0]]);
        let table = curve.to_linear_table(&fixtures()).expect("valid points");
        // Linear between (0, 1) and (1, 3); end values held outside.
        assert!((table.eval(0.5) - 2.0).abs() < 1e-15);
        assert!((table.eval(-1.0) - 1.0).abs() < 1e-15);
        assert!((table.eval(2.0) - 3.0).abs() < 1e-15);
    }

    #[test]
    fn file_is_read_relative_to_the_mission() {
        let curve = Curve::File("drag.csv".into());
        let table = curve
            .to_linear_table(&fixtures())
            .expect("fixture drag.csv");
        // drag.csv: (0.5, 0.48) and (1.0, 0.62); its header line is skipped.
        assert!((table.eval(0.75) - 0.55).abs() < 1e-12);
        assert!(matches!(
            Curve::File("bad_drag.csv".into()).to_linear_table(&fixtures()),
            Err(CurveError::Csv { .. })
        ));
    }
}
