//! Multi-stage rockets (mission-format.md, "Stages"): the flight as a tree of bodies.
//!
//! `[rocket]` with `[motor]` is the top stage; `[[stages]]` lists the stages below it, the last one
//! at the bottom. The stack with `k` lower stages flies as one rigid vehicle: the motor of its
//! bottom stage (the only one that can burn: every stage above ignites after the separation below
//! it) and, as the airframe "without motor", the bottom stage's airframe lumped with the whole
//! stack above it at rest, its motors unburnt (masses summed, centres of mass weighted, inertias
//! moved to the common centre of mass with the parallel-axis theorem, docs/physics.md §5.3, §5.5,
//! §23.1), the surfaces of every member, the stack's own drag curves and the largest radius of the
//! stack as reference (OpenRocket's reference diameter).
//!
//! When the bottom stage's separation trigger fires (a sampled process of the engine, as a
//! parachute trigger without noise), the stack's flight ends ([`Action::SeparateStage`]) and two
//! bodies fly on from the separation state with [`karman_dynamics::simulate_from`]: the stack
//! above, whose motor ignites `ignition_delay` s later (its time tables moved there,
//! [`super::motor::delayed`]), and the spent stage with its own airframe, motor, drag and
//! parachutes, to its own impact; one without parachutes tumbles past its apogee, or once it turns
//! over when it is unstable (`TumbleTrigger`), a point mass under Niskanen's tumble drag
//! (OpenRocket technical documentation §3.5, `tumble_drag_area`; docs/physics.md §23.4). Each
//! starts at its own centre of dry mass: the state's position is moved along the rocket axis from
//! the stack's, its velocity by `ω × r` of that offset (a rigid body). A separation at launch
//! (`"launch + 0"`) happens on the pad: the stack above launches from the rail, and the stage stays
//! there (it is not flown).

use std::sync::Arc;

use karman_airframe::{RigidMass, Rocket};
use karman_atmos::Environment;
use karman_dynamics::flight::{Action, Probe, SampledProcess, StepBounds};
use karman_dynamics::state::{State, rotation};
use karman_dynamics::{
    AtmosphereModel, Configuration, EventRecord, Flight, FlightSettings, Sample, Summary,
    Termination,
};
use karman_model::TriggerCondition;
use karman_propulsion::Motor;
use karman_script::Expression;

use super::environment::{WindAdjusted, build_environment_checked};
use super::motors::ThrustCache;
use super::preflight::{MAX_KNOT_STOPS, checked_models, flight_settings, prepare};
use super::rocket::build_rocket_ignited_at;
use super::scripts::{AfterTime, ExpressionTrigger};
use super::stage_view::{TOP_STAGE, in_stage, stage_mission, stage_name};
use crate::report::trajectory::{RailArms, Track};
use crate::schema::{DragEstimateSpec, Inertia, RocketSpec, Trigger};
use crate::{Mission, MissionError};

/// One integrated flight of a vehicle of the tree: a stack until a separation, or a body to
/// its end.
#[derive(Debug, Clone)]
pub struct Segment {
    /// The bodies that fly together in it, top first (`"sustainer + booster"`).
    pub vehicle: String,
    /// The stage whose motor the vehicle flies (its bottom stage).
    pub motor_stage: String,
    /// The vehicle's model, as flown.
    pub rocket: Rocket,
    /// The flight.
    pub flight: Flight,
}

/// One body of a staged flight and the segments of its path, from the pad to its end.
#[derive(Debug, Clone)]
pub struct Body {
    /// The stage's name (the top stage is `sustainer`).
    pub name: String,
    /// Indices into [`StagedRun::segments`], in time order.
    pub segments: Vec<usize>,
}

/// A stage separation of the flight.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SeparationRecord {
    /// The stage that dropped off.
    pub stage: String,
    /// Time, s.
    pub time_s: f64,
}

/// A flown multi-stage mission.
#[derive(Debug, Clone)]
pub struct StagedRun {
    /// The launch environment.
    pub environment: Environment,
    /// The flight settings of the launch stack.
    pub settings: FlightSettings,
    /// Every integrated flight, in the order flown.
    pub segments: Vec<Segment>,
    /// The bodies: the top stage first, then the lower stages in the order they separated.
    pub bodies: Vec<Body>,
    /// The separations, in time order.
    pub separations: Vec<SeparationRecord>,
    /// The warnings of the launch checks and of every model, each naming its key.
    pub warnings: Vec<String>,
    /// The wind the flight saw: the environment's, multiplied by `wind[0]` and turned by
    /// `wind[1]` degrees ([`WindAdjusted`]; `[1, 0]` but in a Monte Carlo sample).
    wind: [f64; 2],
}

/// The wind of a flight that is the environment's.
const OWN_WIND: [f64; 2] = [1.0, 0.0];

/// The parts of a [`StagedRun`] its flights make.
struct Tree {
    settings: FlightSettings,
    segments: Vec<Segment>,
    bodies: Vec<Body>,
    separations: Vec<SeparationRecord>,
    warnings: Vec<String>,
}

