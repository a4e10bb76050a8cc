//! `[environment]` → [`karman_atmos::Environment`]: the site, the datum, gravity and the
//! atmosphere model (standard, custom, sounding, reanalysis, forecast, ensemble) as RocketPy
//! 1.13's `Environment` + `set_atmospheric_model` would build them, and Open-Meteo forecasts
//! saved as JSON (karman's addition: the levels taken as a weather grid's are).
//!
//! Choices documented here:
//! - The mission's `elevation` is the launch elevation for every model. RocketPy replaces it
//!   with a sounding's station elevation or a forecast's surface height; karman does not (the
//!   mission states where the rocket stands).
//! - Weather grids: the nearest time step to `date` (a tie goes to the earlier step), bilinear
//!   in latitude/longitude (see `karman_atmos::grid`).
//! - `max_expected_height` does not change the gravity table: RocketPy samples it on
//!   0–80 000 m when the notebooks construct the environment (validation README caveat); it
//!   only sets the default extent of the environment report.
//! - `[environment.earth_model]` states the latitude and gravity height range RocketPy's
//!   `Environment()` was built with (docs/physics.md §18): they give the gravity table, the Earth
//!   radius (also that of a weather grid's geopotential heights) and the rotation vector.

use crate::schema::{AtmosphereModel, Curve, Datum, SoundingFormat};
use crate::{Mission, MissionError};
use karman_atmos::{
    AtmosError, Atmosphere, EarthModel, Environment, EnvironmentConfig, Gravity, GridDictionary,
    GridRequest, LevelProfile, OpenMeteo, Profiles, Sounding, WeatherGrid,
};
use karman_dynamics::Air;
use karman_math::{Cursor, PhysicalConstants};

/// Builds the launch environment of a mission.
///
/// # Errors
/// [`MissionError::Model`] (section `environment` or `environment.atmosphere`) wrapping the
/// [`AtmosError`]: an unreadable data file, a date or site outside a weather file, a malformed
/// sounding or profile, ...
pub fn build_environment(mission: &Mission) -> Result<Environment, MissionError> {
    build_environment_checked(mission).map(|(environment, _)| environment)
}

/// [`build_environment`] with the warnings about the weather data: a weather grid, sounding
/// or forecast whose heights do not rise monotonically through its levels (the profiles are
/// sorted by height, which mixes the levels).
///
/// # Errors
/// As [`build_environment`].
pub fn build_environment_checked(
    mission: &Mission,
) -> Result<(Environment, Vec<String>), MissionError> {
    let constants = PhysicalConstants::SI;
    let env = &mission.spec.environment;
    let model_err = |section: &str, e: AtmosError| mission.model_error(section, e);
    let datum = datum(mission);
    let gravity = env.gravity.map_or(Gravity::Somigliana, Gravity::Constant);
    let mut warnings = Vec::new();
    let atmosphere = build_atmosphere(mission, datum, &constants, &mut warnings)
        .map_err(|e| model_err("environment.atmosphere", e))?;
    let config = EnvironmentConfig {
        earth_model: earth_model(mission, &constants),
        latitude_deg: env.latitude_deg,
        longitude_deg: env.longitude_deg,
        elevation: env.elevation,
        datum,
        gravity,
        atmosphere,
    };
    let environment =
        Environment::new(&config, &constants).map_err(|e| model_err("environment", e))?;
    Ok((environment, warnings))
}

/// The mission's geodetic datum.
fn datum(mission: &Mission) -> karman_atmos::Datum {
    match mission.spec.environment.datum {
        None | Some(Datum::Sirgas2000) => karman_atmos::Datum::Sirgas2000,
        Some(Datum::Wgs84) => karman_atmos::Datum::Wgs84,
        Some(Datum::Sad69) => karman_atmos::Datum::Sad69,
        Some(Datum::Nad83) => karman_atmos::Datum::Nad83,
    }
}

/// The Earth radius (m) that turns the weather data's geopotential heights into geometric
/// ones: the datum radius at the earth model's latitude, else the site's.
#[must_use]
pub fn weather_earth_radius(mission: &Mission) -> f64 {
    datum(mission).radius(earth_latitude(mission), &PhysicalConstants::SI)
}

/// `[environment.earth_model]` with its defaults, if present.
fn earth_model(mission: &Mission, constants: &PhysicalConstants) -> Option<EarthModel> {
    let env = &mission.spec.environment;
    env.earth_model.as_ref().map(|m| EarthModel {
        latitude_deg: m.latitude_deg.unwrap_or(env.latitude_deg),
        gravity_max_height: m.gravity_max_height.unwrap_or(constants.table_top_height),
    })
}

