//! The typed mission file: one serde struct per TOML table of
//! `docs/mission-format.md`, every table `deny_unknown_fields`.
//!
//! These structs are the *file format*, not runtime models: the `build` module turns them into
//! the physics crates' types. Angles are in degrees here (field names end in `_deg`, the TOML
//! keys do not); everything else is SI. Defaults that RocketPy 1.13 applies to an omitted
//! argument (docs/physics.md §1) are filled in by serde where they are plain values, and left as
//! `Option` where "absent" selects a different model (e.g. `gravity`: Somigliana).
//!
//! Named tables (`[rocket.surfaces.*]`, `[rocket.parachutes.*]`, `[dispersion.vary]`) are
//! [`IndexMap`]s: they keep the file order, which RocketPy's results depend on (surfaces and
//! parachutes are added in that order).

mod drag;
pub mod names;
mod sensors;
pub(crate) mod surfaces;
pub mod values;

use indexmap::IndexMap;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

pub use drag::{DragEstimateSpec, FinDragSpec, LaunchLugSpec, RailButtonSizeSpec};
pub use names::{
    AngleUnit, AtmosphereModel, Datum, ExtrapolationKind, FinCrossSection, InterpolationKind,
    MotorCoordinateSystem, MotorKind, NoseKind, RocketCoordinateSystem, SoundingFormat,
    SurfaceFinish, SurfaceType, TankGeometryKind, TankKindName, WeatherSource,
};
pub use sensors::{Axes, MeasurementRange, SensorKindName, SensorPosition, SensorSpec};
pub use surfaces::{
    AirfoilSpec, EllipticalFinsSpec, FreeFormFinsSpec, NoseSpec, PodSpec, SurfaceSpec, Sweep,
    TailSpec, TrapezoidalFinsSpec, TubeFinsSpec,
};
pub use toml::value::Datetime;
pub use values::{AirBrakesCurve, Atol, BurnTime, Curve, ESTIMATE, Inertia, STATE_SIZE, Trigger};

/// A whole mission file.
#[derive(Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MissionSpec {
    /// Name shown in reports.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Free description.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// `[environment]`: where and when.
    pub environment: EnvironmentSpec,
    /// `[motor]`: the one motor.
    pub motor: MotorSpec,
    /// `[rocket]`: the airframe without motor.
    pub rocket: RocketSpec,
    /// `[flight]`: launch and integration settings.
    pub flight: FlightSpec,
    /// `[[stages]]`: the stages below `[rocket]` (which is the top stage, with `[motor]`),
    /// from the one right under it down to the bottom stage, which burns first; empty: a
    /// single-stage rocket.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stages: Vec<StageSpec>,
    /// `[[extra_motors]]`: further motors of a single-stage rocket besides `[motor]`, each
    /// at its own place and lit at its own time (an air start, two different motors); empty:
    /// `[motor]` alone.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub extra_motors: Vec<ExtraMotorSpec>,
    /// `[dispersion]`: Monte Carlo settings, optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dispersion: Option<DispersionSpec>,
}

/// The derived form, but without `extra_motors` when there is none: a Monte Carlo study's
/// data fingerprint hashes this text, so a mission written before the key existed keeps its
/// fingerprint (and its study directories stay resumable).
impl std::fmt::Debug for MissionSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut s = f.debug_struct("MissionSpec");
        s.field("name", &self.name)
            .field("description", &self.description)
            .field("environment", &self.environment)
            .field("motor", &self.motor)
            .field("rocket", &self.rocket)
            .field("flight", &self.flight)
            .field("stages", &self.stages);
        if !self.extra_motors.is_empty() {
            s.field("extra_motors", &self.extra_motors);
        }
        s.field("dispersion", &self.dispersion).finish()
    }
}

