//! `[rocket]` → [`karman_airframe::Rocket`]: the airframe, its surfaces, parachutes and rail
//! buttons, with the mission's motor converted to [`karman_airframe::MotorProperties`] by
//! [`motor_properties`] (the airframe crate may not depend on the propulsion crate, so the
//! hand-over lives here, the first crate that sees both).

use std::sync::Arc;

use karman_airframe::{
    self as airframe, AirBrakes, AirBrakesSpec, Airfoil, AirframeError, CoordinateSystem,
    DragEstimate, DragGeometry, MotorProperties, NoseKind, Parachute, RailButtons, Rocket,
    RocketInputs, SurfaceInput, TriggerKind,
};
use karman_script::Expression;

use super::motors::ThrustCache;
use super::scripts::{AfterTime, ExpressionTrigger};
use karman_math::{Extrapolation, Interpolation, Table1};
use karman_model::PropellantPart;
use karman_propulsion::Motor;

use crate::schema::{self, AngleUnit, RocketCoordinateSystem, SurfaceSpec};
use crate::{Mission, MissionError};

/// The motor's tables and constants as the airframe needs them
/// ([`karman_airframe::MotorProperties`]).
///
/// A propellant in parts (a liquid motor whose tanks are on different time grids, a hybrid
/// motor's grain and tanks) is handed over with them ([`MotorProperties::propellant_parts`]),
/// which the rocket sums pointwise as RocketPy does (docs/physics.md §15.3–15.4).
#[must_use]
pub fn motor_properties(motor: &Motor) -> MotorProperties {
    let (i11, i33) = motor.propellant_inertia();
    let propellant_parts = motor.propellant_parts().to_vec();
    MotorProperties {
        thrust: motor.thrust_table().clone(),
        burn_start: motor.burn_start(),
        burn_out: motor.burn_out(),
        exhaust_velocity: motor.exhaust_velocity(),
        propellant_mass: motor.propellant_mass().clone(),
        mass_flow: None,
        propellant_center_of_mass: motor.propellant_center_of_mass().clone(),
        propellant_i11: i11.clone(),
        propellant_i33: i33.clone(),
        propellant_parts,
        dry_mass: motor.dry_mass(),
        center_of_dry_mass: motor.center_of_dry_mass(),
        dry_inertia: motor.dry_inertia(),
        nozzle_position: motor.nozzle_position(),
        nozzle_radius: motor.nozzle_radius(),
        coordinate_system_sign: motor.coordinate_system_sign(),
        reference_pressure: motor.reference_pressure(),
    }
}

/// `motor` ignited `ignition` s after the flight's time origin: every table of time moved by
/// that much (the motor of an upper stage, lit at or after its separation).
///
/// # Errors
/// [`karman_math::MathError`] when the shift rounds two of a table's times together.
pub fn delayed(
    motor: MotorProperties,
    ignition: f64,
) -> Result<MotorProperties, karman_math::MathError> {
    Ok(MotorProperties {
        thrust: motor.thrust.shifted(ignition)?,
        burn_start: motor.burn_start + ignition,
        burn_out: motor.burn_out + ignition,
        propellant_mass: motor.propellant_mass.shifted(ignition)?,
        mass_flow: match &motor.mass_flow {
            Some(table) => Some(table.shifted(ignition)?),
            None => None,
        },
        propellant_center_of_mass: motor.propellant_center_of_mass.shifted(ignition)?,
        propellant_i11: motor.propellant_i11.shifted(ignition)?,
        propellant_i33: motor.propellant_i33.shifted(ignition)?,
        propellant_parts: motor
            .propellant_parts
            .iter()
            .map(|p| {
                Ok(PropellantPart {
                    mass: p.mass.shifted(ignition)?,
                    center_of_mass: p.center_of_mass.shifted(ignition)?,
                    moment: p.moment.shifted(ignition)?,
                    i11: p.i11.shifted(ignition)?,
                })
            })
            .collect::<Result<_, karman_math::MathError>>()?,
        ..motor
    })
}

