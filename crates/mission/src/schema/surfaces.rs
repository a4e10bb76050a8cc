//! `[rocket.surfaces.<name>]`: aerodynamic surfaces, one table per surface with a `type`;
//! `[rocket.pods.<name>]`: the pod sets that carry some of them.
//!
//! A surface table is read as one flat set of keys (so an unknown key is located exactly) and
//! then turned into the [`SurfaceSpec`] variant of its `type`; a key the type needs that is
//! missing, or a key of another type, is an error naming every such key.

use super::names::{AngleUnit, NoseKind, SurfaceType};
use super::values::Curve;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// One aerodynamic surface, RocketPy's `add_nose` / `add_trapezoidal_fins` /
/// `add_elliptical_fins` / `add_free_form_fins` / `add_tail`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawSurface", into = "RawSurface")]
pub enum SurfaceSpec {
    /// `type = "nose"`.
    Nose(NoseSpec),
    /// `type = "trapezoidal_fins"`.
    TrapezoidalFins(TrapezoidalFinsSpec),
    /// `type = "elliptical_fins"`.
    EllipticalFins(EllipticalFinsSpec),
    /// `type = "free_form_fins"`.
    FreeFormFins(FreeFormFinsSpec),
    /// `type = "tail"`.
    Tail(TailSpec),
    /// `type = "tube_fins"`.
    TubeFins(TubeFinsSpec),
}

impl SurfaceSpec {
    /// The surface's `type`.
    pub fn surface_type(&self) -> SurfaceType {
        match self {
            SurfaceSpec::Nose(_) => SurfaceType::Nose,
            SurfaceSpec::TrapezoidalFins(_) => SurfaceType::TrapezoidalFins,
            SurfaceSpec::EllipticalFins(_) => SurfaceType::EllipticalFins,
            SurfaceSpec::FreeFormFins(_) => SurfaceType::FreeFormFins,
            SurfaceSpec::Tail(_) => SurfaceType::Tail,
            SurfaceSpec::TubeFins(_) => SurfaceType::TubeFins,
        }
    }

    /// The airfoil of a fin set, if it has one.
    pub fn airfoil(&self) -> Option<&AirfoilSpec> {
        match self {
            SurfaceSpec::TrapezoidalFins(f) => f.airfoil.as_ref(),
            SurfaceSpec::EllipticalFins(f) => f.airfoil.as_ref(),
            SurfaceSpec::FreeFormFins(f) => f.airfoil.as_ref(),
            SurfaceSpec::Nose(_) | SurfaceSpec::Tail(_) | SurfaceSpec::TubeFins(_) => None,
        }
    }

    /// The airfoil of a fin set, if it has one, mutable.
    pub fn airfoil_mut(&mut self) -> Option<&mut AirfoilSpec> {
        match self {
            SurfaceSpec::TrapezoidalFins(f) => f.airfoil.as_mut(),
            SurfaceSpec::EllipticalFins(f) => f.airfoil.as_mut(),
            SurfaceSpec::FreeFormFins(f) => f.airfoil.as_mut(),
            SurfaceSpec::Nose(_) | SurfaceSpec::Tail(_) | SurfaceSpec::TubeFins(_) => None,
        }
    }
}

/// A tube fin set: `n` open tubes around the body.
#[derive(Debug, Clone, PartialEq)]
pub struct TubeFinsSpec {
    /// Number of tubes.
    pub n: u32,
    /// Tube length, m.
    pub length: f64,
    /// Outer radius of a tube, m.
    pub outer_radius: f64,
    /// Inner radius of a tube, m.
    pub inner_radius: f64,
    /// Position of the tubes' forward end, rocket coordinates, m.
    pub position: f64,
    /// Body radius at the tubes, m; absent: the rocket radius.
    pub radius: Option<f64>,
}

/// A nose cone.
#[derive(Debug, Clone, PartialEq)]
pub struct NoseSpec {
    /// Length, m.
    pub length: f64,
    /// Profile.
    pub kind: NoseKind,
    /// Position of the tip, rocket coordinates, m.
    pub position: f64,
    /// Bluffness ratio (tip radius / base radius); absent: sharp.
    pub bluffness: Option<f64>,
    /// Exponent of a power-series nose (`kind = "powerseries"` only).
    pub power: Option<f64>,
    /// Base radius, m; absent: the rocket radius.
    pub base_radius: Option<f64>,
}

