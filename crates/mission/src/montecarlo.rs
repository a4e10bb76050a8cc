//! Monte Carlo of a mission (mission-format.md, section `[dispersion]`): the `[dispersion.vary]`
//! table turned into a [`karman_dispersion::Study`], each sample's values applied to the
//! mission by dotted path, and the mission flown.
//!
//! - A stored number (`rocket.mass`, `rocket.parachutes.Main.cd_s`, a constant curve) is set
//!   through [`crate::paths::set_number`]: the drawn value, or the nominal value times the
//!   drawn factor / plus the drawn offset.
//! - A component of an array (`rocket.inertia.0`) is a stored number; the whole array
//!   (`rocket.inertia`) takes `factor` / `offset` on every component.
//! - A curve (`rocket.power_off_drag` from a file or points) takes `factor` / `offset` on
//!   every ordinate; a file curve is read once and replaced by its scaled points. A drag
//!   curve estimated from the geometry (`"estimate"`) takes them too, on the sample's own
//!   estimate (geometry varied in the same sample included).
//! - `motor.total_impulse` / `motor.burn_time` reshape the thrust curve
//!   (`reshape_thrust_curve = [burn end time, impulse]`, RocketPy's `reshape_thrust_curve`);
//!   the nominal values are those of the nominal motor.
//! - `environment.wind_factor` multiplies the wind and `environment.wind_direction_offset`
//!   (deg) turns it clockwise seen from above (the direction it blows from grows by that
//!   angle), for every atmosphere model: the flight sees the environment through
//!   [`WindAdjusted`].
//!
//! Each sample is built and flown exactly as [`crate::assemble::flight::simulate_with_seed`]
//! does (a sample drawing the nominal values gives bit-identical results), except that what
//! no varied input reaches is built once from the nominal mission and shared: the
//! environment unless a stored `environment.*` input varies, the motor unless a `motor.*`
//! input or knob varies, the rocket unless the motor or a `rocket.*` input varies; thrust and
//! rocket curve files are read once (those of every motor: each stage's of a multi-stage
//! mission, each `[[extra_motors]]` entry's; [`crate::assemble::motors::ThrustCache`]).
//! Parachute trigger noise of sample `i` is seeded from the sample's reserved stream
//! ([`karman_dispersion::sampling::flight_seed`]), so it replays with the sample.
//!
//! A multi-stage mission (`[[stages]]`) flies each sample as
//! [`crate::assemble::stages::simulate_staged`] does, in the shared environment unless a stored
//! environment input varies, with the wind knobs applied
//! ([`crate::assemble::stages::simulate_staged_in`]); a lower stage's inputs are reached by
//! `stages.<index>.` paths (its motor's knobs reshape that motor's thrust curve), and each lower
//! stage adds its separation time and, when it flies alone, its body's outputs
//! ([`BODY_OUTPUTS`]) and landing points to the study.
//! The KML export converts (x, y) to latitude/longitude with the datum's local Earth radius,
//! as the flight's own track does (RocketPy's ellipse export uses 6.3781e6 m: up to 0.1 %
//! apart, about 1 m per km of drift).

use crate::assemble::environment::{WindAdjusted, build_environment};
use crate::assemble::flight::{early_ending, fly_with_sensors};
use crate::assemble::motors::ThrustCache;
use crate::assemble::preflight::flight_settings;
use crate::assemble::rocket::{EstimateScaling, build_rocket_scaled};
use crate::assemble::scripts::{ControllerEnvironment, compile_controller};
use crate::assemble::sensors::{self, EnvironmentSurroundings};
use crate::assemble::{stage_view, stages};
use crate::distributions::plain;
use crate::paths::{self, DerivedKnob, Input};
use crate::schema::{AirBrakesCurve, Curve, Distribution, MissionSpec};
use crate::{Mission, MissionError, validate};
use karman_airframe::{AirBrakesDrag, Rocket};
use karman_atmos::Environment;
use karman_dispersion::sampling::flight_seed;
use karman_dispersion::{
    BodyPoints, DataFile, DispersionError, Meaning, Outcome, Points, Site, Study, Target,
    Variation, VariedInput,
};
use karman_dynamics::{Flight, Sample, Summary};
use karman_propulsion::Motor;
use karman_script::ControllerScript;
use sha2::{Digest, Sha256};
use std::fmt::Write as _;
use std::sync::Arc;

/// The outputs of every sample: the scalar keys of the flight summary (mission-format.md
/// "The summary").
pub const OUTPUTS: [&str; 18] = [
    "apogee_agl_m",
    "apogee_asl_m",
    "apogee_time_s",
    "apogee_x_m",
    "apogee_y_m",
    "out_of_rail_time_s",
    "out_of_rail_velocity_mps",
    "out_of_rail_stability_margin",
    "initial_static_margin",
    "burnout_static_margin",
    "max_speed_mps",
    "max_mach",
    "max_dynamic_pressure_pa",
    "max_acceleration_mps2",
    "impact_time_s",
    "impact_x_m",
    "impact_y_m",
    "impact_velocity_mps",
];

/// The outputs of each lower stage of a multi-stage rocket that flies to its own landing,
/// after its `<stage name>.` (mission-format.md "Monte Carlo of a multi-stage rocket"); each
/// lower stage also has `<stage name>.separation_time_s`.
pub const BODY_OUTPUTS: [&str; 13] = [
    "apogee_agl_m",
    "apogee_asl_m",
    "apogee_time_s",
    "apogee_x_m",
    "apogee_y_m",
    "max_speed_mps",
    "max_mach",
    "max_dynamic_pressure_pa",
    "max_acceleration_mps2",
    "impact_time_s",
    "impact_x_m",
    "impact_y_m",
    "impact_velocity_mps",
];

/// The output of a lower stage's separation time.
const SEPARATION_OUTPUT: &str = "separation_time_s";

/// The values of [`OUTPUTS`] in a flight summary.
fn output_values(s: &Summary) -> Vec<Option<f64>> {
    vec![
        s.apogee_agl_m,
        s.apogee_asl_m,
        s.apogee_time_s,
        s.apogee_x_m,
        s.apogee_y_m,
        s.out_of_rail_time_s,
        s.out_of_rail_velocity_mps,
        s.out_of_rail_stability_margin,
        Some(s.initial_static_margin),
        Some(s.burnout_static_margin),
        Some(s.max_speed_mps),
        Some(s.max_mach),
        Some(s.max_dynamic_pressure_pa),
        Some(s.max_acceleration_mps2),
        s.impact_time_s,
        s.impact_x_m,
        s.impact_y_m,
        s.impact_velocity_mps,
    ]
}

