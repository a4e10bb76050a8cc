//! Drag coefficient from the geometry: the component build-up of Niskanen (2009), "Development of
//! an Open Source model rocket simulation software" (the OpenRocket technical documentation), §3.4
//! (docs/physics.md §20), which collects Hoerner (1965) *Fluid-Dynamic Drag*, Barrowman (1967) and
//! Fleeman (2001).
//!
//! The zero-angle-of-attack drag coefficient, on the reference area A_ref = π r_ref², is the
//! sum of
//! - skin friction of the body and the fins ([`friction`]),
//! - pressure drag of the nose, transitions, steps in radius and boattails ([`pressure`]),
//!   of the fins' edges ([`fins`]), of launch lugs and rail buttons ([`parasitic`]) and of
//!   tube fins ([`tube_fins`], with their friction),
//! - base drag of every step down in radius and of the rocket's base ([`pressure`]); with the
//!   motor burning the jet fills the nozzle exit, and the base drag acts on the rest of the
//!   base only (the usual power-on treatment, e.g. Mandell, Caporaso & Bengen 1973, *Topics
//!   in Advanced Model Rocketry*, ch. 3).
//!
//! [`DragModel::new`] validates the geometry and precomputes every per-component quantity
//! (wetted areas, nose tables, fin planforms) once; [`DragModel::components`] evaluates the
//! terms at one flight condition and [`DragModel::estimate`] tabulates them against Mach from
//! 0 to [`ESTIMATE_MAX_MACH`] at the Reynolds numbers of one reference atmosphere.
//! [`BodyLift`] gives, from the same geometry, OpenRocket's centre of pressure at an angle of
//! attack (Barrowman with Galejs' body lift), for the estimate's report.

pub mod body_lift;
pub mod fins;
pub mod friction;
pub mod parasitic;
pub mod pressure;
pub mod shape;
pub mod tube_fins;

use std::f64::consts::PI;

use karman_math::{PhysicalConstants, Table1};

use crate::error::{AirframeError, finite, non_negative, positive};
pub use body_lift::BodyLift;
pub use fins::FinCrossSection;
pub use parasitic::{LaunchLug, RailButtonDrag};
pub use shape::Profile;
pub use tube_fins::TubeFinSetDrag;

/// Highest Mach number of the tabulated estimate.
pub const ESTIMATE_MAX_MACH: f64 = 3.0;
/// Mach spacing of the tabulated estimate.
pub const ESTIMATE_MACH_STEP: f64 = 0.01;
/// Extra samples below the first step, where the Reynolds number (∝ M) changes the skin
/// friction fastest.
const LOW_MACH: [f64; 3] = [0.001, 0.002, 0.005];

/// One segment of the body of revolution, in order from the nose tip.
#[derive(Debug, Clone, PartialEq)]
pub struct BodySegment {
    /// Its name, for error messages.
    pub name: String,
    /// Axial length (m).
    pub length: f64,
    /// Radius at its forward end (m); 0 for a nose cone.
    pub fore_radius: f64,
    /// Radius at its aft end (m).
    pub aft_radius: f64,
    /// Profile between the ends (ignored when both radii are equal: a tube).
    pub profile: Profile,
    /// Sand roughness of its surface (m).
    pub roughness: f64,
    /// A drag coefficient (on the reference area) that replaces the segment's own friction,
    /// pressure and base terms (OpenRocket's component CD override); the segment then does
    /// not count in the body's fineness either.
    pub drag_override: Option<f64>,
}

/// A fin set.
#[derive(Debug, Clone, PartialEq)]
pub struct FinSetDrag {
    /// Its name, for error messages.
    pub name: String,
    /// Number of fins.
    pub count: u32,
    /// One fin's outline `(x aft of the root leading edge, y outward from the root)` (m).
    pub outline: Vec<[f64; 2]>,
    /// Distance of the root leading edge aft of the nose tip (m).
    pub position: f64,
    /// Fin thickness (m).
    pub thickness: f64,
    /// Edge profile.
    pub cross_section: FinCrossSection,
    /// Sand roughness of its surface (m).
    pub roughness: f64,
}