impl MissionSpec {
    /// Every data file the mission names, with the dotted key that names it, as written
    /// (relative paths are relative to the mission's folder): the atmosphere's file and
    /// curves, the thrust curve, the drag curves (not `"estimate"`), the fins' airfoils, the
    /// air brakes' drag curve and controller script. The Monte Carlo data fingerprint hashes
    /// exactly these files, so every key that names a file belongs here.
    pub fn data_files(&self) -> Vec<(String, PathBuf)> {
        let mut files = Vec::new();
        let mut curve = |key: &str, curve: Option<&Curve>| {
            if let Some(Curve::File(path)) = curve.filter(|c| !c.is_estimate()) {
                files.push((key.to_owned(), path.clone()));
            }
        };
        let atm = &self.environment.atmosphere;
        curve("environment.atmosphere.pressure", atm.pressure.as_ref());
        curve(
            "environment.atmosphere.temperature",
            atm.temperature.as_ref(),
        );
        curve("environment.atmosphere.wind_u", atm.wind_u.as_ref());
        curve("environment.atmosphere.wind_v", atm.wind_v.as_ref());
        curve("motor.thrust", Some(&self.motor.thrust));
        curve("rocket.power_off_drag", Some(&self.rocket.power_off_drag));
        curve("rocket.power_on_drag", Some(&self.rocket.power_on_drag));
        for (name, surface) in &self.rocket.surfaces {
            let lift = surface.airfoil().map(|a| &a.lift);
            curve(&format!("rocket.surfaces.{name}.airfoil"), lift);
        }
        for (index, stage) in self.stages.iter().enumerate() {
            let key = |k: &str| format!("stages.{index}.{k}");
            if let Some(motor) = &stage.motor {
                curve(&key("motor.thrust"), Some(&motor.thrust));
            }
            curve(
                &key("rocket.power_off_drag"),
                Some(&stage.rocket.power_off_drag),
            );
            curve(
                &key("rocket.power_on_drag"),
                Some(&stage.rocket.power_on_drag),
            );
            curve(
                &key("stack_power_off_drag"),
                Some(&stage.stack_power_off_drag),
            );
            curve(
                &key("stack_power_on_drag"),
                Some(&stage.stack_power_on_drag),
            );
            for (name, surface) in &stage.rocket.surfaces {
                let lift = surface.airfoil().map(|a| &a.lift);
                curve(&key(&format!("rocket.surfaces.{name}.airfoil")), lift);
            }
        }
        for (index, extra) in self.extra_motors.iter().enumerate() {
            curve(
                &format!("extra_motors.{index}.motor.thrust"),
                Some(&extra.motor.thrust),
            );
        }
        if let Some(file) = &atm.file {
            files.insert(0, ("environment.atmosphere.file".to_owned(), file.clone()));
        }
        if let Some(brakes) = &self.rocket.air_brakes {
            let key = "rocket.air_brakes";
            if let AirBrakesCurve::File(path) = &brakes.drag_coefficient_curve {
                files.push((format!("{key}.drag_coefficient_curve"), path.clone()));
            }
            files.push((format!("{key}.controller"), brakes.controller.clone()));
        }
        files
    }
}

/// One `[[stages]]` entry: a lower stage of a multi-stage rocket (mission-format.md,
/// "Stages"), with its own airframe and motor, the trigger of its separation from the stack
/// above it, and the drag of the stack while it is the bottom stage.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StageSpec {
    /// Shown in reports (default `stage <index + 1>`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// When the stage drops off the stack above it: a parachute trigger (`"burnout + X"`
    /// is the burn-out of this stage's motor).
    pub separation: Trigger,
    /// Sampling rate of the separation trigger, Hz.
    #[serde(default = "default_sampling_rate")]
    pub sampling_rate: f64,
    /// Delay from this stage's separation to the ignition of the motor of the stack above,
    /// s (0: ignition at separation).
    #[serde(default)]
    pub ignition_delay: f64,
    /// Power-off drag coefficient of the whole stack while this stage is its bottom, of
    /// Mach, on the largest radius of the stack; or `"estimate"`.
    pub stack_power_off_drag: Curve,
    /// Power-on drag coefficient of that stack.
    pub stack_power_on_drag: Curve,
    /// Drag area `C_D·A` of the spent stage tumbling to the ground, m²; absent: Niskanen's
    /// estimate from its fins and body ([`crate::assemble::stages`]). Used only by a stage
    /// without parachutes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tumble_drag_area: Option<f64>,
    /// The stage's motor; absent: a stage without one, which must separate at launch.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motor: Option<MotorSpec>,
    /// The stage's airframe alone, in the coordinates of `[rocket]` (its drag curves are the
    /// spent stage's, after separation).
    pub rocket: RocketSpec,
}

