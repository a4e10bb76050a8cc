//! Motor report: the `motor` figures of `reference.json` ([`MotorReport`]) — thrust-curve
//! figures and, at chosen times, thrust, masses, centre of mass (motor coordinates) and
//! inertia about the motor's centre of mass — and, for hybrid and liquid motors, each tank's
//! contents at the same times ([`TankReport`]); each `[[extra_motors]]` entry's motor as it
//! would be alone, with where and when it burns ([`ExtraMotorReport`]).

use std::fmt;

use karman_propulsion::Motor;
use serde::Serialize;

use crate::assemble::motors::extra_motor;
use crate::{Mission, MissionError};

/// Number of intervals the burn is split into by the default report times.
const BURN_DIVISIONS: usize = 10;

/// The motor's figures, keyed as `motor` of `reference.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MotorReport {
    /// Total impulse, N·s.
    pub total_impulse_ns: f64,
    /// Initial propellant mass, kg.
    pub propellant_initial_mass_kg: f64,
    /// Burn start, s.
    pub burn_start_s: f64,
    /// Burn out, s.
    pub burn_out_s: f64,
    /// Average thrust over the burn, N.
    pub average_thrust_n: f64,
    /// Largest thrust sample, N.
    pub max_thrust_n: f64,
    /// Exhaust velocity as RocketPy reports it at burn start, m/s: `I_tot / m_p0`, except for
    /// liquid motors, whose tanks give `−T/ṁ_tanks` (docs/physics.md §15.5).
    pub exhaust_velocity_mps: f64,
    /// Sample times, s.
    pub times_s: Vec<f64>,
    /// Thrust at each time, N.
    pub thrust_n: Vec<f64>,
    /// Motor mass (dry + propellant), kg.
    pub total_mass_kg: Vec<f64>,
    /// Propellant mass, kg.
    pub propellant_mass_kg: Vec<f64>,
    /// Motor centre of mass, m, motor coordinates.
    pub center_of_mass_m: Vec<f64>,
    /// Transverse inertia about the motor's centre of mass, kg·m².
    #[serde(rename = "I11_kgm2")]
    pub i11_kgm2: Vec<f64>,
    /// Axial inertia about the motor's centre of mass, kg·m².
    #[serde(rename = "I33_kgm2")]
    pub i33_kgm2: Vec<f64>,
}

/// One tank of a hybrid or liquid motor at chosen times (`karman inspect` lists them after
/// the motor; `reference.json` has no such object).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TankReport {
    /// Sample times, s.
    pub times_s: Vec<f64>,
    /// The tank's name.
    pub name: String,
    /// RocketPy's class of the tank.
    pub kind: &'static str,
    /// Motor coordinate of the tank's height origin, m.
    pub position_m: f64,
    /// Inner volume, m³.
    pub total_volume_m3: f64,
    /// Liquid mass, kg.
    pub liquid_mass_kg: Vec<f64>,
    /// Gas mass, kg.
    pub gas_mass_kg: Vec<f64>,
    /// Liquid level, m, tank frame.
    pub liquid_height_m: Vec<f64>,
    /// Centre of mass of the fluids, m, motor coordinates.
    pub center_of_mass_m: Vec<f64>,
    /// Transverse inertia of the fluids about their centre of mass, kg·m².
    #[serde(rename = "I11_kgm2")]
    pub i11_kgm2: Vec<f64>,
}

/// One `[[extra_motors]]` entry: its motor's report as the motor would be alone (one motor of
/// its cluster, on its own time axis from its ignition), and where and when it burns.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExtraMotorReport {
    /// The entry's `name`, else `extra motor <index>`.
    pub name: String,
    /// Its index in `[[extra_motors]]`.
    pub index: usize,
    /// Rocket coordinate of the motor's origin, m.
    pub motor_position_m: f64,
    /// Ignition after launch, s.
    pub ignition_delay_s: f64,
    /// Motors in its cluster.
    pub cluster_count: u32,
    /// One motor of the cluster, times from its ignition.
    pub motor: MotorReport,
}

