//! Mass, centre of mass and inertia of the design without motor, component by component as
//! OpenRocket builds them: material density times volume (bulk, kg/m³), area (surface,
//! kg/m²) or length (line, kg/m), or a given mass; mass and CG overrides of a component or of
//! its whole subtree (`overridesubcomponents*`): an override mass sits at the component's own
//! CG, a stage's (which has no mass of its own) at its children's.
//!
//! Where OpenRocket computes a dimension itself, so does the reader: a centering ring's
//! automatic bore is the inner tube beside it; a fin's volume is its plate's times
//! OpenRocket's factor for the cross-section, plus its fillets.
//!
//! Inertias are those of the solid each component approximates — thin or thick tubes, disks,
//! shells of revolution integrated along the axis, fins as plates at their centroid — about
//! the component's own centre of mass; the subtree sums them with the parallel-axis theorem.

use std::f64::consts::PI;

use karman_airframe::{Profile, RigidMass};

use crate::OrkError;
use crate::design::{Component, Kind};

/// Mass properties: mass (kg), axial CM from the nose tip (m), longitudinal (pitch) and
/// rotational (roll) moments of inertia about that CM (kg·m²).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MassProps {
    /// Mass, kg.
    pub mass: f64,
    /// Centre of mass from the nose tip, m.
    pub cg: f64,
    /// Pitch/yaw inertia about the CM, kg·m².
    pub i_long: f64,
    /// Roll inertia, kg·m².
    pub i_rot: f64,
}

impl MassProps {
    /// The part as the airframe's rigid mass (axisymmetric: both lateral inertias `i_long`).
    fn rigid(self) -> RigidMass {
        RigidMass {
            mass: self.mass,
            center: self.cg,
            inertia: [self.i_long, self.i_long, self.i_rot, 0.0, 0.0, 0.0],
        }
    }

    /// Two parts as one ([`RigidMass::combined`]: the parallel-axis theorem); nothing when
    /// the two weigh nothing together.
    pub(super) fn add(self, o: MassProps) -> MassProps {
        if self.mass + o.mass <= 0.0 {
            return MassProps::default();
        }
        let sum = self.rigid().combined(o.rigid());
        MassProps {
            mass: sum.mass,
            cg: sum.center,
            i_long: sum.inertia[0],
            i_rot: sum.inertia[2],
        }
    }

    fn scaled(self, mass: f64) -> MassProps {
        let k = if self.mass > 0.0 {
            mass / self.mass
        } else {
            0.0
        };
        MassProps {
            mass,
            cg: self.cg,
            i_long: self.i_long * k,
            i_rot: self.i_rot * k,
        }
    }
}

/// A hollow cylinder of radii `ro` > `ri`, length `l`, density `rho`, forward end at `x`.
/// Radii out of order meet the nearest solid: a negative outer radius is none, an inner
/// radius below zero (a wall thicker than the radius) is a filled cylinder.
fn tube(x: f64, l: f64, ro: f64, ri: f64, rho: f64) -> MassProps {
    let ro = ro.max(0.0);
    let ri = ri.max(0.0).min(ro);
    let m = rho * PI * (ro * ro - ri * ri) * l;
    MassProps {
        mass: m,
        cg: x + 0.5 * l,
        i_long: m * (3.0 * (ro * ro + ri * ri) + l * l) / 12.0,
        i_rot: 0.5 * m * (ro * ro + ri * ri),
    }
}

/// OpenRocket's shape families by name and parameter.
pub(crate) fn profile(shape: &str, parameter: f64) -> Profile {
    match shape {
        "ogive" => Profile::Ogive(parameter),
        "ellipsoid" => Profile::Ellipsoid,
        "power" => Profile::Power(parameter),
        "parabolic" => Profile::Parabolic(parameter),
        "haack" => Profile::Haack(parameter),
        _ => Profile::Conical,
    }
}

/// Radius at `x` aft of the forward end of a nose cone or transition.
fn shell_radius(p: Profile, x: f64, fore: f64, aft: f64, length: f64) -> f64 {
    if aft >= fore {
        fore + p.radius(x, aft - fore, length)
    } else {
        aft + p.radius(length - x, fore - aft, length)
    }
}