/// One `[[extra_motors]]` entry: a motor besides `[motor]` (mission-format.md, "Several
/// motors"), with its own definition, its place on the rocket and its ignition time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtraMotorSpec {
    /// A label for the entry (the importer writes the motor mount's name).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Where this motor's coordinate origin sits, rocket coordinates, m (as
    /// `rocket.motor_position` for `[motor]`).
    pub motor_position: f64,
    /// Ignition time after launch, s (0: lit with `[motor]` at launch).
    #[serde(default)]
    pub ignition_delay: f64,
    /// The motor, the keys of `[motor]`.
    pub motor: MotorSpec,
}

/// `[environment]` (RocketPy `Environment`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentSpec {
    /// Launch latitude, deg (north positive); RocketPy default 0.
    #[serde(rename = "latitude", default)]
    pub latitude_deg: f64,
    /// Launch longitude, deg (east positive); RocketPy default 0.
    #[serde(rename = "longitude", default)]
    pub longitude_deg: f64,
    /// Launch elevation above sea level, m; RocketPy default 0.
    #[serde(default)]
    pub elevation: f64,
    /// Launch date and time; must carry an offset or `Z` (weather files need it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub date: Option<Datetime>,
    /// Constant gravity, m/s²; absent: WGS-84 Somigliana gravity with height (docs/physics.md
    /// §4.3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gravity: Option<f64>,
    /// Geodetic datum; absent: RocketPy's default SIRGAS2000.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub datum: Option<Datum>,
    /// Highest altitude the tables must cover, m ASL; RocketPy default 80 000 m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_expected_height: Option<f64>,
    /// `[environment.atmosphere]`; absent: the standard atmosphere.
    #[serde(default)]
    pub atmosphere: AtmosphereSpec,
    /// `[environment.earth_model]`: the latitude and height range RocketPy's `Environment()`
    /// computed gravity, the Earth radius and the rotation vector from; absent: the site's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub earth_model: Option<EarthModelSpec>,
}

/// `[environment.earth_model]` (docs/physics.md §18).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EarthModelSpec {
    /// Latitude of gravity, Earth radius and rotation, deg; absent: `environment.latitude`.
    #[serde(rename = "latitude", default, skip_serializing_if = "Option::is_none")]
    pub latitude_deg: Option<f64>,
    /// Top of the gravity table, m; RocketPy's default 80 000 m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gravity_max_height: Option<f64>,
}

/// `[environment.atmosphere]`: which model, and that model's inputs. Which keys a model needs
/// or accepts is checked by validation (mission-format.md "Per model").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AtmosphereSpec {
    /// The model.
    pub model: AtmosphereModel,
    /// Data file (`sounding`, `reanalysis`, `forecast`, `ensemble`), relative to the mission.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<PathBuf>,
    /// Sounding file format (`sounding` only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub format: Option<SoundingFormat>,
    /// Variable-name mapping of a weather grid (`"ECMWF"`, `"ECMWF_v0"`, `"NOAA"`, `"GFS"`,
    /// ...); absent: detected from the file's variable names.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dictionary: Option<String>,
    /// Ensemble member index (`ensemble`, `open_meteo`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub member: Option<u32>,
    /// The service `karman simulate/montecarlo --fetch` downloads `file` from (the launch
    /// site and date of `[environment]`); absent: the file is only read.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<WeatherSource>,
    /// Sounding station, WMO number or ICAO id (`source = "wyoming"`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub station: Option<String>,
    /// Pressure of height ASL, Pa (`custom`); absent: standard atmosphere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure: Option<Curve>,
    /// Temperature of height ASL, K (`custom`); absent: standard atmosphere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature: Option<Curve>,
    /// Eastward wind of height ASL, m/s (`custom`); absent: 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wind_u: Option<Curve>,
    /// Northward wind of height ASL, m/s (`custom`); absent: 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wind_v: Option<Curve>,
}