/// The latitude of the Earth radius: the earth model's, else the site's.
fn earth_latitude(mission: &Mission) -> f64 {
    let env = &mission.spec.environment;
    env.earth_model
        .as_ref()
        .and_then(|m| m.latitude_deg)
        .unwrap_or(env.latitude_deg)
}

/// Unix time (s, UTC) of the mission's date, if it has a full date-time with an offset and
/// the date exists.
#[must_use]
pub fn launch_unix_time(mission: &Mission) -> Option<f64> {
    let dt = mission.spec.environment.date.as_ref()?;
    let date = dt.date?;
    let offset_minutes = match dt.offset? {
        toml::value::Offset::Z => 0.0,
        toml::value::Offset::Custom { minutes } => f64::from(minutes),
    };
    let (h, m, s) = dt.time.map_or((0, 0, 0.0), |t| {
        let ns = f64::from(t.nanosecond.unwrap_or(0)) * 1e-9;
        (
            u32::from(t.hour),
            u32::from(t.minute),
            f64::from(t.second.unwrap_or(0)) + ns,
        )
    });
    let local = karman_atmos::time::unix_seconds(
        i64::from(date.year),
        u32::from(date.month),
        u32::from(date.day),
        h,
        m,
        s,
    )?;
    Some(local - offset_minutes * 60.0)
}

fn build_atmosphere(
    mission: &Mission,
    datum: karman_atmos::Datum,
    constants: &PhysicalConstants,
    warnings: &mut Vec<String>,
) -> Result<Atmosphere, AtmosError> {
    let env = &mission.spec.environment;
    let spec = &env.atmosphere;
    let radius = datum.radius(earth_latitude(mission), constants);
    let data_file = || -> Result<std::path::PathBuf, AtmosError> {
        spec.file
            .as_ref()
            .map(|f| mission.resolve(f))
            .ok_or_else(|| AtmosError::Empty {
                source_name: mission.path.display().to_string(),
                what: "`file` of [environment.atmosphere]".into(),
            })
    };
    match spec.model {
        AtmosphereModel::Standard => Ok(Atmosphere::Standard),
        AtmosphereModel::Custom => {
            let curve = |c: &Option<Curve>,
                         what: &str|
             -> Result<Option<karman_atmos::Curve>, AtmosError> {
                c.as_ref()
                    .map(|c| atmos_curve(mission, c, what))
                    .transpose()
            };
            let zero = karman_atmos::Curve::Constant(0.0);
            Ok(Atmosphere::Profiles(Profiles {
                source_name: format!("{} [environment.atmosphere]", mission.path.display()),
                pressure: curve(&spec.pressure, "pressure")?,
                temperature: curve(&spec.temperature, "temperature")?,
                wind_u: curve(&spec.wind_u, "wind_u")?.unwrap_or_else(|| zero.clone()),
                wind_v: curve(&spec.wind_v, "wind_v")?.unwrap_or(zero),
                barometric_points: None,
            }))
        }
        AtmosphereModel::Sounding => {
            let path = data_file()?;
            let name = path.display().to_string();
            let text = read_text(&path, &name)?;
            let sounding = match spec.format.unwrap_or(SoundingFormat::Wyoming) {
                SoundingFormat::Wyoming => Sounding::parse_wyoming(&text, &name)?,
                SoundingFormat::NoaaRuc => Sounding::parse_noaa_ruc(&text, &name)?,
            };
            warn_fold(&sounding.level_profile(radius), warnings);
            Ok(Atmosphere::Profiles(sounding.profiles(radius)?))
        }
        AtmosphereModel::Reanalysis | AtmosphereModel::Forecast | AtmosphereModel::Ensemble => {
            let path = data_file()?;
            let name = path.display().to_string();
            let unix_time =
                launch_unix_time(mission).ok_or(AtmosError::DateRequired { file: name.clone() })?;
            let dictionary = spec
                .dictionary
                .as_deref()
                .map(GridDictionary::builtin)
                .transpose()?;
            let grid = WeatherGrid::open(&path)?;
            let request = GridRequest {
                dictionary,
                unix_time,
                latitude_deg: env.latitude_deg,
                longitude_deg: env.longitude_deg,
                member: spec.member.map(|m| m as usize),
                earth_radius: radius,
                standard_gravity: constants.standard_gravity,
            };
            let levels = grid.profile(&request)?;
            warn_fold(&levels, warnings);
            Ok(Atmosphere::Profiles(levels.profiles(&name)))
        }
        AtmosphereModel::OpenMeteo => {
            let path = data_file()?;
            let name = path.display().to_string();
            let unix_time =
                launch_unix_time(mission).ok_or(AtmosError::DateRequired { file: name.clone() })?;
            let bytes = karman_math::read_data_file(&path).map_err(|e| AtmosError::Io {
                file: name.clone(),
                message: e.to_string(),
            })?;
            let forecast = OpenMeteo::parse(&bytes, &name)?;
            let levels = forecast.profile(unix_time, spec.member.map(|m| m as usize), radius)?;
            warn_fold(&levels, warnings);
            Ok(Atmosphere::Profiles(levels.profiles(&name)))
        }
    }
}

