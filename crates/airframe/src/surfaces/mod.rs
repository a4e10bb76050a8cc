//! Aerodynamic surfaces: nose cones, fin sets, tube fin sets and tails.
//!
//! Each surface is placed at a reference point of the rocket's user axis (docs/physics.md §2.5:
//! the nose tip, the fin root-chord leading edge, the tail's forward end); its CP lies
//! `cp_local` aft of that point. [`Surface`] carries what the equations of motion need (CP in
//! body axes from the CDM, reference area, Mach-dependent coefficients) plus its resolved
//! geometry for reports and drawings.

mod fins;
mod nose;
mod tail;
mod tube_fins;

use std::f64::consts::PI;

use karman_math::PhysicalConstants;

pub use fins::{
    Airfoil, AngleUnit, EllipticalFinsSpec, FinAerodynamics, FreeFormFinsSpec, Sweep,
    TrapezoidalFinsSpec,
};
pub use nose::{NoseConeSpec, NoseKind};
pub use tail::TailSpec;
pub use tube_fins::TubeFinsSpec;

use crate::error::{AirframeError, finite};

/// What kind of surface to build, with its dimensions.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceSpec {
    /// A nose cone (reference point: its tip).
    Nose(NoseConeSpec),
    /// Trapezoidal fins (reference point: the root-chord leading edge).
    TrapezoidalFins(TrapezoidalFinsSpec),
    /// Elliptical fins (reference point: the root-chord leading edge).
    EllipticalFins(EllipticalFinsSpec),
    /// Free-form fins (reference point: the root-chord leading edge).
    FreeFormFins(FreeFormFinsSpec),
    /// A conical tail or transition (reference point: its forward end).
    Tail(TailSpec),
    /// A tube fin set (reference point: the tubes' forward end).
    TubeFins(TubeFinsSpec),
}

/// One named surface of the rocket, at `position` on the user axis.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceInput {
    /// The user's name for it (the mission table name).
    pub name: String,
    /// Position of its reference point in the rocket's user coordinates (m).
    pub position: f64,
    /// Kind and dimensions.
    pub spec: SurfaceSpec,
    /// The pod set it belongs to, if any: the surface is then repeated on every pod.
    pub pod: Option<PodPlacement>,
}

/// Where the copies of a pod surface sit (docs/physics.md §22): OpenRocket's pod set (Niskanen 2009
/// §3.2 sums the Barrowman terms per component; OpenRocket 24.12 sums them per instance of a
/// component). Each copy is the surface on its own pod's axis: the same normal-force slope and
/// axial CP (OpenRocket takes each instance's CP on the rocket's axis), so the set's slope is
/// `count` times one copy's. The roll position matters only for a set of one or two fins, whose
/// slope depends on the flow's roll angle ([`FinAerodynamics::roll_factor`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PodPlacement {
    /// Number of pods, evenly spaced around the rocket axis.
    pub count: u32,
    /// Roll position of the first pod about the rocket axis (rad); the others at
    /// `+ 2π i / count`. A pod's fins sit at their own angular positions plus their pod's.
    pub angular_position: f64,
}

impl PodPlacement {
    /// `count` as a factor.
    #[must_use]
    pub fn factor(&self) -> f64 {
        f64::from(self.count)
    }

    /// The mean over the pods of a fin set's [`FinAerodynamics::roll_factor`] at the flow's
    /// roll angle `theta` (rad): each pod sees the flow at `theta` less its own position.
    #[must_use]
    pub fn mean_roll_factor(&self, fins: &FinAerodynamics, theta: f64) -> f64 {
        let k = self.count.max(1);
        let sum: f64 = (0..k)
            .map(|j| {
                let pod = self.angular_position + 2.0 * PI * f64::from(j) / f64::from(k);
                fins.roll_factor(theta - pod)
            })
            .sum();
        sum / f64::from(k)
    }
}

