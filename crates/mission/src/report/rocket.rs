//! Rocket reports: the `rocket` figures of `reference.json` ([`RocketReport`]), OpenRocket's
//! CP and stability margin at an angle of attack ([`AngleStability`]) and a profile drawing
//! of the rocket to scale with its CG and CP ([`draw_rocket_svg`], like RocketPy's
//! `Rocket.draw()`).

use std::fmt::{self, Write as _};

use karman_airframe::{BodyLift, Geometry, Rocket, Surface};
use serde::Serialize;

use crate::assemble::rocket::estimate_geometry;
use crate::{Mission, MissionError};

/// OpenRocket's centre of pressure and stability margin of a rocket at an angle of attack:
/// Barrowman's terms with Galejs' body lift ([`BodyLift::cp_at_angle`]), the sets of one or
/// two fins at the flow's roll angle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AngleStability {
    /// Time (s) of the centre of mass used.
    pub time_s: f64,
    /// Angle of attack (rad).
    pub alpha_rad: f64,
    /// Mach number.
    pub mach: f64,
    /// The flow's roll angle (rad) in the fins' angular positions.
    pub roll_rad: f64,
    /// CP aft of the nose tip (m).
    pub cp_m: f64,
    /// CG aft of the nose tip (m).
    pub cg_m: f64,
    /// `(CP − CG) / (2 r)`, calibers.
    pub margin_cal: f64,
}

impl AngleStability {
    /// The figures of `mission`'s `rocket` at time `time_s`, angle of attack `alpha` (rad) and
    /// `mach`; the flow's roll angle is `roll` of OpenRocket's worst roll angle
    /// ([`BodyLift::worst_roll_angle`], the one OpenRocket's launch code means to roll the
    /// rocket to on the pad; the OpenRocket comparison passes its 24.12 start, unrolled).
    ///
    /// # Errors
    /// As [`estimate_geometry`].
    pub fn new(
        mission: &Mission,
        rocket: &Rocket,
        time_s: f64,
        alpha: f64,
        mach: f64,
        roll: impl FnOnce(f64) -> f64,
    ) -> Result<Self, MissionError> {
        let lift = BodyLift::new(&estimate_geometry(mission)?);
        let tip = rocket
            .surfaces()
            .iter()
            .find(|s| matches!(s.geometry, Geometry::Nose { .. }))
            .map_or(0.0, |s| s.position);
        let roll_rad = roll(lift.worst_roll_angle(rocket, tip));
        let cp_m = lift.cp_at_angle(rocket, tip, alpha, mach, roll_rad);
        let cg_m = rocket.csys() * (tip - rocket.center_of_mass(time_s));
        Ok(AngleStability {
            time_s,
            alpha_rad: alpha,
            mach,
            roll_rad,
            cp_m,
            cg_m,
            margin_cal: (cp_m - cg_m) / (2.0 * rocket.radius()),
        })
    }
}

impl fmt::Display for AngleStability {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "CP {:.4} m, CG {:.4} m aft of the nose tip, margin {:.2} cal (OpenRocket's CP at t = {:.3} s, \
             α {:.2}°, Mach {:.3}, flow roll angle {:.1}°)",
            self.cp_m,
            self.cg_m,
            self.margin_cal,
            self.time_s,
            self.alpha_rad.to_degrees(),
            self.mach,
            self.roll_rad.to_degrees(),
        )
    }
}

/// One surface's normal-force slope and CP (`rocket.surfaces[]` of `reference.json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SurfaceReport {
    /// The mission's table name of the surface.
    pub name: String,
    /// CNα at Mach 0 per radian, on the surface's own reference area π r_s².
    pub cn_alpha_mach0: f64,
    /// CP in rocket (user) coordinates, m.
    pub cp_m: f64,
}

/// The rocket's mass and stability figures (`rocket` of `reference.json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RocketReport {
    /// Total mass at t = 0, kg.
    pub total_mass_t0_kg: f64,
    /// Rocket + motor dry mass, kg.
    pub dry_mass_kg: f64,
    /// Centre of mass at t = 0, rocket coordinates, m.
    pub center_of_mass_t0_m: f64,
    /// Rocket CP at Mach 0, rocket coordinates, m.
    pub cp_position_mach0_m: f64,
    /// Static margin at t = 0, calibres.
    pub static_margin_t0: f64,
    /// Static margin at burn-out, calibres.
    pub static_margin_burnout: f64,
    /// Every surface, in the mission's order.
    pub surfaces: Vec<SurfaceReport>,
}