/// The bodies of a pod set (OpenRocket's `PodSet`; docs/physics.md §22): `count` copies of one body
/// of revolution beside the main body. OpenRocket 24.12 sums every drag term of a component once
/// per instance (Niskanen 2009 §3.4 per component, times the instance count): each pod's skin
/// friction joins the body's (under the rocket's one fineness correction, whose length and radius
/// span the pods too), its nose and tail pressure drag and the base drag of its aft end count
/// `count` times, and a pod that starts blunt adds the stagnation drag of its front face.
#[derive(Debug, Clone, PartialEq)]
pub struct PodDrag {
    /// Its name, for error messages.
    pub name: String,
    /// Number of pods.
    pub count: u32,
    /// Distance of the pod body's forward end aft of the rocket's nose tip (m).
    pub position: f64,
    /// One pod's body segments from its forward end aft, contiguous.
    pub body: Vec<BodySegment>,
}

/// The geometry the drag estimate needs.
#[derive(Debug, Clone, PartialEq)]
pub struct DragGeometry {
    /// Reference radius (m): the drag coefficients are referred to π r².
    pub reference_radius: f64,
    /// Body segments from the nose tip aft, contiguous.
    pub body: Vec<BodySegment>,
    /// Fin sets.
    pub fins: Vec<FinSetDrag>,
    /// Tube fin sets.
    pub tube_fins: Vec<TubeFinSetDrag>,
    /// Launch lugs.
    pub launch_lugs: Vec<LaunchLug>,
    /// Rail buttons, if any.
    pub rail_buttons: Option<RailButtonDrag>,
    /// Nozzle exit radius (m) of the power-on base.
    pub nozzle_exit_radius: f64,
    /// Pod sets.
    pub pods: Vec<PodDrag>,
}

/// The drag terms at one flight condition, on the reference area.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DragComponents {
    /// Skin friction.
    pub friction: f64,
    /// Pressure drag (forebody, steps, fin edges, protuberances).
    pub pressure: f64,
    /// Base drag with the motor off.
    pub base: f64,
    /// Base drag with the motor burning.
    pub base_power_on: f64,
}

impl DragComponents {
    /// Total drag coefficient with the motor off.
    #[must_use]
    pub fn power_off(&self) -> f64 {
        self.friction + self.pressure + self.base
    }

    /// Total drag coefficient with the motor burning.
    #[must_use]
    pub fn power_on(&self) -> f64 {
        self.friction + self.pressure + self.base_power_on
    }
}

/// The atmosphere the estimate's Reynolds numbers are taken in (usually the launch site's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlowReference {
    /// Speed of sound (m/s).
    pub speed_of_sound: f64,
    /// Kinematic viscosity ν = μ/ρ (m²/s).
    pub kinematic_viscosity: f64,
}

/// The tabulated estimate: every term against Mach.
#[derive(Debug, Clone, PartialEq)]
pub struct DragEstimate {
    /// Mach numbers, 0 to [`ESTIMATE_MAX_MACH`].
    pub mach: Vec<f64>,
    /// The terms at each Mach number.
    pub components: Vec<DragComponents>,
}

impl DragEstimate {
    fn table(&self, f: impl Fn(&DragComponents) -> f64) -> Result<Table1, AirframeError> {
        Table1::linear(self.mach.clone(), self.components.iter().map(f).collect()).map_err(
            |source| AirframeError::Table {
                component: "drag estimate".to_owned(),
                quantity: "drag coefficient",
                error: source,
            },
        )
    }

    /// Cd(Mach) with the motor off, linear between the samples, held beyond them.
    ///
    /// # Errors
    /// [`AirframeError::Table`] if a coefficient is not finite.
    pub fn power_off(&self) -> Result<Table1, AirframeError> {
        self.table(DragComponents::power_off)
    }

    /// Cd(Mach) with the motor burning.
    ///
    /// # Errors
    /// As [`DragEstimate::power_off`].
    pub fn power_on(&self) -> Result<Table1, AirframeError> {
        self.table(DragComponents::power_on)
    }
}

/// Per-segment data computed once.
#[derive(Debug, Clone, PartialEq)]
struct Segment {
    wetted_area: f64,
    roughness: f64,
    /// Pressure coefficient of its own shape on its frontal area.
    shape: SegmentShape,
    frontal_area: f64,
    /// Area of the step up from the previous segment (stagnation).
    step_up: f64,
    /// Area of the step down to the next segment (base), not counting the rocket's base.
    step_down: f64,
    /// Its drag coefficient when overridden.
    drag_override: Option<f64>,
    /// Copies of it: the number of pods of a pod segment, else 1.
    count: f64,
}

#[derive(Debug, Clone, PartialEq)]
enum SegmentShape {
    /// Equal radii: no pressure drag of its own.
    Tube,
    /// A disk (zero length): a face up or down.
    Face { up: bool },
    /// A contraction of this fineness.
    Boattail(f64),
    /// A nose or expanding transition: its coefficient against Mach.
    Nose(pressure::Polyline),
}