/// The resolved shape of a surface, in its local frame (x aft of the reference point).
#[derive(Debug, Clone, PartialEq)]
pub enum Geometry {
    /// A nose cone.
    Nose {
        /// Profile family.
        kind: NoseKind,
        /// Effective length (m), shortened by a bluff tip.
        length: f64,
        /// Base radius (m).
        base_radius: f64,
        /// Profile `(x aft of the tip, radius)`.
        profile: Vec<[f64; 2]>,
    },
    /// A fin set.
    Fins {
        /// Number of fins.
        n: u32,
        /// Root chord (m).
        root_chord: f64,
        /// Span (m).
        span: f64,
        /// Body radius at the fins (m).
        body_radius: f64,
        /// One fin's outline `(x aft of the root leading edge, y outward from the root)`.
        outline: Vec<[f64; 2]>,
    },
    /// A tube fin set.
    TubeFins {
        /// Number of tubes.
        n: u32,
        /// Tube length (m).
        length: f64,
        /// Outer radius of a tube (m).
        outer_radius: f64,
        /// Inner radius of a tube (m).
        inner_radius: f64,
        /// Body radius at the tubes (m).
        body_radius: f64,
    },
    /// A conical tail or transition.
    Tail {
        /// Radius at the forward end (m).
        top_radius: f64,
        /// Radius at the aft end (m).
        bottom_radius: f64,
        /// Length (m).
        length: f64,
    },
}

impl Geometry {
    /// Axial extent of the surface aft of its reference point (m).
    #[must_use]
    pub fn length(&self) -> f64 {
        match self {
            Geometry::Nose { length, .. }
            | Geometry::Tail { length, .. }
            | Geometry::TubeFins { length, .. } => *length,
            Geometry::Fins { outline, .. } => {
                let max = outline
                    .iter()
                    .map(|p| p[0])
                    .fold(f64::NEG_INFINITY, f64::max);
                let min = outline.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
                max - min.min(0.0)
            }
        }
    }

    /// The largest radius the surface reaches (m): base, bottom/top or body + span.
    #[must_use]
    pub fn max_radius(&self) -> f64 {
        match self {
            Geometry::Nose { base_radius, .. } => *base_radius,
            Geometry::Tail {
                top_radius,
                bottom_radius,
                ..
            } => top_radius.max(*bottom_radius),
            Geometry::Fins {
                body_radius, span, ..
            } => body_radius + span,
            Geometry::TubeFins {
                body_radius,
                outer_radius,
                ..
            } => body_radius + 2.0 * outer_radius,
        }
    }
}

/// Mach dependence of a surface's coefficients.
#[derive(Debug, Clone, PartialEq)]
enum Aero {
    /// Constant normal-force slope (nose, tail), no roll terms.
    Constant(f64),
    /// A fin set (closed forms in Mach).
    Fins(Box<FinAerodynamics>),
}

/// One aerodynamic surface as the equations of motion use it (docs/physics.md §7.2).
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    /// The user's name for it.
    pub name: String,
    /// Reference point in the rocket's user coordinates (m).
    pub position: f64,
    /// CP distance aft of the reference point, local frame (m).
    pub cp_local: f64,
    /// CP in body axes measured from the centre of dry mass, `p` of docs/physics.md §2.5 (m).
    pub cp_body: [f64; 3],
    /// Reference area `π r_s²` of the coefficients (m²), times the number of pods for a pod
    /// surface: the force on all its copies is `q · reference_area · CNα · α`.
    pub reference_area: f64,
    /// Reference radius r_s (m): the nose base radius, the fins' body radius, or the tail's
    /// reference radius.
    pub radius: f64,
    /// Resolved shape.
    pub geometry: Geometry,
    /// The pod set it is repeated on, if any ([`SurfaceInput::pod`]); the reference area
    /// then counts every pod.
    pub pod: Option<PodPlacement>,
    aero: Aero,
}