/// A shell of revolution (wall `t` measured normal to the surface) integrated in slices.
fn shell(x0: f64, length: f64, fore: f64, aft: f64, p: Profile, t: f64, rho: f64) -> MassProps {
    const SLICES: usize = 200;
    let dx = length / SLICES as f64;
    let mut total = MassProps::default();
    for i in 0..SLICES {
        let (xa, xb) = (i as f64 * dx, (i + 1) as f64 * dx);
        let (ra, rb) = (
            shell_radius(p, xa, fore, aft, length),
            shell_radius(p, xb, fore, aft, length),
        );
        let r = 0.5 * (ra + rb);
        let slope = (rb - ra) / dx;
        let ri = (r - t * slope.hypot(1.0)).max(0.0);
        total = total.add(tube(x0 + xa, dx, r, ri, rho));
    }
    total
}

/// The volume of a fin of cross-section `crosssection` relative to the flat plate of its
/// outline and thickness, as OpenRocket counts it (`FinSet.CrossSection`, read for the
/// values: square 1, rounded 0.99, airfoil 0.85); the tab is a flat plate.
fn section_volume(c: &Component) -> Result<f64, OrkError> {
    match c.text("crosssection").unwrap_or("square") {
        "square" => Ok(1.0),
        "rounded" => Ok(0.99),
        "airfoil" => Ok(0.85),
        other => Err(c.value_error(
            "crosssection",
            &format!("{other:?} is not square, rounded or airfoil"),
        )),
    }
}

fn fins(c: &Component, body_radius: f64) -> Result<MassProps, OrkError> {
    let n = c.count_or("fincount", 1.0, 1.0)?;
    let t = c.dim("thickness")?;
    let rho = c.density()?;
    let outline: Vec<[f64; 2]> = match c.kind {
        Kind::TrapezoidFins => {
            let (cr, ct, s, sweep) = (
                c.dim("rootchord")?,
                c.dim("tipchord")?,
                c.dim("height")?,
                c.num("sweeplength")?,
            );
            vec![[0.0, 0.0], [sweep, s], [sweep + ct, s], [cr, 0.0]]
        }
        Kind::EllipticalFins => {
            let (cr, s) = (c.dim("rootchord")?, c.dim("height")?);
            (0..=36)
                .map(|i| {
                    let a = PI * f64::from(i) / 36.0;
                    [0.5 * cr * (1.0 - a.cos()), s * a.sin()]
                })
                .collect()
        }
        _ => c.points.clone(),
    };
    // Planform area and centroid (shoelace).
    let (mut a, mut cx, mut cy) = (0.0, 0.0, 0.0);
    for i in 0..outline.len() {
        let (p, q) = (outline[i], outline[(i + 1) % outline.len()]);
        let cross = p[0] * q[1] - q[0] * p[1];
        a += cross;
        cx += (p[0] + q[0]) * cross;
        cy += (p[1] + q[1]) * cross;
    }
    let area = 0.5 * a.abs();
    let (cx, cy) = if a.abs() > 0.0 {
        (cx / (3.0 * a), cy / (3.0 * a))
    } else {
        (0.0, 0.0)
    };
    let tab = c.dim_or("tabheight", 0.0)? * c.dim_or("tablength", 0.0)?;
    let m_fin = rho * t * (area * section_volume(c)? + tab);
    let m = n * m_fin;
    let arm = body_radius + cy;
    let chord = c.length.max(1e-12);
    let fins = MassProps {
        mass: m,
        cg: c.x + cx,
        i_long: m * (0.5 * arm * arm + chord * chord / 12.0),
        i_rot: m * arm * arm,
    };
    // Fillets along the root chord, their centroid a fifth of their radius off the body
    // (OpenRocket's estimate).
    let r = c.dim_or("filletradius", 0.0)?;
    if r <= 0.0 {
        return Ok(fins);
    }
    let density = c
        .fillet_material
        .ok_or_else(|| c.value_error("filletmaterial", "is missing"))?;
    let m = n * density * fillet_area(r, body_radius) * c.length;
    let arm = body_radius + 0.2 * r;
    Ok(fins.add(MassProps {
        mass: m,
        cg: c.x + 0.5 * c.length,
        i_long: m * (0.5 * arm * arm + chord * chord / 12.0),
        i_rot: m * arm * arm,
    }))
}