/// Fin sweep of a trapezoidal fin set: an angle or a leading-edge length, never both.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sweep {
    /// `sweep_angle`, deg.
    AngleDeg(f64),
    /// `sweep_length`, m: axial distance from the root leading edge to the tip leading edge.
    Length(f64),
}

/// A fin airfoil's lift-coefficient curve (RocketPy `airfoil=(source, unit)`).
#[derive(Debug, Clone, PartialEq)]
pub struct AirfoilSpec {
    /// Lift coefficient of angle of attack: [`Curve::File`] from `file`, [`Curve::Points`]
    /// from `curve`.
    pub lift: Curve,
    /// Unit of the angle of attack column.
    pub unit: AngleUnit,
}

/// A trapezoidal fin set.
#[derive(Debug, Clone, PartialEq)]
pub struct TrapezoidalFinsSpec {
    /// Number of fins.
    pub n: u32,
    /// Span, m.
    pub span: f64,
    /// Root chord, m.
    pub root_chord: f64,
    /// Tip chord, m.
    pub tip_chord: f64,
    /// Position of the root leading edge, rocket coordinates, m.
    pub position: f64,
    /// Sweep; absent: RocketPy's default geometry when neither key is given (docs/physics.md §7.5).
    pub sweep: Option<Sweep>,
    /// Cant angle, deg; default 0.
    pub cant_angle_deg: f64,
    /// Roll position of the first fin about the rocket axis, deg; default 0.
    pub angular_position_deg: f64,
    /// Body radius at the fins, m; absent: the rocket radius.
    pub radius: Option<f64>,
    /// Airfoil lift curve; absent: flat plate.
    pub airfoil: Option<AirfoilSpec>,
}

/// An elliptical fin set.
#[derive(Debug, Clone, PartialEq)]
pub struct EllipticalFinsSpec {
    /// Number of fins.
    pub n: u32,
    /// Span, m.
    pub span: f64,
    /// Root chord, m.
    pub root_chord: f64,
    /// Position of the root leading edge, rocket coordinates, m.
    pub position: f64,
    /// Cant angle, deg; default 0.
    pub cant_angle_deg: f64,
    /// Roll position of the first fin about the rocket axis, deg; default 0.
    pub angular_position_deg: f64,
    /// Body radius at the fins, m; absent: the rocket radius.
    pub radius: Option<f64>,
    /// Airfoil lift curve; absent: flat plate.
    pub airfoil: Option<AirfoilSpec>,
}

/// A fin set given by its planform.
#[derive(Debug, Clone, PartialEq)]
pub struct FreeFormFinsSpec {
    /// Number of fins.
    pub n: u32,
    /// Planform points `[x, y]` (m), RocketPy `shape_points`.
    pub shape_points: Vec<[f64; 2]>,
    /// Position of the root leading edge, rocket coordinates, m.
    pub position: f64,
    /// Cant angle, deg; default 0.
    pub cant_angle_deg: f64,
    /// Roll position of the first fin about the rocket axis, deg; default 0.
    pub angular_position_deg: f64,
    /// Body radius at the fins, m; absent: the rocket radius.
    pub radius: Option<f64>,
    /// Airfoil lift curve; absent: flat plate.
    pub airfoil: Option<AirfoilSpec>,
}

/// A conical transition or boattail.
#[derive(Debug, Clone, PartialEq)]
pub struct TailSpec {
    /// Radius at the forward end, m.
    pub top_radius: f64,
    /// Radius at the aft end, m.
    pub bottom_radius: f64,
    /// Length, m.
    pub length: f64,
    /// Position of the forward end, rocket coordinates, m.
    pub position: f64,
}

/// The `airfoil` table as written: `{ file, unit }` or `{ curve, unit }`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAirfoil {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    file: Option<PathBuf>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    curve: Option<Vec<[f64; 2]>>,
    unit: AngleUnit,
}

/// Every key any surface type accepts.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSurface {
    #[serde(rename = "type", default, skip_serializing_if = "Option::is_none")]
    surface_type: Option<SurfaceType>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    position: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    length: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    kind: Option<NoseKind>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    bluffness: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    power: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    base_radius: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    n: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    span: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    root_chord: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    tip_chord: Option<f64>,
    #[serde(
        rename = "sweep_angle",
        default,
        skip_serializing_if = "Option::is_none"
    )]
    sweep_angle_deg: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    sweep_length: Option<f64>,
    #[serde(
        rename = "cant_angle",
        default,
        skip_serializing_if = "Option::is_none"
    )]
    cant_angle_deg: Option<f64>,
    #[serde(
        rename = "angular_position",
        default,
        skip_serializing_if = "Option::is_none"
    )]
    angular_position_deg: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    radius: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    airfoil: Option<RawAirfoil>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    shape_points: Option<Vec<[f64; 2]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    top_radius: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    bottom_radius: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    outer_radius: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    inner_radius: Option<f64>,
}