impl RocketReport {
    /// The figures of `rocket`.
    #[must_use]
    pub fn new(rocket: &Rocket) -> Self {
        let csys = rocket.csys();
        RocketReport {
            total_mass_t0_kg: rocket.total_mass(0.0),
            dry_mass_kg: rocket.dry_mass(),
            center_of_mass_t0_m: rocket.center_of_mass(0.0),
            cp_position_mach0_m: rocket.cp_position(0.0),
            static_margin_t0: rocket.static_margin(0.0),
            static_margin_burnout: rocket.static_margin(rocket.burn_out()),
            surfaces: rocket
                .surfaces()
                .iter()
                .map(|s| SurfaceReport {
                    name: s.name.clone(),
                    cn_alpha_mach0: s.cn_alpha(0.0),
                    cp_m: s.cp_user(csys),
                })
                .collect(),
        }
    }
}

impl fmt::Display for RocketReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let rows = [
            ("total mass at t = 0", self.total_mass_t0_kg, "kg"),
            ("dry mass (rocket + motor)", self.dry_mass_kg, "kg"),
            ("centre of mass at t = 0", self.center_of_mass_t0_m, "m"),
            ("centre of pressure, Mach 0", self.cp_position_mach0_m, "m"),
            ("static margin at t = 0", self.static_margin_t0, "cal"),
            (
                "static margin at burn-out",
                self.static_margin_burnout,
                "cal",
            ),
        ];
        writeln!(f, "Rocket")?;
        for (label, value, unit) in rows {
            writeln!(f, "  {label:<28} {value:>12.6} {unit}")?;
        }
        let width = self
            .surfaces
            .iter()
            .map(|s| s.name.len())
            .max()
            .unwrap_or(0)
            .max(7);
        writeln!(
            f,
            "  {:<width$} {:>14} {:>12}",
            "surface", "CNα(M=0) /rad", "CP (m)"
        )?;
        for s in &self.surfaces {
            writeln!(
                f,
                "  {:<width$} {:>14.6} {:>12.6}",
                s.name, s.cn_alpha_mach0, s.cp_m
            )?;
        }
        Ok(())
    }
}

/// Drawing width in px of [`draw_rocket_svg`].
const WIDTH: f64 = 1000.0;
/// Margin around the drawing, px.
const MARGIN: f64 = 40.0;

/// Escapes text for SVG.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A side view of the rocket to scale, as SVG text: nose, body tubes, tails, fins (top and
/// bottom), nozzle exit, rail buttons, the centre of mass at t = 0 (CG) and of dry mass
/// (CDM), and the centre of pressure at Mach 0 (CP). The horizontal axis is the rocket's user
/// axis growing to the right, as in RocketPy's `Rocket.draw()`. The surfaces of a pod set
/// (`[rocket.pods]`) are drawn as dashed outlines on the rocket's axis, apart from the body
/// (the mission gives a pod's axial place and roll position, not its radial distance).
#[must_use]
pub fn draw_rocket_svg(mission: &Mission, rocket: &Rocket) -> String {
    let csys = rocket.csys();
    let radius = rocket.radius();
    // Axial extent and tallest radial extent of everything drawn, in user coordinates.
    let mut zs = vec![
        rocket.nozzle_position(),
        rocket.center_of_mass(0.0),
        rocket.cp_position(0.0),
    ];
    let mut tallest = radius;
    for s in rocket.surfaces() {
        zs.push(s.position);
        zs.push(s.position - csys * s.geometry.length());
        tallest = tallest.max(s.geometry.max_radius());
    }
    let zmin = zs.iter().copied().fold(f64::INFINITY, f64::min);
    let zmax = zs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let span = (zmax - zmin).max(1e-6);
    let scale = (WIDTH - 2.0 * MARGIN) / span;
    let height = 2.0 * (tallest * scale + MARGIN) + 60.0;
    let axis = height / 2.0 + 10.0;
    let canvas = Canvas {
        zmin,
        scale,
        axis,
        csys,
    };

    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{height:.1}" viewBox="0 0 {WIDTH} {height:.1}" font-family="sans-serif" font-size="12">"#
    );
    let title = mission
        .spec
        .name
        .clone()
        .unwrap_or_else(|| mission.path.display().to_string());
    let _ = writeln!(
        svg,
        r#"<text x="{MARGIN}" y="20" font-size="14">{} — static margin {:.2} cal at t = 0</text>"#,
        escape(&title),
        rocket.static_margin(0.0)
    );
    let _ = writeln!(
        svg,
        r##"<line x1="{:.2}" y1="{axis:.2}" x2="{:.2}" y2="{axis:.2}" stroke="#999" stroke-dasharray="6 4"/>"##,
        MARGIN / 2.0,
        WIDTH - MARGIN / 2.0
    );
    draw_body(&mut svg, rocket, &canvas);
    draw_markers(&mut svg, rocket, &canvas, height);
    svg.push_str("</svg>\n");
    svg
}