/// The cross-section of the two concave fillets of radius `r` at the root of a fin on a body
/// of radius `body` (OpenRocket's `FinSet.calculateFilletCrossSection`, read for the
/// method): each is the triangle between the body's centre, the fillet's centre and its
/// tangent point on the fin, less the sectors of the fillet's circle and of the body in it.
fn fillet_area(r: f64, body: f64) -> f64 {
    let h = r + body;
    let (inner, outer) = ((r / h).asin(), (r / h).acos());
    let one = 0.5 * outer.tan() * r * r - 0.5 * outer * r * r - 0.5 * inner * body * body;
    if one.is_finite() { 2.0 * one } else { 0.0 }
}

/// The automatic inner radius of centering ring `ring` among its `siblings` (OpenRocket's
/// `CenteringRing.getInnerRadius`, read for the method): the largest outer radius of the
/// inner tubes beside it whose length reaches the ring's (touching counts), at most the
/// ring's outer radius `outer`; 0 with no such tube.
fn ring_inner_radius(
    ring: &Component,
    siblings: &[Component],
    outer: f64,
) -> Result<f64, OrkError> {
    let mut inner: f64 = 0.0;
    for tube in siblings.iter().filter(|k| k.kind == Kind::InnerTube) {
        let overlaps = ring.x + ring.length >= tube.x && ring.x <= tube.x + tube.length;
        if overlaps {
            inner = inner.max(tube.dim("outerradius")?);
        }
    }
    Ok(inner.min(outer))
}

/// A radius that OpenRocket may compute (`auto`, with or without the value it last
/// resolved, which may be stale): `automatic` then, else the stored value.
fn radius_or_auto(c: &Component, element: &str, automatic: f64) -> Result<f64, OrkError> {
    match c.text(element) {
        None => Ok(automatic),
        Some(t) if t.trim_start().starts_with("auto") => Ok(automatic),
        Some(_) => c.dim(element),
    }
}