/// The own motor of lower stage `index` (which has one), as it flies after separation, from
/// the stage's own mission `alone` ([`stage_mission`]).
///
/// # Errors
/// The motor builder's errors, named by the stage's keys.
pub(crate) fn stage_motor(
    alone: &Mission,
    thrusts: &ThrustCache,
    index: usize,
) -> Result<Motor, MissionError> {
    thrusts.motor(alone).map_err(|e| in_stage(e, index))
}

/// The top stage alone as a mission (without `[[stages]]`).
fn top_mission(mission: &Mission) -> Mission {
    let mut top = mission.clone();
    top.spec.stages.clear();
    top
}

/// A vehicle at rest before its motor ignites, as one rigid part (rocket coordinates): its
/// dry mass and unburnt propellant, the inertia (the airframe's about the centre of dry mass)
/// moved to the centre of mass.
fn unburnt(rocket: &Rocket) -> RigidMass {
    let t = rocket.burn_start();
    RigidMass::with_inertia_about(
        rocket.total_mass(t),
        rocket.center_of_mass(t),
        rocket.inertia(t),
        rocket.center_of_dry_mass(),
    )
}

/// The airframe of the stack whose bottom is lower stage `bottom`, with `above` (the stack
/// over it, at rest) lumped into its mass.
fn stack_rocket_spec(mission: &Mission, bottom: usize, above: RigidMass) -> RocketSpec {
    let spec = &mission.spec;
    let stage = &spec.stages[bottom];
    let own = &stage.rocket;
    let members: Vec<&RocketSpec> = std::iter::once(&spec.rocket)
        .chain(spec.stages[..=bottom].iter().map(|s| &s.rocket))
        .collect();
    let lump = above.combined(RigidMass {
        mass: own.mass,
        center: own.center_of_mass_without_motor,
        inertia: own.inertia.0,
    });
    let mut surfaces = indexmap::IndexMap::new();
    for member in &members {
        surfaces.extend(member.surfaces.clone());
    }
    // The drag estimate of the stack: every member's fins, lugs and overrides; the bottom
    // stage's body length, finish and button sizes, else the top stage's.
    let mut estimate: Option<DragEstimateSpec> = None;
    for member in members.iter().rev() {
        let Some(d) = &member.drag_estimate else {
            continue;
        };
        match &mut estimate {
            None => estimate = Some(d.clone()),
            Some(e) => {
                e.fins.extend(d.fins.clone());
                e.launch_lugs.extend(d.launch_lugs.clone());
                e.overrides.extend(d.overrides.clone());
                if e.rail_buttons.is_none() {
                    e.rail_buttons.clone_from(&d.rail_buttons);
                }
            }
        }
    }
    RocketSpec {
        radius: members.iter().map(|m| m.radius).fold(0.0, f64::max),
        mass: lump.mass,
        inertia: Inertia(lump.inertia),
        center_of_mass_without_motor: lump.center,
        coordinate_system: spec.rocket.coordinate_system,
        power_off_drag: stage.stack_power_off_drag.clone(),
        power_on_drag: stage.stack_power_on_drag.clone(),
        drag_estimate: estimate,
        interpolation: own.interpolation,
        extrapolation: own.extrapolation,
        motor_position: own.motor_position,
        rail_buttons: members.iter().rev().find_map(|m| m.rail_buttons.clone()),
        surfaces,
        parachutes: indexmap::IndexMap::new(),
        pods: members.iter().flat_map(|m| m.pods.clone()).collect(),
        air_brakes: None,
        sensors: Vec::new(),
        // Checks refuse eccentricities on a rocket with stages.
        cm_eccentricity: None,
        cp_eccentricity: None,
        thrust_eccentricity: None,
    }
}

/// The mission of the stack with `count` lower stages (`count ≥ 1`): its bottom stage's motor
/// and the stack's airframe ([`stack_rocket_spec`]).
fn stack_mission(mission: &Mission, count: usize, above: RigidMass) -> Mission {
    let bottom = count - 1;
    let mut stack = stage_mission(mission, bottom);
    stack.spec.rocket = stack_rocket_spec(mission, bottom, above);
    stack
}

/// The vehicle of the stack with `count` lower stages, its motor ignited at `ignition`.
fn build_stack(
    mission: &Mission,
    thrusts: &ThrustCache,
    count: usize,
    ignition: f64,
) -> Result<(Mission, Rocket), MissionError> {
    if count == 0 {
        let top = top_mission(mission);
        let motor = thrusts.motor(&top)?;
        let rocket = build_rocket_ignited_at(&top, &motor, ignition, thrusts)?;
        return Ok((top, rocket));
    }
    let (_, above) = build_stack(mission, thrusts, count - 1, 0.0)?;
    let stack = stack_mission(mission, count, unburnt(&above));
    let motor = thrusts.motor(&stack).map_err(|e| in_stage(e, count - 1))?;
    let rocket = build_rocket_ignited_at(&stack, &motor, ignition, thrusts)
        .map_err(|e| in_stage(e, count - 1))?;
    Ok((stack, rocket))
}

/// What fires a separation.
enum Condition {
    Apogee,
    Height(f64),
    Custom(Arc<dyn TriggerCondition>),
}