impl Default for AtmosphereSpec {
    fn default() -> Self {
        AtmosphereSpec {
            model: AtmosphereModel::Standard,
            file: None,
            format: None,
            dictionary: None,
            member: None,
            source: None,
            station: None,
            pressure: None,
            temperature: None,
            wind_u: None,
            wind_v: None,
        }
    }
}

fn default_nozzle_to_chamber() -> MotorCoordinateSystem {
    MotorCoordinateSystem::NozzleToCombustionChamber
}

fn default_linear() -> InterpolationKind {
    InterpolationKind::Linear
}

/// `[motor]` (RocketPy `SolidMotor` / `GenericMotor`). Keys of the other kind are rejected
/// by validation; required keys per kind are checked there too.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotorSpec {
    /// Motor model.
    pub kind: MotorKind,
    /// Thrust of time, N (file: `.eng`, `.rse`, `.csv`, `.txt`).
    pub thrust: Curve,
    /// Burn interval, s; absent: the thrust curve's time span.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub burn_time: Option<BurnTime>,
    /// `[burn_time, total_impulse]`: stretch the curve in time and scale it to this impulse
    /// (RocketPy `reshape_thrust_curve`, docs/physics.md §6.1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reshape_thrust_curve: Option<[f64; 2]>,
    /// Interpolation of the thrust curve; RocketPy default linear.
    #[serde(default = "default_linear")]
    pub interpolation: InterpolationKind,
    /// Mass of the motor without propellant, kg.
    pub dry_mass: f64,
    /// Dry inertia about the motor's dry CM, kg·m²; RocketPy default zero.
    #[serde(default)]
    pub dry_inertia: Inertia,
    /// Motor's dry CM, motor coordinates, m (generic motor default: `chamber_position`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub center_of_dry_mass_position: Option<f64>,
    /// Nozzle exit position, motor coordinates, m; RocketPy default 0.
    #[serde(default)]
    pub nozzle_position: f64,
    /// Nozzle exit radius, m.
    pub nozzle_radius: f64,
    /// Nozzle throat radius, m (solid motors; RocketPy default 0.01 m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub throat_radius: Option<f64>,
    /// Direction of the motor coordinate; RocketPy default nozzle to combustion chamber.
    #[serde(default = "default_nozzle_to_chamber")]
    pub coordinate_system: MotorCoordinateSystem,
    /// Nozzle design ambient pressure, Pa, for the pressure thrust term (docs/physics.md §6.3);
    /// absent: no pressure correction.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference_pressure: Option<f64>,
    /// Number of BATES grains (solid).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grain_number: Option<u32>,
    /// Gap between grains, m (solid).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grain_separation: Option<f64>,
    /// Propellant density, kg/m³ (solid).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grain_density: Option<f64>,
    /// Grain outer radius, m (solid).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grain_outer_radius: Option<f64>,
    /// Initial grain bore radius, m (solid).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grain_initial_inner_radius: Option<f64>,
    /// Initial height of one grain, m (solid).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grain_initial_height: Option<f64>,
    /// Centre of the grain stack, motor coordinates, m (solid).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grains_center_of_mass_position: Option<f64>,
    /// Initial propellant mass, kg (generic).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub propellant_initial_mass: Option<f64>,
    /// Radius of the propellant cylinder, m (generic).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub chamber_radius: Option<f64>,
    /// Height of the propellant cylinder, m (generic).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub chamber_height: Option<f64>,
    /// Centre of the propellant cylinder, motor coordinates, m (generic).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub chamber_position: Option<f64>,
    /// Burn only on the grain bore (solid default false, hybrid default true).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub only_radial_burn: Option<bool>,
    /// `[[motor.tanks]]` (hybrid and liquid), in `add_tank` order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub tanks: Vec<TankSpec>,
    /// A cluster of this many identical motors, lit together; absent: 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cluster_count: Option<u32>,
    /// Distance of the clustered motors' axes from the rocket's axis, m (their root mean
    /// square distance for a cluster not on one ring); absent: 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cluster_radius: Option<f64>,
}