/// The warning for heights that fold back through the levels ([`LevelProfile::height_fold`]).
fn warn_fold(levels: &LevelProfile, warnings: &mut Vec<String>) {
    if let Some(([p0, h0], [p1, h1])) = levels.height_fold() {
        warnings.push(format!(
            "`environment.atmosphere.file`: the heights are not monotonic through the levels: \
             {:.1} hPa at {h0:.0} m, then {:.1} hPa at {h1:.0} m (the profile is sorted by \
             height, which mixes these levels; is the file damaged?)",
            p0 / 100.0,
            p1 / 100.0
        ));
    }
}

/// A mission curve of height as an atmosphere curve (files parsed by
/// [`karman_atmos::parse_table`]).
fn atmos_curve(
    mission: &Mission,
    curve: &Curve,
    what: &str,
) -> Result<karman_atmos::Curve, AtmosError> {
    match curve {
        Curve::Constant(v) => Ok(karman_atmos::Curve::Constant(*v)),
        Curve::Points(p) => Ok(karman_atmos::Curve::Points(p.clone())),
        Curve::File(f) => {
            let path = mission.resolve(f);
            let name = format!("{} ({what})", path.display());
            let text = read_text(&path, &name)?;
            Ok(karman_atmos::Curve::Points(karman_atmos::parse_table(
                &text, &name,
            )?))
        }
    }
}

/// The text of an atmosphere data file (a regular file only; bytes that are not UTF-8 are
/// replaced, and then reported by the parser as text it cannot read).
fn read_text(path: &std::path::Path, name: &str) -> Result<String, AtmosError> {
    let bytes = karman_math::read_data_file(path).map_err(|e| AtmosError::Io {
        file: name.to_owned(),
        message: e.to_string(),
    })?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// An environment whose wind is multiplied by `factor` and turned clockwise (seen from
/// above) by `offset_deg`: `(u, v) → factor · (u cos δ + v sin δ, −u sin δ + v cos δ)`.
#[derive(Debug, Clone, Copy)]
pub struct WindAdjusted<'a> {
    environment: &'a Environment,
    factor: f64,
    sin: f64,
    cos: f64,
}

impl<'a> WindAdjusted<'a> {
    /// The adjusted environment.
    pub fn new(environment: &'a Environment, factor: f64, offset_deg: f64) -> Self {
        let (sin, cos) = offset_deg.to_radians().sin_cos();
        WindAdjusted {
            environment,
            factor,
            sin,
            cos,
        }
    }
}

impl WindAdjusted<'_> {
    /// The adjusted wind vector.
    #[inline]
    fn turn(&self, [u, v]: [f64; 2]) -> [f64; 2] {
        [
            self.factor * (u * self.cos + v * self.sin),
            self.factor * (-u * self.sin + v * self.cos),
        ]
    }
}

impl karman_dynamics::AtmosphereModel for WindAdjusted<'_> {
    #[inline]
    fn elevation(&self) -> f64 {
        self.environment.elevation()
    }
    #[inline]
    fn pressure(&self, z: f64) -> f64 {
        self.environment.pressure(z)
    }
    #[inline]
    fn density(&self, z: f64) -> f64 {
        self.environment.density(z)
    }
    #[inline]
    fn speed_of_sound(&self, z: f64) -> f64 {
        self.environment.speed_of_sound(z)
    }
    #[inline]
    fn dynamic_viscosity(&self, z: f64) -> f64 {
        self.environment.dynamic_viscosity(z)
    }
    #[inline]
    fn wind(&self, z: f64) -> [f64; 2] {
        self.turn(self.environment.wind(z))
    }
    fn uniform_wind(&self) -> Option<[f64; 2]> {
        self.environment.uniform_wind().map(|wind| self.turn(wind))
    }
    #[inline]
    fn air(&self, z: f64) -> Air {
        self.environment.air(z)
    }
    #[inline]
    fn air_near(&self, z: f64, cursor: &mut Cursor) -> Air {
        karman_dynamics::AtmosphereModel::air_near(self.environment, z, cursor)
    }
    #[inline]
    fn gravity(&self, z: f64) -> f64 {
        self.environment.gravity(z)
    }
    #[inline]
    fn earth_rotation_enu(&self) -> [f64; 3] {
        self.environment.earth_rotation_enu()
    }
    #[inline]
    fn barometric_height(&self, pressure: f64) -> f64 {
        self.environment.barometric_height(pressure)
    }
}