#[derive(Debug, Clone, PartialEq)]
struct Fins {
    count: f64,
    area: f64,
    span: f64,
    mean_chord: f64,
    cos_leading_sweep: f64,
    thickness: f64,
    cross_section: FinCrossSection,
    roughness: f64,
}

/// The drag build-up of one rocket, precomputed.
#[derive(Debug, Clone, PartialEq)]
pub struct DragModel {
    reference_area: f64,
    length: f64,
    body_correction: f64,
    segments: Vec<Segment>,
    fins: Vec<Fins>,
    /// Tube fin sets with their `[interstice, wetted]` areas of one tube.
    tube_fins: Vec<(TubeFinSetDrag, [f64; 2])>,
    launch_lugs: Vec<LaunchLug>,
    rail_buttons: Option<RailButtonDrag>,
    base_area: f64,
    nozzle_area: f64,
}

/// The per-segment data of one body of revolution whose segments count `count` times; the
/// last segment of a `closed` body (a pod) has its aft face as a step down to nothing (base
/// drag), the main body's base is the rocket's (with the jet).
fn body_segments(body: &[BodySegment], gamma: f64, count: f64, closed: bool) -> Vec<Segment> {
    let n = body.len();
    let mut segments = Vec::with_capacity(n);
    for (i, s) in body.iter().enumerate() {
        let (fore, aft) = if s.length > 0.0 {
            (s.fore_radius, s.aft_radius)
        } else {
            let r = s.fore_radius.max(s.aft_radius);
            (r, r)
        };
        let frontal_area = PI * (fore * fore - aft * aft).abs();
        let shape = if s.length <= 0.0 {
            SegmentShape::Face {
                up: s.fore_radius > s.aft_radius,
            }
        } else if (fore - aft).abs() <= f64::EPSILON * fore.max(aft) {
            SegmentShape::Tube
        } else {
            let fineness = s.length / (2.0 * (aft - fore).abs());
            if aft < fore {
                SegmentShape::Boattail(fineness)
            } else {
                let sin_phi = shape::aft_slope_sine(s.profile, fore, aft, s.length);
                SegmentShape::Nose(pressure::nose_table(s.profile, fineness, sin_phi, gamma))
            }
        };
        let previous_aft = if i == 0 { 0.0 } else { body[i - 1].aft_radius };
        let next_fore = body.get(i + 1).map_or(0.0, |b| b.fore_radius);
        let face_fore = if s.length <= 0.0 {
            fore.max(aft)
        } else {
            s.fore_radius
        };
        let step_up = PI * (face_fore * face_fore - previous_aft * previous_aft).max(0.0);
        let step_down = if i + 1 < n || closed {
            PI * (aft * aft - next_fore * next_fore).max(0.0)
        } else {
            0.0
        };
        segments.push(Segment {
            wetted_area: shape::wetted_area(s.profile, fore, aft, s.length),
            roughness: s.roughness,
            shape,
            frontal_area,
            step_up,
            step_down,
            drag_override: s.drag_override,
            count,
        });
    }
    segments
}

/// A body segment's dimensions, roughness, drag override and nose profile, checked.
fn check_segment(s: &BodySegment) -> Result<(), AirframeError> {
    non_negative(&s.name, "length", s.length)?;
    non_negative(&s.name, "fore radius", s.fore_radius)?;
    non_negative(&s.name, "aft radius", s.aft_radius)?;
    non_negative(&s.name, "roughness", s.roughness)?;
    if let Some(cd) = s.drag_override {
        finite(&s.name, "drag override", cd)?;
    }
    check_profile(&s.name, s.profile)
}

fn check_profile(name: &str, profile: Profile) -> Result<(), AirframeError> {
    if let Some((p, min, max)) = profile.parameter() {
        finite(name, "shape parameter", p)?;
        if !(min..=max).contains(&p) {
            return Err(AirframeError::OutOfRange {
                component: name.to_owned(),
                quantity: "shape parameter",
                value: p,
                min,
                max,
            });
        }
    }
    Ok(())
}