/// The separation trigger of a stage as a sampled process of the stack's flight: the
/// parachute triggers' conditions on the noise-free pressure.
struct SeparationTrigger<'a, A> {
    atmosphere: &'a A,
    elevation: f64,
    rate: f64,
    condition: Condition,
    stage: usize,
    fired: bool,
}

impl<A: AtmosphereModel> SampledProcess for SeparationTrigger<'_, A> {
    fn rate(&self) -> f64 {
        self.rate
    }
    fn whole_step(&self) -> bool {
        matches!(self.condition, Condition::Custom(_))
    }
    fn sample(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        let atm = self.atmosphere;
        let fires = match &self.condition {
            Condition::Apogee => probe.vz() < 0.0,
            Condition::Height(h) => {
                probe.vz() < 0.0
                    && atm.barometric_height(atm.pressure(probe.z())) - self.elevation < *h
            }
            Condition::Custom(condition) => {
                let pressure = atm.pressure(probe.z());
                let height = atm.barometric_height(pressure) - self.elevation;
                condition.fires(probe.t(), pressure, height, &probe.state())
            }
        };
        self.fired |= fires;
        fires.then_some(Action::SeparateStage(self.stage))
    }
    fn is_done(&self) -> bool {
        self.fired
    }
}

/// The tumbling descent of a spent stage without parachutes: from the first instant of the
/// stage's `sampling_rate` past its apogee (`v_z < 0`), or, for a stage that is statically
/// unstable when it separates (negative static margin), at more than
/// [`TUMBLE_ANGLE_OF_ATTACK`] (OpenRocket's condition), it falls as a point mass under its
/// tumble drag area ([`Action::Tumble`]).
struct TumbleTrigger<'a, A> {
    atmosphere: &'a A,
    rate: f64,
    drag_area: f64,
    unstable: bool,
    fired: bool,
}

/// The angle of attack past which a statically unstable stage tumbles: OpenRocket's 20°.
const TUMBLE_ANGLE_OF_ATTACK: f64 = 20.0 * std::f64::consts::PI / 180.0;

impl<A: AtmosphereModel> SampledProcess for TumbleTrigger<'_, A> {
    fn rate(&self) -> f64 {
        self.rate
    }
    fn whole_step(&self) -> bool {
        self.unstable
    }
    fn cannot_act(&self, bounds: &StepBounds) -> bool {
        self.fired || (!self.unstable && bounds.vz[0] > 0.0)
    }
    fn sample(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        self.fired = probe.vz() < 0.0
            || (self.unstable && {
                let u = probe.state();
                let wind = self.atmosphere.wind(u[2]);
                // The air speed and the rocket axis (third column of the attitude matrix).
                let air = [u[3] - wind[0], u[4] - wind[1], u[5]];
                let k = rotation([u[6], u[7], u[8], u[9]]);
                let along = k[0][2] * air[0] + k[1][2] * air[1] + k[2][2] * air[2];
                let speed = (air[0] * air[0] + air[1] * air[1] + air[2] * air[2]).sqrt();
                along < speed * TUMBLE_ANGLE_OF_ATTACK.cos()
            });
        self.fired.then_some(Action::Tumble {
            drag_area: self.drag_area,
        })
    }
    fn is_done(&self) -> bool {
        self.fired
    }
}

/// Drag coefficients of a tumbling stage on the profile areas of its fins and of its body,
/// fitted by Niskanen to drop tests of lower stages (OpenRocket technical documentation,
/// §3.5, eq. 3.98–3.99).
const TUMBLE_FIN_CD: f64 = 1.42;
/// See [`TUMBLE_FIN_CD`]: half the broadside drag coefficient of a circular cylinder.
const TUMBLE_BODY_CD: f64 = 0.56;
/// The effective profile area of a set of `N = 1, …, 8` fins, in units of one fin's
/// planform area (Niskanen, Table 3.4); more fins take the factor of eight.
const TUMBLE_FIN_EFFICIENCY: [f64; 8] = [0.50, 1.00, 1.50, 1.41, 1.81, 1.73, 1.90, 1.85];