/// One `[[motor.tanks]]` entry (RocketPy's tank classes and `add_tank(tank, position)`).
/// Which curves a kind needs is checked by validation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TankSpec {
    /// Tank kind.
    pub kind: TankKindName,
    /// Name shown in reports; absent: `tank <index>`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Motor coordinate of the tank's height origin, m.
    pub position: f64,
    /// Geometry.
    pub geometry: TankGeometrySpec,
    /// Flux time, s: end, or `[start, end]`.
    pub flux_time: BurnTime,
    /// The liquid.
    pub liquid: FluidSpec,
    /// The gas.
    pub gas: FluidSpec,
    /// Grid nodes of the tank's tables; RocketPy default 100.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub discretize: Option<Discretize>,
    /// Temperature of time, K; default 273.15 K.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature: Option<Curve>,
    /// Pressure of time, Pa; default 101 325 Pa.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure: Option<Curve>,
    /// Initial liquid mass, kg (`mass_flow_rate`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial_liquid_mass: Option<f64>,
    /// Initial gas mass, kg (`mass_flow_rate`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial_gas_mass: Option<f64>,
    /// Liquid flowing in, kg/s (`mass_flow_rate`; default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub liquid_mass_flow_rate_in: Option<Curve>,
    /// Liquid flowing out, kg/s (`mass_flow_rate`; default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub liquid_mass_flow_rate_out: Option<Curve>,
    /// Gas flowing in, kg/s (`mass_flow_rate`; default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gas_mass_flow_rate_in: Option<Curve>,
    /// Gas flowing out, kg/s (`mass_flow_rate`; default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gas_mass_flow_rate_out: Option<Curve>,
    /// Gas volume, m³ (`ullage`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ullage: Option<Curve>,
    /// Liquid surface height in the tank frame, m (`level`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub liquid_height: Option<Curve>,
    /// Liquid mass, kg (`mass`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub liquid_mass: Option<Curve>,
    /// Gas mass, kg (`mass`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gas_mass: Option<Curve>,
}

/// `geometry = { kind, radius, height, spherical_caps }` of a tank.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TankGeometrySpec {
    /// Shape.
    pub kind: TankGeometryKind,
    /// Radius, m (a number; `custom`: a curve of height). RocketPy 1.13 spells it
    /// `radius_function`.
    #[serde(alias = "radius_function")]
    pub radius: Curve,
    /// Total height, m (`cylindrical`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    /// Hemispherical caps inside the height (`cylindrical`).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub spherical_caps: bool,
}

/// `liquid = { name, density }` / `gas = { ... }`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FluidSpec {
    /// Name.
    pub name: String,
    /// Density: kg/m³, or `[T K, p Pa, ρ]` rows, or a three-column file of them.
    pub density: DensitySpec,
}

/// A fluid density.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum DensitySpec {
    /// Constant, kg/m³.
    Constant(f64),
    /// `[temperature K, pressure Pa, density kg/m³]` rows.
    Rows(Vec<[f64; 3]>),
    /// A three-column file of such rows, relative to the mission.
    File(PathBuf),
}

/// `discretize`: the number of grid nodes, or `false` for no resampling.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Discretize {
    /// Grid nodes.
    Nodes(u32),
    /// `false`: no resampling (`true` means the default grid).
    Flag(bool),
}

fn default_hold() -> ExtrapolationKind {
    ExtrapolationKind::Constant
}

fn default_tail_to_nose() -> RocketCoordinateSystem {
    RocketCoordinateSystem::TailToNose
}

