//! `[rocket]` → [`karman_airframe::Rocket`]: the airframe, its surfaces, parachutes and rail
//! buttons, with the mission's motor converted to [`karman_airframe::MotorProperties`] by
//! [`super::motor::motor_properties`].

use std::sync::Arc;

use karman_airframe::{
    self as airframe, AirBrakes, AirBrakesSpec, Airfoil, AirframeError, CoordinateSystem,
    DragEstimate, DragGeometry, Eccentricities, NoseKind, Parachute, RailButtons, Rocket,
    RocketInputs, SurfaceInput, TriggerKind,
};
use karman_script::Expression;

use super::drag::pod_of;
use super::motor::{cluster_of, clustered, delayed, motor_properties};
use super::motors::ThrustCache;
use super::scripts::{AfterTime, ExpressionTrigger};
use karman_math::{Extrapolation, Interpolation, Table1};
use karman_propulsion::Motor;

use crate::schema::{self, AngleUnit, RocketCoordinateSystem, SurfaceSpec};
use crate::{Mission, MissionError};

/// Builds the rocket of `mission` with `motor` at `rocket.motor_position`.
///
/// # Errors
/// [`MissionError::Model`] (the curve's key) for a drag or airfoil curve that is not a table,
/// and (section `rocket`, `rocket.surfaces.<name>`,
/// `rocket.parachutes.<name>` or `rocket.rail_buttons`) for impossible airframe inputs.
pub fn build_rocket(mission: &Mission, motor: &Motor) -> Result<Rocket, MissionError> {
    build(mission, motor, 0.0, EstimateScaling::default(), None)
}

/// [`build_rocket`] with the motor ignited at `ignition` s ([`delayed`]; a `"burnout + X"`
/// trigger counts from its delayed burn-out): an upper stage of a multi-stage rocket. Its
/// extra motors' thrust data come from `thrusts`.
///
/// # Errors
/// As [`build_rocket`], and [`MissionError::Model`] (section `motor`) when the delay cannot be
/// represented in the motor's tables.
pub fn build_rocket_ignited_at(
    mission: &Mission,
    motor: &Motor,
    ignition: f64,
    thrusts: &ThrustCache,
) -> Result<Rocket, MissionError> {
    build(
        mission,
        motor,
        ignition,
        EstimateScaling::default(),
        Some(thrusts),
    )
}

/// A change `a · Cd + b` of each drag curve estimated from the geometry (`"estimate"`), as
/// `[a, b]`: a Monte Carlo `factor` (`[f, 0]`) or `offset` (`[1, o]`) on
/// `rocket.power_off_drag` / `rocket.power_on_drag`, applied to the sample's own estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EstimateScaling {
    /// Of the power-off curve.
    pub power_off: [f64; 2],
    /// Of the power-on curve.
    pub power_on: [f64; 2],
}

impl Default for EstimateScaling {
    fn default() -> Self {
        EstimateScaling {
            power_off: [1.0, 0.0],
            power_on: [1.0, 0.0],
        }
    }
}

/// [`build_rocket`] with its estimated drag curves changed by `scaling` (curves read from the
/// mission are not estimates, and stay as they are), its extra motors' thrust data from
/// `thrusts`: a Monte Carlo sample.
///
/// # Errors
/// As [`build_rocket`].
pub fn build_rocket_scaled(
    mission: &Mission,
    motor: &Motor,
    scaling: EstimateScaling,
    thrusts: &ThrustCache,
) -> Result<Rocket, MissionError> {
    build(mission, motor, 0.0, scaling, Some(thrusts))
}