impl DragModel {
    /// Validates `geometry` and precomputes its terms, with the ratio of specific heats of
    /// `constants` (the transonic slope of the cone law).
    ///
    /// # Errors
    /// [`AirframeError`] naming the segment, fin set or protuberance with a non-finite,
    /// negative or out-of-range dimension, or a body without a positive length.
    pub fn new(
        geometry: &DragGeometry,
        constants: &PhysicalConstants,
    ) -> Result<DragModel, AirframeError> {
        let r_ref = positive(
            "drag estimate",
            "reference radius",
            geometry.reference_radius,
        )?;
        let nozzle = non_negative(
            "drag estimate",
            "nozzle exit radius",
            geometry.nozzle_exit_radius,
        )?;
        let reference_area = PI * r_ref * r_ref;
        let mut body_length = 0.0;
        let mut fineness_length = 0.0;
        let mut max_radius: f64 = 0.0;
        for s in &geometry.body {
            check_segment(s)?;
            body_length += s.length;
            if s.drag_override.is_none() {
                fineness_length += s.length;
                max_radius = max_radius.max(s.fore_radius).max(s.aft_radius);
            }
        }
        if body_length <= 0.0 || max_radius <= 0.0 {
            return Err(AirframeError::Geometry {
                component: "drag estimate".to_owned(),
                reason: "the body has no length or no radius".to_owned(),
            });
        }
        let mut length = body_length;
        let mut fins = Vec::with_capacity(geometry.fins.len());
        for f in &geometry.fins {
            finite(&f.name, "position", f.position)?;
            non_negative(&f.name, "thickness", f.thickness)?;
            non_negative(&f.name, "roughness", f.roughness)?;
            for p in &f.outline {
                finite(&f.name, "outline point", p[0])?;
                finite(&f.name, "outline point", p[1])?;
            }
            let p = fins::planform(&f.outline);
            length = length.max(f.position + p.aft_extent);
            fins.push(Fins {
                count: f64::from(f.count),
                area: p.area,
                span: p.span,
                mean_chord: p.mean_chord,
                cos_leading_sweep: p.cos_leading_sweep,
                thickness: f.thickness,
                cross_section: f.cross_section,
                roughness: f.roughness,
            });
        }
        let mut tube_fins = Vec::with_capacity(geometry.tube_fins.len());
        for t in &geometry.tube_fins {
            finite(&t.name, "position", t.position)?;
            positive(&t.name, "length", t.length)?;
            positive(&t.name, "outer radius", t.outer_radius)?;
            non_negative(&t.name, "inner radius", t.inner_radius)?;
            non_negative(&t.name, "body radius", t.body_radius)?;
            non_negative(&t.name, "roughness", t.roughness)?;
            if t.inner_radius > t.outer_radius {
                return Err(AirframeError::Geometry {
                    component: t.name.clone(),
                    reason: "inner radius larger than the outer radius".to_owned(),
                });
            }
            length = length.max(t.position + t.length);
            tube_fins.push((t.clone(), tube_fins::areas(t)));
        }
        for l in &geometry.launch_lugs {
            positive(&l.name, "outer radius", l.outer_radius)?;
            non_negative(&l.name, "inner radius", l.inner_radius)?;
            non_negative(&l.name, "length", l.length)?;
            non_negative(&l.name, "roughness", l.roughness)?;
            if l.inner_radius > l.outer_radius {
                return Err(AirframeError::Geometry {
                    component: l.name.clone(),
                    reason: "inner radius larger than the outer radius".to_owned(),
                });
            }
        }
        if let Some(b) = &geometry.rail_buttons {
            const C: &str = "rail_buttons";
            non_negative(C, "outer diameter", b.outer_diameter)?;
            non_negative(C, "inner diameter", b.inner_diameter)?;
            non_negative(C, "height", b.height)?;
            non_negative(C, "inner height", b.inner_height)?;
            for x in &b.positions {
                finite(C, "position", *x)?;
            }
        }

        let gamma = constants.heat_capacity_ratio;
        let mut segments = body_segments(&geometry.body, gamma, 1.0, false);
        for pod in &geometry.pods {
            finite(&pod.name, "position", pod.position)?;
            if pod.count == 0 {
                return Err(AirframeError::NotPositive {
                    component: pod.name.clone(),
                    quantity: "pod count",
                    value: 0.0,
                });
            }
            let mut pod_length = 0.0;
            for s in &pod.body {
                check_segment(s)?;
                pod_length += s.length;
                if s.drag_override.is_none() {
                    max_radius = max_radius.max(s.fore_radius).max(s.aft_radius);
                }
            }
            // OpenRocket's fineness and Reynolds lengths run over every body component,
            // the pods' included.
            fineness_length = fineness_length.max(pod.position + pod_length);
            length = length.max(pod.position + pod_length);
            segments.extend(body_segments(&pod.body, gamma, f64::from(pod.count), true));
        }
        // The rocket's base, unless its last segment's drag is overridden.
        let last_aft = geometry
            .body
            .last()
            .filter(|s| s.drag_override.is_none())
            .map_or(0.0, |s| s.aft_radius);
        Ok(DragModel {
            reference_area,
            length,
            body_correction: friction::body_fineness_correction(fineness_length, max_radius),
            segments,
            fins,
            tube_fins,
            launch_lugs: geometry.launch_lugs.clone(),
            rail_buttons: geometry.rail_buttons.clone(),
            base_area: PI * last_aft * last_aft,
            nozzle_area: PI * nozzle * nozzle,
        })
    }