/// `[rocket]` (RocketPy `Rocket`), without its motor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RocketSpec {
    /// Body radius, m (the reference radius).
    pub radius: f64,
    /// Mass without motor, kg.
    pub mass: f64,
    /// Inertia without motor about its own CM, kg·m².
    pub inertia: Inertia,
    /// CM without motor, rocket coordinates, m.
    pub center_of_mass_without_motor: f64,
    /// Direction of the rocket coordinate; RocketPy default tail to nose.
    #[serde(default = "default_tail_to_nose")]
    pub coordinate_system: RocketCoordinateSystem,
    /// Drag coefficient of Mach, motor off; `"estimate"`: from the geometry.
    pub power_off_drag: Curve,
    /// Drag coefficient of Mach, motor burning; `"estimate"`: from the geometry.
    pub power_on_drag: Curve,
    /// `[rocket.drag_estimate]`: geometry of the drag estimate, optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drag_estimate: Option<DragEstimateSpec>,
    /// How both drag curves interpolate between their points.
    #[serde(default = "default_linear")]
    pub interpolation: InterpolationKind,
    /// What both drag curves give outside their Mach range.
    #[serde(default = "default_hold")]
    pub extrapolation: ExtrapolationKind,
    /// Position of the motor's coordinate origin, rocket coordinates, m.
    pub motor_position: f64,
    /// `[rocket.rail_buttons]`, optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rail_buttons: Option<RailButtonsSpec>,
    /// `[rocket.surfaces.<name>]`, in file order.
    #[serde(default, skip_serializing_if = "IndexMap::is_empty")]
    pub surfaces: IndexMap<String, SurfaceSpec>,
    /// `[rocket.parachutes.<name>]`, in file order.
    #[serde(default, skip_serializing_if = "IndexMap::is_empty")]
    pub parachutes: IndexMap<String, ParachuteSpec>,
    /// `[rocket.pods.<name>]`: pod sets and the surfaces each pod carries.
    #[serde(default, skip_serializing_if = "IndexMap::is_empty")]
    pub pods: IndexMap<String, PodSpec>,
    /// `[rocket.air_brakes]`, optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub air_brakes: Option<AirBrakesSpec>,
    /// `[[rocket.sensors]]`, in file order (docs/physics.md §29).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sensors: Vec<SensorSpec>,
    /// `cm_eccentricity = [x, y]`: the centre of dry mass off the axis, m (RocketPy's
    /// `add_cm_eccentricity`, docs/physics.md §7.8); optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cm_eccentricity: Option<[f64; 2]>,
    /// `cp_eccentricity = [x, y]`: the aerodynamic forces' line of action off the axis, m
    /// (`add_cp_eccentricity`); optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cp_eccentricity: Option<[f64; 2]>,
    /// `thrust_eccentricity = [x, y]`: the thrust's line of action off the axis, m
    /// (`add_thrust_eccentricity`); optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thrust_eccentricity: Option<[f64; 2]>,
}

fn default_true() -> bool {
    true
}

/// `[rocket.air_brakes]` (RocketPy `Rocket.add_air_brakes` with its controller,
/// docs/physics.md §16).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AirBrakesSpec {
    /// `Cd(deployment_level, Mach)`: a number, `[[level, mach, cd], ...]` or a 3-column file.
    pub drag_coefficient_curve: AirBrakesCurve,
    /// The controller script (Rhai), relative to the mission.
    pub controller: PathBuf,
    /// Controller calls per second, Hz.
    pub sampling_rate: f64,
    /// Clip every level written to `[0, 1]`; RocketPy default true.
    #[serde(default = "default_true")]
    pub clamp: bool,
    /// Reference area of the curve, m²; absent: the rocket's `π r²`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference_area: Option<f64>,
    /// While deployed, the curve is the whole rocket's drag; RocketPy default false.
    #[serde(default)]
    pub override_rocket_drag: bool,
    /// Level at `t = 0`; RocketPy default 0.
    #[serde(default)]
    pub deployment_level: f64,
    /// The controller record's first entry.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial_observed_variables: Option<Vec<f64>>,
    /// Name shown in reports; RocketPy default "AirBrakes".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Name of the controller in reports; RocketPy default "AirBrakes Controller".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub controller_name: Option<String>,
    /// `[rocket.air_brakes.constants]`: values for top-level constants of the script
    /// (`const NAME = ...;`), which `--set` and `[dispersion.vary]` reach by dotted path.
    #[serde(default, skip_serializing_if = "IndexMap::is_empty")]
    pub constants: IndexMap<String, f64>,
}

fn default_button_angle() -> f64 {
    45.0
}

