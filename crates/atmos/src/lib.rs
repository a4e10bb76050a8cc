//! # karman-atmos
//!
//! The launch environment: atmosphere (pressure, temperature, density, speed of sound,
//! viscosity), wind and gravity as functions of height above sea level, from the ISA
//! (ISO 2533), custom profiles, soundings and reanalysis/forecast grids, reproducing RocketPy
//! 1.13's `Environment` (docs/physics.md §4).
//!
//! - [`Environment`]: built once from an [`EnvironmentConfig`]; every query is an
//!   allocation-free table evaluation.
//! - [`isa`]: the standard atmosphere as RocketPy discretises it.
//! - [`curve`]: user profiles and the two-column table parser.
//! - [`sounding`]: Wyoming TEXT:LIST and NOAA RUC soundings.
//! - [`grid`]: netCDF weather grids (ERA5, GFS-style, ensembles, projected NAM/RAP/HRRR).
//! - [`open_meteo`]: Open-Meteo pressure-level forecasts saved as JSON.
//! - [`earth`]: datums, Somigliana gravity, Earth rotation.
//! - [`time`]: calendar and CF time units.
//! - `fetch` (cargo feature `fetch`): live download of soundings and forecasts.

mod column;
pub mod curve;
pub mod earth;
mod environment;
mod error;
#[cfg(feature = "fetch")]
pub mod fetch;
pub mod grid;
pub mod isa;
mod model;
pub mod open_meteo;
mod profile;
pub mod sounding;
pub mod time;

pub use curve::{Curve, parse_table};
pub use earth::Datum;
pub use environment::{
    AirSample, Atmosphere, AtmosphereSample, EarthModel, Environment, EnvironmentConfig, Gravity,
};
pub use error::AtmosError;
pub use grid::{GridDictionary, GridRequest, WeatherGrid};
pub use open_meteo::OpenMeteo;
pub use profile::{LevelProfile, Profiles};
pub use sounding::{Sounding, SoundingFormat, SoundingLevel};

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