/// The keys each surface type accepts (besides `type`), the first `required` of them required.
pub(crate) fn keys_of(surface_type: SurfaceType) -> (&'static [&'static str], usize) {
    match surface_type {
        SurfaceType::Nose => (
            &[
                "length",
                "kind",
                "position",
                "bluffness",
                "power",
                "base_radius",
            ],
            3,
        ),
        SurfaceType::TrapezoidalFins => (
            &[
                "n",
                "span",
                "root_chord",
                "tip_chord",
                "position",
                "sweep_angle",
                "sweep_length",
                "cant_angle",
                "angular_position",
                "radius",
                "airfoil",
            ],
            5,
        ),
        SurfaceType::EllipticalFins => (
            &[
                "n",
                "span",
                "root_chord",
                "position",
                "cant_angle",
                "angular_position",
                "radius",
                "airfoil",
            ],
            4,
        ),
        SurfaceType::FreeFormFins => (
            &[
                "n",
                "shape_points",
                "position",
                "cant_angle",
                "angular_position",
                "radius",
                "airfoil",
            ],
            3,
        ),
        SurfaceType::Tail => (&["top_radius", "bottom_radius", "length", "position"], 4),
        SurfaceType::TubeFins => (
            &[
                "n",
                "length",
                "outer_radius",
                "inner_radius",
                "position",
                "radius",
            ],
            5,
        ),
    }
}

impl RawSurface {
    /// The keys present in this table (besides `type`).
    fn present(&self) -> Vec<&'static str> {
        let flags = [
            ("position", self.position.is_some()),
            ("length", self.length.is_some()),
            ("kind", self.kind.is_some()),
            ("bluffness", self.bluffness.is_some()),
            ("power", self.power.is_some()),
            ("base_radius", self.base_radius.is_some()),
            ("n", self.n.is_some()),
            ("span", self.span.is_some()),
            ("root_chord", self.root_chord.is_some()),
            ("tip_chord", self.tip_chord.is_some()),
            ("sweep_angle", self.sweep_angle_deg.is_some()),
            ("sweep_length", self.sweep_length.is_some()),
            ("cant_angle", self.cant_angle_deg.is_some()),
            ("angular_position", self.angular_position_deg.is_some()),
            ("radius", self.radius.is_some()),
            ("airfoil", self.airfoil.is_some()),
            ("shape_points", self.shape_points.is_some()),
            ("top_radius", self.top_radius.is_some()),
            ("bottom_radius", self.bottom_radius.is_some()),
            ("outer_radius", self.outer_radius.is_some()),
            ("inner_radius", self.inner_radius.is_some()),
        ];
        flags
            .iter()
            .filter(|(_, present)| *present)
            .map(|(key, _)| *key)
            .collect()
    }
}

/// Takes a value that [`check_keys`] guaranteed to be present.
fn take<T>(value: Option<T>, key: &str) -> Result<T, String> {
    value.ok_or_else(|| format!("missing key `{key}`"))
}

