//! `power_off_drag = "estimate"`: the rocket's body, fins and protuberances as
//! [`karman_airframe::DragGeometry`] from its surfaces and `[rocket.drag_estimate]`, and the
//! estimated Cd(Mach) curves (karman-airframe `drag`, Niskanen 2009 §3.4).
//!
//! The body is implied by the surfaces: the nose cone from its tip, the tails (transitions)
//! where they are placed, and cylinders of the radius reached so far between them, to
//! `body_length` (default: the aftmost end of a tail or a fin root chord). The Reynolds numbers
//! of the tabulated curves are those of the standard atmosphere at the launch elevation.

use karman_airframe::{
    self as airframe, BodySegment, DragEstimate, DragGeometry, DragModel, FinSetDrag,
    FlowReference, Geometry, LaunchLug, NoseKind, PodDrag, Profile, RailButtonDrag, SurfaceInput,
    TubeFinSetDrag,
};
use karman_math::PhysicalConstants;

use crate::schema::{self, DragEstimateSpec, FinCrossSection, SurfaceFinish};
use crate::{Mission, MissionError};

const SECTION: &str = "rocket.drag_estimate";

fn profile(kind: NoseKind) -> Profile {
    match kind {
        NoseKind::Conical => Profile::Conical,
        NoseKind::Ogive => Profile::Ogive(1.0),
        NoseKind::VonKarman => Profile::Haack(0.0),
        NoseKind::LvHaack => Profile::Haack(1.0 / 3.0),
        NoseKind::Parabolic => Profile::Parabolic(1.0),
        NoseKind::Elliptical => Profile::Ellipsoid,
        NoseKind::PowerSeries(n) => Profile::Power(n),
    }
}

fn cross_section(c: FinCrossSection) -> airframe::FinCrossSection {
    match c {
        FinCrossSection::Square => airframe::FinCrossSection::Square,
        FinCrossSection::Rounded => airframe::FinCrossSection::Rounded,
        FinCrossSection::Airfoil => airframe::FinCrossSection::Airfoil,
    }
}

/// Standard air at the launch elevation: the speed of sound √(γ R T) and ν = μ/ρ with
/// Sutherland's viscosity (ISO 2533).
pub fn launch_air(elevation: f64, c: &PhysicalConstants) -> FlowReference {
    let re = c.isa_earth_radius;
    let big_h = re * elevation / (re + elevation);
    let index = c
        .isa_layers
        .partition_point(|l| l.base_height <= big_h)
        .saturating_sub(1);
    let layer = c.isa_layers[index];
    let t = layer.base_temperature + layer.lapse_rate * (big_h - layer.base_height);
    let p = karman_atmos::isa::analytic_pressure(elevation, c);
    let rho = p / (c.air_gas_constant * t);
    let mu = c.sutherland_b * t.powf(1.5) / (t + c.sutherland_s);
    FlowReference {
        speed_of_sound: (c.heat_capacity_ratio * c.air_gas_constant * t).sqrt(),
        kinematic_viscosity: mu / rho,
    }
}

fn geometry_error(mission: &Mission, reason: String) -> MissionError {
    mission.model_error(
        SECTION,
        airframe::AirframeError::Geometry {
            component: SECTION.to_owned(),
            reason,
        },
    )
}