fn build(
    mission: &Mission,
    motor: &Motor,
    ignition: f64,
    scaling: EstimateScaling,
    thrusts: Option<&ThrustCache>,
) -> Result<Rocket, MissionError> {
    let spec = &mission.spec.rocket;
    // A curve as a table of the given kind: airfoils are linear with held ends, the drag
    // curves follow the rocket's `interpolation` / `extrapolation`.
    let curve = |key: String, c: &schema::Curve, kind: (Interpolation, Extrapolation)| {
        c.to_table(&mission.dir, kind.0, kind.1)
            .map_err(|source| mission.model_error(&key, source))
    };
    let linear = (Interpolation::Linear, Extrapolation::Constant);
    let drag = (spec.interpolation.into(), spec.extrapolation.into());
    let model = |section: String, source: AirframeError| mission.model_error(&section, source);

    let mut surfaces = Vec::with_capacity(spec.surfaces.len());
    for (name, surface) in &spec.surfaces {
        let airfoil = match surface.airfoil() {
            Some(a) => Some(Airfoil {
                lift_curve: curve(format!("rocket.surfaces.{name}.airfoil"), &a.lift, linear)?,
                unit: match a.unit {
                    AngleUnit::Radians => airframe::AngleUnit::Radians,
                    AngleUnit::Degrees => airframe::AngleUnit::Degrees,
                },
            }),
            None => None,
        };
        surfaces.push(surface_input(spec, name, surface, airfoil));
    }

    let (count, radius) = cluster_of(mission);
    let single = clustered(motor_properties(motor), count, radius)
        .map_err(|e| mission.model_error("motor", e))?;
    let properties = if ignition == 0.0 {
        single
    } else {
        delayed(single, ignition).map_err(|e| mission.model_error("motor", e))?
    };
    // `[[extra_motors]]`: the motors flown as one, burning out at the last burn-out.
    let properties = super::motors::with_extra_motors(mission, properties, thrusts)?;
    let burn_out = if mission.spec.extra_motors.is_empty() {
        motor.burn_out() + ignition
    } else {
        properties.burn_out
    };

    let parachutes = parachutes(mission, burn_out)?;

    let rail_buttons = match &spec.rail_buttons {
        Some(b) => Some(
            RailButtons::new(b.upper_position, b.lower_position, b.angular_position_deg)
                .map_err(|e| model("rocket.rail_buttons".to_owned(), e))?,
        ),
        None => None,
    };

    // Drag curves: tables from the mission, or the geometric estimate (computed once for
    // both when either asks for it).
    let estimated = estimated_drag(mission, motor)?;
    let drag_table = |key: &str, c: &schema::Curve, on: bool| match &estimated {
        Some(e) if c.is_estimate() => {
            let [a, b] = if on {
                scaling.power_on
            } else {
                scaling.power_off
            };
            let table = if on { e.power_on() } else { e.power_off() }
                .map_err(|e| model("rocket.drag_estimate".to_owned(), e))?;
            // `1 · Cd + 0` is `Cd` exactly: the nominal estimate is unchanged.
            let ys = table.ys().iter().map(|cd| a * cd + b).collect();
            Table1::linear(table.xs().to_vec(), ys)
                .map_err(|source| mission.model_error(key, source))
        }
        _ => curve(key.to_owned(), c, drag),
    };
    let power_off_drag = drag_table("rocket.power_off_drag", &spec.power_off_drag, false)?;
    let power_on_drag = drag_table("rocket.power_on_drag", &spec.power_on_drag, true)?;
    let inputs = RocketInputs {
        radius: spec.radius,
        mass: spec.mass,
        inertia: spec.inertia.0,
        center_of_mass_without_motor: spec.center_of_mass_without_motor,
        coordinate_system: match spec.coordinate_system {
            RocketCoordinateSystem::TailToNose => CoordinateSystem::TailToNose,
            RocketCoordinateSystem::NoseToTail => CoordinateSystem::NoseToTail,
        },
        power_off_drag,
        power_on_drag,
        motor_position: spec.motor_position,
        surfaces,
        parachutes,
        rail_buttons,
        eccentricities: Eccentricities {
            center_of_mass: spec.cm_eccentricity.unwrap_or_default(),
            center_of_pressure: spec.cp_eccentricity.unwrap_or_default(),
            thrust: spec.thrust_eccentricity.unwrap_or_default(),
        },
    };
    let rocket =
        Rocket::new(inputs, properties).map_err(|e| model(airframe_error_key(spec, &e), e))?;
    with_air_brakes(mission, rocket)
}

/// The mission key an error of the airframe's rocket builder belongs to: the surface it
/// names, `motor`, or `rocket`.
fn airframe_error_key(spec: &schema::RocketSpec, e: &AirframeError) -> String {
    match e {
        AirframeError::NotFinite { component, .. }
        | AirframeError::NotPositive { component, .. }
        | AirframeError::Negative { component, .. }
        | AirframeError::OutOfRange { component, .. }
        | AirframeError::Geometry { component, .. }
        | AirframeError::InertiaComponents { component, .. }
        | AirframeError::Table { component, .. } => {
            if spec.surfaces.contains_key(component) {
                format!("rocket.surfaces.{component}")
            } else if component == "motor" {
                "motor".to_owned()
            } else {
                "rocket".to_owned()
            }
        }
    }
}

