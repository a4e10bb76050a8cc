//! The launch environment the equations of motion query: every quantity is a table on
//! height built once, so each query is a binary search and a polynomial step (no allocation).
//!
//! How each quantity is derived follows RocketPy 1.13's `Function` arithmetic
//! (`Environment.calculate_density_profile`, `calculate_speed_of_sound_profile`,
//! `calculate_dynamic_viscosity`; docs/physics.md §4.1–§4.2):
//! - density `ρ = P/(R T)`: node by node (then interpolated like the pressure) when pressure
//!   and temperature are tables on the same heights, pointwise otherwise (e.g. the ISA, whose
//!   pressure has 100 nodes and temperature 9);
//! - speed of sound `√(γ R T)` and Sutherland viscosity `B T^1.5/(T + S)`: node by node when
//!   the temperature is a table (the ISA and every tabulated profile), pointwise for a
//!   constant temperature.

use crate::AtmosError;
use crate::column::{AirColumn, AirRow, ColumnTables};
use crate::curve::{Curve, sorted_unique};
use crate::earth::{Datum, earth_rotation_enu, somigliana_gravity};
use crate::isa::IsaTables;
use crate::profile::Profiles;
use karman_math::{Cursor, Extrapolation, Interpolation, PhysicalConstants, Table1};

/// The atmosphere model of an environment.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Atmosphere {
    /// ISO 2533 standard atmosphere as RocketPy discretises it, no wind.
    #[default]
    Standard,
    /// Tabulated profiles (custom, sounding, reanalysis, forecast, ensemble member).
    Profiles(Profiles),
}

/// The gravity model.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Gravity {
    /// WGS-84 Somigliana normal gravity with height (docs/physics.md §4.3), sampled at 100 points
    /// on [0, 80 km] into a natural cubic spline with constant extrapolation.
    #[default]
    Somigliana,
    /// A constant (m/s²).
    Constant(f64),
}

/// Everything needed to build an [`Environment`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EnvironmentConfig {
    /// Launch latitude (deg, north positive).
    pub latitude_deg: f64,
    /// Launch longitude (deg, east positive).
    pub longitude_deg: f64,
    /// Launch elevation (m ASL).
    pub elevation: f64,
    /// Geodetic datum (sets the local Earth radius).
    pub datum: Datum,
    /// Gravity model.
    pub gravity: Gravity,
    /// Atmosphere model.
    pub atmosphere: Atmosphere,
    /// Where the Earth quantities come from, if not from the launch site ([`EarthModel`]).
    pub earth_model: Option<EarthModel>,
}

/// The latitude and height range from which gravity, the local Earth radius and the
/// Earth-rotation vector are computed, when they differ from the launch site's (docs/physics.md
/// §18: RocketPy computes them once, in `Environment()`, from the arguments given there; a
/// script that sets the location afterwards flies with those of the first latitude).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EarthModel {
    /// Latitude (deg) of the Somigliana gravity, the Earth radius and the rotation vector.
    pub latitude_deg: f64,
    /// Top of the gravity table (m): 100 samples on `[0, gravity_max_height]`.
    pub gravity_max_height: f64,
}

/// Every height-dependent quantity of an [`Environment`] at one height ([`Environment::sample`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtmosphereSample {
    /// Pressure (Pa).
    pub pressure: f64,
    /// Temperature (K).
    pub temperature: f64,
    /// Density (kg/m³).
    pub density: f64,
    /// Speed of sound (m/s).
    pub speed_of_sound: f64,
    /// Dynamic viscosity (Pa·s).
    pub dynamic_viscosity: f64,
    /// Wind `[east, north]` (m/s).
    pub wind: [f64; 2],
    /// Gravity (m/s²).
    pub gravity: f64,
}

/// The quantities the equations of motion read at one height ([`Environment::air_near`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AirSample {
    /// Pressure (Pa).
    pub pressure: f64,
    /// Density (kg/m³).
    pub density: f64,
    /// Speed of sound (m/s).
    pub speed_of_sound: f64,
    /// Gravity (m/s²).
    pub gravity: f64,
}

