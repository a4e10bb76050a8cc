//! Units of the columns of a log, and their conversion to SI.
//!
//! Conversion factors are the exact definitions: 1 ft = 0.3048 m (international foot, 1959),
//! 1 g = 9.80665 m/s² (standard gravity, `PhysicalConstants::SI`), 1 atm = 101 325 Pa,
//! °F → K by (F − 32)·5/9 + 273.15.

use karman_math::PhysicalConstants;

/// Metres per international foot (exact).
pub(crate) const FOOT: f64 = 0.3048;

/// A unit a log column may be written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    /// Metre.
    Metre,
    /// International foot.
    Foot,
    /// Second.
    Second,
    /// Millisecond.
    Millisecond,
    /// Metre per second.
    MetrePerSecond,
    /// Foot per second.
    FootPerSecond,
    /// Standard gravity, 9.80665 m/s².
    StandardGravity,
    /// Metre per second squared.
    MetrePerSecondSquared,
    /// Pascal.
    Pascal,
    /// Hectopascal (= millibar).
    Hectopascal,
    /// Kilopascal.
    Kilopascal,
    /// Standard atmosphere, 101 325 Pa.
    Atmosphere,
    /// Degree Celsius.
    Celsius,
    /// Degree Fahrenheit.
    Fahrenheit,
    /// Kelvin.
    Kelvin,
    /// Degree of angle (latitude, longitude): kept as is.
    Degree,
}

impl Unit {
    /// The unit a mapping's suffix names (`m`, `ft`, `s`, `ms`, `m/s`, `ft/s`, `g`, `m/s2`,
    /// `Pa`, `hPa`, `mbar`, `kPa`, `atm`, `C`, `F`, `K`, `deg`), case-sensitive for the
    /// prefixes that differ only in case, or `None`.
    #[must_use]
    pub fn parse(text: &str) -> Option<Unit> {
        Some(match text.trim() {
            "m" => Unit::Metre,
            "ft" | "feet" => Unit::Foot,
            "s" => Unit::Second,
            "ms" => Unit::Millisecond,
            "m/s" | "mps" => Unit::MetrePerSecond,
            "ft/s" | "fps" => Unit::FootPerSecond,
            "g" | "G" => Unit::StandardGravity,
            "m/s2" | "m/s^2" | "m/s²" => Unit::MetrePerSecondSquared,
            "Pa" | "pa" => Unit::Pascal,
            "hPa" | "hpa" | "mbar" | "mb" => Unit::Hectopascal,
            "kPa" | "kpa" => Unit::Kilopascal,
            "atm" => Unit::Atmosphere,
            "C" | "degC" | "°C" => Unit::Celsius,
            "F" | "degF" | "°F" => Unit::Fahrenheit,
            "K" => Unit::Kelvin,
            "deg" | "°" => Unit::Degree,
            _ => return None,
        })
    }

    /// `value` in this unit, converted to the SI unit of its quantity (m, s, m/s, m/s², Pa,
    /// K, degrees).
    #[must_use]
    pub fn to_si(self, value: f64) -> f64 {
        match self {
            Unit::Metre
            | Unit::Second
            | Unit::MetrePerSecond
            | Unit::MetrePerSecondSquared
            | Unit::Pascal
            | Unit::Kelvin
            | Unit::Degree => value,
            Unit::Foot | Unit::FootPerSecond => value * FOOT,
            Unit::Millisecond => value * 1e-3,
            Unit::StandardGravity => value * PhysicalConstants::SI.standard_gravity,
            Unit::Hectopascal => value * 100.0,
            Unit::Kilopascal => value * 1000.0,
            Unit::Atmosphere => value * 101_325.0,
            Unit::Celsius => value + 273.15,
            Unit::Fahrenheit => (value - 32.0) * 5.0 / 9.0 + 273.15,
        }
    }

    /// The quantity the unit measures, to check a mapping (`length`, `time`, …).
    pub(crate) fn quantity(self) -> &'static str {
        match self {
            Unit::Metre | Unit::Foot => "length",
            Unit::Second | Unit::Millisecond => "time",
            Unit::MetrePerSecond | Unit::FootPerSecond => "velocity",
            Unit::StandardGravity | Unit::MetrePerSecondSquared => "acceleration",
            Unit::Pascal | Unit::Hectopascal | Unit::Kilopascal | Unit::Atmosphere => "pressure",
            Unit::Celsius | Unit::Fahrenheit | Unit::Kelvin => "temperature",
            Unit::Degree => "angle",
        }
    }
}

/// Height of pressure `pressure_pa` above the level of pressure `ground_pa`, each taken as
/// a height of the ISA troposphere (ISO 2533: base 288.15 K and 101 325 Pa, lapse
/// −6.5 K/km): `H(p) = T0/L · (1 − (p/p0)^(R·L/g0))`, the result `H(p) − H(ground)`. A
/// pressure altitude: it differs from the true height by the ratio of the day's air
/// temperature to the standard one (a few per cent).
pub(crate) fn pressure_height(pressure_pa: f64, ground_pa: f64) -> f64 {
    let c = PhysicalConstants::SI;
    let layer = c.isa_layers[1];
    let lapse = -layer.lapse_rate;
    let exponent = c.air_gas_constant * lapse / c.standard_gravity;
    let height =
        |p: f64| layer.base_temperature / lapse * (1.0 - (p / layer.base_pressure).powf(exponent));
    height(pressure_pa) - height(ground_pa)
}