/// The drag area `C_D·A` (m², docs/physics.md §23.4) of lower stage `index` tumbling to the ground:
/// its `tumble_drag_area`, or Niskanen's estimate `1.42 Σ η(N) A_fin + 0.56 L d` over the planar
/// fin sets of the stage (`A_fin` one fin's planform area, `η` the efficiency factor of its `N`
/// fins) and its body tube of diameter `d` and length `L`, from its fore end (the stage above's
/// `drag_estimate.body_length`) to its aft end (its own).
///
/// # Errors
/// A located error when the estimate lacks a body length, or gives no positive area.
fn tumble_drag_area(mission: &Mission, index: usize, spent: &Rocket) -> Result<f64, MissionError> {
    let spec = &mission.spec;
    let stage = &spec.stages[index];
    if let Some(area) = stage.tumble_drag_area {
        return Ok(area);
    }
    let above = if index == 0 {
        &spec.rocket
    } else {
        &spec.stages[index - 1].rocket
    };
    let length = |r: &RocketSpec| r.drag_estimate.as_ref().and_then(|d| d.body_length);
    let missing = |reason: &str| {
        mission.model_error(
            &format!("stages.{index}"),
            format!(
                "the stage has no parachutes, so it tumbles to the ground: {reason}; give its \
                 drag area as `tumble_drag_area` (m²)"
            ),
        )
    };
    let (Some(fore), Some(aft)) = (length(above), length(&stage.rocket)) else {
        return Err(missing(
            "its length for the tumble drag estimate is the difference of the \
             `drag_estimate.body_length` of the stage above and its own, and one is missing",
        ));
    };
    let fins: f64 = spent
        .surfaces()
        .iter()
        .filter_map(|s| s.fin_aerodynamics())
        .map(|f| {
            let n = (f.n as usize).clamp(1, TUMBLE_FIN_EFFICIENCY.len());
            TUMBLE_FIN_EFFICIENCY[n - 1] * f.fin_area
        })
        .sum();
    let body = (aft - fore).max(0.0) * 2.0 * stage.rocket.radius;
    let area = TUMBLE_FIN_CD * fins + TUMBLE_BODY_CD * body;
    if area > 0.0 {
        Ok(area)
    } else {
        Err(missing(
            "it has neither fins nor a body length to estimate it from",
        ))
    }
}

/// The separation condition of lower stage `index`, whose motor burns out at `burn_out`.
fn condition(mission: &Mission, index: usize, burn_out: f64) -> Result<Condition, MissionError> {
    Ok(match &mission.spec.stages[index].separation {
        Trigger::Apogee => Condition::Apogee,
        Trigger::HeightAboveGround(h) => Condition::Height(*h),
        Trigger::Launch(delay) => Condition::Custom(Arc::new(AfterTime(*delay))),
        Trigger::Burnout(delay) => Condition::Custom(Arc::new(AfterTime(burn_out + delay))),
        Trigger::Expression(text) => {
            let expression = Expression::parse(text).map_err(|e| {
                mission.model_error(&format!("stages.{index}.separation.expression"), e)
            })?;
            Condition::Custom(Arc::new(ExpressionTrigger::new(expression, &[])))
        }
    })
}

/// `state` of a rigid body moved from its point at rocket coordinate `from` to the one at
/// `to` (`csys` the rocket's coordinate sign): position along the rocket axis, velocity by
/// `ω × r` (docs/physics.md §23.3).
fn moved(state: &State, from: f64, to: f64, csys: f64) -> State {
    let along = csys * (to - from);
    if along == 0.0 {
        return *state;
    }
    let k = rotation([state[6], state[7], state[8], state[9]]);
    // The offset (0, 0, along) in body axes and ω × offset there.
    let (w1, w2) = (state[10], state[11]);
    let spin = [w2 * along, -w1 * along, 0.0];
    let mut out = *state;
    for i in 0..3 {
        out[i] += k[i][2] * along;
        out[3 + i] += k[i][0] * spin[0] + k[i][1] * spin[1];
    }
    out
}

/// The settings of one vehicle: the mission's, without knot stops for a dense thrust curve.
fn vehicle_settings(mission: &Mission, rocket: &Rocket, seed: u64) -> FlightSettings {
    let mut settings = flight_settings(mission, seed);
    if rocket.motor().thrust.xs().len() > MAX_KNOT_STOPS {
        settings.stop_at_thrust_knots = false;
    }
    settings
}

/// Builds every vehicle of a multi-stage mission and checks the launch stack's launch, as
/// [`simulate_staged`] does before it integrates (motors ignited at their separation, here
/// taken at `t = 0`, build the same models up to that shift); returns the warnings.
///
/// # Errors
/// As [`simulate_staged`], without the flight's.
pub fn prepare_staged(mission: &Mission, seed: u64) -> Result<Vec<String>, MissionError> {
    let stages = &mission.spec.stages;
    let thrusts = ThrustCache::read(mission)?;
    let mut warnings = Vec::new();
    let pad = stages
        .iter()
        .rev()
        .take_while(|s| matches!(s.separation, Trigger::Launch(d) if d <= 0.0))
        .count();
    for count in (0..=stages.len() - pad).rev() {
        let (vehicle, rocket) = build_stack(mission, &thrusts, count, 0.0)?;
        if count == stages.len() - pad {
            let models = prepare(&vehicle, seed).map_err(|e| match count {
                0 => e,
                n => in_stage(e, n - 1),
            })?;
            warnings.extend(models.warnings);
        } else {
            warnings.extend(rocket.warnings().iter().map(|w| match count {
                0 => format!("`rocket`: {w}"),
                n => format!("`stages.{}`: {w}", n - 1),
            }));
        }
        if count > 0 {
            condition(mission, count - 1, rocket.burn_out())?;
            let stage = &stages[count - 1];
            if stage.rocket.mass > 0.0 && stage.motor.is_some() {
                let alone = stage_mission(mission, count - 1);
                let motor = stage_motor(&alone, &thrusts, count - 1)?;
                let spent = build_rocket_ignited_at(&alone, &motor, 0.0, &thrusts)
                    .map_err(|e| in_stage(e, count - 1))?;
                warnings.extend(
                    spent
                        .warnings()
                        .iter()
                        .map(|w| format!("`stages.{}.rocket`: {w}", count - 1)),
                );
                if stage.rocket.parachutes.is_empty() {
                    tumble_drag_area(mission, count - 1, &spent)?;
                }
            }
        }
    }
    Ok(warnings)
}