/// A quantity derived from pressure and temperature: a table, or computed at each query.
#[derive(Debug, Clone, PartialEq)]
enum Derived {
    Table(Table1),
    Pointwise,
}

impl Derived {
    /// The table, if node-wise.
    fn table(&self) -> Option<&Table1> {
        match self {
            Derived::Table(t) => Some(t),
            Derived::Pointwise => None,
        }
    }
}

/// The launch environment (contracts.md "karman-atmos").
#[derive(Debug, Clone, PartialEq)]
pub struct Environment {
    elevation: f64,
    latitude_deg: f64,
    longitude_deg: f64,
    datum: Datum,
    datum_radius: f64,
    earth_rotation: [f64; 3],
    pressure: Table1,
    temperature: Table1,
    density: Derived,
    speed_of_sound: Derived,
    viscosity: Derived,
    wind_u: Table1,
    wind_v: Table1,
    /// The wind when it is the same at every height ([`Environment::uniform_wind`]).
    uniform_wind: Option<[f64; 2]>,
    gravity: Table1,
    /// The tables above re-cut on the union of their heights ([`Environment::sample_near`]).
    column: AirColumn,
    barometric_height: Table1,
    gas_constant: f64,
    gamma: f64,
    sutherland_b: f64,
    sutherland_s: f64,
}

impl Environment {
    /// Builds the environment and all its tables.
    ///
    /// # Errors
    /// Invalid site values (non-finite, latitude outside ±90°), unusable profiles (empty,
    /// non-finite, a non-positive temperature or pressure, a custom pressure that is not
    /// invertible).
    pub fn new(config: &EnvironmentConfig, c: &PhysicalConstants) -> Result<Self, AtmosError> {
        let lat = config.latitude_deg;
        checked(
            "latitude",
            lat,
            (-90.0..=90.0).contains(&lat),
            "must be within ±90°",
        )?;
        checked("longitude", config.longitude_deg, true, "must be finite")?;
        checked("elevation", config.elevation, true, "must be finite")?;

        let isa = IsaTables::new(c).map_err(|error| AtmosError::Table {
            source_name: "standard atmosphere".into(),
            quantity: "ISA".into(),
            error,
        })?;

        let ProfileTables {
            pressure,
            p_nodes,
            temperature,
            t_nodes,
            wind_u,
            wind_v,
            barometric_height,
        } = profiles(&config.atmosphere, isa)?;

        let r = c.air_gas_constant;
        let gamma = c.heat_capacity_ratio;
        let (b, s) = (c.sutherland_b, c.sutherland_s);
        let node_table = |base: &Table1, f: &dyn Fn(f64, f64) -> f64| {
            let ys: Vec<f64> = base
                .xs()
                .iter()
                .zip(base.ys())
                .map(|(&x, &y)| f(x, y))
                .collect();
            Table1::new(
                base.xs().to_vec(),
                ys,
                base.interpolation(),
                base.extrapolation(),
            )
            .map_err(|error| AtmosError::Table {
                source_name: "environment".into(),
                quantity: "derived".into(),
                error,
            })
        };
        let density = match (&p_nodes, &t_nodes) {
            (Some(a), Some(t)) if a == t => {
                let temps = temperature.clone();
                Derived::Table(node_table(&pressure, &|x, p| p / (r * temps.eval(x)))?)
            }
            _ => Derived::Pointwise,
        };
        let (speed_of_sound, viscosity) = if t_nodes.is_some() {
            (
                Derived::Table(node_table(&temperature, &|_, t| (gamma * r * t).sqrt())?),
                Derived::Table(node_table(&temperature, &|_, t| b * t.powf(1.5) / (t + s))?),
            )
        } else {
            (Derived::Pointwise, Derived::Pointwise)
        };

        let (earth_lat, gravity) = gravity_table(config, c)?;

        let column = AirColumn::new(&ColumnTables {
            pressure: &pressure,
            temperature: &temperature,
            density: density.table(),
            speed_of_sound: speed_of_sound.table(),
            viscosity: viscosity.table(),
            gravity: &gravity,
        })
        .ok_or_else(|| AtmosError::InvalidValue {
            what: "atmosphere tables".into(),
            value: f64::NAN,
            reason: "must be piecewise with held or extended ends".into(),
        })?;
        let uniform_wind = uniform_wind(&wind_u, &wind_v);
        Ok(Environment {
            elevation: config.elevation,
            latitude_deg: lat,
            longitude_deg: config.longitude_deg,
            datum: config.datum,
            datum_radius: config.datum.radius(earth_lat, c),
            earth_rotation: earth_rotation_enu(earth_lat, c),
            pressure,
            temperature,
            density,
            speed_of_sound,
            viscosity,
            wind_u,
            wind_v,
            uniform_wind,
            gravity,
            column,
            barometric_height,
            gas_constant: r,
            gamma,
            sutherland_b: b,
            sutherland_s: s,
        })
    }