/// How a varied input is applied to the mission.
#[derive(Debug, Clone)]
enum Apply {
    /// A stored number at this path, with its nominal value.
    Number { path: String, nominal: f64 },
    /// An array of numbers: the paths of its components, with their nominal values.
    Array { components: Vec<(String, f64)> },
    /// A curve at this path, with its nominal points.
    Curve { path: String, points: Vec<[f64; 2]> },
    /// A drag curve estimated from the geometry (power-on or off): each sample's own estimate
    /// is scaled or shifted.
    Estimate { power_on: bool },
    /// The air brakes' drag table, with its nominal rows (the Cd column varies).
    Rows { rows: Vec<[f64; 3]> },
    /// A derived knob, with its nominal value, of the top stage's motor (`stage` none) or of
    /// a lower stage's.
    Knob {
        knob: DerivedKnob,
        nominal: f64,
        stage: Option<usize>,
    },
}

/// A lower stage of a multi-stage study and the outputs it adds.
#[derive(Debug, Clone)]
struct LowerStage {
    /// Its name in reports and before its columns.
    name: String,
    /// It flies to its own landing (it has a motor and a mass): its [`BODY_OUTPUTS`] exist.
    flies: bool,
}

/// Which models the varied inputs reach (the others are built once and shared).
#[derive(Debug, Clone, Copy, Default)]
struct Reach {
    /// A stored `environment.*` input: the environment is rebuilt per sample.
    environment: bool,
    /// A `motor.*` input or knob: the motor is rebuilt per sample.
    motor: bool,
    /// A `rocket.*` or `extra_motors.*` input, or the motor: the rocket (which carries the
    /// extra motors) is rebuilt per sample.
    rocket: bool,
}

impl Reach {
    fn add(&mut self, path: &str) {
        let section = path.split('.').next().unwrap_or_default();
        let knob = DerivedKnob::from_path(path);
        self.environment |= section == "environment" && knob.is_none();
        self.motor |= section == "motor";
        self.rocket |= matches!(section, "motor" | "rocket" | "extra_motors");
    }
}

/// A mission's Monte Carlo study, ready to fly samples.
#[derive(Debug, Clone)]
pub struct MonteCarlo {
    /// The mission, its rocket's curve files read into inline points.
    mission: Mission,
    study: Study,
    applies: Vec<Apply>,
    reach: Reach,
    /// The nominal environment, shared by the samples when no stored environment input varies.
    environment: Option<Arc<Environment>>,
    /// The air-brake controller script, compiled once.
    controller: Option<ControllerScript>,
    /// The thrust data of every motor of the mission, read once.
    thrusts: ThrustCache,
    /// The nominal motor and rocket, shared by the samples that do not vary them.
    motor: Motor,
    rocket: Rocket,
    /// The nominal motor's burn end time and total impulse (the `motor.burn_time` and
    /// `motor.total_impulse` knobs reshape the thrust curve from them).
    nominal_reshape: [f64; 2],
    /// The same of each lower stage's own motor (none without one).
    stage_reshapes: Vec<Option<[f64; 2]>>,
    /// The lower stages of a multi-stage mission (each sample flies the staged flight).
    lower: Vec<LowerStage>,
}

/// `--samples` / `--seed` overrides of the `[dispersion]` table.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct StudyOverrides {
    /// Number of samples.
    pub samples: Option<u64>,
    /// Seed.
    pub seed: Option<u64>,
}

fn dispersion_error(mission: &Mission, e: DispersionError) -> MissionError {
    mission.model_error("dispersion", e)
}

/// The variation of a `[dispersion.vary]` entry (`std` inside `factor` is a normal around 1,
/// inside `offset` around 0); the error says what is wrong with it.
fn variation(distribution: &Distribution) -> Result<Variation, String> {
    Ok(match distribution {
        Distribution::Std(std) => Variation::Std(*std),
        Distribution::Factor(inner) => Variation::Factor(plain(inner, 1.0)?),
        Distribution::Offset(inner) => Variation::Offset(plain(inner, 0.0)?),
        other => Variation::Value(plain(other, 0.0)?),
    })
}

/// What a varied input is in a study (its nominal target) and how a sample applies a drawn
/// value to it: a number or integer, each component of an array, a drag curve (points, a
/// file, rows of a table or the geometric estimate) or a derived knob (its nominal read from
/// the motor of its stage).
fn input_target(
    mission: &Mission,
    path: &str,
    input: Input<'_>,
    motor: &Motor,
    stage_reshapes: &[Option<[f64; 2]>],
) -> Result<(Target, Apply), MissionError> {
    let spec = &mission.spec;
    let invalid =
        |reason: String| dispersion_error(mission, DispersionError::InvalidStudy { reason });
    Ok(match input {
        Input::Number { value, integer } => {
            let target = if integer {
                Target::Integer(value as i64)
            } else {
                Target::Number(value)
            };
            let apply = Apply::Number {
                path: path.to_owned(),
                nominal: value,
            };
            (target, apply)
        }
        Input::Array(values) => {
            let components = values
                .iter()
                .enumerate()
                .map(|(i, v)| (format!("{path}.{i}"), *v))
                .collect();
            (Target::Array(values), Apply::Array { components })
        }
        Input::Curve(curve) if curve.is_estimate() => {
            if !spec.stages.is_empty() {
                return Err(invalid(format!(
                    "`{path}`: the estimated drag of a multi-stage rocket takes no \
                     `factor` or `offset` yet; give the curve as points or a file"
                )));
            }
            let power_on = path == "rocket.power_on_drag";
            (Target::Curve, Apply::Estimate { power_on })
        }
        Input::Curve(curve) => {
            let points = curve
                .points(&mission.dir)
                .map_err(|e| invalid(format!("`{path}`: {e}")))?;
            let apply = Apply::Curve {
                path: path.to_owned(),
                points,
            };
            (Target::Curve, apply)
        }
        Input::Table(curve) => {
            let rows = match curve
                .to_drag(&mission.dir)
                .map_err(|e| invalid(format!("`{path}`: {e}")))?
            {
                AirBrakesDrag::Table(rows) => rows,
                AirBrakesDrag::Constant(cd) => vec![[0.0, 0.0, cd]],
            };
            (Target::Curve, Apply::Rows { rows })
        }
        Input::Knob(knob) => {
            let stage = paths::stage_path(path).map(|(index, _)| index);
            let [burn, impulse] = match stage {
                None => [motor.burn_out(), motor.total_impulse()],
                Some(index) => stage_reshapes
                    .get(index)
                    .copied()
                    .flatten()
                    .ok_or_else(|| invalid(format!("`{path}`: the stage has no motor")))?,
            };
            let nominal = match knob {
                DerivedKnob::TotalImpulse => impulse,
                DerivedKnob::BurnTime => burn,
                DerivedKnob::WindFactor => 1.0,
                DerivedKnob::WindDirectionOffset => 0.0,
            };
            let apply = Apply::Knob {
                knob,
                nominal,
                stage,
            };
            (Target::Number(nominal), apply)
        }
    })
}

