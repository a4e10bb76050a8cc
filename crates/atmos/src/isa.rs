//! The International Standard Atmosphere (ISO 2533:1975, with the −2 km extension) as
//! RocketPy 1.13 discretises it (docs/physics.md §4.1).
//!
//! - Pressure: the analytic layer formula sampled at `linspace(0, 80 000, 100)` geometric
//!   heights and stored as a natural cubic spline with natural extrapolation.
//! - Temperature: linear through the nine layer bases converted to geometric height
//!   `h = R_E H / (R_E − H)`, constant outside.
//! - Speed of sound and viscosity: linear between the *node* values `√(γ R T_i)` and
//!   `B T_i^1.5 / (T_i + S)` (RocketPy's `Function` arithmetic on a tabulated temperature).
//! - Barometric height: the natural spline through the same 100 `(P, h)` pairs.
//!
//! `R_E` is [`PhysicalConstants::isa_earth_radius`] (6 378 100 m), the radius in force when
//! RocketPy builds these tables (docs/physics.md §4.1 item 6).

use karman_math::{Extrapolation, Interpolation, MathError, PhysicalConstants, Table1, linspace};

/// Number of samples of the ISA pressure table (RocketPy `pressure_ISA`).
pub const PRESSURE_SAMPLES: usize = 100;

/// Analytic ISA pressure (Pa) at geometric height `h` (m), ISO 2533 layer formula:
/// `P = P_i [1 + β_i (H − H_i)/T_i]^(−g0/(β_i R))`, or `P_i exp(−g0 (H − H_i)/(R T_i))` when
/// `β_i = 0`, with geopotential height `H = R_E h / (R_E + h)`. Below the table it returns the
/// first base pressure and above it the last, as RocketPy does.
#[must_use]
pub fn analytic_pressure(h: f64, c: &PhysicalConstants) -> f64 {
    let re = c.isa_earth_radius;
    let big_h = re * h / (re + h);
    let layers = &c.isa_layers;
    let (first, last) = (layers[0], layers[layers.len() - 1]);
    if big_h < first.base_height {
        return first.base_pressure;
    }
    if big_h > last.base_height {
        return last.base_pressure;
    }
    // bisect_right − 1: the last layer whose base is ≤ H.
    let idx = layers
        .partition_point(|l| l.base_height <= big_h)
        .saturating_sub(1);
    let l = layers[idx];
    let g0 = c.standard_gravity;
    let r = c.air_gas_constant;
    if l.lapse_rate == 0.0 {
        l.base_pressure * (-(big_h - l.base_height) * (g0 / (r * l.base_temperature))).exp()
    } else {
        l.base_pressure
            * (1.0 + (l.lapse_rate / l.base_temperature) * (big_h - l.base_height))
                .powf(-g0 / (l.lapse_rate * r))
    }
}

/// Geometric height (m) of a geopotential height `big_h` (m') for Earth radius `radius`:
/// `h = R H / (R − H)` (RocketPy `geopotential_height_to_geometric_height`).
#[inline]
#[must_use]
pub fn geopotential_to_geometric(big_h: f64, radius: f64) -> f64 {
    radius * big_h / (radius - big_h)
}

/// The ISA tables RocketPy builds.
#[derive(Debug, Clone)]
pub struct IsaTables {
    /// Pressure vs geometric height: natural spline, natural extrapolation.
    pub pressure: Table1,
    /// Temperature vs geometric height: linear through the layer bases, constant outside.
    pub temperature: Table1,
    /// Barometric height vs pressure: natural spline through the pressure samples, natural
    /// extrapolation.
    pub barometric_height: Table1,
}

impl IsaTables {
    /// Builds the tables from the constants.
    ///
    /// # Errors
    /// Only if the constants are degenerate (non-finite or non-increasing samples).
    pub fn new(c: &PhysicalConstants) -> Result<Self, MathError> {
        let pressure = Table1::sample(
            |h| analytic_pressure(h, c),
            0.0,
            c.table_top_height,
            PRESSURE_SAMPLES,
            Interpolation::Spline,
            Extrapolation::Natural,
        )?;
        let heights: Vec<f64> = c
            .isa_layers
            .iter()
            .map(|l| geopotential_to_geometric(l.base_height, c.isa_earth_radius))
            .collect();
        let temps: Vec<f64> = c.isa_layers.iter().map(|l| l.base_temperature).collect();
        let temperature = Table1::new(
            heights,
            temps,
            Interpolation::Linear,
            Extrapolation::Constant,
        )?;
        // Inverse: (P, h) sorted by increasing pressure.
        let hs = linspace(0.0, c.table_top_height, PRESSURE_SAMPLES);
        let mut pairs: Vec<(f64, f64)> = hs.iter().map(|&h| (pressure.eval(h), h)).collect();
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (ps, hs): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
        let barometric_height = Table1::new(ps, hs, Interpolation::Spline, Extrapolation::Natural)?;
        Ok(IsaTables {
            pressure,
            temperature,
            barometric_height,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    #[test]
    fn layer_bases_in_geometric_height_match_physics_md() {
        // docs/physics.md §4.1 item 2 lists the converted bases.
        let c = PhysicalConstants::SI;
        let expected = [
            -1999.373, 0.0, 11019.004, 20062.912, 32161.359, 47348.913, 51411.089, 71799.258,
            81016.179,
        ];
        for (l, e) in c.isa_layers.iter().zip(expected) {
            let h = geopotential_to_geometric(l.base_height, c.isa_earth_radius);
            assert!((h - e).abs() < 1e-3, "{h} vs {e}");
        }
    }

    #[test]
    fn spot_values_match_rocketpy() {
        // docs/physics.md §4.1 spot values at 1400 m and §13 at 4700 m.
        let c = PhysicalConstants::SI;
        let t = IsaTables::new(&c).expect("ISA tables");
        assert!(rel(t.pressure.eval(1400.0), 85596.6788) < 1e-8);
        assert!((t.temperature.eval(1400.0) - 279.06569).abs() < 1e-5);
        assert!(rel(t.pressure.eval(4700.0), 56246.7691) < 1e-8);
        assert!((t.temperature.eval(4700.0) - 257.65269).abs() < 1e-5);
    }

    #[test]
    fn analytic_formula_at_layer_bases() {
        let c = PhysicalConstants::SI;
        // At sea level the formula returns the base pressure exactly.
        assert!(rel(analytic_pressure(0.0, &c), 101_325.0) < 1e-12);
        // Above the table it is held.
        assert!(rel(analytic_pressure(200_000.0, &c), 0.088_627_2) < 1e-12);
    }

    #[test]
    fn barometric_height_inverts_pressure_near_ground() {
        // docs/physics.md §4.4: h_baro(P(z)) − z = +0.16 m at 1400 m, −0.07 m at 2200 m.
        let c = PhysicalConstants::SI;
        let t = IsaTables::new(&c).expect("ISA tables");
        let d1 = t.barometric_height.eval(t.pressure.eval(1400.0)) - 1400.0;
        let d2 = t.barometric_height.eval(t.pressure.eval(2200.0)) - 2200.0;
        assert!((d1 - 0.16).abs() < 0.01, "{d1}");
        assert!((d2 + 0.07).abs() < 0.01, "{d2}");
    }
}