impl ExtraMotorReport {
    /// Every `[[extra_motors]]` entry of `mission`, at `times` (s from each motor's ignition)
    /// or at [`default_times`] of each motor.
    ///
    /// # Errors
    /// The motor builder's errors, named by the entry's keys.
    pub fn for_mission(
        mission: &Mission,
        times: Option<&[f64]>,
    ) -> Result<Vec<ExtraMotorReport>, MissionError> {
        mission
            .spec
            .extra_motors
            .iter()
            .enumerate()
            .map(|(index, extra)| {
                let motor = extra_motor(mission, index, None)?;
                Ok(ExtraMotorReport {
                    name: extra
                        .name
                        .clone()
                        .unwrap_or_else(|| format!("extra motor {index}")),
                    index,
                    motor_position_m: extra.motor_position,
                    ignition_delay_s: extra.ignition_delay,
                    cluster_count: extra.motor.cluster_count.unwrap_or(1),
                    motor: MotorReport::at(&motor, times),
                })
            })
            .collect()
    }
}

impl fmt::Display for ExtraMotorReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "Extra motor '{}' ([[extra_motors]] {}: origin at {:.6} m, lit {:.6} s after launch, \
             cluster of {}; one motor, times from its ignition)",
            self.name, self.index, self.motor_position_m, self.ignition_delay_s, self.cluster_count
        )?;
        self.motor.write_figures(f)
    }
}

/// The reference's sample times: burn start + k/10 of the burn (k = 0..10), then burn-out
/// + 1 s.
#[must_use]
pub fn default_times(motor: &Motor) -> Vec<f64> {
    // `start + k·burn/10` for k < 10, then burn-out itself, computed as the references were
    // (not `linspace`, whose `start + k·step` rounds differently, e.g. 1.9500000000000002).
    let burn = motor.burn_out() - motor.burn_start();
    let mut times: Vec<f64> = (0..BURN_DIVISIONS)
        .map(|k| motor.burn_start() + k as f64 * burn / BURN_DIVISIONS as f64)
        .collect();
    times.push(motor.burn_out());
    times.push(motor.burn_out() + 1.0);
    times
}

impl MotorReport {
    /// The report at [`default_times`].
    #[must_use]
    pub fn new(motor: &Motor) -> Self {
        Self::at_times(motor, &default_times(motor))
    }

    /// The report at `times` (s) when given, else at [`default_times`].
    #[must_use]
    pub fn at(motor: &Motor, times: Option<&[f64]>) -> Self {
        match times {
            Some(times) => Self::at_times(motor, times),
            None => Self::new(motor),
        }
    }

    /// The report at the given times, s.
    #[must_use]
    pub fn at_times(motor: &Motor, times: &[f64]) -> Self {
        let column = |f: &dyn Fn(f64) -> f64| times.iter().map(|&t| f(t)).collect::<Vec<_>>();
        MotorReport {
            total_impulse_ns: motor.total_impulse(),
            propellant_initial_mass_kg: motor.propellant_initial_mass(),
            burn_start_s: motor.burn_start(),
            burn_out_s: motor.burn_out(),
            average_thrust_n: motor.average_thrust(),
            max_thrust_n: motor.max_thrust(),
            exhaust_velocity_mps: motor.reported_exhaust_velocity(motor.burn_start()),
            times_s: times.to_vec(),
            thrust_n: column(&|t| motor.thrust(t)),
            total_mass_kg: column(&|t| motor.total_mass(t)),
            propellant_mass_kg: column(&|t| motor.propellant_mass().eval(t)),
            center_of_mass_m: column(&|t| motor.center_of_mass(t)),
            i11_kgm2: column(&|t| motor.inertia(t).0),
            i33_kgm2: column(&|t| motor.inertia(t).1),
        }
    }
}

