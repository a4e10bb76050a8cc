//! The environment report: the atmosphere, wind and gravity of a built
//! [`karman_atmos::Environment`] at a list of heights, shaped exactly like the `environment`
//! object of the validation `reference.json` files.

use karman_atmos::Environment;
use serde::Serialize;
use std::fmt;

/// Atmosphere, wind and gravity at a list of heights (keys of `reference.json`'s
/// `environment`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EnvironmentReport {
    /// Heights above sea level (m).
    pub heights_asl_m: Vec<f64>,
    /// Pressure (Pa).
    pub pressure_pa: Vec<f64>,
    /// Temperature (K).
    pub temperature_k: Vec<f64>,
    /// Density (kg/m³).
    pub density_kgpm3: Vec<f64>,
    /// Speed of sound (m/s).
    pub speed_of_sound_mps: Vec<f64>,
    /// Dynamic viscosity (Pa·s).
    pub dynamic_viscosity_pas: Vec<f64>,
    /// Eastward wind (m/s).
    pub wind_u_mps: Vec<f64>,
    /// Northward wind (m/s).
    pub wind_v_mps: Vec<f64>,
    /// Gravity at the launch elevation (m/s²).
    pub gravity_mps2_at_launch: f64,
}

/// The default report heights: the launch elevation plus 0, 50, 100, 200 m and then every
/// 250 m up to `top_asl` (the `reference.json` pattern). Without a usable `top_asl` (e.g. no
/// `max_expected_height`) the heights reach 3000 m above the launch site.
#[must_use]
pub fn default_heights(elevation: f64, top_asl: Option<f64>) -> Vec<f64> {
    let top = top_asl
        .filter(|t| t.is_finite() && *t > elevation)
        .unwrap_or(elevation + 3000.0);
    let mut heights: Vec<f64> = [0.0, 50.0, 100.0, 200.0]
        .iter()
        .map(|d| elevation + d)
        .take_while(|h| *h <= top)
        .collect();
    let mut k = 1.0;
    while elevation + 250.0 * k <= top {
        heights.push(elevation + 250.0 * k);
        k += 1.0;
    }
    heights
}

/// Evaluates the environment at `heights_asl_m`.
#[must_use]
pub fn environment_report(env: &Environment, heights_asl_m: &[f64]) -> EnvironmentReport {
    let col = |f: &dyn Fn(f64) -> f64| heights_asl_m.iter().map(|&h| f(h)).collect::<Vec<_>>();
    EnvironmentReport {
        heights_asl_m: heights_asl_m.to_vec(),
        pressure_pa: col(&|h| env.pressure(h)),
        temperature_k: col(&|h| env.temperature(h)),
        density_kgpm3: col(&|h| env.density(h)),
        speed_of_sound_mps: col(&|h| env.speed_of_sound(h)),
        dynamic_viscosity_pas: col(&|h| env.dynamic_viscosity(h)),
        wind_u_mps: col(&|h| env.wind(h)[0]),
        wind_v_mps: col(&|h| env.wind(h)[1]),
        gravity_mps2_at_launch: env.gravity(env.elevation()),
    }
}

impl fmt::Display for EnvironmentReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "gravity at launch: {:.7} m/s²",
            self.gravity_mps2_at_launch
        )?;
        writeln!(
            f,
            "{:>10} {:>12} {:>9} {:>10} {:>9} {:>12} {:>8} {:>8}",
            "h ASL (m)",
            "P (Pa)",
            "T (K)",
            "ρ (kg/m³)",
            "a (m/s)",
            "μ (Pa·s)",
            "u (m/s)",
            "v (m/s)"
        )?;
        for i in 0..self.heights_asl_m.len() {
            let at = |v: &[f64]| v.get(i).copied().unwrap_or(f64::NAN);
            writeln!(
                f,
                "{:>10.1} {:>12.3} {:>9.4} {:>10.6} {:>9.4} {:>12.5e} {:>8.3} {:>8.3}",
                at(&self.heights_asl_m),
                at(&self.pressure_pa),
                at(&self.temperature_k),
                at(&self.density_kgpm3),
                at(&self.speed_of_sound_mps),
                at(&self.dynamic_viscosity_pas),
                at(&self.wind_u_mps),
                at(&self.wind_v_mps),
            )?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_heights_follow_the_reference_pattern() {
        let h = default_heights(407.0, Some(1000.0));
        assert_eq!(h, vec![407.0, 457.0, 507.0, 607.0, 657.0, 907.0]);
        assert_eq!(default_heights(0.0, None).last().copied(), Some(3000.0));
    }
}