/// Where the current stack starts.
enum Start {
    Rail,
    Separation { t: f64, state: State, cdm: f64 },
}

/// Builds and flies a multi-stage mission (module documentation), with parachute trigger
/// noise seeded by `seed`.
///
/// # Errors
/// The builders' [`MissionError`]s (lower stages' keys under `stages.<index>`), the launch
/// checks of the launch stack, and [`MissionError::Flight`] (section `flight`) when a flight
/// cannot be integrated.
pub fn simulate_staged(mission: &Mission, seed: u64) -> Result<StagedRun, MissionError> {
    let thrusts = ThrustCache::read(mission)?;
    let (environment, weather) = build_environment_checked(mission)?;
    let tree = fly_tree(mission, &thrusts, &environment, &environment, weather, seed)?;
    Ok(StagedRun::of(environment, tree, OWN_WIND))
}

/// [`simulate_staged`] with the thrust data read before (`thrusts`, of the nominal mission),
/// in a built `environment` whose wind is multiplied by `wind[0]` and turned clockwise by
/// `wind[1]` degrees ([`WindAdjusted`]), as a Monte Carlo sample flies (without the weather's
/// warnings).
///
/// # Errors
/// As [`simulate_staged`].
pub fn simulate_staged_in(
    mission: &Mission,
    thrusts: &ThrustCache,
    environment: Environment,
    wind: [f64; 2],
    seed: u64,
) -> Result<StagedRun, MissionError> {
    let tree = if wind == OWN_WIND {
        fly_tree(
            mission,
            thrusts,
            &environment,
            &environment,
            Vec::new(),
            seed,
        )?
    } else {
        let adjusted = WindAdjusted::new(&environment, wind[0], wind[1]);
        fly_tree(mission, thrusts, &environment, &adjusted, Vec::new(), seed)?
    };
    Ok(StagedRun::of(environment, tree, wind))
}

impl StagedRun {
    /// The run of a flown tree in `environment` with the wind adjustment `wind`.
    fn of(environment: Environment, tree: Tree, wind: [f64; 2]) -> Self {
        StagedRun {
            environment,
            settings: tree.settings,
            segments: tree.segments,
            bodies: tree.bodies,
            separations: tree.separations,
            warnings: tree.warnings,
            wind,
        }
    }
}

