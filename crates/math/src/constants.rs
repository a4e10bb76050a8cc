//! Every physical constant of the karman model, in one place.
//!
//! Models take a [`PhysicalConstants`] value when they are built (never in the equations-of-
//! motion hot path), so the whole simulator can be run in a randomly scaled unit system to
//! check that its equations are dimensionally consistent (the "numericalunits" test layer of
//! RocketPy, Ceotto et al. 2021). [`PhysicalConstants::SI`] holds the values in SI units;
//! [`PhysicalConstants::in_units`] expresses them in another unit system.
//!
//! Sources: ISO 2533:1975 (standard atmosphere, layer table including the −2 km extension), U.S.
//! Standard Atmosphere 1976 (Sutherland law), NIMA TR8350.2 (2000) and Moritz (1980) (WGS-84
//! ellipsoid and Somigliana normal gravity). RocketPy 1.13 uses exactly these values
//! (`docs/physics.md` §1); the ISA tables use the Earth radius 6 378 100 m as RocketPy does (§4.1
//! item 6).

/// A unit system given by the size of its base units relative to SI.
///
/// A quantity whose SI value is `v` and whose dimension is `L^a M^b T^c Θ^d` has the value
/// `v · length^a · mass^b · time^c · temperature^d` in this system. [`Units::SI`] is the
/// identity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Units {
    /// Value of one metre in this system.
    pub length: f64,
    /// Value of one kilogram in this system.
    pub mass: f64,
    /// Value of one second in this system.
    pub time: f64,
    /// Value of one kelvin in this system.
    pub temperature: f64,
}

impl Units {
    /// The SI unit system (every factor 1).
    pub const SI: Units = Units {
        length: 1.0,
        mass: 1.0,
        time: 1.0,
        temperature: 1.0,
    };

    /// Factor converting an SI value of dimension `L^l M^m T^t Θ^k` into this system.
    #[must_use]
    pub fn factor(&self, l: f64, m: f64, t: f64, k: f64) -> f64 {
        self.length.powf(l) * self.mass.powf(m) * self.time.powf(t) * self.temperature.powf(k)
    }

    /// Converts an SI length (m).
    #[must_use]
    pub fn length(&self, v: f64) -> f64 {
        v * self.length
    }
    /// Converts an SI mass (kg).
    #[must_use]
    pub fn mass(&self, v: f64) -> f64 {
        v * self.mass
    }
    /// Converts an SI time (s).
    #[must_use]
    pub fn time(&self, v: f64) -> f64 {
        v * self.time
    }
    /// Converts an SI temperature (K).
    #[must_use]
    pub fn temperature(&self, v: f64) -> f64 {
        v * self.temperature
    }
}

/// One layer base of the standard atmosphere (ISO 2533), heights geopotential.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtmosphereLayer {
    /// Geopotential height of the layer base (m').
    pub base_height: f64,
    /// Temperature at the base (K).
    pub base_temperature: f64,
    /// Temperature lapse rate dT/dH (K/m).
    pub lapse_rate: f64,
    /// Pressure at the base (Pa).
    pub base_pressure: f64,
}