/// Mass properties of `c` alone (not its children); `parent_inner` is the inner radius of
/// the tube it sits in, `siblings` the components beside it (its parent's children).
fn own(
    c: &Component,
    parent_inner: f64,
    body_radius: f64,
    siblings: &[Component],
) -> Result<MassProps, OrkError> {
    let x = c.x;
    Ok(match c.kind {
        Kind::Stage | Kind::PodSet => MassProps::default(),
        Kind::BodyTube | Kind::InnerTube | Kind::TubeCoupler | Kind::LaunchLug => {
            let ro = match c.kind {
                Kind::BodyTube | Kind::LaunchLug => c.dim("radius")?,
                _ => c.dim_or("outerradius", parent_inner)?,
            };
            let t = c.dim("thickness")?;
            let mut p = tube(x, c.length, ro, ro - t, c.density()?);
            if c.kind == Kind::LaunchLug {
                let n = c.count_or("instancecount", 1.0, 1.0)?;
                let arm = body_radius + ro;
                p = p.scaled(p.mass * n);
                p.i_long += p.mass * arm * arm;
                p.i_rot += p.mass * arm * arm;
            }
            p
        }
        Kind::NoseCone | Kind::Transition => {
            let (fore, aft) = if c.kind == Kind::NoseCone {
                (0.0, c.dim("aftradius")?)
            } else {
                (c.dim("foreradius")?, c.dim("aftradius")?)
            };
            let shape = c.text("shape").unwrap_or("conical");
            let parameter = c.num_or("shapeparameter", 1.0)?;
            // A filled (solid) part stores "filled" as its thickness.
            let wall = if c.text("thickness") == Some("filled") || c.text("filled") == Some("true")
            {
                f64::INFINITY
            } else {
                c.dim("thickness")?
            };
            let rho = c.density()?;
            let mut p = shell(x, c.length, fore, aft, profile(shape, parameter), wall, rho);
            for (end, at) in [("aft", x + c.length), ("fore", x)] {
                let l = c.dim_or(&format!("{end}shoulderlength"), 0.0)?;
                if l <= 0.0 {
                    continue;
                }
                let radius_key = format!("{end}shoulderradius");
                let thickness_key = format!("{end}shoulderthickness");
                let r = c.dim_or(&radius_key, 0.0)?;
                if r < 0.0 {
                    return Err(c.value_error(&radius_key, &format!("{r} must not be negative")));
                }
                let ts = match c.text(&thickness_key) {
                    Some("filled") => r,
                    _ => c.dim_or(&thickness_key, 0.0)?,
                };
                if ts < 0.0 {
                    return Err(
                        c.value_error(&thickness_key, &format!("{ts} must not be negative"))
                    );
                }
                // A wall thicker than the shoulder's radius fills it (OpenRocket clamps the
                // thickness to the radius the same way).
                let ts = ts.min(r);
                let start = if end == "aft" { at } else { at - l };
                p = p.add(tube(start, l, r, r - ts, rho));
                if c.text(&format!("{end}shouldercapped")) == Some("true") {
                    let cap = if end == "aft" { start + l - ts } else { start };
                    p = p.add(tube(cap, ts, r - ts, 0.0, rho));
                }
            }
            p
        }
        Kind::TrapezoidFins | Kind::EllipticalFins | Kind::FreeFormFins => fins(c, body_radius)?,
        Kind::TubeFins => {
            // `n` tubes around the axis at `arm` from it: on the axis as a whole, the ring
            // adding `M arm² / 2` to the transverse and `M arm²` to the roll inertia.
            let (ro, ri) = c.tube_fin_radii(body_radius)?;
            let n = c.count_or("fincount", 1.0, 1.0)?;
            let mut p = tube(x, c.length, ro, ri, c.density()?);
            p = p.scaled(p.mass * n);
            let arm = body_radius + ro;
            p.i_long += 0.5 * p.mass * arm * arm;
            p.i_rot += p.mass * arm * arm;
            p
        }
        Kind::CenteringRing | Kind::Bulkhead | Kind::EngineBlock => {
            let ro = c.dim_or("outerradius", parent_inner)?;
            let ri = match c.kind {
                Kind::CenteringRing => {
                    let automatic = ring_inner_radius(c, siblings, ro)?;
                    radius_or_auto(c, "innerradius", automatic)?
                }
                Kind::EngineBlock => ro - c.dim("thickness")?,
                _ => 0.0,
            };
            let n = c.count_or("instancecount", 1.0, 1.0)?;
            let p = tube(x, c.length, ro, ri, c.density()?);
            p.scaled(p.mass * n)
        }
        Kind::RailButton => {
            let od = c.dim("outerdiameter")?;
            let id = c.dim("innerdiameter")?;
            let h = c.dim("height")?;
            let base = c.dim_or("baseheight", 0.0)?;
            let flange = c.dim_or("flangeheight", 0.0)?;
            let n = c.count_or("instancecount", 1.0, 1.0)?;
            let v =
                PI * 0.25 * (od * od * (base + flange) + id * id * (h - base - flange).max(0.0));
            let m = n * v * c.density()?;
            let separation = c.dim_or("instanceseparation", 0.0)?;
            MassProps {
                mass: m,
                cg: x + 0.5 * od + 0.5 * (n - 1.0) * separation,
                i_long: m * (body_radius * body_radius),
                i_rot: m * body_radius * body_radius,
            }
        }
        Kind::Parachute | Kind::Streamer | Kind::ShockCord | Kind::MassComponent => {
            let m = match c.kind {
                Kind::Parachute => {
                    let d = c.dim("diameter")?;
                    let lines = c.count_or("linecount", 0.0, 0.0)? * c.dim_or("linelength", 0.0)?;
                    c.density()? * PI * 0.25 * d * d + lines * c.line_material.unwrap_or(0.0)
                }
                Kind::Streamer => c.density()? * c.dim("striplength")? * c.dim("stripwidth")?,
                Kind::ShockCord => c.density()? * c.dim("cordlength")?,
                _ => c.dim("mass")?,
            };
            let r = c.dim_or("packedradius", 0.0)?;
            let l = c.length;
            MassProps {
                mass: m,
                cg: x + 0.5 * l,
                i_long: m * (3.0 * r * r + l * l) / 12.0,
                i_rot: 0.5 * m * r * r,
            }
        }
    })
}