impl MonteCarlo {
    /// The study of `mission`'s `[dispersion]` table (samples and seed overridable). The
    /// nominal motor and environment are built once here.
    ///
    /// # Errors
    /// [`MissionError::Model`] (section `dispersion`) when the mission has no `[dispersion]`
    /// table and no sample count is given, or a distribution does not fit its input; the
    /// builders' errors for the nominal models.
    pub fn new(mission: &Mission, overrides: StudyOverrides) -> Result<Self, MissionError> {
        let spec = &mission.spec;
        let invalid =
            |reason: String| dispersion_error(mission, DispersionError::InvalidStudy { reason });
        let table = spec.dispersion.as_ref();
        let samples = overrides
            .samples
            .or(table.map(|d| u64::from(d.samples)))
            .ok_or_else(|| {
                invalid("the mission has no [dispersion] table; give --samples".into())
            })?;
        let seed = overrides.seed.or(table.map(|d| d.seed)).unwrap_or(0);
        let thrusts = ThrustCache::read(mission)?;
        let motor = thrusts.motor(mission)?;
        let rocket = build_rocket_scaled(mission, &motor, EstimateScaling::default(), &thrusts)?;
        let environment = build_environment(mission)?;
        let mut stage_reshapes = Vec::with_capacity(spec.stages.len());
        for (index, stage) in spec.stages.iter().enumerate() {
            stage_reshapes.push(match &stage.motor {
                Some(_) => {
                    let alone = stage_view::stage_mission(mission, index);
                    let motor = stages::stage_motor(&alone, &thrusts, index)?;
                    Some([motor.burn_out(), motor.total_impulse()])
                }
                None => None,
            });
        }
        let mut inputs = Vec::new();
        let mut applies = Vec::new();
        let mut reach = Reach::default();
        for (path, distribution) in table.map(|d| d.vary.iter()).into_iter().flatten() {
            let input = paths::resolve(spec, path).map_err(|e| invalid(e.to_string()))?;
            let variation =
                variation(distribution).map_err(|reason| invalid(format!("`{path}`: {reason}")))?;
            reach.add(path);
            let (target, apply) = input_target(mission, path, input, &motor, &stage_reshapes)?;
            inputs.push(VariedInput::new(path.clone(), target, variation));
            applies.push(apply);
        }
        let lower = lower_stages(spec);
        let mut outputs: Vec<String> = OUTPUTS.iter().map(|s| (*s).to_owned()).collect();
        outputs.extend(stage_outputs(spec));
        let mut bodies = Vec::new();
        for stage in &lower {
            let column = |output: &str| format!("{}.{output}", stage.name);
            if stage.flies {
                bodies.push(BodyPoints {
                    name: stage.name.clone(),
                    apogee: Some([column("apogee_x_m"), column("apogee_y_m")]),
                    landing: Some([column("impact_x_m"), column("impact_y_m")]),
                });
            }
        }
        let mut study = Study::new(seed, samples, inputs, outputs);
        study.points = Points {
            apogee: Some(["apogee_x_m".into(), "apogee_y_m".into()]),
            landing: Some(["impact_x_m".into(), "impact_y_m".into()]),
            histogram: Some("apogee_agl_m".into()),
            body: (!lower.is_empty()).then(|| stage_view::TOP_STAGE.to_owned()),
            bodies,
        };
        study.site = Some(Site {
            latitude_deg: spec.environment.latitude_deg,
            longitude_deg: spec.environment.longitude_deg,
            earth_radius: environment.datum_radius(),
        });
        study.context = spec
            .name
            .clone()
            .unwrap_or_else(|| mission.path.display().to_string());
        study.data = data_fingerprint(mission)?;
        study.validate().map_err(|e| dispersion_error(mission, e))?;
        let mut base = mission.clone();
        inline_rocket_curves(&mut base)?;
        Ok(MonteCarlo {
            mission: base,
            study,
            applies,
            reach,
            environment: (!reach.environment).then(|| Arc::new(environment)),
            controller: compile_controller(mission)?,
            thrusts,
            nominal_reshape: [motor.burn_out(), motor.total_impulse()],
            stage_reshapes,
            lower,
            motor,
            rocket,
        })
    }

    /// The study.
    pub fn study(&self) -> &Study {
        &self.study
    }

    /// The mission with sampled `values` applied, the wind (factor, direction offset in
    /// degrees) and the change of the estimated drag curves.
    fn sample_spec(
        &self,
        values: &[f64],
    ) -> Result<(MissionSpec, [f64; 2], EstimateScaling), String> {
        let mut spec = self.mission.spec.clone();
        let mut wind = [1.0, 0.0];
        let mut drag = EstimateScaling::default();
        let mut reshape: [Option<f64>; 2] = [None, None];
        let mut stage_reshape: Vec<[Option<f64>; 2]> = vec![[None, None]; spec.stages.len()];
        for ((apply, input), &value) in self.applies.iter().zip(&self.study.inputs).zip(values) {
            let combine = |nominal: f64| match input.meaning() {
                Meaning::Value => value,
                Meaning::Factor => nominal * value,
                Meaning::Offset => nominal + value,
            };
            match apply {
                Apply::Number { path, nominal } => {
                    paths::set_number(&mut spec, path, combine(*nominal))
                        .map_err(|e| e.to_string())?;
                }
                Apply::Array { components } => {
                    for (path, nominal) in components {
                        paths::set_number(&mut spec, path, combine(*nominal))
                            .map_err(|e| e.to_string())?;
                    }
                }
                Apply::Curve { path, points } => {
                    let scaled = points.iter().map(|[x, y]| [*x, combine(*y)]).collect();
                    let slot = paths::curve_mut(&mut spec, path)
                        .ok_or_else(|| format!("`{path}` is not a curve"))?;
                    *slot = Curve::Points(scaled);
                }
                Apply::Estimate { power_on } => {
                    let slot = if *power_on {
                        &mut drag.power_on
                    } else {
                        &mut drag.power_off
                    };
                    *slot = match input.meaning() {
                        Meaning::Factor => [value, 0.0],
                        Meaning::Offset => [1.0, value],
                        Meaning::Value => {
                            return Err(format!(
                                "`{}`: an estimated curve takes a factor or an offset",
                                input.name
                            ));
                        }
                    };
                }
                Apply::Rows { rows } => {
                    let scaled = rows.iter().map(|&[l, m, cd]| [l, m, combine(cd)]).collect();
                    if let Some(ab) = spec.rocket.air_brakes.as_mut() {
                        ab.drag_coefficient_curve = AirBrakesCurve::Rows(scaled);
                    }
                }
                Apply::Knob {
                    knob,
                    nominal,
                    stage,
                } => {
                    let value = combine(*nominal);
                    let target = match stage {
                        None => &mut reshape,
                        Some(index) => stage_reshape
                            .get_mut(*index)
                            .ok_or_else(|| format!("no stage {index}"))?,
                    };
                    match knob {
                        DerivedKnob::TotalImpulse => target[1] = Some(value),
                        DerivedKnob::BurnTime => target[0] = Some(value),
                        DerivedKnob::WindFactor => wind[0] = value,
                        DerivedKnob::WindDirectionOffset => wind[1] = value,
                    }
                }
            }
        }
        let merged = |drawn: [Option<f64>; 2], [burn, impulse]: [f64; 2]| {
            [drawn[0].unwrap_or(burn), drawn[1].unwrap_or(impulse)]
        };
        if reshape.iter().any(Option::is_some) {
            spec.motor.reshape_thrust_curve = Some(merged(reshape, self.nominal_reshape));
        }
        for ((stage, drawn), nominal) in spec
            .stages
            .iter_mut()
            .zip(stage_reshape)
            .zip(&self.stage_reshapes)
        {
            if let (Some(motor), Some(nominal)) = (stage.motor.as_mut(), nominal)
                && drawn.iter().any(Option::is_some)
            {
                motor.reshape_thrust_curve = Some(merged(drawn, *nominal));
            }
        }
        Ok((spec, wind, drag))
    }