/// Flies the tree of bodies of a multi-stage mission in `environment` (`base` as built, in
/// which the launch is checked; `weather` its warnings, reported with the launch checks).
fn fly_tree<A: AtmosphereModel>(
    mission: &Mission,
    thrusts: &ThrustCache,
    base: &Environment,
    environment: &A,
    weather: Vec<String>,
    seed: u64,
) -> Result<Tree, MissionError> {
    let stages = &mission.spec.stages;
    let elevation = environment.elevation();
    let mut count = stages.len();
    let mut ignition = 0.0;
    let mut warnings = Vec::new();
    let mut separations = Vec::new();
    // Separations on the pad: the stack above launches, the stage stays.
    while count > 0 && matches!(stages[count - 1].separation, Trigger::Launch(d) if d <= 0.0) {
        separations.push(SeparationRecord {
            stage: stage_name(&stages[count - 1], count - 1),
            time_s: 0.0,
        });
        ignition = stages[count - 1].ignition_delay;
        count -= 1;
    }
    let settings = launch_settings(
        mission,
        thrusts,
        base,
        count,
        ignition,
        weather,
        seed,
        &mut warnings,
    )?;

    let launch_checked = ignition == 0.0;
    let mut segments: Vec<Segment> = Vec::new();
    let mut bodies = Vec::new();
    let mut shared: Vec<usize> = Vec::new();
    let mut start = Start::Rail;
    let flight_error = |e| mission.flight_error("flight", e);
    loop {
        let (vehicle_mission, rocket) = build_stack(mission, thrusts, count, ignition)?;
        if !(segments.is_empty() && launch_checked) {
            warnings.extend(rocket.warnings().iter().map(|w| match count {
                0 => format!("`rocket`: {w}"),
                n => format!("`stages.{}`: {w}", n - 1),
            }));
        }
        let own_settings = vehicle_settings(&vehicle_mission, &rocket, seed);
        let mut processes: Vec<Box<dyn SampledProcess + '_>> = Vec::new();
        if count > 0 {
            processes.push(Box::new(SeparationTrigger {
                atmosphere: environment,
                elevation,
                rate: stages[count - 1].sampling_rate,
                condition: condition(mission, count - 1, rocket.burn_out())?,
                stage: count - 1,
                fired: false,
            }));
        }
        let flight = match start {
            Start::Rail => {
                karman_dynamics::simulate_with(environment, &rocket, &own_settings, processes)
            }
            Start::Separation { t, state, cdm } => karman_dynamics::simulate_from(
                environment,
                &rocket,
                &own_settings,
                t,
                moved(&state, cdm, rocket.center_of_dry_mass(), rocket.csys()),
                Configuration::default(),
                processes,
            ),
        }
        .map_err(flight_error)?;
        let names: Vec<String> = std::iter::once(TOP_STAGE.to_owned())
            .chain((0..count).map(|i| stage_name(&stages[i], i)))
            .collect();
        let separated = flight.termination == Termination::Separation;
        let end = flight.points.last().map(|p| (p.t, p.state));
        let stack_cdm = rocket.center_of_dry_mass();
        let csys = rocket.csys();
        segments.push(Segment {
            vehicle: names.join(" + "),
            motor_stage: names[names.len() - 1].clone(),
            rocket,
            flight,
        });
        shared.push(segments.len() - 1);
        let (true, Some((t, state))) = (separated, end) else {
            // The stack flew to its end together: every member ends here.
            for name in names.iter().rev() {
                bodies.push(Body {
                    name: name.clone(),
                    segments: shared.clone(),
                });
            }
            break;
        };
        let index = count - 1;
        let stage = &stages[index];
        let name = stage_name(stage, index);
        separations.push(SeparationRecord {
            stage: name.clone(),
            time_s: t,
        });
        // The spent stage flies on alone (a massless one has nothing to fly).
        if stage.rocket.mass > 0.0 && stage.motor.is_some() {
            let spent = SpentStage {
                index,
                ignition,
                t,
                state,
                stack_cdm,
                csys,
            };
            let (rocket, flight) =
                fly_spent_stage(mission, thrusts, environment, &spent, seed, &mut warnings)?;
            segments.push(Segment {
                vehicle: name.clone(),
                motor_stage: name.clone(),
                rocket,
                flight,
            });
            let mut own = shared.clone();
            own.push(segments.len() - 1);
            bodies.push(Body {
                name,
                segments: own,
            });
        }
        ignition = t + stage.ignition_delay;
        start = Start::Separation {
            t,
            state,
            cdm: stack_cdm,
        };
        count -= 1;
    }
    // The top stage first, then the lower stages in the order they separated.
    bodies.sort_by_key(|b| b.name != TOP_STAGE);
    Ok(Tree {
        settings,
        segments,
        bodies,
        separations,
        warnings,
    })
}

/// The flight settings of the launch, from the vehicle that leaves the pad (the `count`
/// bottom-most stages' stack; the top stage alone when `count` is 0) checked with every
/// launch check when it lights at launch (`ignition` 0), its warnings and the weather's
/// added to `warnings`; the mission's own settings for a stack lit later.
///
/// # Errors
/// The launch vehicle's models or launch checks, named by the bottom stage's keys.
#[allow(clippy::too_many_arguments)]
fn launch_settings(
    mission: &Mission,
    thrusts: &ThrustCache,
    base: &Environment,
    count: usize,
    ignition: f64,
    weather: Vec<String>,
    seed: u64,
    warnings: &mut Vec<String>,
) -> Result<FlightSettings, MissionError> {
    // The launch vehicle with every launch check.
    let launch = if count == 0 {
        top_mission(mission)
    } else {
        let (_, above) = build_stack(mission, thrusts, count - 1, 0.0)?;
        stack_mission(mission, count, unburnt(&above))
    };
    if ignition == 0.0 {
        let thrust = thrusts.source(&launch)?;
        let (_, _, settings, launch_warnings) = checked_models(&launch, base, &thrust, seed)
            .map_err(|e| match count {
                0 => e,
                n => in_stage(e, n - 1),
            })?;
        warnings.extend(weather);
        warnings.extend(launch_warnings);
        Ok(settings)
    } else {
        Ok(flight_settings(mission, seed))
    }
}

/// A spent lower stage at its separation: its `index` in `[[stages]]`, the ignition time of
/// its motor, the separation time `t` (s) and the stack's state there about the stack's
/// centre of dry mass `stack_cdm` (rocket coordinates of sign `csys`).
struct SpentStage {
    index: usize,
    ignition: f64,
    t: f64,
    state: State,
    stack_cdm: f64,
    csys: f64,
}