    /// The rocket's aerodynamic length L of the Reynolds number (m): nose tip to the aftmost
    /// point of the body or the fins.
    #[must_use]
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The drag terms at Mach `mach` and airspeed `speed` in air of kinematic viscosity `nu`
    /// (Reynolds number V L / ν).
    #[must_use]
    pub fn components(&self, mach: f64, speed: f64, nu: f64) -> DragComponents {
        let a_ref = self.reference_area;
        let reynolds = speed * self.length / nu;
        let cf = |k: f64| friction::component_coefficient(mach, reynolds, k, self.length);
        let stagnation = pressure::stagnation_coefficient(mach);
        let base = pressure::base_coefficient(mach);

        let mut body_friction = 0.0;
        let mut pressure_cd = 0.0;
        let mut base_cd = 0.0;
        // `count` is 1 on the main body (a product by 1 is exact) and the number of pods on
        // a pod's segments.
        for s in &self.segments {
            if let Some(cd) = s.drag_override {
                pressure_cd += cd * a_ref * s.count;
                continue;
            }
            body_friction += cf(s.roughness) * s.wetted_area * s.count;
            pressure_cd += match &s.shape {
                SegmentShape::Tube => 0.0,
                SegmentShape::Face { up: true } => stagnation * s.frontal_area,
                SegmentShape::Face { up: false } => base * s.frontal_area,
                SegmentShape::Boattail(f) => {
                    pressure::boattail_coefficient(*f, base) * s.frontal_area
                }
                SegmentShape::Nose(t) => t.eval(mach) * s.frontal_area,
            } * s.count;
            pressure_cd += stagnation * s.step_up * s.count;
            base_cd += base * s.step_down * s.count;
        }
        let mut fin_friction = 0.0;
        for f in &self.fins {
            if f.area <= 0.0 || f.mean_chord <= 0.0 {
                continue;
            }
            fin_friction +=
                f.count * cf(f.roughness) * (1.0 + 2.0 * f.thickness / f.mean_chord) * 2.0 * f.area;
            pressure_cd += f.count
                * fins::edge_coefficient(f.cross_section, f.cos_leading_sweep, mach)
                * f.span
                * f.thickness;
        }
        for (t, [interstice, wetted]) in &self.tube_fins {
            let count = f64::from(t.count);
            fin_friction += count * cf(t.roughness) * wetted;
            pressure_cd += count * tube_fins::pressure(t, *interstice, mach, speed, nu);
        }
        let mut parasitic = 0.0;
        for l in &self.launch_lugs {
            parasitic += parasitic::launch_lug(l, mach, speed, nu, a_ref);
        }
        if let Some(b) = &self.rail_buttons {
            parasitic += parasitic::rail_buttons(b, mach, speed, nu, a_ref);
        }
        let friction = (body_friction * self.body_correction + fin_friction) / a_ref;
        let pressure = pressure_cd / a_ref + parasitic;
        let rocket_base = base * self.base_area / a_ref;
        let jet_base = base * (self.base_area - self.nozzle_area).max(0.0) / a_ref;
        DragComponents {
            friction,
            pressure,
            base: base_cd / a_ref + rocket_base,
            base_power_on: base_cd / a_ref + jet_base,
        }
    }

    /// The terms tabulated every [`ESTIMATE_MACH_STEP`] from Mach 0 to [`ESTIMATE_MAX_MACH`]
    /// (and at Mach 0.001, 0.002, 0.005), at airspeed M·a and Reynolds number M a L / ν of
    /// `flow`.
    #[must_use]
    pub fn estimate(&self, flow: &FlowReference) -> DragEstimate {
        let n = (ESTIMATE_MAX_MACH / ESTIMATE_MACH_STEP).round() as usize;
        let mut mach: Vec<f64> = (0..=n).map(|i| i as f64 * ESTIMATE_MACH_STEP).collect();
        mach.splice(1..1, LOW_MACH);
        let components = mach
            .iter()
            .map(|&m| self.components(m, m * flow.speed_of_sound, flow.kinematic_viscosity))
            .collect();
        DragEstimate { mach, components }
    }
}