    /// Launch elevation (m ASL).
    #[inline]
    #[must_use]
    pub fn elevation(&self) -> f64 {
        self.elevation
    }

    /// Launch latitude (deg).
    #[inline]
    #[must_use]
    pub fn latitude_deg(&self) -> f64 {
        self.latitude_deg
    }

    /// Launch longitude (deg).
    #[inline]
    #[must_use]
    pub fn longitude_deg(&self) -> f64 {
        self.longitude_deg
    }

    /// The geodetic datum.
    #[inline]
    #[must_use]
    pub fn datum(&self) -> Datum {
        self.datum
    }

    /// Air pressure (Pa) at height `z` (m ASL).
    #[inline]
    #[must_use]
    pub fn pressure(&self, z: f64) -> f64 {
        self.pressure.eval(z)
    }

    /// Air temperature (K) at height `z` (m ASL).
    #[inline]
    #[must_use]
    pub fn temperature(&self, z: f64) -> f64 {
        self.temperature.eval(z)
    }

    /// Air density (kg/m³) at height `z` (m ASL).
    #[inline]
    #[must_use]
    pub fn density(&self, z: f64) -> f64 {
        match &self.density {
            Derived::Table(t) => t.eval(z),
            Derived::Pointwise => self.pressure(z) / (self.gas_constant * self.temperature(z)),
        }
    }

    /// Speed of sound (m/s) at height `z` (m ASL).
    #[inline]
    #[must_use]
    pub fn speed_of_sound(&self, z: f64) -> f64 {
        match &self.speed_of_sound {
            Derived::Table(t) => t.eval(z),
            Derived::Pointwise => (self.gamma * self.gas_constant * self.temperature(z)).sqrt(),
        }
    }

    /// Dynamic viscosity (Pa·s) at height `z` (m ASL).
    #[inline]
    #[must_use]
    pub fn dynamic_viscosity(&self, z: f64) -> f64 {
        match &self.viscosity {
            Derived::Table(t) => t.eval(z),
            Derived::Pointwise => {
                let t = self.temperature(z);
                self.sutherland_b * t.powf(1.5) / (t + self.sutherland_s)
            }
        }
    }

    /// Wind velocity `[east u, north v]` (m/s) at height `z` (m ASL).
    #[inline]
    #[must_use]
    pub fn wind(&self, z: f64) -> [f64; 2] {
        match self.uniform_wind {
            Some(w) => w,
            None => [self.wind_u.eval(z), self.wind_v.eval(z)],
        }
    }

    /// The wind `[east u, north v]` (m/s) when it is the same at every height (a constant
    /// profile, such as the calm of the standard atmosphere), so that a caller may skip the
    /// per-height lookups of [`Environment::wind`]; `None` when it varies with height.
    #[must_use]
    pub fn uniform_wind(&self) -> Option<[f64; 2]> {
        self.uniform_wind
    }

    /// Gravity (m/s², positive down) at height `z` (m ASL).
    #[inline]
    #[must_use]
    pub fn gravity(&self, z: f64) -> f64 {
        self.gravity.eval(z)
    }