/// The airframe's parachutes of `[rocket.parachutes]`, in file order; a `"burnout + X"`
/// trigger counts from `burn_out` (s).
///
/// # Errors
/// A trigger expression that does not parse; impossible parachute inputs, at their table.
fn parachutes(mission: &Mission, burn_out: f64) -> Result<Vec<Parachute>, MissionError> {
    let spec = &mission.spec.rocket;
    let mut parachutes = Vec::with_capacity(spec.parachutes.len());
    for (name, p) in &spec.parachutes {
        let chute = Parachute::new(&airframe::ParachuteSpec {
            name: name.clone(),
            cd_s: p.cd_s,
            trigger: match &p.trigger {
                schema::Trigger::Apogee => TriggerKind::Apogee,
                schema::Trigger::HeightAboveGround(h) => TriggerKind::HeightAboveGround(*h),
                schema::Trigger::Launch(delay) => TriggerKind::Custom(Arc::new(AfterTime(*delay))),
                schema::Trigger::Burnout(delay) => {
                    TriggerKind::Custom(Arc::new(AfterTime(burn_out + delay)))
                }
                schema::Trigger::Expression(text) => {
                    let sensors = &mission.spec.rocket.sensors;
                    let expression = Expression::parse_with(text, &super::sensors::shapes(sensors))
                        .map_err(|e| {
                            mission.model_error(&format!("rocket.parachutes.{name}.trigger"), e)
                        })?;
                    TriggerKind::Custom(Arc::new(ExpressionTrigger::new(expression, sensors)))
                }
            },
            sampling_rate: Some(p.sampling_rate),
            lag: Some(p.lag),
            noise: Some(p.noise),
            radius: p.radius,
            height: p.height,
            porosity: p.porosity,
            drag_coefficient: None,
        })
        .map_err(|e| mission.model_error(&format!("rocket.parachutes.{name}"), e))?;
        parachutes.push(chute);
    }
    Ok(parachutes)
}

/// `rocket` with the air brakes of `[rocket.air_brakes]`, if the mission has them.
///
/// # Errors
/// The brakes' drag curve that cannot be read; impossible brake inputs.
fn with_air_brakes(mission: &Mission, rocket: Rocket) -> Result<Rocket, MissionError> {
    let spec = &mission.spec.rocket;
    match &spec.air_brakes {
        Some(ab) => {
            let drag = ab
                .drag_coefficient_curve
                .to_drag(&mission.dir)
                .map_err(|source| MissionError::Curve {
                    file: mission.path.clone(),
                    key: crate::paths::AIR_BRAKES_CURVE.into(),
                    source,
                })?;
            let brakes = AirBrakes::new(&AirBrakesSpec {
                name: ab.name.clone().unwrap_or_else(|| "AirBrakes".into()),
                drag,
                reference_area: ab.reference_area.unwrap_or(rocket.reference_area()),
                clamp: ab.clamp,
                override_rocket_drag: ab.override_rocket_drag,
                initial_level: ab.deployment_level,
            })
            .map_err(|e| mission.model_error("rocket.air_brakes", e))?;
            Ok(rocket.with_air_brakes(brakes))
        }
        None => Ok(rocket),
    }
}

/// The drag estimated from the geometry when `power_off_drag` or `power_on_drag` is
/// `"estimate"` (see [`super::drag`]), with `motor`'s nozzle exit for the power-on base.
///
/// # Errors
/// [`MissionError::Model`] for a geometry the estimate cannot use.
pub fn estimated_drag(
    mission: &Mission,
    motor: &Motor,
) -> Result<Option<DragEstimate>, MissionError> {
    let spec = &mission.spec.rocket;
    if !(spec.power_off_drag.is_estimate() || spec.power_on_drag.is_estimate()) {
        return Ok(None);
    }
    // The airfoil changes lift only, not the planform the estimate needs.
    let surfaces: Vec<SurfaceInput> = spec
        .surfaces
        .iter()
        .map(|(name, s)| surface_input(spec, name, s, None))
        .collect();
    let nozzle_radius = super::motors::combined_exit_radius(mission, motor.nozzle_radius());
    super::drag::estimate(mission, &surfaces, nozzle_radius).map(Some)
}