/// The physical constants of the model, in one unit system, and the few numerical parameters
/// of the models that carry a unit (a grid step, a finite-difference step, a length
/// tolerance): a dimensional literal hidden in a model would not follow a change of units
/// (the dimensional-analysis tests of every crate check this).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicalConstants {
    /// Standard gravity g0 (m/s²), used by the ISA and geopotential conversions.
    pub standard_gravity: f64,
    /// Specific gas constant of dry air R (J/(kg·K)).
    pub air_gas_constant: f64,
    /// Ratio of specific heats of air γ (dimensionless).
    pub heat_capacity_ratio: f64,
    /// Sutherland's constant B of μ = B T^1.5 / (T + S) (kg/(m·s·K^0.5)).
    pub sutherland_b: f64,
    /// Sutherland's temperature S (K).
    pub sutherland_s: f64,
    /// Earth radius used for geopotential height in the ISA tables (m).
    pub isa_earth_radius: f64,
    /// The ISA layer table, ISO 2533 with the −2 km extension.
    pub isa_layers: [AtmosphereLayer; 9],
    /// Top of the height domain on which atmosphere and gravity tables are sampled (m).
    pub table_top_height: f64,
    /// WGS-84 semi-major axis a (m).
    pub wgs84_semi_major_axis: f64,
    /// WGS-84 flattening f (dimensionless).
    pub wgs84_flattening: f64,
    /// WGS-84 m = ω² a² b / GM (dimensionless).
    pub wgs84_m: f64,
    /// WGS-84 normal gravity at the equator γ_e (m/s²).
    pub wgs84_equatorial_gravity: f64,
    /// WGS-84 Somigliana constant k (dimensionless).
    pub wgs84_somigliana_k: f64,
    /// WGS-84 first eccentricity squared e² (dimensionless).
    pub wgs84_eccentricity_squared: f64,
    /// Earth's rotation rate Ω = 2π / sidereal day (rad/s).
    pub earth_rotation_rate: f64,
    /// Earth's gravitational parameter GM (m³/s²), WGS-84's, as RocketPy 1.13's
    /// `Flight.potential_energy` takes it.
    pub earth_gravitational_parameter: f64,
    /// SAD69 (South American Datum 1969) semi-major axis a (m); NIMA TR8350.2 appendix A.
    pub sad69_semi_major_axis: f64,
    /// SAD69 flattening f (dimensionless); NIMA TR8350.2 appendix A.
    pub sad69_flattening: f64,
    /// NAD83 (GRS 80 ellipsoid) flattening f (dimensionless); Moritz (1980). Its semi-major
    /// axis equals WGS-84's.
    pub nad83_flattening: f64,
    /// Largest time spacing of a solid motor's propellant tables (s). A numerical parameter,
    /// not a physical one: it is kept here so that it follows the unit of time (karman-
    /// propulsion `BatesGrains`, where 5 ms reproduces RocketPy's LSODA-sampled tables).
    pub propellant_grid_step: f64,
    /// Step of the central second difference of a pointwise function of time (s): RocketPy's
    /// `Function.differentiate` default `dx = 1e-6`, applied to time (karman-airframe
    /// `com_to_cdm_accel`). Numerical; kept here so that it follows the unit of time.
    pub time_difference_step: f64,
    /// RocketPy's 1 mm length scale of `NoseCone.evaluate_nose_shape` (m): the smallest
    /// shortening of a nose cone by its bluff tip that is applied, and the abscissa where the
    /// tip circle of an elliptical nose is tested against the profile. Numerical; kept here so
    /// that it follows the unit of length (karman-airframe nose cones).
    pub nose_shape_tolerance: f64,
    /// RocketPy's guard of a tank's moment tables (m): a height range `[lo, up]` shorter than
    /// this (an empty fluid column) is widened by [`PhysicalConstants::tank_degenerate_widening`]
    /// (`TankGeometry.volume_moment`, karman-propulsion). Numerical; follows the unit of length.
    pub tank_degenerate_range: f64,
    /// The widening of a degenerate tank moment range (m), RocketPy's `1e-12`.
    pub tank_degenerate_widening: f64,
    /// RocketPy's slack of a tank's gas-mass check (kg): below minus this is an error.
    pub tank_gas_mass_slack: f64,
    /// RocketPy's slack of a tank's volume checks (m³).
    pub tank_volume_slack: f64,
    /// RocketPy's slack of a tank's height checks (m).
    pub tank_height_slack: f64,
    /// Temperature at which RocketPy 1.13's sensor model is ideal (K, 25 °C): a sensor's
    /// temperature bias and scale drift act on `T − T_ref` (`rocketpy/sensors/sensor.py`,
    /// docs/physics.md §29.1).
    pub sensor_reference_temperature: f64,
}

const fn layer(h: f64, t: f64, beta: f64, p: f64) -> AtmosphereLayer {
    AtmosphereLayer {
        base_height: h,
        base_temperature: t,
        lapse_rate: beta,
        base_pressure: p,
    }
}

impl PhysicalConstants {
    /// The constants in SI units.
    pub const SI: PhysicalConstants = PhysicalConstants {
        standard_gravity: 9.80665,
        air_gas_constant: 287.05287,
        heat_capacity_ratio: 1.4,
        sutherland_b: 1.458e-6,
        sutherland_s: 110.4,
        isa_earth_radius: 6_378_100.0,
        isa_layers: [
            layer(-2000.0, 301.15, -0.0065, 127_774.0),
            layer(0.0, 288.15, -0.0065, 101_325.0),
            layer(11_000.0, 216.65, 0.0, 22_632.0),
            layer(20_000.0, 216.65, 0.0010, 5474.87),
            layer(32_000.0, 228.65, 0.0028, 868.0164),
            layer(47_000.0, 270.65, 0.0, 110.906),
            layer(51_000.0, 270.65, -0.0028, 66.9384),
            layer(71_000.0, 214.65, -0.0020, 3.95639),
            layer(80_000.0, 196.65, 0.0, 0.088_627_2),
        ],
        table_top_height: 80_000.0,
        wgs84_semi_major_axis: 6_378_137.0,
        wgs84_flattening: 1.0 / 298.257_223_563,
        wgs84_m: 3.449_786_506_841e-3,
        wgs84_equatorial_gravity: 9.780_325_335_9,
        wgs84_somigliana_k: 1.931_852_652_458e-3,
        wgs84_eccentricity_squared: 6.694_379_990_141e-3,
        earth_rotation_rate: 2.0 * std::f64::consts::PI / 86_164.1,
        earth_gravitational_parameter: 3.986_004_418e14,
        sad69_semi_major_axis: 6_378_160.0,
        sad69_flattening: 1.0 / 298.25,
        nad83_flattening: 1.0 / 298.257_024_899,
        propellant_grid_step: 0.005,
        time_difference_step: 1e-6,
        nose_shape_tolerance: 1e-3,
        tank_degenerate_range: 1e-8,
        tank_degenerate_widening: 1e-12,
        tank_gas_mass_slack: 1e-6,
        tank_volume_slack: 1e-6,
        tank_height_slack: 1e-4,
        sensor_reference_temperature: 298.15,
    };