    /// Every height-dependent quantity at once, equal to the individual methods (the pointwise
    /// derived quantities from the same pressure and temperature).
    #[inline]
    #[must_use]
    pub fn sample(&self, z: f64) -> AtmosphereSample {
        self.sample_near(z, &mut Cursor::default())
    }

    /// [`Environment::sample`] with the height located from `cursor` (updated): the same
    /// values, found faster when successive heights are close, as along an integration.
    #[inline]
    #[must_use]
    pub fn sample_near(&self, z: f64, cursor: &mut Cursor) -> AtmosphereSample {
        let row = self.column.row_near(z, cursor);
        let temperature = row.temperature.eval(z);
        let dynamic_viscosity = match &self.viscosity {
            Derived::Table(_) => row.viscosity.eval(z),
            Derived::Pointwise => {
                self.sutherland_b * temperature.powf(1.5) / (temperature + self.sutherland_s)
            }
        };
        let air = self.air_in(row, z, temperature);
        AtmosphereSample {
            pressure: air.pressure,
            temperature,
            density: air.density,
            speed_of_sound: air.speed_of_sound,
            dynamic_viscosity,
            wind: self.wind(z),
            gravity: air.gravity,
        }
    }

    /// What the equations of motion read at height `z` (pressure, density, speed of sound and
    /// gravity, equal to [`Environment::sample`]'s), located from `cursor` (updated).
    #[inline]
    #[must_use]
    pub fn air_near(&self, z: f64, cursor: &mut Cursor) -> AirSample {
        let row = self.column.row_near(z, cursor);
        self.air_in(row, z, row.temperature.eval(z))
    }

    /// [`Environment::air_near`] on a located row, given the temperature there.
    #[inline(always)]
    fn air_in(&self, row: &AirRow, z: f64, temperature: f64) -> AirSample {
        let pressure = row.pressure.eval(z);
        AirSample {
            pressure,
            density: match &self.density {
                Derived::Table(_) => row.density.eval(z),
                Derived::Pointwise => pressure / (self.gas_constant * temperature),
            },
            speed_of_sound: match &self.speed_of_sound {
                Derived::Table(_) => row.speed_of_sound.eval(z),
                Derived::Pointwise => (self.gamma * self.gas_constant * temperature).sqrt(),
            },
            gravity: row.gravity.eval(z),
        }
    }

    /// Earth's rotation vector in the launch ENU frame, `Ω (0, cos φ, sin φ)` (rad/s).
    #[inline]
    #[must_use]
    pub fn earth_rotation_enu(&self) -> [f64; 3] {
        self.earth_rotation
    }

    /// Barometric height (m ASL) of a pressure (Pa), docs/physics.md §4.4.
    #[inline]
    #[must_use]
    pub fn barometric_height(&self, pressure: f64) -> f64 {
        self.barometric_height.eval(pressure)
    }

    /// Latitude and longitude (deg) of the point `east`, `north` (m) of the launch point, on
    /// the sphere of the datum radius ([`karman_math::geodesy::destination`]).
    #[must_use]
    pub fn geodetic(&self, east: f64, north: f64) -> (f64, f64) {
        karman_math::geodesy::destination(
            self.latitude_deg,
            self.longitude_deg,
            east,
            north,
            self.datum_radius,
        )
    }

    /// Local Earth radius of the datum at the launch latitude (m), docs/physics.md §4.6.
    #[inline]
    #[must_use]
    pub fn datum_radius(&self) -> f64 {
        self.datum_radius
    }
}

/// Rejects non-positive values of a pressure or temperature curve.
fn positive(curve: &Curve, source_name: &str, quantity: &str) -> Result<(), AtmosError> {
    let bad = match curve {
        Curve::Constant(v) => (v.is_nan() || *v <= 0.0).then_some((0.0, *v)),
        Curve::Points(p) => p
            .iter()
            .find(|[_, v]| v.is_nan() || *v <= 0.0)
            .map(|[h, v]| (*h, *v)),
    };
    match bad {
        Some((h, v)) => Err(AtmosError::InvalidValue {
            what: format!("{source_name}: {quantity} at {h} m"),
            value: v,
            reason: "must be positive".into(),
        }),
        None => Ok(()),
    }
}