/// `[rocket.rail_buttons]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RailButtonsSpec {
    /// Position of the upper (nose-side) button, rocket coordinates, m.
    pub upper_position: f64,
    /// Position of the lower button, rocket coordinates, m.
    pub lower_position: f64,
    /// Angular position of the buttons, deg; RocketPy default 45.
    #[serde(rename = "angular_position", default = "default_button_angle")]
    pub angular_position_deg: f64,
}

fn default_sampling_rate() -> f64 {
    100.0
}

/// `[rocket.parachutes.<name>]` (RocketPy `Parachute`; defaults of docs/physics.md §1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParachuteSpec {
    /// Drag coefficient times reference area, m².
    pub cd_s: f64,
    /// When to eject.
    pub trigger: Trigger,
    /// Pressure-signal sampling rate of the trigger, Hz; RocketPy default 100.
    #[serde(default = "default_sampling_rate")]
    pub sampling_rate: f64,
    /// Delay between trigger and full inflation, s; RocketPy default 0.
    #[serde(default)]
    pub lag: f64,
    /// Pressure-signal noise: mean (Pa), standard deviation (Pa), time correlation;
    /// RocketPy default (0, 0, 0).
    #[serde(default)]
    pub noise: [f64; 3],
    /// Canopy radius, m (added mass, docs/physics.md §8.4); absent: RocketPy's default.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// Canopy height, m; absent: RocketPy's default.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    /// Canopy porosity; absent: RocketPy's default 0.0432.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub porosity: Option<f64>,
}

fn default_inclination() -> f64 {
    80.0
}

fn default_heading() -> f64 {
    90.0
}

fn default_max_time() -> f64 {
    600.0
}

fn default_rtol() -> f64 {
    1e-6
}

fn default_max_time_step() -> f64 {
    f64::INFINITY
}

/// `[flight]` (RocketPy `Flight`; defaults of docs/physics.md §1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlightSpec {
    /// Launch rail length, m.
    pub rail_length: f64,
    /// Rail inclination from horizontal, deg; RocketPy default 80.
    #[serde(rename = "inclination", default = "default_inclination")]
    pub inclination_deg: f64,
    /// Rail heading from north, clockwise, deg; RocketPy default 90.
    #[serde(rename = "heading", default = "default_heading")]
    pub heading_deg: f64,
    /// Simulation time limit, s; RocketPy default 600.
    #[serde(default = "default_max_time")]
    pub max_time: f64,
    /// Stop at apogee; RocketPy default false.
    #[serde(default)]
    pub terminate_on_apogee: bool,
    /// Relative tolerance of the integrator; RocketPy default 1e-6.
    #[serde(default = "default_rtol")]
    pub rtol: f64,
    /// Absolute tolerance; absent: RocketPy's per-state default (docs/physics.md §10.1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub atol: Option<Atol>,
    /// Largest integrator step, s; RocketPy default +∞ (`inf` in TOML).
    #[serde(default = "default_max_time_step")]
    pub max_time_step: f64,
    /// `true`: sampled processes (parachute triggers, controllers) look at the solver's free
    /// steps afterwards; `false`: every sampling instant is a hard time node (RocketPy's
    /// `time_overshoot`, docs/physics.md §16.4); RocketPy default true.
    #[serde(default = "default_true")]
    pub time_overshoot: bool,
    /// The form of the 6-DOF equations: `"standard"` (default; physically consistent lever
    /// arms and mass flow) or `"rocketpy_1_13"` (RocketPy 1.13 exactly).
    #[serde(default)]
    pub equations: Equations,
    /// The equations of the free flight: `"6 DOF"` (default) or `"3 DOF"`, RocketPy 1.12+'s
    /// point mass (docs/physics.md §8.5).
    #[serde(default)]
    pub simulation_mode: Mode,
    /// The 3-DOF weathercock coefficient, 1/s (RocketPy's `PointMassRocket.weathercock_coeff`);
    /// absent: 0, the attitude held at the rail's. Only with `simulation_mode = "3 DOF"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weathercock_coeff: Option<f64>,
}

/// `[flight] equations`: the form of the 6-DOF equations, as the file spells it (the
/// assembly maps it to the engine's [`karman_dynamics::EquationsForm`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Equations {
    /// `"standard"`: the physically consistent form (default).
    #[default]
    Standard,
    /// `"rocketpy_1_13"`: RocketPy 1.13 exactly.
    #[serde(rename = "rocketpy_1_13")]
    RocketPy113,
}