    /// The same constants expressed in the unit system `u`.
    #[must_use]
    pub fn in_units(&self, u: &Units) -> PhysicalConstants {
        let acc = u.factor(1.0, 0.0, -2.0, 0.0);
        let len = u.length;
        let mut layers = self.isa_layers;
        for l in &mut layers {
            l.base_height *= len;
            l.base_temperature *= u.temperature;
            l.lapse_rate *= u.factor(-1.0, 0.0, 0.0, 1.0);
            l.base_pressure *= u.factor(-1.0, 1.0, -2.0, 0.0);
        }
        PhysicalConstants {
            standard_gravity: self.standard_gravity * acc,
            air_gas_constant: self.air_gas_constant * u.factor(2.0, 0.0, -2.0, -1.0),
            heat_capacity_ratio: self.heat_capacity_ratio,
            sutherland_b: self.sutherland_b * u.factor(-1.0, 1.0, -1.0, -0.5),
            sutherland_s: self.sutherland_s * u.temperature,
            isa_earth_radius: self.isa_earth_radius * len,
            isa_layers: layers,
            table_top_height: self.table_top_height * len,
            wgs84_semi_major_axis: self.wgs84_semi_major_axis * len,
            wgs84_flattening: self.wgs84_flattening,
            wgs84_m: self.wgs84_m,
            wgs84_equatorial_gravity: self.wgs84_equatorial_gravity * acc,
            wgs84_somigliana_k: self.wgs84_somigliana_k,
            wgs84_eccentricity_squared: self.wgs84_eccentricity_squared,
            earth_rotation_rate: self.earth_rotation_rate / u.time,
            earth_gravitational_parameter: self.earth_gravitational_parameter
                * u.factor(3.0, 0.0, -2.0, 0.0),
            sad69_semi_major_axis: self.sad69_semi_major_axis * len,
            sad69_flattening: self.sad69_flattening,
            nad83_flattening: self.nad83_flattening,
            propellant_grid_step: self.propellant_grid_step * u.time,
            time_difference_step: self.time_difference_step * u.time,
            nose_shape_tolerance: self.nose_shape_tolerance * len,
            tank_degenerate_range: self.tank_degenerate_range * len,
            tank_degenerate_widening: self.tank_degenerate_widening * len,
            tank_gas_mass_slack: self.tank_gas_mass_slack * u.mass,
            tank_volume_slack: self.tank_volume_slack * len * len * len,
            tank_height_slack: self.tank_height_slack * len,
            sensor_reference_temperature: self.sensor_reference_temperature * u.temperature,
        }
    }
}

impl Default for PhysicalConstants {
    fn default() -> Self {
        Self::SI
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn si_is_identity() {
        assert_eq!(
            PhysicalConstants::SI.in_units(&Units::SI),
            PhysicalConstants::SI
        );
    }

    #[test]
    fn scaling_keeps_dimensionless_groups() {
        let u = Units {
            length: 3.7,
            mass: 0.21,
            time: 11.0,
            temperature: 0.5,
        };
        let si = PhysicalConstants::SI;
        let sc = si.in_units(&u);
        // g0 / (R T) has dimension 1/L; multiply by a length to get a pure number.
        let group = |c: &PhysicalConstants, len: f64| {
            c.standard_gravity * len / (c.air_gas_constant * c.isa_layers[1].base_temperature)
        };
        let a = group(&si, 1000.0);
        let b = group(&sc, 1000.0 * u.length);
        assert!((a - b).abs() < 1e-12 * a.abs());
        // Sutherland viscosity over (ρ a L) is dimensionless.
        let re = |c: &PhysicalConstants, rho: f64, len: f64| {
            let t = c.isa_layers[1].base_temperature;
            let mu = c.sutherland_b * t.powf(1.5) / (t + c.sutherland_s);
            let a = (c.heat_capacity_ratio * c.air_gas_constant * t).sqrt();
            rho * a * len / mu
        };
        let r1 = re(&si, 1.225, 0.1);
        let r2 = re(&sc, 1.225 * u.factor(-3.0, 1.0, 0.0, 0.0), 0.1 * u.length);
        assert!((r1 - r2).abs() < 1e-9 * r1);
    }
}