/// Flies spent stage `at` alone from its separation to the ground: its own rocket (its
/// warnings added to `warnings`), under its parachutes or tumbling when it has none.
///
/// # Errors
/// The stage's models, named by its keys; a flight that fails.
fn fly_spent_stage<A: AtmosphereModel>(
    mission: &Mission,
    thrusts: &ThrustCache,
    environment: &A,
    at: &SpentStage,
    seed: u64,
    warnings: &mut Vec<String>,
) -> Result<(Rocket, Flight), MissionError> {
    let index = at.index;
    let stage = &mission.spec.stages[index];
    let name = stage_name(stage, index);
    let alone = stage_mission(mission, index);
    let motor = stage_motor(&alone, thrusts, index)?;
    let spent = build_rocket_ignited_at(&alone, &motor, at.ignition, thrusts)
        .map_err(|e| in_stage(e, index))?;
    warnings.extend(
        spent
            .warnings()
            .iter()
            .map(|w| format!("`stages.{index}.rocket`: {w}")),
    );
    let spent_settings = vehicle_settings(&alone, &spent, seed);
    let mut descent: Vec<Box<dyn SampledProcess + '_>> = Vec::new();
    if stage.rocket.parachutes.is_empty() {
        descent.push(Box::new(TumbleTrigger {
            atmosphere: environment,
            rate: stage.sampling_rate,
            drag_area: tumble_drag_area(mission, index, &spent)?,
            unstable: spent.static_margin(at.t) < 0.0,
            fired: false,
        }));
    }
    let flight = karman_dynamics::simulate_from(
        environment,
        &spent,
        &spent_settings,
        at.t,
        moved(&at.state, at.stack_cdm, spent.center_of_dry_mass(), at.csys),
        Configuration::default(),
        descent,
    )
    .map_err(|e| {
        mission.model_error(
            &format!("stages.{index}"),
            format!(
                "the stage `{name}` flying alone from its separation at t = {} s: {e}",
                at.t
            ),
        )
    })?;
    Ok((spent, flight))
}

impl Segment {
    /// The segment's summary, its events restricted to its own time span (a flight resumed
    /// at a separation does not repeat the burn-out before it) and its burn-out named by the
    /// stage whose motor burnt out.
    fn summary<A: AtmosphereModel>(&self, atmosphere: &A) -> Summary {
        let mut summary = self.flight.summary(atmosphere, &self.rocket);
        let start = self.flight.points.first().map_or(0.0, |p| p.t);
        summary.events.retain(|e| e.time_s >= start);
        for event in &mut summary.events {
            if event.name == "burnout" {
                event.name = format!("burnout:{}", self.motor_stage);
            }
        }
        summary
    }
}

impl StagedRun {
    /// The summary of segment `index` in the atmosphere the flight saw.
    fn segment_summary(&self, index: usize) -> Summary {
        let segment = &self.segments[index];
        if self.wind == OWN_WIND {
            segment.summary(&self.environment)
        } else {
            let [factor, offset] = self.wind;
            segment.summary(&WindAdjusted::new(&self.environment, factor, offset))
        }
    }

    /// The post-processed samples of segment `index` in the atmosphere the flight saw.
    fn segment_samples(&self, index: usize) -> Vec<Sample> {
        let segment = &self.segments[index];
        if self.wind == OWN_WIND {
            segment.flight.samples(&self.environment, &segment.rocket)
        } else {
            let [factor, offset] = self.wind;
            let atmosphere = WindAdjusted::new(&self.environment, factor, offset);
            segment.flight.samples(&atmosphere, &segment.rocket)
        }
    }

    /// The summary of body `body`: the launch's rail exit and margins, the first apogee of
    /// its path, the extremes over every segment, the end of its last segment, and its
    /// events with the separations it took part in.
    #[must_use]
    pub fn summary(&self, body: usize) -> Summary {
        let segments = &self.bodies[body].segments;
        let parts: Vec<Summary> = segments.iter().map(|&s| self.segment_summary(s)).collect();
        let mut joined = parts[0].clone();
        let apogee = parts.iter().find(|p| p.apogee_time_s.is_some());
        if let Some(a) = apogee {
            joined.apogee_agl_m = a.apogee_agl_m;
            joined.apogee_asl_m = a.apogee_asl_m;
            joined.apogee_time_s = a.apogee_time_s;
            joined.apogee_x_m = a.apogee_x_m;
            joined.apogee_y_m = a.apogee_y_m;
        }
        let last = &parts[parts.len() - 1];
        joined.impact_time_s = last.impact_time_s;
        joined.impact_x_m = last.impact_x_m;
        joined.impact_y_m = last.impact_y_m;
        joined.impact_velocity_mps = last.impact_velocity_mps;
        joined.termination = last.termination;
        joined.events.clear();
        for part in &parts {
            joined.max_speed_mps = joined.max_speed_mps.max(part.max_speed_mps);
            joined.max_mach = joined.max_mach.max(part.max_mach);
            joined.max_dynamic_pressure_pa = joined
                .max_dynamic_pressure_pa
                .max(part.max_dynamic_pressure_pa);
            joined.max_acceleration_mps2 =
                joined.max_acceleration_mps2.max(part.max_acceleration_mps2);
            joined.events.extend(part.events.iter().cloned());
        }
        // The separations are in time order: a body took part in those up to its own (the
        // stages below it went first), or in all of them.
        let name = &self.bodies[body].name;
        let own = self.separations.iter().position(|s| &s.stage == name);
        for (i, separation) in self.separations.iter().enumerate() {
            if own.is_none_or(|m| i <= m) {
                joined.events.push(EventRecord {
                    name: format!("separation:{}", separation.stage),
                    time_s: separation.time_s,
                });
            }
        }
        joined.events.sort_by(|a, b| a.time_s.total_cmp(&b.time_s));
        joined
    }