/// The body and fins the drag estimate implies for `mission`'s rocket (no nozzle): the
/// geometry of [`karman_airframe::BodyLift`].
///
/// # Errors
/// As [`estimated_drag`].
pub fn estimate_geometry(mission: &Mission) -> Result<DragGeometry, MissionError> {
    let rocket = &mission.spec.rocket;
    let surfaces: Vec<SurfaceInput> = rocket
        .surfaces
        .iter()
        .map(|(name, s)| surface_input(rocket, name, s, None))
        .collect();
    super::drag::drag_geometry(mission, &surfaces, 0.0)
}

/// The airframe's description of one mission surface of `rocket`.
fn surface_input(
    rocket: &schema::RocketSpec,
    name: &str,
    surface: &SurfaceSpec,
    airfoil: Option<Airfoil>,
) -> SurfaceInput {
    let (position, spec) = match surface {
        SurfaceSpec::Nose(s) => (
            s.position,
            airframe::SurfaceSpec::Nose(airframe::NoseConeSpec {
                length: s.length,
                kind: match s.kind {
                    schema::NoseKind::Conical => NoseKind::Conical,
                    // RocketPy's NoseCone treats "ogive" as a tangent ogive.
                    schema::NoseKind::Ogive | schema::NoseKind::Tangent => NoseKind::Ogive,
                    schema::NoseKind::VonKarman => NoseKind::VonKarman,
                    schema::NoseKind::LvHaack => NoseKind::LvHaack,
                    schema::NoseKind::Parabolic => NoseKind::Parabolic,
                    schema::NoseKind::Elliptical => NoseKind::Elliptical,
                    schema::NoseKind::PowerSeries => {
                        // Validation guarantees `power` for this kind; a missing one becomes NaN,
                        // which the airframe rejects with a located error.
                        NoseKind::PowerSeries(s.power.unwrap_or(f64::NAN))
                    }
                },
                base_radius: s.base_radius,
                bluffness: s.bluffness.unwrap_or(0.0),
            }),
        ),
        SurfaceSpec::TrapezoidalFins(s) => (
            s.position,
            airframe::SurfaceSpec::TrapezoidalFins(airframe::TrapezoidalFinsSpec {
                n: s.n,
                root_chord: s.root_chord,
                tip_chord: s.tip_chord,
                span: s.span,
                sweep: match s.sweep {
                    None => airframe::Sweep::Default,
                    Some(schema::Sweep::Length(l)) => airframe::Sweep::Length(l),
                    Some(schema::Sweep::AngleDeg(a)) => airframe::Sweep::AngleDeg(a),
                },
                cant_angle_deg: s.cant_angle_deg,
                angular_position_deg: s.angular_position_deg,
                radius: s.radius,
                airfoil,
            }),
        ),
        SurfaceSpec::EllipticalFins(s) => (
            s.position,
            airframe::SurfaceSpec::EllipticalFins(airframe::EllipticalFinsSpec {
                n: s.n,
                root_chord: s.root_chord,
                span: s.span,
                cant_angle_deg: s.cant_angle_deg,
                angular_position_deg: s.angular_position_deg,
                radius: s.radius,
                airfoil,
            }),
        ),
        SurfaceSpec::FreeFormFins(s) => (
            s.position,
            airframe::SurfaceSpec::FreeFormFins(airframe::FreeFormFinsSpec {
                n: s.n,
                shape_points: s.shape_points.clone(),
                cant_angle_deg: s.cant_angle_deg,
                angular_position_deg: s.angular_position_deg,
                radius: s.radius,
                airfoil,
            }),
        ),
        SurfaceSpec::Tail(s) => (
            s.position,
            airframe::SurfaceSpec::Tail(airframe::TailSpec {
                top_radius: s.top_radius,
                bottom_radius: s.bottom_radius,
                length: s.length,
                radius: None,
            }),
        ),
        SurfaceSpec::TubeFins(s) => (
            s.position,
            airframe::SurfaceSpec::TubeFins(airframe::TubeFinsSpec {
                n: s.n,
                length: s.length,
                outer_radius: s.outer_radius,
                inner_radius: s.inner_radius,
                radius: s.radius,
            }),
        ),
    };
    SurfaceInput {
        name: name.to_owned(),
        position,
        spec,
        pod: pod_of(rocket, name).map(|(_, pod)| airframe::PodPlacement {
            count: pod.count,
            angular_position: pod.angular_position_deg.to_radians(),
        }),
    }
}