/// The drawing's coordinates: user axial positions `z` to the right from `zmin`, radii up
/// from the axis at `axis`, both at `scale` pixels per metre (`csys`: the rocket's axis sign).
struct Canvas {
    zmin: f64,
    scale: f64,
    axis: f64,
    csys: f64,
}

impl Canvas {
    /// The drawing's abscissa of axial position `z`.
    fn x(&self, z: f64) -> f64 {
        MARGIN + (z - self.zmin) * self.scale
    }
    /// The drawing's ordinate of radius `r` (negative below the axis).
    fn y(&self, r: f64) -> f64 {
        self.axis - r * self.scale
    }
}

/// Polygon points as SVG's `points` attribute.
fn points_text(points: &[(f64, f64)]) -> String {
    points
        .iter()
        .map(|(a, b)| format!("{a:.2},{b:.2}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A filled, outlined polygon.
fn polygon(svg: &mut String, points: &[(f64, f64)], fill: &str) {
    let _ = writeln!(
        svg,
        r##"<polygon points="{}" fill="{fill}" stroke="#222" stroke-width="1"/>"##,
        points_text(points)
    );
}

/// A pod surface: a dashed outline, named, over the body.
fn pod_outline(svg: &mut String, s: &Surface, points: &[(f64, f64)]) {
    let count = s.pod.map_or(1, |p| p.count);
    let _ = writeln!(
        svg,
        r##"<polygon points="{}" fill="none" stroke="#6a3d9a" stroke-width="1" stroke-dasharray="4 3"><title>{} (on {count} pod(s), drawn on the rocket axis)</title></polygon>"##,
        points_text(points),
        escape(&s.name)
    );
}

/// A surface's outline polygons, in drawing coordinates: a nose's profile above and below the
/// axis, a tail's quadrilateral, one tube fin and one fin above and below the body.
fn outlines(c: &Canvas, s: &Surface) -> Vec<Vec<(f64, f64)>> {
    let csys = c.csys;
    let (z0, z1) = (s.position, s.position - csys * s.geometry.length());
    let quad = |r0: f64, r1: f64| {
        vec![
            (c.x(z0), c.y(r0)),
            (c.x(z1), c.y(r1)),
            (c.x(z1), c.y(-r1)),
            (c.x(z0), c.y(-r0)),
        ]
    };
    match &s.geometry {
        Geometry::Nose { profile, .. } => {
            let mut pts: Vec<(f64, f64)> = profile
                .iter()
                .map(|p| (c.x(s.position - csys * p[0]), c.y(p[1])))
                .collect();
            pts.extend(
                profile
                    .iter()
                    .rev()
                    .map(|p| (c.x(s.position - csys * p[0]), c.y(-p[1]))),
            );
            vec![pts]
        }
        Geometry::Tail {
            top_radius,
            bottom_radius,
            ..
        } => vec![quad(*top_radius, *bottom_radius)],
        // One tube seen from the side above and below the body.
        Geometry::TubeFins {
            outer_radius,
            body_radius,
            ..
        } => [1.0, -1.0]
            .iter()
            .map(|side| {
                let (r0, r1) = (
                    side * body_radius,
                    side * (body_radius + 2.0 * outer_radius),
                );
                vec![
                    (c.x(z0), c.y(r0)),
                    (c.x(z1), c.y(r0)),
                    (c.x(z1), c.y(r1)),
                    (c.x(z0), c.y(r1)),
                ]
            })
            .collect(),
        // One fin above and one below the axis.
        Geometry::Fins {
            outline,
            body_radius,
            ..
        } => [1.0, -1.0]
            .iter()
            .map(|side| {
                outline
                    .iter()
                    .map(|p| {
                        (
                            c.x(s.position - csys * p[0]),
                            c.y(side * (body_radius + p[1])),
                        )
                    })
                    .collect()
            })
            .collect(),
    }
}

/// The rocket's own surfaces (noses, tails and tube fins, then body tubes laid between the
/// shells, then fins on top) and its pod surfaces as dashed outlines.
fn draw_body(svg: &mut String, rocket: &Rocket, c: &Canvas) {
    let csys = c.csys;
    // Shells (nose, tails) from front to aft, to lay body tubes between them.
    let body = |z: f64| csys * (z - rocket.center_of_dry_mass());
    let mut shells: Vec<(f64, f64, f64, f64)> = Vec::new(); // (front z, aft z, front r, aft r)
    let mut aft_most = rocket.nozzle_position();
    let own = || rocket.surfaces().iter().filter(|s| s.pod.is_none());
    for s in own() {
        let aft = s.position - csys * s.geometry.length();
        if body(aft) < body(aft_most) {
            aft_most = aft;
        }
        let fill = match &s.geometry {
            Geometry::Nose {
                base_radius,
                length,
                ..
            } => {
                shells.push((s.position, s.position - csys * length, 0.0, *base_radius));
                "#d9e4f5"
            }
            Geometry::Tail {
                top_radius,
                bottom_radius,
                ..
            } => {
                shells.push((s.position, aft, *top_radius, *bottom_radius));
                "#d9e4f5"
            }
            Geometry::TubeFins { .. } => "#f2d8c9",
            Geometry::Fins { .. } => continue,
        };
        for pts in outlines(c, s) {
            polygon(svg, &pts, fill);
        }
    }
    shells.sort_by(|a, b| body(b.0).total_cmp(&body(a.0)));
    let mut tube_start: Option<(f64, f64)> = None; // (z, radius)
    for &(front, aft, _, aft_radius) in &shells {
        if let Some((z0, r)) = tube_start {
            if body(z0) > body(front) {
                let pts = [
                    (c.x(z0), c.y(r)),
                    (c.x(front), c.y(r)),
                    (c.x(front), c.y(-r)),
                    (c.x(z0), c.y(-r)),
                ];
                polygon(svg, &pts, "#eef2f8");
            }
        }
        tube_start = Some((aft, aft_radius));
    }
    if let Some((z0, r)) = tube_start {
        if body(z0) > body(aft_most) {
            let pts = [
                (c.x(z0), c.y(r)),
                (c.x(aft_most), c.y(r)),
                (c.x(aft_most), c.y(-r)),
                (c.x(z0), c.y(-r)),
            ];
            polygon(svg, &pts, "#eef2f8");
        }
    }
    // Fins on top of the tubes.
    for s in own().filter(|s| matches!(s.geometry, Geometry::Fins { .. })) {
        for pts in outlines(c, s) {
            polygon(svg, &pts, "#b8c9e6");
        }
    }
    // Pod surfaces: dashed outlines on the rocket's axis, named.
    for s in rocket.surfaces().iter().filter(|s| s.pod.is_some()) {
        for pts in outlines(c, s) {
            pod_outline(svg, s, &pts);
        }
    }
}

/// The nozzle exit, the rail buttons, the CG, CDM and CP markers and their labels.
fn draw_markers(svg: &mut String, rocket: &Rocket, c: &Canvas, height: f64) {
    let radius = rocket.radius();
    let axis = c.axis;
    // Nozzle exit.
    let noz = rocket.nozzle_position();
    let rn = rocket.motor().nozzle_radius;
    let _ = writeln!(
        svg,
        r##"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="#c03" stroke-width="3"><title>nozzle exit</title></line>"##,
        c.x(noz),
        c.y(rn),
        c.x(noz),
        c.y(-rn)
    );
    if let Some(b) = rocket.rail_buttons() {
        for z in [b.upper_position, b.lower_position] {
            let _ = writeln!(
                svg,
                r##"<rect x="{:.2}" y="{:.2}" width="6" height="5" fill="#555"><title>rail button</title></rect>"##,
                c.x(z) - 3.0,
                c.y(radius) - 5.0
            );
        }
    }
    // Markers: CG (black/white quartered disc), CDM (hollow), CP (red disc with dot).
    let marker_y = axis;
    let cg = c.x(rocket.center_of_mass(0.0));
    let _ = writeln!(
        svg,
        r##"<g><title>centre of mass, t = 0</title><circle cx="{cg:.2}" cy="{marker_y:.2}" r="7" fill="#fff" stroke="#000"/><path d="M{cg:.2},{marker_y:.2} h7 a7,7 0 0,0 -7,-7 z M{cg:.2},{marker_y:.2} h-7 a7,7 0 0,0 7,7 z" fill="#000"/></g>"##
    );
    let cdm = c.x(rocket.center_of_dry_mass());
    let _ = writeln!(
        svg,
        r##"<circle cx="{cdm:.2}" cy="{marker_y:.2}" r="4" fill="none" stroke="#000"><title>centre of dry mass</title></circle>"##
    );
    let cp = c.x(rocket.cp_position(0.0));
    let _ = writeln!(
        svg,
        r##"<g><title>centre of pressure, Mach 0</title><circle cx="{cp:.2}" cy="{marker_y:.2}" r="7" fill="#c03" fill-opacity="0.8"/><circle cx="{cp:.2}" cy="{marker_y:.2}" r="2" fill="#fff"/></g>"##
    );
    let label_y = height - 12.0;
    let _ = writeln!(
        svg,
        r#"<text x="{cg:.2}" y="{label_y:.2}" text-anchor="middle">CG {:.3} m</text>"#,
        rocket.center_of_mass(0.0)
    );
    let _ = writeln!(
        svg,
        r##"<text x="{cp:.2}" y="{:.2}" text-anchor="middle" fill="#c03">CP {:.3} m</text>"##,
        label_y - 16.0,
        rocket.cp_position(0.0)
    );
}