/// The drag geometry of `mission`'s rocket, whose surfaces are `surfaces` (as built for the
/// airframe), with a motor nozzle of exit radius `nozzle_radius`.
///
/// # Errors
/// [`MissionError::Model`] (section `rocket.drag_estimate` or the surface's) when there is no
/// nose cone, surfaces overlap along the body, a fin set has no `thickness`, or a surface
/// cannot be built.
pub fn drag_geometry(
    mission: &Mission,
    surfaces: &[SurfaceInput],
    nozzle_radius: f64,
) -> Result<DragGeometry, MissionError> {
    let rocket = &mission.spec.rocket;
    let empty = DragEstimateSpec {
        body_length: None,
        finish: SurfaceFinish::Normal,
        roughness: None,
        fins: Default::default(),
        launch_lugs: Default::default(),
        overrides: Default::default(),
        rail_buttons: None,
    };
    let spec = rocket.drag_estimate.as_ref().unwrap_or(&empty);
    let roughness = spec.roughness.unwrap_or_else(|| spec.finish.roughness());
    let csys = match rocket.coordinate_system {
        schema::RocketCoordinateSystem::TailToNose => 1.0,
        schema::RocketCoordinateSystem::NoseToTail => -1.0,
    };
    let constants = PhysicalConstants::SI;
    let model = |name: &str, e: airframe::AirframeError| {
        mission.model_error(&format!("rocket.surfaces.{name}"), e)
    };

    // The rocket's own parts, and each pod's (by pod name).
    let mut parts = Parts::default();
    let mut pods: indexmap::IndexMap<&str, (&schema::PodSpec, Parts)> = indexmap::IndexMap::new();
    for s in surfaces {
        let g = airframe::Surface::geometry_of(s, rocket.radius, &constants)
            .map_err(|e| model(&s.name, e))?;
        let (pod_name, pod) = match pod_of(rocket, &s.name) {
            Some((name, pod)) => (Some(name), Some(pod)),
            None => (None, None),
        };
        let part = match pod_name.zip(pod) {
            Some((name, pod)) => &mut pods.entry(name).or_insert((pod, Parts::default())).1,
            None => &mut parts,
        };
        let copies = pod.map_or(1, |p| p.count);
        part.add(mission, s, g, pod_name, copies, roughness)?;
    }
    let Some((tip, nose_length, nose_radius, nose_profile, nose_name)) = parts.nose.take() else {
        return Err(geometry_error(
            mission,
            "the drag estimate needs a nose cone among the surfaces".to_owned(),
        ));
    };
    let aft_of_tip = |position: f64| csys * (tip - position);
    let (mut fin_sets, mut tube_fins, aft_end) =
        parts.appendages(mission, spec, roughness, nose_length, &aft_of_tip)?;
    let body_end = spec.body_length.unwrap_or(aft_end);
    let body = implied_body(
        mission,
        (nose_name, nose_length, nose_radius, nose_profile),
        std::mem::take(&mut parts.tails),
        body_end,
        spec,
        roughness,
        &aft_of_tip,
    )?;

    let mut pod_bodies = Vec::new();
    for (name, (pod, mut p)) in pods {
        let (fins, tubes, pod_aft) = p.appendages(mission, spec, roughness, 0.0, &aft_of_tip)?;
        fin_sets.extend(fins);
        tube_fins.extend(tubes);
        let Some((pod_tip, length, radius, shape, nose)) = p.nose.take() else {
            if let Some(t) = p.tails.first() {
                return Err(geometry_error(
                    mission,
                    format!(
                        "pod `{name}` has tail `{}` but no nose cone: a pod's body starts with its nose",
                        t.4
                    ),
                ));
            }
            // Fins on no body: no pod body.
            continue;
        };
        let start = aft_of_tip(pod_tip);
        // The pod's end, from its own tip.
        let pod_end = pod.body_length.unwrap_or((pod_aft - start).max(length));
        let pod_of_tip = |position: f64| csys * (tip - position) - start;
        let segments = implied_body(
            mission,
            (nose, length, radius, shape),
            p.tails,
            pod_end,
            spec,
            roughness,
            &pod_of_tip,
        )?;
        pod_bodies.push(PodDrag {
            name: format!("rocket.pods.{name}"),
            count: pod.count,
            position: start,
            body: segments,
        });
    }

    let launch_lugs = spec
        .launch_lugs
        .iter()
        .map(|(name, l)| LaunchLug {
            name: format!("{SECTION}.launch_lugs.{name}"),
            outer_radius: l.outer_radius,
            inner_radius: l.inner_radius,
            length: l.length,
            count: l.count,
            roughness,
        })
        .collect();
    let rail_buttons = match (&spec.rail_buttons, &rocket.rail_buttons) {
        (Some(size), Some(at)) => Some(RailButtonDrag {
            outer_diameter: size.outer_diameter,
            inner_diameter: size.inner_diameter,
            height: size.height,
            inner_height: size.inner_height,
            positions: vec![aft_of_tip(at.upper_position), aft_of_tip(at.lower_position)],
        }),
        _ => None,
    };
    Ok(DragGeometry {
        tube_fins,
        reference_radius: rocket.radius,
        body,
        fins: fin_sets,
        launch_lugs,
        rail_buttons,
        nozzle_exit_radius: nozzle_radius,
        pods: pod_bodies,
    })
}