    /// Flies sample `index` with its sampled `values` (in the order of the study's inputs);
    /// an error is the whole message chain. A multi-stage mission's sample flies the staged
    /// flight as [`stages::simulate_staged`] does: the top stage's [`OUTPUTS`], then each
    /// lower stage's separation time and, when it flies alone, its [`BODY_OUTPUTS`] (none
    /// where its flight did not get there); a body ending early ends the sample.
    pub fn fly(&self, index: u64, values: &[f64]) -> Result<Outcome, String> {
        let (values, ended) = self.fly_read(
            index,
            values,
            |flight, atmosphere, rocket| output_values(&flight.summary(atmosphere, rocket)),
            |run| staged_values(run, &self.lower),
        )?;
        Ok(match ended {
            None => Outcome::new(values),
            Some((kind, message)) => Outcome::ended(values, kind, message),
        })
    }

    /// Flies sample `index` with `values` as [`MonteCarlo::fly`] does and returns its
    /// trajectory: the stored points and the summary (of the top stage for a multi-stage
    /// mission), with how the flight ended early if it did. A fit to a flight log
    /// (karman-fit) flies its trial values through this, so that they reach the mission
    /// exactly as a study's draws do.
    ///
    /// # Errors
    /// As [`MonteCarlo::fly`]: the whole message chain.
    pub fn track(&self, index: u64, values: &[f64]) -> Result<SampleTrack, String> {
        let ((samples, summary), ended) = self.fly_read(
            index,
            values,
            |flight, atmosphere, rocket| {
                (
                    flight.samples(atmosphere, rocket),
                    flight.summary(atmosphere, rocket),
                )
            },
            |run| {
                let (_, ended) = staged_values(run, &self.lower)?;
                Ok(((run.samples(0), run.summary(0)), ended))
            },
        )?;
        Ok(SampleTrack {
            samples,
            summary,
            ended,
        })
    }