impl From<Equations> for karman_dynamics::EquationsForm {
    fn from(equations: Equations) -> Self {
        match equations {
            Equations::Standard => karman_dynamics::EquationsForm::Standard,
            Equations::RocketPy113 => karman_dynamics::EquationsForm::RocketPy113,
        }
    }
}

/// `[flight] simulation_mode`: the equations of the free flight, as the file spells it (the
/// assembly maps it to the engine's [`karman_dynamics::SimulationMode`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Mode {
    /// `"6 DOF"`: the variable-mass rigid body (default).
    #[default]
    #[serde(rename = "6 DOF")]
    SixDof,
    /// `"3 DOF"`: RocketPy 1.12+'s point mass.
    #[serde(rename = "3 DOF")]
    ThreeDof,
}

impl From<Mode> for karman_dynamics::SimulationMode {
    fn from(mode: Mode) -> Self {
        match mode {
            Mode::SixDof => karman_dynamics::SimulationMode::SixDof,
            Mode::ThreeDof => karman_dynamics::SimulationMode::ThreeDof,
        }
    }
}

/// `[dispersion]`: Monte Carlo run settings and the inputs that vary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DispersionSpec {
    /// Number of sampled flights.
    pub samples: u32,
    /// Seed of the random streams (sample `i` draws from a stream derived from (seed, i)).
    pub seed: u64,
    /// `[dispersion.vary]`: dotted input path → distribution, in file order.
    #[serde(default)]
    pub vary: IndexMap<String, Distribution>,
}

/// A distribution of `[dispersion.vary]` (mission-format.md "Distributions"; NumPy
/// `Generator` parameter conventions, docs/physics.md §12.1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Distribution {
    /// Normal around the nominal value with this standard deviation.
    Std(f64),
    /// Normal `[mean, std]`.
    Normal([f64; 2]),
    /// Uniform `[low, high]`.
    Uniform([f64; 2]),
    /// Triangular `[low, mode, high]`.
    Triangular([f64; 3]),
    /// Log-normal `[mu, sigma]` of the underlying normal.
    Lognormal([f64; 2]),
    /// Uniform choice among these values.
    Choice(Vec<f64>),
    /// Multiply the nominal value (number or curve) by a draw of this distribution.
    Factor(Box<Distribution>),
    /// Add a draw of this distribution to the nominal value (number or curve).
    Offset(Box<Distribution>),
    /// NumPy's `exponential(scale)`.
    Exponential(Parameters),
    /// NumPy's `gamma(shape, scale)`.
    Gamma(Parameters),
    /// NumPy's `gumbel(loc, scale)`.
    Gumbel(Parameters),
    /// NumPy's `laplace(loc, scale)`.
    Laplace(Parameters),
    /// NumPy's `logistic(loc, scale)`.
    Logistic(Parameters),
    /// NumPy's `poisson(lam)`.
    Poisson(Parameters),
    /// NumPy's `wald(mean, scale)`.
    Wald(Parameters),
    /// NumPy's `binomial(n, p)`.
    Binomial(Parameters),
    /// NumPy's `chisquare(df)`.
    Chisquare(Parameters),
    /// A distribution restricted to `[low, high]` (`crate::distributions`).
    Truncated(Box<Truncated>),
}

/// The parameters of a named distribution (`crate::distributions`): a table by NumPy's
/// names (`{ shape = 2, scale = 0.5 }`) or an array in NumPy's positional order (`[2, 0.5]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Parameters {
    /// By name, in the file's order.
    Named(IndexMap<String, f64>),
    /// In NumPy's positional order.
    Positional(Vec<f64>),
}

/// `{ truncated = { distribution = { ... }, low = L, high = H } }`: either bound may be left
/// out.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Truncated {
    /// The distribution that is truncated.
    pub distribution: Distribution,
    /// The lower bound (inclusive).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub low: Option<f64>,
    /// The upper bound (inclusive).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub high: Option<f64>,
}