impl TankReport {
    /// Every tank of `motor` (none for solid and generic motors) at `times`, s.
    #[must_use]
    pub fn for_motor(motor: &Motor, times: &[f64]) -> Vec<TankReport> {
        let column = |f: &dyn Fn(f64) -> f64| times.iter().map(|&t| f(t)).collect::<Vec<_>>();
        motor
            .tanks()
            .iter()
            .map(|p| {
                let tank = &p.tank;
                TankReport {
                    times_s: times.to_vec(),
                    name: tank.name().to_owned(),
                    kind: tank.spec().kind.class_name(),
                    position_m: p.position,
                    total_volume_m3: tank.spec().geometry.total_volume(),
                    liquid_mass_kg: column(&|t| tank.liquid_mass().eval(t)),
                    gas_mass_kg: column(&|t| tank.gas_mass().eval(t)),
                    liquid_height_m: column(&|t| tank.liquid_height().eval(t)),
                    center_of_mass_m: column(&|t| p.position + tank.center_of_mass().eval(t)),
                    i11_kgm2: column(&|t| tank.inertia().eval(t)),
                }
            })
            .collect()
    }
}

impl fmt::Display for TankReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "Tank '{}' ({}, at {:.6} m, volume {:.6e} m³)",
            self.name, self.kind, self.position_m, self.total_volume_m3
        )?;
        writeln!(
            f,
            "  {:>9} {:>12} {:>12} {:>12} {:>12} {:>12}",
            "t [s]", "liquid [kg]", "gas [kg]", "level [m]", "CM [m]", "I11 [kg·m²]"
        )?;
        for (i, t) in self.times_s.iter().enumerate() {
            let cell = |v: &[f64]| v.get(i).copied().unwrap_or(f64::NAN);
            writeln!(
                f,
                "  {t:>9.4} {:>12.6} {:>12.6} {:>12.6} {:>12.6} {:>12.6e}",
                cell(&self.liquid_mass_kg),
                cell(&self.gas_mass_kg),
                cell(&self.liquid_height_m),
                cell(&self.center_of_mass_m),
                cell(&self.i11_kgm2),
            )?;
        }
        Ok(())
    }
}

impl fmt::Display for MotorReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "Motor")?;
        self.write_figures(f)
    }
}

impl MotorReport {
    /// The figures and the table, without a title.
    fn write_figures(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let rows = [
            ("total impulse", self.total_impulse_ns, "N·s"),
            (
                "propellant initial mass",
                self.propellant_initial_mass_kg,
                "kg",
            ),
            ("burn start", self.burn_start_s, "s"),
            ("burn out", self.burn_out_s, "s"),
            ("average thrust", self.average_thrust_n, "N"),
            ("maximum thrust", self.max_thrust_n, "N"),
            ("exhaust velocity", self.exhaust_velocity_mps, "m/s"),
        ];
        for (label, value, unit) in rows {
            writeln!(f, "  {label:<26} {value:>14.6} {unit}")?;
        }
        writeln!(f)?;
        writeln!(
            f,
            "  {:>9} {:>12} {:>12} {:>12} {:>12} {:>12} {:>12}",
            "t [s]",
            "thrust [N]",
            "mass [kg]",
            "prop. [kg]",
            "CM [m]",
            "I11 [kg·m²]",
            "I33 [kg·m²]"
        )?;
        for (i, t) in self.times_s.iter().enumerate() {
            let cell = |v: &[f64]| v.get(i).copied().unwrap_or(f64::NAN);
            writeln!(
                f,
                "  {t:>9.4} {:>12.3} {:>12.6} {:>12.6} {:>12.6} {:>12.6e} {:>12.6e}",
                cell(&self.thrust_n),
                cell(&self.total_mass_kg),
                cell(&self.propellant_mass_kg),
                cell(&self.center_of_mass_m),
                cell(&self.i11_kgm2),
                cell(&self.i33_kgm2),
            )?;
        }
        Ok(())
    }
}