/// The wind of two constant profiles: every value [`Table1::eval`] returns is then the
/// sample, bit for bit — a single sample, or equal samples whose pieces are flat (not a
/// fitted polynomial), with no zero extrapolation of a non-zero value.
fn uniform_wind(wind_u: &Table1, wind_v: &Table1) -> Option<[f64; 2]> {
    let uniform = |t: &Table1| {
        let y0 = *t.ys().first()?;
        let flat = t.xs().len() == 1 || t.interpolation() != Interpolation::Polynomial;
        let same = t.ys().iter().all(|y| y.to_bits() == y0.to_bits());
        let held = t.extrapolation() != Extrapolation::Zero || y0.to_bits() == 0;
        (flat && same && held).then_some(y0)
    };
    Some([uniform(wind_u)?, uniform(wind_v)?])
}

/// The barometric-height table of a tabulated atmosphere (see [`Profiles::barometric_points`]).
fn barometric(p: &Profiles, pressure: &Table1, isa: &IsaTables) -> Result<Table1, AtmosError> {
    let src = p.source_name.as_str();
    let table_err = |error| AtmosError::Table {
        source_name: src.into(),
        quantity: "barometric height".into(),
        error,
    };
    if let Some(points) = &p.barometric_points {
        let (ps, hs) = sorted_unique(points);
        return Table1::new(ps, hs, Interpolation::Linear, Extrapolation::Natural)
            .map_err(table_err);
    }
    match &p.pressure {
        Some(Curve::Points(_)) if pressure.xs().len() > 1 => {
            let (hs, ps) = (pressure.xs(), pressure.ys());
            let rising = ps[1] > ps[0];
            for k in 1..ps.len() {
                if (ps[k] > ps[k - 1]) != rising || (ps[k] - ps[k - 1]).abs() <= 0.0 {
                    return Err(AtmosError::NotInvertible {
                        source_name: src.into(),
                        height: hs[k],
                    });
                }
            }
            let mut pairs: Vec<[f64; 2]> = ps.iter().zip(hs).map(|(&p, &h)| [p, h]).collect();
            if !rising {
                pairs.reverse();
            }
            let (xs, ys): (Vec<f64>, Vec<f64>) = pairs.into_iter().map(|[a, b]| (a, b)).unzip();
            Table1::new(xs, ys, pressure.interpolation(), pressure.extrapolation())
                .map_err(table_err)
        }
        Some(Curve::Points(_)) => Err(AtmosError::NotInvertible {
            source_name: src.into(),
            height: pressure.xs()[0],
        }),
        _ => Ok(isa.barometric_height.clone()),
    }
}

/// `Ok` when `v` is finite and `ok`; otherwise the invalid value `what` with its `reason`.
fn checked(what: &str, v: f64, ok: bool, reason: &str) -> Result<(), AtmosError> {
    if v.is_finite() && ok {
        Ok(())
    } else {
        Err(AtmosError::InvalidValue {
            what: what.into(),
            value: v,
            reason: reason.into(),
        })
    }
}

/// The tabulated profiles of an atmosphere: pressure and temperature with the heights of
/// their nodes (`None`: a constant, which RocketPy holds as a callable), the winds and the
/// barometric height.
struct ProfileTables {
    pressure: Table1,
    p_nodes: Option<Vec<f64>>,
    temperature: Table1,
    t_nodes: Option<Vec<f64>>,
    wind_u: Table1,
    wind_v: Table1,
    barometric_height: Table1,
}