    /// Flies sample `index` with `values` and reads the flight with `read` (a single-stage
    /// flight, with the atmosphere and rocket it flew) or `read_staged` (a multi-stage one,
    /// which says itself how it ended early); returns what they read and how the flight
    /// ended early, if it did.
    fn fly_read<R>(
        &self,
        index: u64,
        values: &[f64],
        read: impl FnOnce(&Flight, &WindAdjusted<'_>, &Rocket) -> R,
        read_staged: impl FnOnce(&stages::StagedRun) -> Result<(R, Ended), String>,
    ) -> Result<(R, Ended), String> {
        let (spec, [factor, offset_deg], drag) = self.sample_spec(values)?;
        drawn_in_range(&spec, &self.mission.dir)?;
        let mission = Mission {
            path: self.mission.path.clone(),
            dir: self.mission.dir.clone(),
            spec,
            keys: self.mission.keys.clone(),
        };
        let environment = match &self.environment {
            Some(environment) => Arc::clone(environment),
            None => Arc::new(build_environment(&mission).map_err(|e| chain(&e))?),
        };
        let noise_seed = flight_seed(self.study.seed, index);
        if !self.lower.is_empty() {
            let run = stages::simulate_staged_in(
                &mission,
                &self.thrusts,
                (*environment).clone(),
                [factor, offset_deg],
                noise_seed,
            )
            .map_err(|e| chain(&e))?;
            return read_staged(&run);
        }
        let (sample_motor, sample_rocket);
        let rocket = if self.reach.rocket {
            let motor = if self.reach.motor {
                sample_motor = self.thrusts.motor(&mission).map_err(|e| chain(&e))?;
                &sample_motor
            } else {
                &self.motor
            };
            sample_rocket =
                build_rocket_scaled(&mission, motor, drag, &self.thrusts).map_err(|e| chain(&e))?;
            &sample_rocket
        } else {
            &self.rocket
        };
        let settings = flight_settings(&mission, noise_seed);
        let atmosphere = WindAdjusted::new(&environment, factor, offset_deg);
        // The sample's sensors, seeded as its parachutes (sensor `i` by the sample's seed and
        // `i`), so that their readings reach the controller and the triggers as in a single
        // flight; their noise parameters are the sample's (dispersible by dotted path).
        let sensors = sensors::build(&mission, rocket, noise_seed).map_err(|e| chain(&e))?;
        let surroundings = EnvironmentSurroundings(&environment);
        let (flight, _, _) = fly_with_sensors(
            &mission,
            &atmosphere,
            rocket,
            &settings,
            self.controller.as_ref().into(),
            || {
                Arc::new(ControllerEnvironment::new(
                    Arc::clone(&environment),
                    factor,
                    offset_deg,
                ))
            },
            (sensors, &surroundings),
        )
        .map_err(|e| chain(&e))?;
        let read = read(&flight, &atmosphere, rocket);
        Ok((read, early_ending(flight.termination, &settings)))
    }
}

/// How a flight ended before the end a study asks for: the status word and the message
/// ([`early_ending`]); `None` for a flight that ended as asked.
pub type Ended = Option<(&'static str, String)>;

/// The trajectory of one sample ([`MonteCarlo::track`]).
#[derive(Debug, Clone)]
pub struct SampleTrack {
    /// Post-processed quantities at every stored point (the top stage's).
    pub samples: Vec<Sample>,
    /// The flight summary (the top stage's).
    pub summary: Summary,
    /// How the flight ended early, if it did.
    pub ended: Ended,
}

/// A sample's mission must pass the range checks of a mission file and `--set`
/// ([`validate::validate_drawn`]): a draw outside them (a negative trigger height, a
/// relative tolerance of 0.5, a sampling rate of 1e10 Hz) fails the sample with every
/// offending key and value named, instead of flying a flight the file would be refused for.
fn drawn_in_range(spec: &MissionSpec, dir: &std::path::Path) -> Result<(), String> {
    let problems = validate::validate_drawn(spec, dir);
    if problems.is_empty() {
        return Ok(());
    }
    let listed: Vec<String> = problems
        .iter()
        .map(|(key, kind)| format!("{key}: {kind}"))
        .collect();
    Err(format!(
        "a drawn value is out of range: {}",
        listed.join("; ")
    ))
}

/// The lower stages of a multi-stage mission, as its study and sweep report them.
fn lower_stages(spec: &MissionSpec) -> Vec<LowerStage> {
    spec.stages
        .iter()
        .enumerate()
        .map(|(index, stage)| LowerStage {
            name: stage_view::stage_name(stage, index),
            flies: stage.rocket.mass > 0.0 && stage.motor.is_some(),
        })
        .collect()
}

/// The outputs a multi-stage mission's flights have after [`OUTPUTS`] (the top stage's):
/// for each lower stage, in the order of `[[stages]]`, `<name>.separation_time_s` and, when
/// the stage flies alone, its [`BODY_OUTPUTS`] after `<name>.`. None for a single stage.
#[must_use]
pub fn stage_outputs(spec: &MissionSpec) -> Vec<String> {
    let mut outputs = Vec::new();
    for stage in lower_stages(spec) {
        let column = |output: &str| format!("{}.{output}", stage.name);
        outputs.push(column(SEPARATION_OUTPUT));
        if stage.flies {
            outputs.extend(BODY_OUTPUTS.iter().map(|o| column(o)));
        }
    }
    outputs
}

/// A staged flight's output values and how it ended early, if it did: the status word and
/// the message ([`early_ending`]).
pub type StagedValues = (Vec<Option<f64>>, Ended);

/// The values of [`OUTPUTS`] and [`stage_outputs`] of the staged flight `run` of `spec` (none
/// where a body's flight did not get there: no separation, no landing), and how it ended
/// early if a body did (its message naming a lower body).
///
/// # Errors
/// When the top stage did not fly (it always does).
pub fn staged_outputs(run: &stages::StagedRun, spec: &MissionSpec) -> Result<StagedValues, String> {
    staged_values(run, &lower_stages(spec))
}

fn staged_values(run: &stages::StagedRun, lower: &[LowerStage]) -> Result<StagedValues, String> {
    let body = |name: &str| run.bodies.iter().position(|b| b.name == name);
    let top = body(stage_view::TOP_STAGE).ok_or("the top stage did not fly")?;
    let top_summary = run.summary(top);
    let mut values = output_values(&top_summary);
    let mut ended = early_ending(top_summary.termination, &run.settings);
    for stage in lower {
        let separation = run.separations.iter().find(|s| s.stage == stage.name);
        values.push(separation.map(|s| s.time_s));
        if !stage.flies {
            continue;
        }
        let summary = body(&stage.name).map(|b| run.summary(b));
        let all = summary.as_ref().map(output_values);
        for output in BODY_OUTPUTS {
            let at = OUTPUTS.iter().position(|o| *o == output);
            values.push(all.as_ref().zip(at).and_then(|(all, i)| all[i]));
        }
        if ended.is_none()
            && let Some(summary) = &summary
            && let Some((kind, message)) = early_ending(summary.termination, &run.settings)
        {
            ended = Some((kind, format!("{}: {message}", stage.name)));
        }
    }
    Ok((values, ended))
}

/// The study's data ([`DataFile`]): the mission after overrides (its `Debug` text, which
/// prints every number exactly) and every data file it names ([`MissionSpec::data_files`]),
/// each with the SHA-256 of its content, so that a study is not resumed or merged with rows
/// flown on other data.
///
/// # Errors
/// [`MissionError::Model`] at the file's key when a data file cannot be read.
pub fn data_fingerprint(mission: &Mission) -> Result<Vec<DataFile>, MissionError> {
    let hex = |bytes: &[u8]| {
        Sha256::digest(bytes)
            .iter()
            .fold(String::with_capacity(64), |mut s, b| {
                let _ = write!(s, "{b:02x}");
                s
            })
    };
    let spec = &mission.spec;
    let mut data = vec![DataFile {
        role: "mission".to_owned(),
        path: mission.path.file_name().map_or_else(
            || mission.path.display().to_string(),
            |name| name.to_string_lossy().into_owned(),
        ),
        sha256: hex(format!("{spec:?}").as_bytes()),
    }];
    for (key, path) in spec.data_files() {
        let resolved = mission.dir.join(&path);
        let bytes = karman_math::read_data_file(&resolved).map_err(|e| {
            mission.model_error(&key, format!("cannot read {}: {e}", resolved.display()))
        })?;
        data.push(DataFile {
            role: key,
            path: path.display().to_string(),
            sha256: hex(&bytes),
        });
    }
    Ok(data)
}

/// Reads the curve files (drag, airfoil lift) of the rocket and of every lower stage (its own
/// and its stack's drag) into inline points, so that samples rebuilding the rocket do not
/// read them again (the same points, so the same tables).
fn inline_rocket_curves(mission: &mut Mission) -> Result<(), MissionError> {
    let dir = mission.dir.clone();
    let path = mission.path.clone();
    let spec = &mut mission.spec;
    let rocket = &mut spec.rocket;
    if let Some(ab) = rocket.air_brakes.as_mut()
        && matches!(ab.drag_coefficient_curve, AirBrakesCurve::File(_))
    {
        let rows = match ab.drag_coefficient_curve.to_drag(&dir) {
            Ok(AirBrakesDrag::Table(rows)) => rows,
            Ok(AirBrakesDrag::Constant(cd)) => vec![[0.0, 0.0, cd]],
            Err(source) => {
                return Err(MissionError::Curve {
                    file: path.clone(),
                    key: paths::AIR_BRAKES_CURVE.into(),
                    source,
                });
            }
        };
        ab.drag_coefficient_curve = AirBrakesCurve::Rows(rows);
    }
    let mut curves: Vec<(String, &mut Curve)> = vec![
        ("rocket.power_off_drag".into(), &mut rocket.power_off_drag),
        ("rocket.power_on_drag".into(), &mut rocket.power_on_drag),
    ];
    for (name, surface) in &mut rocket.surfaces {
        if let Some(airfoil) = surface.airfoil_mut() {
            curves.push((format!("rocket.surfaces.{name}.airfoil"), &mut airfoil.lift));
        }
    }
    for (index, stage) in spec.stages.iter_mut().enumerate() {
        let at = |key: &str| format!("stages.{index}.{key}");
        curves.push((at("stack_power_off_drag"), &mut stage.stack_power_off_drag));
        curves.push((at("stack_power_on_drag"), &mut stage.stack_power_on_drag));
        let own = &mut stage.rocket;
        curves.push((at("rocket.power_off_drag"), &mut own.power_off_drag));
        curves.push((at("rocket.power_on_drag"), &mut own.power_on_drag));
        for (name, surface) in &mut own.surfaces {
            if let Some(airfoil) = surface.airfoil_mut() {
                let key = at(&format!("rocket.surfaces.{name}.airfoil"));
                curves.push((key, &mut airfoil.lift));
            }
        }
    }
    for (key, curve) in curves {
        if matches!(curve, Curve::File(_)) && !curve.is_estimate() {
            let points = curve.points(&dir).map_err(|source| MissionError::Curve {
                file: path.clone(),
                key,
                source,
            })?;
            *curve = Curve::Points(points);
        }
    }
    Ok(())
}

/// An error and its sources, `: `-separated.
fn chain(error: &dyn std::error::Error) -> String {
    let mut text = error.to_string();
    let mut source = error.source();
    while let Some(e) = source {
        text.push_str(": ");
        text.push_str(&e.to_string());
        source = e.source();
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assemble::flight::simulate_with_seed;
    use karman_dynamics::AtmosphereModel;
    use karman_math::Cursor;
    use std::path::PathBuf;

    /// The test fixture `minimal.toml` in a custom atmosphere with a constant wind
    /// (5, −2) m/s, and a `[dispersion]` table.
    fn mission(vary: &str) -> Mission {
        let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures");
        let text = std::fs::read_to_string(dir.join("minimal.toml"))
            .expect("fixture")
            .replace(
                "model = \"standard\"",
                "model = \"custom\"\nwind_u = 5\nwind_v = -2",
            );
        let text =
            format!("{text}\n[dispersion]\nsamples = 10\nseed = 3\n\n[dispersion.vary]\n{vary}");
        crate::parse(&text, &dir.join("minimal.toml"), &[]).expect("valid mission")
    }

    #[test]
    fn neutral_draws_fly_the_nominal_mission() {
        let mission = mission(
            "\"rocket.mass\" = { offset = { normal = [0, 0.1] } }\n\
             \"rocket.power_on_drag\" = { factor = { normal = [1, 0.05] } }\n\
             \"rocket.power_off_drag\" = { factor = { normal = [1, 0.05] } }\n\
             \"flight.inclination\" = { std = 1 }\n\
             \"environment.wind_direction_offset\" = { normal = [0, 5] }\n\
             \"environment.wind_factor\" = { normal = [1, 0.1] }\n\
             \"rocket.parachutes.main.cd_s\" = { std = 0.1 }\n",
        );
        let mc = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
        let columns: Vec<String> = mc.study().inputs.iter().map(VariedInput::column).collect();
        assert_eq!(columns[1], "rocket.power_on_drag:factor");
        // Offsets 0, factors 1, values equal to the nominal ones: the nominal flight.
        let neutral = [0.0, 1.0, 1.0, 85.0, 0.0, 1.0, 1.2];
        let outcome = mc.fly(4, &neutral).expect("flight");
        let nominal = simulate_with_seed(&mission, flight_seed(3, 4)).expect("nominal flight");
        let expected = output_values(&nominal.summary());
        for (name, (a, b)) in OUTPUTS.iter().zip(outcome.values().iter().zip(&expected)) {
            assert_eq!(
                a.map(f64::to_bits),
                b.map(f64::to_bits),
                "{name}: {a:?} vs {b:?}"
            );
        }
        // A heavier rocket flies lower.
        let heavier = [0.5, 1.0, 1.0, 85.0, 0.0, 1.0, 1.2];
        let apogee = |o: &Outcome| o.values()[0].expect("apogee");
        assert!(apogee(&mc.fly(4, &heavier).expect("flight")) < apogee(&outcome));
    }

    #[test]
    fn a_draw_out_of_range_fails_its_sample_with_the_key_and_value() {
        let mission = mission(
            "\"flight.rtol\" = { std = 1e-7 }\n\
             \"rocket.parachutes.main.sampling_rate\" = { std = 1 }\n\
             \"rocket.parachutes.main.trigger\" = { std = 10 }\n",
        );
        let mc = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
        let nominal = [mission.spec.flight.rtol, 100.0, 200.0];
        assert!(mc.fly(0, &nominal).is_ok(), "in-range draws fly");
        // The audit's cases: a tolerance that lets the states turn to NaN, a sampling rate
        // that multiplies the instants without bound, a trigger below the ground.
        for (values, key, value) in [
            ([0.5, 100.0, 200.0], "flight.rtol", "0.5"),
            (
                [nominal[0], 1e10, 200.0],
                "rocket.parachutes.main.sampling_rate",
                "10000000000",
            ),
            (
                [nominal[0], 100.0, -5.0],
                "rocket.parachutes.main.trigger",
                "-5",
            ),
        ] {
            let message = mc.fly(0, &values).expect_err("out of range");
            assert!(
                message.starts_with("a drawn value is out of range: ")
                    && message.contains(&format!("{key}: {value} is out of range")),
                "{message}"
            );
        }
        let message = mc.fly(0, &[0.5, 1e10, -5.0]).expect_err("out of range");
        assert_eq!(
            message.matches("is out of range: must").count(),
            3,
            "{message}"
        );
    }

    #[test]
    fn shared_models_fly_as_rebuilt_ones() {
        // Inputs that reach nothing but the flight settings, only the rocket, or the motor:
        // the shared environment / motor / rocket must give the flight a fresh build gives.
        for (vary, neutral, reach) in [
            (
                "\"flight.heading\" = { std = 2 }\n",
                10.0,
                [false, false, false],
            ),
            (
                "\"rocket.mass\" = { std = 0.1 }\n",
                3.0,
                [false, false, true],
            ),
            (
                "\"motor.dry_mass\" = { std = 0.01 }\n",
                0.5,
                [false, true, true],
            ),
        ] {
            let mission = mission(vary);
            let mc = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
            let r = mc.reach;
            assert_eq!([r.environment, r.motor, r.rocket], reach, "{vary}");
            let outcome = mc.fly(2, &[neutral]).expect("flight");
            let nominal = simulate_with_seed(&mission, flight_seed(3, 2)).expect("nominal");
            let expected = output_values(&nominal.summary());
            let bits =
                |v: &[Option<f64>]| v.iter().map(|x| x.map(f64::to_bits)).collect::<Vec<_>>();
            assert_eq!(bits(outcome.values()), bits(&expected), "{vary}");
        }
    }

    #[test]
    fn wind_is_scaled_and_turned_clockwise() {
        let mission = mission("");
        let environment = build_environment(&mission).expect("environment");
        let adjusted = WindAdjusted::new(&environment, 2.0, 90.0);
        // (5, −2) blows toward east-south-east; turned 90° clockwise it blows toward
        // south-south-west, (−2, −5), doubled.
        let [u, v] = adjusted.wind(1500.0);
        assert!(
            (u + 4.0).abs() < 1e-12 && (v + 10.0).abs() < 1e-12,
            "({u}, {v})"
        );
        if let Some(uniform) = adjusted.uniform_wind() {
            assert_eq!(uniform.map(f64::to_bits), [u, v].map(f64::to_bits));
        }
        // The thermodynamics pass through untouched, with or without cursors.
        let mut cursor = Cursor::default();
        for z in [1500.0, 3000.0, 1400.0] {
            let (a, b) = (adjusted.air_near(z, &mut cursor), environment.air(z));
            assert_eq!(
                [a.pressure, a.density, a.speed_of_sound, a.gravity].map(f64::to_bits),
                [b.pressure, b.density, b.speed_of_sound, b.gravity].map(f64::to_bits)
            );
        }
        let same = WindAdjusted::new(&environment, 1.0, 0.0).wind(1500.0);
        assert_eq!(
            same.map(f64::to_bits),
            environment.wind(1500.0).map(f64::to_bits)
        );
    }

    #[test]
    fn knobs_reshape_the_thrust_curve() {
        let mission = mission(
            "\"motor.total_impulse\" = { factor = { normal = [1, 0.05] } }\n\
             \"motor.burn_time\" = { std = 0.1 }\n",
        );
        let mc = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
        let [burn, impulse] = mc.nominal_reshape;
        assert!(
            (burn - 2.2).abs() < 1e-12,
            "burn-out of the fixture's curve: {burn}"
        );
        let (spec, _, _) = mc.sample_spec(&[1.1, 2.5]).expect("applied");
        let reshaped = spec.motor.reshape_thrust_curve.expect("reshaped");
        assert!((reshaped[0] - 2.5).abs() < 1e-12);
        assert!((reshaped[1] - 1.1 * impulse).abs() < 1e-9);
        let outcome = mc.fly(0, &[1.1, 2.5]).expect("flight");
        assert!(outcome.values()[0].is_some());
    }

    #[test]
    fn arrays_vary_by_component_and_as_a_whole() {
        // The fixture's inertia is [0.5, 0.5, 0.002] (six components, products zero).
        let mission = mission(
            "\"rocket.inertia\" = { factor = { normal = [1, 0.1] } }\n\
             \"rocket.inertia.0\" = { std = 0.05 }\n\
             \"motor.dry_inertia\" = { offset = { uniform = [0, 0.001] } }\n",
        );
        let mc = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
        let columns: Vec<String> = mc.study().inputs.iter().map(VariedInput::column).collect();
        assert_eq!(
            columns,
            [
                "rocket.inertia:factor",
                "rocket.inertia.0",
                "motor.dry_inertia:offset"
            ]
        );
        assert_eq!(
            mc.study().inputs[0].target,
            Target::Array(vec![0.5, 0.5, 0.002, 0.0, 0.0, 0.0])
        );
        // In file order: the factor scales every component, then component 0 is set.
        let (spec, _, _) = mc.sample_spec(&[2.0, 0.7, 0.001]).expect("applied");
        let bits = |v: [f64; 6]| v.map(f64::to_bits);
        assert_eq!(
            bits(spec.rocket.inertia.0),
            bits([0.7, 1.0, 0.004, 0.0, 0.0, 0.0])
        );
        assert_eq!(
            bits(spec.motor.dry_inertia.0),
            bits([0.011, 0.011, 0.002, 0.001, 0.001, 0.001])
        );
        // A whole array takes only a factor or an offset (checked when the mission is read).
        let mut bad = mission.spec.clone();
        let entry = Distribution::Std(0.1);
        let input = paths::resolve(&bad, "rocket.inertia").expect("an array");
        let error = paths::check_distribution(&input, &entry).expect_err("misfit");
        assert!(error.starts_with("an array only takes"), "{error}");
        bad.dispersion.as_mut().expect("table").vary = [("rocket.inertia".into(), entry)].into();
        let bad = Mission {
            spec: bad,
            ..mission.clone()
        };
        assert!(MonteCarlo::new(&bad, StudyOverrides::default()).is_err());
        // Neutral draws fly the nominal mission.
        let outcome = mc.fly(1, &[1.0, 0.5, 0.0]).expect("flight");
        let nominal = simulate_with_seed(&mission, flight_seed(3, 1)).expect("nominal");
        let bits = |v: &[Option<f64>]| v.iter().map(|x| x.map(f64::to_bits)).collect::<Vec<_>>();
        assert_eq!(
            bits(outcome.values()),
            bits(&output_values(&nominal.summary()))
        );
    }

    #[test]
    fn a_sample_too_weak_to_leave_the_rail_is_stuck_on_it() {
        // 5 N·s in 0.05 s: at burn-out the rocket has slid about 2 cm of the 2 m rail at under
        // 1 m/s; it ends there, not by creeping off the rail at that speed seconds later.
        let mission = mission(
            "\"motor.total_impulse\" = { choice = [5.0] }\n\
             \"motor.burn_time\" = { choice = [0.05] }\n",
        );
        let mc = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
        let outcome = mc.fly(0, &[5.0, 0.05]).expect("flight");
        match outcome.status() {
            karman_dispersion::Status::Ended { kind, message } => {
                assert_eq!(kind, "stuck_on_rail");
                assert!(message.contains("too slow to coast"), "{message}");
            }
            other => panic!("expected stuck_on_rail, got {other:?}"),
        }
        let out_of_rail = OUTPUTS.iter().position(|o| *o == "out_of_rail_time_s");
        assert_eq!(outcome.values()[out_of_rail.expect("output")], None);
        // The nominal motor leaves the rail.
        let [burn, impulse] = mc.nominal_reshape;
        let nominal = mc.fly(0, &[impulse, burn]).expect("flight");
        assert_eq!(nominal.status(), &karman_dispersion::Status::Completed);
    }

    /// The two-stage fixture in a custom atmosphere with a constant wind (5, −2) m/s, with
    /// `vary` as its `[dispersion.vary]` table.
    fn two_stage(vary: &str) -> Mission {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/two_stage.toml");
        let text = std::fs::read_to_string(&path).expect("fixture").replace(
            "model = \"standard\"",
            "model = \"custom\"\nwind_u = 5\nwind_v = -2",
        );
        let end = text
            .find("[dispersion.vary]")
            .expect("the fixture has a study");
        let text = format!("{}[dispersion.vary]\n{vary}", &text[..end]);
        crate::parse(&text, &path, &[]).expect("valid mission")
    }

    #[test]
    fn a_staged_study_reads_its_data_files_once() {
        // The two-stage fixture in a folder of its own, the stack's drag from a file too: once
        // the study is built its data files go, and a sample flies the same bits without them.
        let fixtures = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures");
        let dir = std::env::temp_dir().join(format!("karman-staged-once-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("folder");
        let files = [
            "example_K1960.eng",
            "power_off_drag.csv",
            "power_on_drag.csv",
        ];
        for file in files {
            std::fs::copy(fixtures.join(file), dir.join(file)).expect("copy");
        }
        let text = std::fs::read_to_string(fixtures.join("two_stage.toml")).expect("fixture");
        let stack = text
            .lines()
            .find(|l| l.starts_with("stack_power_off_drag = "))
            .expect("the stack's drag");
        let text = text.replace(stack, "stack_power_off_drag = \"power_off_drag.csv\"");
        let end = text.find("[dispersion.vary]").expect("a study");
        let text = format!(
            "{}[dispersion.vary]\n\"stages.0.rocket.mass\" = {{ std = 0.05 }}\n\
             \"stages.0.motor.total_impulse\" = {{ factor = {{ normal = [1, 0.03] }} }}\n",
            &text[..end]
        );
        let mission = crate::parse(&text, &dir.join("two_stage.toml"), &[]).expect("mission");
        let mc = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
        let values = [1.13, 1.02];
        let with_files = mc.fly(2, &values).expect("flight");
        for file in files {
            std::fs::remove_file(dir.join(file)).expect("remove");
        }
        let without = mc.fly(2, &values).expect("flight without the files");
        std::fs::remove_dir_all(&dir).expect("clean up");
        assert_eq!(without.status(), &karman_dispersion::Status::Completed);
        let bits = |o: &Outcome| {
            o.values()
                .iter()
                .map(|x| x.map(f64::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&without), bits(&with_files));
    }

    #[test]
    fn neutral_draws_fly_the_nominal_stack_and_each_body_has_its_columns() {
        let mission = two_stage(
            "\"stages.0.rocket.mass\" = { std = 0.05 }\n\
             \"stages.0.separation\" = { uniform = [0.3, 0.8] }\n\
             \"stages.0.stack_power_off_drag\" = { factor = { normal = [1, 0.05] } }\n\
             \"environment.wind_factor\" = { normal = [1, 0.1] }\n",
        );
        let mc = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
        let outputs = &mc.study().outputs;
        assert_eq!(outputs.len(), OUTPUTS.len() + 1 + BODY_OUTPUTS.len());
        assert_eq!(outputs[OUTPUTS.len()], "booster.separation_time_s");
        assert_eq!(outputs[OUTPUTS.len() + 1], "booster.apogee_agl_m");
        let points = &mc.study().points;
        assert_eq!(points.body.as_deref(), Some("sustainer"));
        assert_eq!(points.bodies[0].name, "booster");
        let neutral = [1.1, 0.5, 1.0, 1.0];
        let outcome = mc.fly(3, &neutral).expect("flight");
        assert_eq!(outcome.status(), &karman_dispersion::Status::Completed);
        let run = stages::simulate_staged(&mission, flight_seed(11, 3)).expect("nominal");
        let mut expected = output_values(&run.summary(0));
        expected.push(Some(run.separations[0].time_s));
        let booster = output_values(&run.summary(1));
        for output in BODY_OUTPUTS {
            let at = OUTPUTS.iter().position(|o| *o == output).expect("output");
            expected.push(booster[at]);
        }
        let bits = |v: &[Option<f64>]| v.iter().map(|x| x.map(f64::to_bits)).collect::<Vec<_>>();
        assert_eq!(bits(outcome.values()), bits(&expected));
        // A later separation, a heavier booster: the booster separates later and lands
        // elsewhere; three times the wind carries both bodies farther.
        let value = |o: &Outcome, name: &str| {
            let at = outputs.iter().position(|n| n == name).expect("column");
            o.values()[at].expect("value")
        };
        let later = mc.fly(3, &[1.1, 0.8, 1.0, 1.0]).expect("flight");
        let shift = value(&later, "booster.separation_time_s")
            - value(&outcome, "booster.separation_time_s");
        assert!((shift - 0.3).abs() < 0.02, "{shift}");
        let windy = mc.fly(3, &[1.1, 0.5, 1.0, 3.0]).expect("flight");
        for body in ["", "booster."] {
            let distance = |o: &Outcome| {
                value(o, &format!("{body}impact_x_m")).hypot(value(o, &format!("{body}impact_y_m")))
            };
            assert!(distance(&windy) > distance(&outcome) + 100.0, "{body}");
        }
    }

    #[test]
    fn an_estimated_drag_of_a_stack_is_not_scaled() {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/two_stage.toml");
        let text = std::fs::read_to_string(&path).expect("fixture");
        let end = text
            .find("[dispersion.vary]")
            .expect("the fixture has a study");
        let lines: Vec<&str> = text[..end]
            .lines()
            .map(|line| {
                if line.starts_with("stack_power_on_drag") {
                    "stack_power_on_drag = \"estimate\""
                } else {
                    line
                }
            })
            .collect();
        let text = format!(
            "{}\n[dispersion.vary]\n\"stages.0.stack_power_on_drag\" = {{ factor = {{ std = 0.05 }} }}\n",
            lines.join("\n")
        );
        let error = crate::parse(&text, &path, &[]).expect_err("refused");
        let text = error.to_string();
        assert!(text.contains("stages.0.stack_power_on_drag"), "{text}");
        assert!(text.contains("multi-stage"), "{text}");
    }

    #[test]
    fn a_stage_motor_knob_reshapes_that_motor_only() {
        let mission =
            two_stage("\"stages.0.motor.total_impulse\" = { factor = { normal = [1, 0.03] } }\n");
        let mc = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
        let [burn, impulse] = mc.stage_reshapes[0].expect("the booster's motor");
        assert_eq!(mc.study().inputs[0].target, Target::Number(impulse));
        let (spec, _, _) = mc.sample_spec(&[1.1]).expect("applied");
        let reshaped = spec.stages[0]
            .motor
            .as_ref()
            .and_then(|m| m.reshape_thrust_curve)
            .expect("reshaped");
        assert_eq!(reshaped[0].to_bits(), burn.to_bits());
        assert!((reshaped[1] - 1.1 * impulse).abs() < 1e-9 * impulse);
        assert_eq!(spec.motor.reshape_thrust_curve, None);
        // More impulse in the booster: a higher booster apogee.
        let apogee = |factor: f64| {
            let o = mc.fly(0, &[factor]).expect("flight");
            let at = mc
                .study()
                .outputs
                .iter()
                .position(|n| n == "booster.apogee_agl_m");
            o.values()[at.expect("column")].expect("apogee")
        };
        assert!(apogee(1.1) > apogee(0.9));
    }

    #[test]
    fn overrides_and_missing_table() {
        let mission = mission("\"rocket.mass\" = { std = 0.1 }\n");
        let overrides = StudyOverrides {
            samples: Some(77),
            seed: Some(9),
        };
        let mc = MonteCarlo::new(&mission, overrides).expect("study");
        assert_eq!((mc.study().samples, mc.study().seed), (77, 9));
        let mut bare = mission.clone();
        bare.spec.dispersion = None;
        assert!(MonteCarlo::new(&bare, StudyOverrides::default()).is_err());
        let mc = MonteCarlo::new(&bare, overrides).expect("noise-only study");
        assert!(mc.study().inputs.is_empty());
    }
}
