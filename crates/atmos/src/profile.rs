//! Tabulated atmospheres: what custom profiles, soundings and weather grids all reduce to
//! before an [`crate::Environment`] is built from them.

use crate::curve::Curve;

/// Pressure, temperature and wind profiles of height above sea level.
///
/// A missing pressure or temperature falls back to the standard atmosphere (RocketPy
/// `process_custom_atmosphere`, docs/physics.md §4.2).
#[derive(Debug, Clone, PartialEq)]
pub struct Profiles {
    /// Where the data came from (a file name or "custom atmosphere"), for messages.
    pub source_name: String,
    /// Pressure (Pa) vs height; `None` → ISA.
    pub pressure: Option<Curve>,
    /// Temperature (K) vs height; `None` → ISA.
    pub temperature: Option<Curve>,
    /// Eastward wind (m/s) vs height.
    pub wind_u: Curve,
    /// Northward wind (m/s) vs height.
    pub wind_v: Curve,
    /// Explicit `(pressure Pa, height m)` pairs for barometric height, interpolated linearly
    /// with natural extrapolation (RocketPy's soundings and grids). `None`: the inverse of
    /// the pressure profile with its own (constant) extrapolation, as RocketPy's custom
    /// atmosphere does: a tabulated pressure must then be strictly monotonic (RocketPy
    /// raises otherwise, and so does karman); a constant pressure has no inverse, and the ISA
    /// barometric height is used instead (RocketPy would search a root that does not exist).
    pub barometric_points: Option<Vec<[f64; 2]>>,
}

impl Profiles {
    /// The standard atmosphere's thermodynamics with the given winds.
    #[must_use]
    pub fn wind_only(source_name: &str, wind_u: Curve, wind_v: Curve) -> Profiles {
        Profiles {
            source_name: source_name.into(),
            pressure: None,
            temperature: None,
            wind_u,
            wind_v,
            barometric_points: None,
        }
    }
}

/// One column of a pressure-level profile (soundings and weather grids) as RocketPy's
/// `data_array`: every vector has one entry per level, in the file's order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LevelProfile {
    /// Pressure of each level (Pa).
    pub pressure_pa: Vec<f64>,
    /// Geometric height of each level (m ASL).
    pub height_m: Vec<f64>,
    /// Temperature (K).
    pub temperature_k: Vec<f64>,
    /// Eastward wind (m/s).
    pub wind_u_mps: Vec<f64>,
    /// Northward wind (m/s).
    pub wind_v_mps: Vec<f64>,
    /// Surface elevation (m ASL) the file gives at the site, if any (GFS-style
    /// `surface_geopotential_height`).
    pub surface_elevation_m: Option<f64>,
}

impl LevelProfile {
    /// The first place where the heights do not rise strictly from level to level (in the
    /// file's level order, either direction): `(pressure Pa, height m)` of the two levels,
    /// or `None` when the column is monotonic. A column that folds back on itself is sorted
    /// by height when the profiles are built, which mixes its levels.
    #[must_use]
    pub fn height_fold(&self) -> Option<([f64; 2], [f64; 2])> {
        let h = &self.height_m;
        let rising = h.len() < 2 || h[h.len() - 1] >= h[0];
        h.windows(2)
            .position(|w| if rising { w[1] <= w[0] } else { w[1] >= w[0] })
            .map(|k| {
                (
                    [self.pressure_pa[k], h[k]],
                    [self.pressure_pa[k + 1], h[k + 1]],
                )
            })
    }

    /// The profiles RocketPy 1.13 builds from these levels (`process_forecast_reanalysis`):
    /// pressure, temperature and winds linear in height with constant extrapolation, and
    /// barometric height linear in pressure with natural extrapolation.
    #[must_use]
    pub fn profiles(&self, source_name: &str) -> Profiles {
        let col = |v: &[f64]| -> Vec<[f64; 2]> {
            self.height_m.iter().zip(v).map(|(&h, &y)| [h, y]).collect()
        };
        Profiles {
            source_name: source_name.into(),
            pressure: Some(Curve::Points(col(&self.pressure_pa))),
            temperature: Some(Curve::Points(col(&self.temperature_k))),
            wind_u: Curve::Points(col(&self.wind_u_mps)),
            wind_v: Curve::Points(col(&self.wind_v_mps)),
            barometric_points: Some(
                self.pressure_pa
                    .iter()
                    .zip(&self.height_m)
                    .map(|(&p, &h)| [p, h])
                    .collect(),
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::LevelProfile;

    #[test]
    fn folded_heights_are_found() {
        let mut p = LevelProfile {
            pressure_pa: vec![100_000.0, 85_000.0, 70_000.0],
            height_m: vec![100.0, 1500.0, 3000.0],
            ..LevelProfile::default()
        };
        assert_eq!(p.height_fold(), None);
        p.height_m.reverse();
        assert_eq!(
            p.height_fold(),
            None,
            "a column from the top down is monotonic"
        );
        p.height_m = vec![100.0, 3100.0, 3000.0];
        assert_eq!(
            p.height_fold(),
            Some(([85_000.0, 3100.0], [70_000.0, 3000.0]))
        );
    }
}