/// A motor carried unlit: a solid cylinder of `mass`, `length` and `radius` whose aft end
/// is at `aft`, repeated by a cluster of `count` motors at the root mean square distance
/// `offset` from the axis (as [`subtree`] repeats a clustered inner tube).
pub fn unlit_motor(
    aft: f64,
    length: f64,
    radius: f64,
    mass: f64,
    (count, offset): (u32, f64),
) -> MassProps {
    let n = f64::from(count);
    let total = n * mass;
    MassProps {
        mass: total,
        cg: aft - 0.5 * length,
        i_long: total * ((3.0 * radius * radius + length * length) / 12.0 + 0.5 * offset * offset),
        i_rot: total * (0.5 * radius * radius + offset * offset),
    }
}

fn flag(c: &Component, element: &str) -> bool {
    c.text(element) == Some("true")
}

/// Mass properties of `c` and its subtree, overrides applied; `parent_inner` and
/// `body_radius` describe the tube it sits in.
///
/// # Errors
/// [`OrkError::Value`] for a missing or malformed dimension or material.
pub fn subtree(c: &Component, parent_inner: f64, body_radius: f64) -> Result<MassProps, OrkError> {
    within(c, parent_inner, body_radius, &[])
}

/// [`subtree`] of `c` among `siblings` (its parent's children, `c` included).
fn within(
    c: &Component,
    parent_inner: f64,
    body_radius: f64,
    siblings: &[Component],
) -> Result<MassProps, OrkError> {
    // OpenRocket's overrides (`MassCalculation.calculateStructure`, read for the method): a
    // component's override mass replaces its own mass at its own CG, and with
    // `overridesubcomponentsmass` its children's too; a stage, which has no mass of its own,
    // puts its override at its children's CG (beside them, or in their place).
    let mut p = own(c, parent_inner, body_radius, siblings)?;
    let own_mass = p;
    let massive = c.kind != Kind::Stage;
    let subs_override = flag(c, "overridesubcomponentsmass");
    let override_mass = c
        .fields
        .get("overridemass")
        .and_then(|t| crate::design::number(t));
    if let Some(m) = override_mass {
        if massive && !subs_override {
            p = p.scaled(m);
        }
    }
    if let Some(cg) = c
        .fields
        .get("overridecg")
        .and_then(|t| crate::design::number(t))
    {
        if !flag(c, "overridesubcomponentscg") {
            p.cg = c.x + cg;
        }
    }
    let (inner, radius) = match c.kind {
        Kind::BodyTube => {
            let r = c.dim("radius")?;
            (r - c.dim("thickness")?, r)
        }
        Kind::InnerTube | Kind::TubeCoupler => {
            let r = c.dim_or("outerradius", parent_inner)?;
            (r - c.dim("thickness")?, body_radius)
        }
        Kind::NoseCone | Kind::Transition => {
            let r = c.dim_or("aftshoulderradius", c.dim_or("aftradius", parent_inner)?)?;
            let t = match c.text("aftshoulderthickness") {
                Some("filled") => r,
                _ => c.dim_or("aftshoulderthickness", 0.0)?,
            };
            (r - t, r)
        }
        _ => (parent_inner, body_radius),
    };
    let children = c
        .children
        .iter()
        .map(|k| within(k, inner, radius, &c.children))
        .collect::<Result<Vec<_>, _>>()?;
    if let (Some(m), false, false) = (override_mass, massive, subs_override) {
        let all = children.iter().fold(MassProps::default(), |a, &k| a.add(k));
        p = MassProps {
            mass: m,
            cg: if all.mass > 0.0 { all.cg } else { c.x },
            i_long: 0.0,
            i_rot: 0.0,
        };
    }
    // Summed in the order of the file, one child after the other.
    for k in children {
        p = p.add(k);
    }
    if c.kind == Kind::PodSet {
        // `n` pods, their axes `d` from the rocket's: as a cluster, `M d²` more roll
        // inertia and `M d² / 2` more transverse inertia (the mean over the two lateral
        // axes, exact for two or more evenly spaced pods).
        let (n, d, _) = c.pod_placement(body_radius)?;
        p = p.scaled(p.mass * f64::from(n));
        p.i_long += 0.5 * p.mass * d * d;
        p.i_rot += p.mass * d * d;
    }
    if c.kind == Kind::InnerTube {
        // A cluster repeats the tube with what it holds: `n` copies at the root mean square
        // distance `r` from the axis add `M r²` to the roll inertia and `M r² / 2` to the
        // transverse one (the mean over the two lateral axes).
        let (n, r) = c.cluster()?;
        if n > 1 {
            p = p.scaled(p.mass * f64::from(n));
            p.i_long += 0.5 * p.mass * r * r;
            p.i_rot += p.mass * r * r;
        }
    }
    if let (Some(m), true) = (override_mass, subs_override) {
        p = if massive {
            own_mass.scaled(m)
        } else {
            p.scaled(m)
        };
    }
    if flag(c, "overridesubcomponentscg") {
        if let Some(cg) = c
            .fields
            .get("overridecg")
            .and_then(|t| crate::design::number(t))
        {
            p.cg = c.x + cg;
        }
    }
    Ok(p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Design;

    /// A stage (with `stage` extra elements) holding a 1 m paper tube (with `tube` extra
    /// elements) and, in the tube, a 0.1 kg mass at its aft end.
    fn stage(stage: &str, tube: &str) -> Component {
        let text = format!(
            r#"<openrocket version="1.10"><rocket><name>r</name><subcomponents>
            <stage><name>S</name>{stage}<subcomponents>
            <bodytube><name>T</name>{tube}<material type="bulk" density="800">paper</material>
            <length>1.0</length><thickness>0.001</thickness><radius>0.05</radius>
            <subcomponents><masscomponent><name>M</name><axialoffset method="bottom">0.0</axialoffset>
            <packedlength>0.0</packedlength><mass>0.1</mass></masscomponent></subcomponents>
            </bodytube></subcomponents></stage></subcomponents></rocket></openrocket>"#
        );
        let design = Design::parse(std::path::Path::new("t.ork"), &text).expect("a design");
        design.stages[0].clone()
    }

    #[test]
    fn overrides_replace_a_components_own_mass_as_openrocket_does() {
        let plain = subtree(&stage("", ""), 0.0, 0.05).expect("mass");
        // A stage's override comes beside its children, at their CG.
        let s = "<overridemass>0.5</overridemass><overridesubcomponentsmass>false</overridesubcomponentsmass>";
        let p = subtree(&stage(s, ""), 0.0, 0.05).expect("mass");
        assert!((p.mass - (plain.mass + 0.5)).abs() < 1e-12, "{p:?}");
        assert!((p.cg - plain.cg).abs() < 1e-12, "{p:?} vs {plain:?}");
        // A tube's override with its subcomponents': the whole at the tube's own CG.
        let t = "<overridemass>0.5</overridemass><overridesubcomponentsmass>true</overridesubcomponentsmass>";
        let p = subtree(&stage("", t), 0.0, 0.05).expect("mass");
        assert!(
            (p.mass - 0.5).abs() < 1e-12 && (p.cg - 0.5).abs() < 1e-12,
            "{p:?}"
        );
        // Without them: the tube's own mass replaced, the aft mass kept.
        let t = "<overridemass>0.5</overridemass><overridesubcomponentsmass>false</overridesubcomponentsmass>";
        let p = subtree(&stage("", t), 0.0, 0.05).expect("mass");
        assert!((p.mass - 0.6).abs() < 1e-12, "{p:?}");
        assert!(
            (p.cg - (0.5 * 0.5 + 0.1 * 1.0) / 0.6).abs() < 1e-12,
            "{p:?}"
        );
    }

    #[test]
    fn fillets_on_a_flat_wall_fill_a_square_less_a_quarter_circle() {
        // On a body much larger than the fillet, each side's fillet is the square of its
        // radius less the quarter disc: both together r² (2 − π/2).
        let r = 0.005;
        let area = fillet_area(r, 1e4 * r);
        let flat = r * r * (2.0 - 0.5 * PI);
        assert!((area - flat).abs() < 1e-3 * flat, "{area} vs {flat}");
        // A body of twice the fillet's radius curves away under it: less fillet.
        let round = fillet_area(r, 2.0 * r);
        assert!(round > 0.0 && round < area, "{round} vs {area}");
    }
}