impl Surface {
    /// Builds a surface; `cdm` is the rocket's centre of dry mass, `csys` its coordinate
    /// system sign and `constants` the unit system. Returns the surface and any warnings about
    /// its geometry.
    ///
    /// # Errors
    /// [`AirframeError`] for impossible dimensions.
    pub(crate) fn build(
        input: &SurfaceInput,
        rocket_radius: f64,
        csys: f64,
        cdm: f64,
        constants: &PhysicalConstants,
    ) -> Result<(Surface, Vec<String>), AirframeError> {
        let name = input.name.as_str();
        let position = finite(name, "position", input.position)?;
        if let Some(pod) = input.pod {
            if pod.count == 0 {
                return Err(AirframeError::NotPositive {
                    component: name.to_owned(),
                    quantity: "pod count",
                    value: 0.0,
                });
            }
            finite(name, "pod angular position", pod.angular_position)?;
        }
        let (geometry, aero, cp_local, radius, warnings) = match &input.spec {
            SurfaceSpec::Nose(spec) => {
                let (n, w) = nose::build(name, spec, rocket_radius, constants)?;
                // Rocket.add_nose passes the base radius as the reference radius: CNα = 2.
                let g = Geometry::Nose {
                    kind: n.kind,
                    length: n.length,
                    base_radius: n.base_radius,
                    profile: n.profile,
                };
                (g, Aero::Constant(2.0), n.cp_local, n.base_radius, w)
            }
            SurfaceSpec::TrapezoidalFins(spec) => {
                fin_parts(fins::trapezoidal(name, spec, rocket_radius)?)
            }
            SurfaceSpec::EllipticalFins(spec) => {
                fin_parts(fins::elliptical(name, spec, rocket_radius)?)
            }
            SurfaceSpec::FreeFormFins(spec) => {
                fin_parts(fins::free_form(name, spec, rocket_radius)?)
            }
            SurfaceSpec::Tail(spec) => {
                let t = tail::build(name, spec, rocket_radius)?;
                let g = Geometry::Tail {
                    top_radius: t.top_radius,
                    bottom_radius: t.bottom_radius,
                    length: t.length,
                };
                (
                    g,
                    Aero::Constant(t.cn_alpha),
                    t.cp_local,
                    t.reference_radius,
                    Vec::new(),
                )
            }
            SurfaceSpec::TubeFins(spec) => {
                let (body, cn_alpha, cp_local) = tube_fins::build(name, spec, rocket_radius)?;
                let g = Geometry::TubeFins {
                    n: spec.n,
                    length: spec.length,
                    outer_radius: spec.outer_radius,
                    inner_radius: spec.inner_radius,
                    body_radius: body,
                };
                (g, Aero::Constant(cn_alpha), cp_local, body, Vec::new())
            }
        };
        let surface = Surface {
            name: input.name.clone(),
            position,
            cp_local,
            cp_body: [0.0, 0.0, csys * (position - cdm) - cp_local],
            reference_area: match input.pod {
                None => PI * radius * radius,
                Some(pod) => PI * radius * radius * pod.factor(),
            },
            radius,
            geometry,
            pod: input.pod,
            aero,
        };
        Ok((surface, warnings))
    }

    /// The resolved shape of the surface `input` on a rocket of radius `rocket_radius`, as
    /// [`Surface::geometry`] holds it once built (the drag estimate reads it before the
    /// rocket exists).
    ///
    /// # Errors
    /// [`AirframeError`] for impossible dimensions.
    pub fn geometry_of(
        input: &SurfaceInput,
        rocket_radius: f64,
        constants: &PhysicalConstants,
    ) -> Result<Geometry, AirframeError> {
        Surface::build(input, rocket_radius, 1.0, 0.0, constants).map(|(s, _)| s.geometry)
    }

    /// Normal-force slope CNα(Mach) per radian on [`Surface::reference_area`].
    #[inline]
    #[must_use]
    pub fn cn_alpha(&self, mach: f64) -> f64 {
        match &self.aero {
            Aero::Constant(c) => *c,
            Aero::Fins(f) => f.cn_alpha(mach),
        }
    }

    /// Roll forcing coefficient `C_lf,δ(Mach) · δ` (cant folded in; 0 for non-fins), such
    /// that the forcing moment is `½ρV² A d · roll_forcing(Mach)` (docs/physics.md §7.6).
    #[inline]
    #[must_use]
    pub fn roll_forcing(&self, mach: f64) -> f64 {
        match &self.aero {
            Aero::Constant(_) => 0.0,
            Aero::Fins(f) => f.roll_forcing_derivative(mach) * f.cant_angle,
        }
    }

    /// Roll damping coefficient derivative `C_ld,ω(Mach)` (0 for non-fins); the damping
    /// moment is `½ρV² A d · C_ld,ω · ω3 d / (2V)` (docs/physics.md §7.6).
    #[inline]
    #[must_use]
    pub fn roll_damping(&self, mach: f64) -> f64 {
        match &self.aero {
            Aero::Constant(_) => 0.0,
            Aero::Fins(f) => f.roll_damping_derivative(mach),
        }
    }

    /// `[CNα, roll forcing, roll damping]` at `mach`: the values of [`Surface::cn_alpha`],
    /// [`Surface::roll_forcing`] and [`Surface::roll_damping`] with the fin set's
    /// Mach-dependent slope evaluated once (the equations of motion need all three).
    #[inline]
    #[must_use]
    pub fn coefficients(&self, mach: f64) -> [f64; 3] {
        match &self.aero {
            Aero::Constant(c) => [*c, 0.0, 0.0],
            Aero::Fins(f) => f.coefficients(mach),
        }
    }