/// The profiles of `atmosphere`, the standard atmosphere's (`isa`) where it gives none.
///
/// # Errors
/// A curve that is not positive (pressure, temperature) or cannot be tabulated.
fn profiles(atmosphere: &Atmosphere, isa: IsaTables) -> Result<ProfileTables, AtmosError> {
    let lin = Interpolation::Linear;
    let hold = Extrapolation::Constant;
    Ok(match atmosphere {
        Atmosphere::Standard => {
            let zero = Curve::Constant(0.0).to_table("standard", "wind", lin, hold)?;
            let p_nodes = Some(isa.pressure.xs().to_vec());
            let t_nodes = Some(isa.temperature.xs().to_vec());
            ProfileTables {
                pressure: isa.pressure,
                p_nodes,
                temperature: isa.temperature,
                t_nodes,
                wind_u: zero.clone(),
                wind_v: zero,
                barometric_height: isa.barometric_height,
            }
        }
        Atmosphere::Profiles(p) => {
            let src = p.source_name.as_str();
            let (pressure, p_nodes) = match &p.pressure {
                None => {
                    let nodes = Some(isa.pressure.xs().to_vec());
                    (isa.pressure.clone(), nodes)
                }
                Some(curve) => {
                    positive(curve, src, "pressure")?;
                    (curve.to_table(src, "pressure", lin, hold)?, curve.heights())
                }
            };
            let (temperature, t_nodes) = match &p.temperature {
                None => {
                    let nodes = Some(isa.temperature.xs().to_vec());
                    (isa.temperature.clone(), nodes)
                }
                Some(curve) => {
                    positive(curve, src, "temperature")?;
                    (
                        curve.to_table(src, "temperature", lin, hold)?,
                        curve.heights(),
                    )
                }
            };
            let wind_u = p.wind_u.to_table(src, "wind_u", lin, hold)?;
            let wind_v = p.wind_v.to_table(src, "wind_v", lin, hold)?;
            let baro = barometric(p, &pressure, &isa)?;
            ProfileTables {
                pressure,
                p_nodes,
                temperature,
                t_nodes,
                wind_u,
                wind_v,
                barometric_height: baro,
            }
        }
    })
}