/// A nose: (tip position, length, base radius, profile, name).
type Nose = (f64, f64, f64, Profile, String);
/// A tail: (forward end, length, fore radius, aft radius, name).
type Tail = (f64, f64, f64, f64, String);
/// A fin set: (root leading edge, fin count, root chord, outline, name).
type Fin = (f64, u32, f64, Vec<[f64; 2]>, String);

/// The surfaces of one body (the rocket's or a pod's), sorted by kind.
#[derive(Default)]
struct Parts {
    nose: Option<Nose>,
    tails: Vec<Tail>,
    fins: Vec<Fin>,
    tube_fins: Vec<TubeFinSetDrag>,
}

impl Parts {
    /// Adds surface `s` of geometry `g` (of pod `pod_name`, `copies` of it around the rocket,
    /// or of the rocket itself) to its kind's list.
    ///
    /// # Errors
    /// A second nose cone in the rocket or in one pod.
    fn add(
        &mut self,
        mission: &Mission,
        s: &SurfaceInput,
        g: Geometry,
        pod_name: Option<&str>,
        copies: u32,
        roughness: f64,
    ) -> Result<(), MissionError> {
        match g {
            Geometry::Nose {
                kind,
                length,
                base_radius,
                ..
            } => {
                if self.nose.is_some() {
                    let within = pod_name.map_or(String::new(), |p| format!(" in pod `{p}`"));
                    return Err(geometry_error(
                        mission,
                        format!(
                            "a second nose cone `{}`{within}: the estimate needs one",
                            s.name
                        ),
                    ));
                }
                self.nose = Some((
                    s.position,
                    length,
                    base_radius,
                    profile(kind),
                    s.name.clone(),
                ));
            }
            Geometry::Tail {
                top_radius,
                bottom_radius,
                length,
            } => self.tails.push((
                s.position,
                length,
                top_radius,
                bottom_radius,
                s.name.clone(),
            )),
            Geometry::Fins {
                n,
                root_chord,
                outline,
                ..
            } => self
                .fins
                .push((s.position, n * copies, root_chord, outline, s.name.clone())),
            Geometry::TubeFins {
                n,
                length,
                outer_radius,
                inner_radius,
                body_radius,
            } => self.tube_fins.push(TubeFinSetDrag {
                name: s.name.clone(),
                count: n * copies,
                length,
                outer_radius,
                inner_radius,
                body_radius,
                // Aft of the tip once the nose is known.
                position: s.position,
                roughness,
            }),
        }
        Ok(())
    }