    /// Reference length `d = 2 r_s` of the roll coefficients (m).
    #[inline]
    #[must_use]
    pub fn reference_length(&self) -> f64 {
        2.0 * self.radius
    }

    /// The CP in the rocket's user coordinates, `z_u − csys · cp_local` (docs/physics.md §2.5).
    #[must_use]
    pub fn cp_user(&self, csys: f64) -> f64 {
        self.position - csys * self.cp_local
    }

    /// The fin-set constants (K_f, K_d, G, Y_ma, ...) if this surface is a fin set.
    #[must_use]
    pub fn fin_aerodynamics(&self) -> Option<&FinAerodynamics> {
        match &self.aero {
            Aero::Fins(f) => Some(f),
            Aero::Constant(_) => None,
        }
    }

    /// True for fin sets.
    #[must_use]
    pub fn is_fin_set(&self) -> bool {
        matches!(self.aero, Aero::Fins(_))
    }
}

type Parts = (Geometry, Aero, f64, f64, Vec<String>);

fn fin_parts((set, warnings): (fins::FinSet, Vec<String>)) -> Parts {
    let radius = set.aero.reference_radius;
    let g = Geometry::Fins {
        n: set.aero.n,
        root_chord: set.root_chord,
        span: set.span,
        body_radius: set.aero.body_radius,
        outline: set.outline,
    };
    (
        g,
        Aero::Fins(Box::new(set.aero)),
        set.cp_local,
        radius,
        warnings,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn pod_fins(pod: Option<PodPlacement>) -> Surface {
        let input = SurfaceInput {
            name: "fins".into(),
            position: 0.4,
            spec: SurfaceSpec::TrapezoidalFins(TrapezoidalFinsSpec {
                n: 2,
                root_chord: 0.03,
                tip_chord: 0.01,
                span: 0.02,
                sweep: Sweep::Length(0.01),
                cant_angle_deg: 0.0,
                angular_position_deg: 90.0,
                radius: Some(0.007),
                airfoil: None,
            }),
            pod,
        };
        Surface::build(&input, 0.017, -1.0, 0.2, &PhysicalConstants::SI)
            .expect("surface")
            .0
    }

    #[test]
    fn a_pod_surface_counts_once_per_pod() {
        let one = pod_fins(None);
        let three = pod_fins(Some(PodPlacement {
            count: 3,
            angular_position: 0.0,
        }));
        assert!((three.reference_area - 3.0 * one.reference_area).abs() < 1e-18);
        assert!(three.cn_alpha(0.3).to_bits() == one.cn_alpha(0.3).to_bits());
        assert!(three.cp_body.map(f64::to_bits) == one.cp_body.map(f64::to_bits));
        // No pods is an error, not a surface that vanishes.
        let input = SurfaceInput {
            pod: Some(PodPlacement {
                count: 0,
                angular_position: 0.0,
            }),
            ..SurfaceInput {
                name: "n".into(),
                position: 0.0,
                spec: SurfaceSpec::Nose(NoseConeSpec {
                    length: 0.1,
                    kind: NoseKind::Conical,
                    base_radius: Some(0.01),
                    bluffness: 0.0,
                }),
                pod: None,
            }
        };
        assert!(Surface::build(&input, 0.017, -1.0, 0.0, &PhysicalConstants::SI).is_err());
    }

    #[test]
    fn pod_fins_see_the_flow_at_their_pod_s_roll_position() {
        let fins = pod_fins(None);
        let aero = fins.fin_aerodynamics().expect("fins");
        // One pod at 90°: its fins (at 90° and 270° on it) face the flow at θ − 90°.
        let one = PodPlacement {
            count: 1,
            angular_position: FRAC_PI_2,
        };
        for theta in [0.0, 0.3, 1.2, 2.5] {
            let expected = aero.roll_factor(theta - FRAC_PI_2);
            assert!((one.mean_roll_factor(aero, theta) - expected).abs() < 1e-15);
        }
        // Two opposite pods average two sets half a turn apart: the same as one for fins at
        // 90° and 270°; four pods a quarter turn apart average sin² and cos² to 1.
        let four = PodPlacement {
            count: 4,
            angular_position: 0.0,
        };
        for theta in [0.0, 0.7, 2.0] {
            assert!((four.mean_roll_factor(aero, theta) - 1.0).abs() < 1e-12);
        }
    }
}