/// Lists missing required keys and keys of other types, all at once.
fn check_keys(raw: &RawSurface, surface_type: SurfaceType) -> Result<(), String> {
    let (accepted, required) = keys_of(surface_type);
    let present = raw.present();
    let mut problems = Vec::new();
    let missing: Vec<&str> = accepted[..required]
        .iter()
        .filter(|key| !present.contains(key))
        .copied()
        .collect();
    if !missing.is_empty() {
        problems.push(format!(
            "a {} surface needs {}",
            surface_type,
            missing
                .iter()
                .map(|k| format!("`{k}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let foreign: Vec<&str> = present
        .iter()
        .filter(|key| !accepted.contains(key))
        .copied()
        .collect();
    if !foreign.is_empty() {
        problems.push(format!(
            "{} not accepted by a {} surface (it accepts {})",
            foreign
                .iter()
                .map(|k| format!("`{k}`"))
                .collect::<Vec<_>>()
                .join(", "),
            surface_type,
            accepted
                .iter()
                .map(|k| format!("`{k}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    if raw.sweep_angle_deg.is_some() && raw.sweep_length.is_some() {
        problems.push("give `sweep_angle` or `sweep_length`, not both".to_owned());
    }
    if raw.power.is_some() && raw.kind.is_some_and(|k| k != NoseKind::PowerSeries) {
        problems.push("`power` applies only to kind = \"powerseries\"".to_owned());
    }
    if raw.kind == Some(NoseKind::PowerSeries) && raw.power.is_none() {
        problems.push("kind = \"powerseries\" needs `power`".to_owned());
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(problems.join("; "))
    }
}

fn airfoil(raw: Option<RawAirfoil>) -> Result<Option<AirfoilSpec>, String> {
    let Some(raw) = raw else { return Ok(None) };
    let lift = match (raw.file, raw.curve) {
        (Some(file), None) => Curve::File(file),
        (None, Some(points)) if !points.is_empty() => Curve::Points(points),
        (None, Some(_)) => return Err("`airfoil.curve` needs at least one point".to_owned()),
        _ => return Err("`airfoil` needs exactly one of `file` and `curve`".to_owned()),
    };
    Ok(Some(AirfoilSpec {
        lift,
        unit: raw.unit,
    }))
}

impl TryFrom<RawSurface> for SurfaceSpec {
    type Error = String;

    fn try_from(raw: RawSurface) -> Result<Self, String> {
        let surface_type = raw.surface_type.ok_or_else(|| {
            format!(
                "a surface needs `type` (one of {})",
                SurfaceType::expected()
            )
        })?;
        check_keys(&raw, surface_type)?;
        let cant_angle_deg = raw.cant_angle_deg.unwrap_or(0.0);
        let angular_position_deg = raw.angular_position_deg.unwrap_or(0.0);
        Ok(match surface_type {
            SurfaceType::Nose => SurfaceSpec::Nose(NoseSpec {
                length: take(raw.length, "length")?,
                kind: take(raw.kind, "kind")?,
                position: take(raw.position, "position")?,
                bluffness: raw.bluffness,
                power: raw.power,
                base_radius: raw.base_radius,
            }),
            SurfaceType::TrapezoidalFins => SurfaceSpec::TrapezoidalFins(TrapezoidalFinsSpec {
                n: take(raw.n, "n")?,
                span: take(raw.span, "span")?,
                root_chord: take(raw.root_chord, "root_chord")?,
                tip_chord: take(raw.tip_chord, "tip_chord")?,
                position: take(raw.position, "position")?,
                sweep: match (raw.sweep_angle_deg, raw.sweep_length) {
                    (Some(angle), _) => Some(Sweep::AngleDeg(angle)),
                    (None, Some(length)) => Some(Sweep::Length(length)),
                    (None, None) => None,
                },
                cant_angle_deg,
                angular_position_deg,
                radius: raw.radius,
                airfoil: airfoil(raw.airfoil)?,
            }),
            SurfaceType::EllipticalFins => SurfaceSpec::EllipticalFins(EllipticalFinsSpec {
                n: take(raw.n, "n")?,
                span: take(raw.span, "span")?,
                root_chord: take(raw.root_chord, "root_chord")?,
                position: take(raw.position, "position")?,
                cant_angle_deg,
                angular_position_deg,
                radius: raw.radius,
                airfoil: airfoil(raw.airfoil)?,
            }),
            SurfaceType::FreeFormFins => SurfaceSpec::FreeFormFins(FreeFormFinsSpec {
                n: take(raw.n, "n")?,
                shape_points: take(raw.shape_points, "shape_points")?,
                position: take(raw.position, "position")?,
                cant_angle_deg,
                angular_position_deg,
                radius: raw.radius,
                airfoil: airfoil(raw.airfoil)?,
            }),
            SurfaceType::Tail => SurfaceSpec::Tail(TailSpec {
                top_radius: take(raw.top_radius, "top_radius")?,
                bottom_radius: take(raw.bottom_radius, "bottom_radius")?,
                length: take(raw.length, "length")?,
                position: take(raw.position, "position")?,
            }),
            SurfaceType::TubeFins => SurfaceSpec::TubeFins(TubeFinsSpec {
                n: take(raw.n, "n")?,
                length: take(raw.length, "length")?,
                outer_radius: take(raw.outer_radius, "outer_radius")?,
                inner_radius: take(raw.inner_radius, "inner_radius")?,
                position: take(raw.position, "position")?,
                radius: raw.radius,
            }),
        })
    }
}

fn raw_airfoil(airfoil: Option<AirfoilSpec>) -> Option<RawAirfoil> {
    airfoil.map(|a| {
        let (file, curve) = match a.lift {
            Curve::File(file) => (Some(file), None),
            Curve::Points(points) => (None, Some(points)),
            Curve::Constant(value) => (None, Some(vec![[0.0, value]])),
        };
        RawAirfoil {
            file,
            curve,
            unit: a.unit,
        }
    })
}

impl From<SurfaceSpec> for RawSurface {
    fn from(surface: SurfaceSpec) -> Self {
        let surface_type = Some(surface.surface_type());
        match surface {
            SurfaceSpec::Nose(s) => RawSurface {
                surface_type,
                length: Some(s.length),
                kind: Some(s.kind),
                position: Some(s.position),
                bluffness: s.bluffness,
                power: s.power,
                base_radius: s.base_radius,
                ..RawSurface::default()
            },
            SurfaceSpec::TrapezoidalFins(s) => RawSurface {
                surface_type,
                n: Some(s.n),
                span: Some(s.span),
                root_chord: Some(s.root_chord),
                tip_chord: Some(s.tip_chord),
                position: Some(s.position),
                sweep_angle_deg: match s.sweep {
                    Some(Sweep::AngleDeg(angle)) => Some(angle),
                    _ => None,
                },
                sweep_length: match s.sweep {
                    Some(Sweep::Length(length)) => Some(length),
                    _ => None,
                },
                cant_angle_deg: Some(s.cant_angle_deg),
                angular_position_deg: Some(s.angular_position_deg),
                radius: s.radius,
                airfoil: raw_airfoil(s.airfoil),
                ..RawSurface::default()
            },
            SurfaceSpec::EllipticalFins(s) => RawSurface {
                surface_type,
                n: Some(s.n),
                span: Some(s.span),
                root_chord: Some(s.root_chord),
                position: Some(s.position),
                cant_angle_deg: Some(s.cant_angle_deg),
                angular_position_deg: Some(s.angular_position_deg),
                radius: s.radius,
                airfoil: raw_airfoil(s.airfoil),
                ..RawSurface::default()
            },
            SurfaceSpec::FreeFormFins(s) => RawSurface {
                surface_type,
                n: Some(s.n),
                shape_points: Some(s.shape_points),
                position: Some(s.position),
                cant_angle_deg: Some(s.cant_angle_deg),
                angular_position_deg: Some(s.angular_position_deg),
                radius: s.radius,
                airfoil: raw_airfoil(s.airfoil),
                ..RawSurface::default()
            },
            SurfaceSpec::Tail(s) => RawSurface {
                surface_type,
                top_radius: Some(s.top_radius),
                bottom_radius: Some(s.bottom_radius),
                length: Some(s.length),
                position: Some(s.position),
                ..RawSurface::default()
            },
            SurfaceSpec::TubeFins(s) => RawSurface {
                surface_type,
                n: Some(s.n),
                length: Some(s.length),
                outer_radius: Some(s.outer_radius),
                inner_radius: Some(s.inner_radius),
                position: Some(s.position),
                radius: s.radius,
                ..RawSurface::default()
            },
        }
    }
}

fn one_pod() -> u32 {
    1
}

/// `[rocket.pods.<name>]`: a pod set (OpenRocket's `podset`), `count` identical side bodies
/// evenly spaced around the rocket axis, each carrying the surfaces named in `surfaces`.
/// Those surfaces are placed on the rocket's axis as usual (their `position`s along it, a
/// fin set's `radius` the pod's body radius, 0 for fins on no body) and count once per pod;
/// a pod holding a nose cone also has a body for the drag estimate (nose, tails and
/// cylinders between, like the rocket's own body).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PodSpec {
    /// Names of the `[rocket.surfaces.<name>]` tables one pod carries.
    pub surfaces: Vec<String>,
    /// Number of pods; default 1.
    #[serde(default = "one_pod")]
    pub count: u32,
    /// Roll position of the first pod about the rocket axis, deg; the others follow at
    /// `360° / count`. Default 0.
    #[serde(rename = "angular_position", default, skip_serializing_if = "is_zero")]
    pub angular_position_deg: f64,
    /// Length of a pod's body from its nose tip, m; absent: to the aftmost end of its tails
    /// and fin root chords. Only a pod with a nose cone has a body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body_length: Option<f64>,
}

#[allow(clippy::trivially_copy_pass_by_ref)] // serde's `skip_serializing_if` passes a reference
fn is_zero(v: &f64) -> bool {
    *v == 0.0
}