/// The gravity table of `config` (Somigliana's on the latitude of its Earth model, or a
/// constant) and the latitude the Earth's figure is taken at, deg.
///
/// # Errors
/// An Earth model's latitude outside ±90° or a gravity top that is not positive; a constant
/// gravity that is not positive.
fn gravity_table(
    config: &EnvironmentConfig,
    c: &PhysicalConstants,
) -> Result<(f64, Table1), AtmosError> {
    let lin = Interpolation::Linear;
    let hold = Extrapolation::Constant;
    let (earth_lat, gravity_top) = match config.earth_model {
        Some(model) => {
            checked(
                "earth_model latitude",
                model.latitude_deg,
                (-90.0..=90.0).contains(&model.latitude_deg),
                "must be within [-90, 90] deg",
            )?;
            checked(
                "earth_model gravity_max_height",
                model.gravity_max_height,
                model.gravity_max_height > 0.0,
                "must be positive",
            )?;
            (model.latitude_deg, model.gravity_max_height)
        }
        None => (config.latitude_deg, c.table_top_height),
    };
    let gravity = match config.gravity {
        Gravity::Somigliana => Table1::sample(
            |h| somigliana_gravity(earth_lat, h, c),
            0.0,
            gravity_top,
            100,
            Interpolation::Spline,
            Extrapolation::Constant,
        ),
        Gravity::Constant(g) => {
            checked("gravity", g, g > 0.0, "must be positive")?;
            Table1::new(vec![0.0], vec![g], lin, hold)
        }
    }
    .map_err(|error| AtmosError::Table {
        source_name: "gravity".into(),
        quantity: "gravity".into(),
        error,
    })?;
    Ok((earth_lat, gravity))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn isa_env() -> Environment {
        let config = EnvironmentConfig {
            earth_model: None,
            latitude_deg: 32.990254,
            longitude_deg: -106.974998,
            elevation: 1400.0,
            ..EnvironmentConfig::default()
        };
        Environment::new(&config, &PhysicalConstants::SI).expect("environment")
    }

    #[test]
    fn isa_spot_values_match_rocketpy() {
        // docs/physics.md §4.1 spot values at 1400 m and §13 anchors at 4700 m (RocketPy 1.13).
        let e = isa_env();
        let rel = |a: f64, b: f64| ((a - b) / b).abs();
        assert!(rel(e.pressure(1400.0), 85596.6788) < 1e-8);
        assert!(rel(e.density(1400.0), 1.0685345) < 1e-7);
        assert!(rel(e.speed_of_sound(1400.0), 334.54807) < 1e-7);
        assert!(rel(e.dynamic_viscosity(1400.0), 1.742654e-5) < 1e-6);
        assert!(rel(e.density(4700.0), 0.7605031) < 1e-7);
        assert!(rel(e.speed_of_sound(4700.0), 321.00412) < 1e-7);
        assert!(rel(e.gravity(1400.0), 9.7913331) < 2e-8);
        assert!(rel(e.gravity(4700.0), 9.7811624) < 2e-8);
        // Sea-level density of the docstring of calculate_density_profile.
        assert!(rel(e.density(0.0), 1.225000018124288) < 1e-12);
        assert!(
            e.wind(1000.0).iter().all(|w| w.abs() < 1e-300),
            "no wind in the ISA"
        );
    }

    #[test]
    fn sample_equals_the_individual_queries() {
        let isa = isa_env();
        let profiles = Profiles {
            source_name: "inline".into(),
            pressure: Some(Curve::Points(vec![[0.0, 100_000.0], [1000.0, 90_000.0]])),
            temperature: Some(Curve::Points(vec![
                [-200.0, 291.0],
                [0.0, 290.0],
                [1000.0, 280.0],
            ])),
            ..Profiles::wind_only("inline", Curve::Constant(1.0), Curve::Constant(2.0))
        };
        let custom = |gravity, profiles: &Profiles| {
            Environment::new(
                &EnvironmentConfig {
                    earth_model: None,
                    atmosphere: Atmosphere::Profiles(profiles.clone()),
                    gravity,
                    ..Default::default()
                },
                &PhysicalConstants::SI,
            )
            .expect("environment")
        };
        let same_heights = Profiles {
            temperature: Some(Curve::Points(vec![[0.0, 290.0], [1000.0, 280.0]])),
            ..profiles.clone()
        };
        let environments = [
            isa,
            custom(Gravity::Constant(9.8), &profiles),
            custom(Gravity::Somigliana, &profiles),
            custom(Gravity::Somigliana, &same_heights),
        ];
        for e in environments {
            // Every sample height of every table (where the air column's pieces change),
            // points between them and beyond both ends.
            let mut knots: Vec<f64> = [&e.pressure, &e.temperature, &e.gravity]
                .into_iter()
                .chain(
                    [&e.density, &e.speed_of_sound, &e.viscosity]
                        .map(Derived::table)
                        .into_iter()
                        .flatten(),
                )
                .flat_map(|t| t.xs().to_vec())
                .collect();
            knots.sort_by(f64::total_cmp);
            let between: Vec<f64> = knots.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
            let (low, high) = (knots[0], knots[knots.len() - 1]);
            let heights: Vec<f64> = knots
                .iter()
                .chain(&between)
                .copied()
                .chain([low - 700.0, low - 1e-9, high + 1e-6, high + 9000.0])
                .collect();
            // A cursor carried up, down and across the heights changes nothing.
            let mut cursor = Cursor::default();
            for &z in heights.iter().chain(heights.iter().rev()) {
                let s = e.sample(z);
                assert_eq!(e.sample_near(z, &mut cursor), s);
                // Bit for bit: the equations of motion use `air_near`, post-processing the rest.
                let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
                assert!(same(s.pressure, e.pressure(z)), "{z}");
                assert!(same(s.density, e.density(z)), "{z}");
                assert!(same(s.temperature, e.temperature(z)), "{z}");
                assert!(same(s.speed_of_sound, e.speed_of_sound(z)), "{z}");
                assert!(same(s.dynamic_viscosity, e.dynamic_viscosity(z)), "{z}");
                assert!(same(s.gravity, e.gravity(z)), "{z}");
                assert!(s.wind.iter().zip(e.wind(z)).all(|(a, b)| same(*a, b)));
                let air = e.air_near(z, &mut cursor);
                assert!(same(air.pressure, s.pressure) && same(air.density, s.density));
                assert!(same(air.speed_of_sound, s.speed_of_sound));
                assert!(same(air.gravity, s.gravity));
            }
        }
    }

    #[test]
    fn custom_tables_are_node_wise() {
        let profiles = Profiles {
            source_name: "inline".into(),
            pressure: Some(Curve::Points(vec![[0.0, 100_000.0], [1000.0, 90_000.0]])),
            temperature: Some(Curve::Points(vec![[0.0, 290.0], [1000.0, 280.0]])),
            wind_u: Curve::Constant(5.0),
            wind_v: Curve::Points(vec![[0.0, -2.0], [5000.0, -6.0]]),
            barometric_points: None,
        };
        let config = EnvironmentConfig {
            earth_model: None,
            atmosphere: Atmosphere::Profiles(profiles),
            ..Default::default()
        };
        let e = Environment::new(&config, &PhysicalConstants::SI).expect("environment");
        let r = PhysicalConstants::SI.air_gas_constant;
        let rho = 0.5 * (100_000.0 / (r * 290.0) + 90_000.0 / (r * 280.0));
        assert!((e.density(500.0) - rho).abs() < 1e-12);
        assert!((e.barometric_height(95_000.0) - 500.0).abs() < 1e-9);
        assert!((e.wind(2500.0)[1] + 4.0).abs() < 1e-12);
        assert!((e.wind(1e5)[0] - 5.0).abs() < 1e-12);
        assert_eq!(e.uniform_wind(), None, "the north wind varies with height");
    }

    #[test]
    fn uniform_wind_is_every_height_s_wind() {
        let calm = isa_env();
        let steady = Environment::new(
            &EnvironmentConfig {
                earth_model: None,
                atmosphere: Atmosphere::Profiles(Profiles::wind_only(
                    "inline",
                    Curve::Constant(5.0),
                    Curve::Points(vec![[0.0, -2.0], [3000.0, -2.0], [9000.0, -2.0]]),
                )),
                ..Default::default()
            },
            &PhysicalConstants::SI,
        )
        .expect("environment");
        for e in [calm, steady] {
            let w = e.uniform_wind().expect("a uniform wind");
            for z in [-100.0, 0.0, 1400.0, 2999.0, 4700.0, 1e5] {
                let at = e.wind(z);
                // Bit for bit: a caller uses it instead of the lookups.
                assert!(w.iter().zip(at).all(|(a, b)| a.to_bits() == b.to_bits()));
            }
        }
    }

    #[test]
    fn bad_inputs_are_errors() {
        let mut config = EnvironmentConfig {
            earth_model: None,
            latitude_deg: 95.0,
            ..Default::default()
        };
        assert!(Environment::new(&config, &PhysicalConstants::SI).is_err());
        config.latitude_deg = 0.0;
        config.atmosphere = Atmosphere::Profiles(Profiles {
            pressure: Some(Curve::Points(vec![[0.0, 1e5], [10.0, 1e5], [20.0, 9e4]])),
            ..Profiles::wind_only("x.csv", Curve::Constant(0.0), Curve::Constant(0.0))
        });
        let e = Environment::new(&config, &PhysicalConstants::SI).expect_err("not invertible");
        assert!(matches!(e, AtmosError::NotInvertible { .. }), "{e}");
        config.atmosphere = Atmosphere::Profiles(Profiles {
            temperature: Some(Curve::Constant(-3.0)),
            ..Profiles::wind_only("x.csv", Curve::Constant(0.0), Curve::Constant(0.0))
        });
        assert!(Environment::new(&config, &PhysicalConstants::SI).is_err());
    }
}