/// A cluster of `count` copies of `motor` (docs/physics.md §24.1), lit together, their axes at
/// `radius` from the rocket's axis (the `[motor]` keys `cluster_count`, `cluster_radius`): thrust,
/// mass flow, masses and mass moments times `count`, the centres of mass and the exhaust velocity
/// unchanged. Each inertia is the sum over the copies with the parallel-axis theorem: about the
/// roll axis `+ m r²` per copy, about each lateral axis `+ m r²/2` (the mean over the two lateral
/// axes of `m y²` and `m z²`, exact for three or more motors evenly on a ring; karman's rocket is
/// axisymmetric). The propellant's terms are tabulated on the union of the nodes of its inertia and
/// mass tables. The nozzle exit radius becomes [`cluster_exit_radius`]. One motor on the axis is
/// returned unchanged.
///
/// # Errors
/// [`karman_math::MathError`] for a propellant table that cannot be rebuilt.
pub fn clustered(
    motor: MotorProperties,
    count: u32,
    radius: f64,
) -> Result<MotorProperties, karman_math::MathError> {
    if count == 1 && radius == 0.0 {
        return Ok(motor);
    }
    let n = f64::from(count);
    let arm2 = radius * radius;
    // n (I(t) + k m(t)) on the union of the two tables' nodes, with I's interpolation and
    // extrapolation: exact for two linear tables.
    let with_mass = |inertia: &Table1, mass: &Table1, k: f64| {
        let mut xs: Vec<f64> = inertia.xs().iter().chain(mass.xs()).copied().collect();
        xs.sort_by(f64::total_cmp);
        xs.dedup();
        let ys = xs
            .iter()
            .map(|&t| n * (inertia.eval(t) + k * mass.eval(t)))
            .collect();
        Table1::new(xs, ys, inertia.interpolation(), inertia.extrapolation())
    };
    let d = motor.dry_inertia;
    let dry = motor.dry_mass;
    Ok(MotorProperties {
        thrust: motor.thrust.scaled(n),
        propellant_mass: motor.propellant_mass.scaled(n),
        mass_flow: motor.mass_flow.as_ref().map(|t| t.scaled(n)),
        propellant_i11: with_mass(&motor.propellant_i11, &motor.propellant_mass, 0.5 * arm2)?,
        propellant_i33: with_mass(&motor.propellant_i33, &motor.propellant_mass, arm2)?,
        propellant_parts: motor
            .propellant_parts
            .iter()
            .map(|p| {
                Ok(PropellantPart {
                    mass: p.mass.scaled(n),
                    center_of_mass: p.center_of_mass.clone(),
                    moment: p.moment.scaled(n),
                    i11: with_mass(&p.i11, &p.mass, 0.5 * arm2)?,
                })
            })
            .collect::<Result<_, karman_math::MathError>>()?,
        dry_mass: n * dry,
        dry_inertia: [
            n * (d[0] + 0.5 * dry * arm2),
            n * (d[1] + 0.5 * dry * arm2),
            n * (d[2] + dry * arm2),
            n * d[3],
            n * d[4],
            n * d[5],
        ],
        nozzle_radius: cluster_exit_radius(motor.nozzle_radius, count),
        ..motor
    })
}

/// The exit radius of one nozzle whose area is that of a cluster of `count` nozzles of
/// `radius`, `radius √count` (the pressure thrust and the power-on base drag see the total
/// exit area).
#[must_use]
pub fn cluster_exit_radius(radius: f64, count: u32) -> f64 {
    radius * f64::from(count).sqrt()
}

/// The `[motor]` cluster of `mission`: `(cluster_count, cluster_radius)`, `(1, 0)` by default.
#[must_use]
pub fn cluster_of(mission: &Mission) -> (u32, f64) {
    let m = &mission.spec.motor;
    (
        m.cluster_count.unwrap_or(1),
        m.cluster_radius.unwrap_or(0.0),
    )
}

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
        .map_err(|e| model(format!("rocket.parachutes.{name}"), e))?;
        parachutes.push(chute);
    }

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
    };
    let rocket = Rocket::new(inputs, properties).map_err(|e| {
        let section = match &e {
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
        };
        model(section, e)
    })?;
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
            .map_err(|e| model("rocket.air_brakes".into(), e))?;
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

/// The pod set of `rocket` that carries surface `name`, if any (`[rocket.pods.<pod>]`).
pub(crate) fn pod_of<'a>(
    rocket: &'a schema::RocketSpec,
    name: &str,
) -> Option<(&'a str, &'a schema::PodSpec)> {
    rocket
        .pods
        .iter()
        .find(|(_, pod)| pod.surfaces.iter().any(|s| s == name))
        .map(|(key, pod)| (key.as_str(), pod))
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