    /// The fin and tube-fin sets, placed aft of the nose tip by `aft_of_tip`, and the aftmost
    /// end of a tail, a fin root chord or a tube (at least `end`).
    fn appendages(
        &mut self,
        mission: &Mission,
        spec: &DragEstimateSpec,
        roughness: f64,
        end: f64,
        aft_of_tip: &dyn Fn(f64) -> f64,
    ) -> Result<(Vec<FinSetDrag>, Vec<TubeFinSetDrag>, f64), MissionError> {
        let mut aft_end = end;
        for t in &self.tails {
            aft_end = aft_end.max(aft_of_tip(t.0) + t.1);
        }
        let mut fin_sets = Vec::with_capacity(self.fins.len());
        for (position, n, root_chord, outline, name) in std::mem::take(&mut self.fins) {
            let at = aft_of_tip(position);
            aft_end = aft_end.max(at + root_chord);
            let Some(f) = spec.fins.get(&name) else {
                return Err(geometry_error(
                    mission,
                    format!(
                        "fin set `{name}` needs [rocket.drag_estimate.fins.{name}] with its thickness"
                    ),
                ));
            };
            fin_sets.push(FinSetDrag {
                name: name.clone(),
                count: n,
                outline,
                position: at,
                thickness: f.thickness,
                cross_section: cross_section(f.cross_section),
                roughness: f.finish.map_or(roughness, SurfaceFinish::roughness),
            });
        }
        let mut tube_fins = std::mem::take(&mut self.tube_fins);
        for t in &mut tube_fins {
            t.position = aft_of_tip(t.position);
            aft_end = aft_end.max(t.position + t.length);
        }
        Ok((fin_sets, tube_fins, aft_end))
    }
}

/// The body a nose and tails imply: the nose from the tip, the tails where they are placed
/// (`place` gives a position's distance aft of this body's tip), cylinders of the radius
/// reached so far between them, to `body_end` aft of the tip.
fn implied_body(
    mission: &Mission,
    (nose_name, nose_length, nose_radius, nose_profile): (String, f64, f64, Profile),
    tails: Vec<Tail>,
    body_end: f64,
    spec: &DragEstimateSpec,
    roughness: f64,
    place: &dyn Fn(f64) -> f64,
) -> Result<Vec<BodySegment>, MissionError> {
    let mut tails: Vec<_> = tails
        .into_iter()
        .map(|(p, l, top, bottom, name)| (place(p), l, top, bottom, name))
        .collect();
    tails.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut body = vec![BodySegment {
        drag_override: spec.overrides.get(&nose_name).copied(),
        name: nose_name,
        length: nose_length,
        fore_radius: 0.0,
        aft_radius: nose_radius,
        profile: nose_profile,
        roughness,
    }];
    let mut x = nose_length;
    let mut radius = nose_radius;
    let tolerance = 1e-9 * body_end.max(nose_length);
    for (start, length, top, bottom, name) in tails {
        if start < x - tolerance {
            return Err(geometry_error(
                mission,
                format!(
                    "surface `{name}` starts {start} m aft of the nose tip, inside the part before it (which ends at {x} m)"
                ),
            ));
        }
        if start > x + tolerance {
            body.push(tube(start - x, radius, roughness));
        }
        body.push(BodySegment {
            drag_override: spec.overrides.get(&name).copied(),
            name,
            length,
            fore_radius: top,
            aft_radius: bottom,
            profile: Profile::Conical,
            roughness,
        });
        x = start.max(x) + length;
        radius = bottom;
    }
    if body_end > x + tolerance {
        body.push(tube(body_end - x, radius, roughness));
    }
    Ok(body)
}

fn tube(length: f64, radius: f64, roughness: f64) -> BodySegment {
    BodySegment {
        name: "body tube".to_owned(),
        length,
        fore_radius: radius,
        aft_radius: radius,
        profile: Profile::Conical,
        roughness,
        drag_override: None,
    }
}

/// The estimated drag of `mission`'s rocket (see [`drag_geometry`]), tabulated at the
/// standard atmosphere of the launch elevation.
///
/// # Errors
/// As [`drag_geometry`], and [`MissionError::Model`] for dimensions the build-up rejects.
pub fn estimate(
    mission: &Mission,
    surfaces: &[SurfaceInput],
    nozzle_radius: f64,
) -> Result<DragEstimate, MissionError> {
    let geometry = drag_geometry(mission, surfaces, nozzle_radius)?;
    let constants = PhysicalConstants::SI;
    let model =
        DragModel::new(&geometry, &constants).map_err(|e| mission.model_error(SECTION, e))?;
    Ok(model.estimate(&launch_air(mission.spec.environment.elevation, &constants)))
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