    /// Post-processed quantities along body `body`'s path, each segment with its own model
    /// (the point a segment starts from, the previous segment's last, once).
    #[must_use]
    pub fn samples(&self, body: usize) -> Vec<Sample> {
        let mut samples: Vec<Sample> = Vec::new();
        for &s in &self.bodies[body].segments {
            let mut part = self.segment_samples(s);
            if !samples.is_empty() && !part.is_empty() {
                part.remove(0);
            }
            samples.extend(part);
        }
        samples
    }

    /// The flight's events in one timeline: every segment's, named by its vehicle, and the
    /// separations.
    #[must_use]
    pub fn timeline(&self) -> Vec<(f64, String)> {
        let mut events = Vec::new();
        for (index, segment) in self.segments.iter().enumerate() {
            for event in self.segment_summary(index).events {
                events.push((event.time_s, format!("{}: {}", segment.vehicle, event.name)));
            }
        }
        for separation in &self.separations {
            events.push((
                separation.time_s,
                format!("separation of {}", separation.stage),
            ));
        }
        events.sort_by(|a, b| a.0.total_cmp(&b.0));
        events
    }

    /// Body `body` as the trajectory series read it.
    #[must_use]
    pub fn track(&self, body: usize) -> BodyTrack<'_> {
        BodyTrack { run: self, body }
    }

    /// The static margin of body `body` at `t`, of the model flown then, calibers.
    #[must_use]
    pub fn static_margin(&self, body: usize, t: f64) -> f64 {
        self.rocket_at(body, t).static_margin(t)
    }

    /// The vehicle body `body` flies at `t`: its segment's.
    fn rocket_at(&self, body: usize, t: f64) -> &Rocket {
        let segments = &self.bodies[body].segments;
        let at = segments
            .iter()
            .find(|&&s| t <= self.segments[s].flight.t_final)
            .or(segments.last())
            .copied()
            .unwrap_or(0);
        &self.segments[at].rocket
    }
}

/// One body of a [`StagedRun`] for the trajectory report (`trajectory.csv`, KML).
#[derive(Debug, Clone, Copy)]
pub struct BodyTrack<'a> {
    run: &'a StagedRun,
    body: usize,
}

impl Track for BodyTrack<'_> {
    fn environment(&self) -> &Environment {
        &self.run.environment
    }
    fn static_margin(&self, t: f64) -> f64 {
        self.run.static_margin(self.body, t)
    }
    fn reference_radius(&self, t: f64) -> f64 {
        self.run.rocket_at(self.body, t).radius()
    }
    fn rail(&self) -> Option<RailArms> {
        // The launch stack leaves the rail in the first segment, which the top body's path
        // starts with; the lower bodies separate in flight.
        let first = *self.run.bodies[self.body].segments.first()?;
        let segment = &self.run.segments[first];
        RailArms::of(&segment.rocket, segment.flight.rail_exit?.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_moved_state_is_another_point_of_the_same_rigid_body() {
        // A tilted, spinning, translating body.
        let (half, axis) = (0.4_f64, [0.3_f64, -0.5, 0.81]);
        let n = axis.iter().map(|a| a * a).sum::<f64>().sqrt();
        let (s, c) = half.sin_cos();
        let state: State = [
            10.0,
            -4.0,
            1500.0,
            3.0,
            -7.0,
            120.0,
            c,
            s * axis[0] / n,
            s * axis[1] / n,
            s * axis[2] / n,
            0.7,
            -1.3,
            25.0,
        ];
        let moved_state = moved(&state, 1.2, 0.45, -1.0);
        let k = rotation([state[6], state[7], state[8], state[9]]);
        let dr: Vec<f64> = (0..3).map(|i| moved_state[i] - state[i]).collect();
        let dv: Vec<f64> = (0..3).map(|i| moved_state[3 + i] - state[3 + i]).collect();
        // 0.75 m toward the nose (nose_to_tail coordinates decrease toward it), on the axis.
        for i in 0..3 {
            assert!((dr[i] - 0.75 * k[i][2]).abs() < 1e-12);
        }
        // v_b − v_a = ω × (r_b − r_a), with ω in inertial axes.
        let w: Vec<f64> = (0..3)
            .map(|i| k[i][0] * state[10] + k[i][1] * state[11] + k[i][2] * state[12])
            .collect();
        let cross = [
            w[1] * dr[2] - w[2] * dr[1],
            w[2] * dr[0] - w[0] * dr[2],
            w[0] * dr[1] - w[1] * dr[0],
        ];
        for i in 0..3 {
            assert!((dv[i] - cross[i]).abs() < 1e-12, "{dv:?} {cross:?}");
        }
        // Attitude and rates are the body's; moving back returns the state.
        assert_eq!(moved_state[6..], state[6..]);
        let back = moved(&moved_state, 0.45, 1.2, -1.0);
        for i in 0..13 {
            assert!((back[i] - state[i]).abs() < 1e-9 * (1.0 + state[i].abs()));
        }
        let still = moved(&state, 0.8, 0.8, 1.0);
        assert!(
            still
                .iter()
                .zip(&state)
                .all(|(a, b)| a.to_bits() == b.to_bits())
        );
    }
}
