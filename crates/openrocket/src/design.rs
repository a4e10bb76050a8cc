//! The OpenRocket document as a component tree with absolute axial positions, and its
//! simulations (launch conditions, motor per configuration).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::OrkError;

/// The component types the reader knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// `<stage>`.
    Stage,
    /// `<nosecone>`.
    NoseCone,
    /// `<bodytube>`.
    BodyTube,
    /// `<transition>`.
    Transition,
    /// `<trapezoidfinset>`.
    TrapezoidFins,
    /// `<ellipticalfinset>`.
    EllipticalFins,
    /// `<freeformfinset>`.
    FreeFormFins,
    /// `<launchlug>`.
    LaunchLug,
    /// `<railbutton>`.
    RailButton,
    /// `<innertube>` (a motor mount, possibly).
    InnerTube,
    /// `<tubecoupler>`.
    TubeCoupler,
    /// `<centeringring>`.
    CenteringRing,
    /// `<bulkhead>`.
    Bulkhead,
    /// `<engineblock>`.
    EngineBlock,
    /// `<parachute>`.
    Parachute,
    /// `<streamer>`.
    Streamer,
    /// `<shockcord>`.
    ShockCord,
    /// `<masscomponent>`.
    MassComponent,
    /// `<tubefinset>`.
    TubeFins,
    /// `<podset>`: `instancecount` side bodies around the body it sits on.
    PodSet,
}

impl Kind {
    fn from_tag(tag: &str) -> Option<Kind> {
        Some(match tag {
            "stage" => Kind::Stage,
            "nosecone" => Kind::NoseCone,
            "bodytube" => Kind::BodyTube,
            "transition" => Kind::Transition,
            "trapezoidfinset" => Kind::TrapezoidFins,
            "ellipticalfinset" => Kind::EllipticalFins,
            "freeformfinset" => Kind::FreeFormFins,
            "launchlug" => Kind::LaunchLug,
            "railbutton" => Kind::RailButton,
            "innertube" => Kind::InnerTube,
            "tubecoupler" => Kind::TubeCoupler,
            "centeringring" => Kind::CenteringRing,
            "bulkhead" => Kind::Bulkhead,
            "engineblock" => Kind::EngineBlock,
            "parachute" => Kind::Parachute,
            "streamer" => Kind::Streamer,
            "shockcord" => Kind::ShockCord,
            "masscomponent" => Kind::MassComponent,
            "tubefinset" => Kind::TubeFins,
            "podset" => Kind::PodSet,
            _ => return None,
        })
    }

    /// A part of the outer body of revolution.
    pub fn is_body(self) -> bool {
        matches!(self, Kind::NoseCone | Kind::BodyTube | Kind::Transition)
    }

    /// A part in the airflow: the body, fins, tube fins, launch lugs and rail buttons.
    pub fn is_aerodynamic(self) -> bool {
        self.is_body()
            || self.is_fins()
            || matches!(self, Kind::TubeFins | Kind::LaunchLug | Kind::RailButton)
    }

    /// A fin set.
    pub fn is_fins(self) -> bool {
        matches!(
            self,
            Kind::TrapezoidFins | Kind::EllipticalFins | Kind::FreeFormFins
        )
    }
}

/// One component, its position resolved.
#[derive(Debug, Clone)]
pub struct Component {
    /// Its type.
    pub kind: Kind,
    /// Its name in the design.
    pub name: String,
    /// Axial position of its forward end, from the nose tip (m).
    pub x: f64,
    /// Its axial length (m).
    pub length: f64,
    /// Text of its direct child elements (`length`, `thickness`, ...).
    pub fields: BTreeMap<String, String>,
    /// Material density (kg/m³, kg/m² or kg/m by the material type) and type.
    pub material: Option<(f64, String)>,
    /// A second material (the line of a parachute).
    pub line_material: Option<f64>,
    /// The density of a fin set's fillets (kg/m³).
    pub fillet_material: Option<f64>,
    /// Fin outline points of a free-form fin set.
    pub points: Vec<[f64; 2]>,
    /// Motors of a motor mount by configuration id: (manufacturer, designation, delay).
    pub motors: BTreeMap<String, MotorRef>,
    /// Mount overhang (m).
    pub overhang: f64,
    /// Of a stage: its separation by configuration id, and under `""` its default.
    pub separations: BTreeMap<String, SeparationRef>,
    /// Of a recovery device: its deployment settings (`deployevent`, `deployaltitude`,
    /// `deploydelay`) by configuration id, where a configuration has its own.
    pub deployments: BTreeMap<String, BTreeMap<String, String>>,
    /// Sub-components.
    pub children: Vec<Component>,
    file: PathBuf,
}

/// A motor as the design names it.
#[derive(Debug, Clone, PartialEq)]
pub struct MotorRef {
    /// Manufacturer.
    pub manufacturer: String,
    /// Designation.
    pub designation: String,
    /// Ejection delay (s), `None` for a plugged motor.
    pub delay: Option<f64>,
    /// Diameter (m).
    pub diameter: f64,
    /// Length (m).
    pub length: f64,
    /// What ignites it (`automatic`, `launch`, `burnout`, `ejection`, `never`) and the delay
    /// after that event (s): the mount's setting for this configuration, else its default.
    pub ignition: (String, f64),
}

/// When a stage separates from the stack above it: OpenRocket's event (`upperignition`,
/// `ignition`, `burnout`, `ejection`, `launch`, `never`) and the delay after it (s).
#[derive(Debug, Clone, PartialEq)]
pub struct SeparationRef {
    /// The event.
    pub event: String,
    /// The delay, s.
    pub delay: f64,
}

/// One stored simulation.
#[derive(Debug, Clone)]
pub struct Simulation {
    /// Its name.
    pub name: String,
    /// Motor configuration id.
    pub config: String,
    /// The stages (by number, top first) that configuration leaves inactive.
    pub inactive_stages: Vec<usize>,
    /// `<conditions>` children.
    pub conditions: BTreeMap<String, String>,
}

/// The whole design.
#[derive(Debug, Clone)]
pub struct Design {
    /// Rocket name.
    pub name: String,
    /// The stages, top (the sustainer, OpenRocket's stage 0) first: the bottom one burns
    /// first.
    pub stages: Vec<Component>,
    /// Stored simulations.
    pub simulations: Vec<Simulation>,
}

/// A number, OpenRocket's way: `"auto 0.0125"` is the automatic value it resolved.
pub(crate) fn number(text: &str) -> Option<f64> {
    let t = text.trim();
    let t = t.strip_prefix("auto").map_or(t, str::trim);
    t.parse::<f64>().ok()
}

impl Component {
    /// The number in child element `element`.
    ///
    /// # Errors
    /// [`OrkError::Value`] when it is absent, not a number or not finite.
    pub fn num(&self, element: &str) -> Result<f64, OrkError> {
        let problem = |p: &str| OrkError::Value {
            file: self.file.clone(),
            component: self.name.clone(),
            element: element.to_owned(),
            problem: p.to_owned(),
        };
        let text = self
            .fields
            .get(element)
            .ok_or_else(|| problem("is missing"))?;
        let v = number(text).ok_or_else(|| problem(&format!("{text:?} is not a number")))?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(problem(&format!("{text:?} is not a finite number")))
        }
    }

    /// The number in `element`, or `default` when the element is absent or `auto` without a
    /// value.
    ///
    /// # Errors
    /// As [`Component::num`] for a present value that is not a finite number.
    pub fn num_or(&self, element: &str, default: f64) -> Result<f64, OrkError> {
        match self.fields.get(element) {
            None => Ok(default),
            Some(t) if t.trim() == "auto" => Ok(default),
            Some(_) => self.num(element),
        }
    }

    /// The motor cluster of an inner tube: `(count, radius)`, the number of tubes (and
    /// motors) and the root mean square distance of their axes from the tube's position
    /// (m). OpenRocket places the tubes of a cluster configuration at unit points scaled
    /// by the separation `2 r_o · clusterscale` (the closest two tubes that far apart):
    /// rows, rings and rings around a centre tube, and a 3 × 3 grid, listed here by their
    /// count and `Σ |p|²` over the unit points (the rotation leaves it alone).
    ///
    /// # Errors
    /// [`OrkError::Unsupported`] for a configuration OpenRocket 24.12 does not have;
    /// [`OrkError::Value`] for a malformed radius or scale.
    pub fn cluster(&self) -> Result<(u32, f64), OrkError> {
        let ring5 = 1.0 / (2.0 * (std::f64::consts::PI / 5.0).sin());
        let (count, sum_squares) = match self.text("clusterconfiguration").unwrap_or("single") {
            "single" => (1, 0.0),
            "double" => (2, 0.5),
            "3-row" => (3, 2.0),
            "4-row" => (4, 5.0),
            "3-ring" => (3, 1.0),
            "4-ring" => (4, 2.0),
            "5-ring" => (5, 5.0 * ring5 * ring5),
            "6-ring" => (6, 6.0),
            "3-star" => (4, 3.0),
            "4-star" => (5, 4.0),
            "5-star" => (6, 5.0),
            "6-star" => (7, 6.0),
            "9-grid" => (9, 12.0 * 1.4 * 1.4),
            "9-star" => (9, 8.0 * 1.4 * 1.4),
            other => return Err(self.unsupported(&format!("a motor cluster ({other})"))),
        };
        if count == 1 {
            return Ok((1, 0.0));
        }
        let separation = 2.0 * self.dim("outerradius")? * self.positive_or("clusterscale", 1.0)?;
        Ok((count, separation * (sum_squares / f64::from(count)).sqrt()))
    }

    /// Outer and inner radius of a tube fin set of `fincount` tubes on a body of radius
    /// `body_radius` (m). OpenRocket's automatic radius makes three or more tubes touch
    /// each other around the body, `r = R sin(π/n) / (1 − sin(π/n))` (fewer: the body radius);
    /// the inner radius is the outer less `thickness`.
    ///
    /// # Errors
    /// As [`Component::dim`] for `radius`, `thickness` or `fincount`.
    pub fn tube_fin_radii(&self, body_radius: f64) -> Result<(f64, f64), OrkError> {
        let n = self.count_or("fincount", 1.0, 1.0)?;
        let outer = if self
            .text("radius")
            .is_none_or(|t| t.trim().starts_with("auto"))
        {
            if n < 3.0 {
                body_radius
            } else {
                let s = (std::f64::consts::PI / n).sin();
                body_radius * s / (1.0 - s)
            }
        } else {
            self.dim("radius")?
        };
        let inner = (outer - self.dim("thickness")?).max(0.0);
        Ok((outer, inner))
    }

    /// The placement of a pod set on a body of outer radius `parent_radius`: the number of
    /// pods, the distance of their axes from the rocket's axis (m) and the first pod's roll
    /// position (rad). OpenRocket's radius methods: `relative` (the offset from the parent
    /// tube's surface to the pod's surface: parent radius + offset + the pod's largest body
    /// radius), `surface` (touching: parent radius + pod radius), `free` (the offset is the
    /// distance) and `coaxial` (0).
    ///
    /// # Errors
    /// [`OrkError::Value`] for a malformed count or offset, [`OrkError::Unsupported`] for a
    /// radius method OpenRocket does not have.
    pub fn pod_placement(&self, parent_radius: f64) -> Result<(u32, f64, f64), OrkError> {
        let count = self.count_or("instancecount", 1.0, 1.0)?;
        let mut pod_radius: f64 = 0.0;
        for c in self.children.iter().filter(|c| c.kind.is_body()) {
            for e in ["radius", "aftradius", "foreradius"] {
                if c.fields.contains_key(e) {
                    pod_radius = pod_radius.max(c.dim(e)?);
                }
            }
        }
        let offset = self.num_or("radiusoffset", 0.0)?;
        let distance = match self.text("radiusoffsetmethod").unwrap_or("relative") {
            "relative" => parent_radius + offset + pod_radius,
            "surface" => parent_radius + pod_radius,
            "free" => offset,
            "coaxial" => 0.0,
            other => {
                return Err(self.unsupported(&format!("a pod radius method {other:?}")));
            }
        };
        let angle = self.num_or("angleoffset", 0.0)?.to_radians();
        Ok((count as u32, distance.max(0.0), angle))
    }

    /// A non-negative dimension.
    ///
    /// # Errors
    /// As [`Component::num`], and for a negative value.
    pub fn dim(&self, element: &str) -> Result<f64, OrkError> {
        let v = self.num(element)?;
        if v < 0.0 {
            return Err(self.value_error(element, &format!("{v} must not be negative")));
        }
        Ok(v)
    }

    /// A non-negative dimension, `default` when absent or `auto` (as [`Component::num_or`]).
    ///
    /// # Errors
    /// As [`Component::dim`].
    pub fn dim_or(&self, element: &str, default: f64) -> Result<f64, OrkError> {
        match self.fields.get(element) {
            None => Ok(default),
            Some(t) if t.trim() == "auto" => Ok(default),
            Some(_) => self.dim(element),
        }
    }

    /// A whole count of at least `least` (fins, instances, lines), `default` when absent or
    /// `auto` (as [`Component::num_or`]).
    ///
    /// # Errors
    /// As [`Component::num`], and for a fraction, a count below `least` or above 10,000.
    pub fn count_or(&self, element: &str, default: f64, least: f64) -> Result<f64, OrkError> {
        let v = self.num_or(element, default)?;
        if v.fract() != 0.0 || v < least || v > 10_000.0 {
            return Err(self.value_error(
                element,
                &format!("{v} is not a whole number from {least} to 10000"),
            ));
        }
        Ok(v)
    }

    /// A positive number (a drag coefficient, a scale), `default` when absent or `auto`.
    ///
    /// # Errors
    /// As [`Component::num`], and for zero or a negative value.
    pub fn positive_or(&self, element: &str, default: f64) -> Result<f64, OrkError> {
        let v = self.num_or(element, default)?;
        if v <= 0.0 {
            return Err(self.value_error(element, &format!("{v} must be positive")));
        }
        Ok(v)
    }

    /// The text of `element`.
    pub fn text(&self, element: &str) -> Option<&str> {
        self.fields.get(element).map(String::as_str)
    }

    /// An [`OrkError::Value`] about `element`.
    pub fn value_error(&self, element: &str, problem: &str) -> OrkError {
        OrkError::Value {
            file: self.file.clone(),
            component: self.name.clone(),
            element: element.to_owned(),
            problem: problem.to_owned(),
        }
    }

    /// An [`OrkError::Unsupported`] about this component.
    pub fn unsupported(&self, what: &str) -> OrkError {
        OrkError::Unsupported {
            file: self.file.clone(),
            component: self.name.clone(),
            what: what.to_owned(),
        }
    }

    /// The material density.
    ///
    /// # Errors
    /// [`OrkError::Value`] when there is none.
    pub fn density(&self) -> Result<f64, OrkError> {
        let density = self
            .material
            .as_ref()
            .map(|m| m.0)
            .ok_or_else(|| self.value_error("material", "is missing"))?;
        if density.is_finite() && density >= 0.0 {
            Ok(density)
        } else {
            Err(self.value_error(
                "material",
                &format!("density {density} is not a non-negative number"),
            ))
        }
    }

    /// This component and every descendant, depth first.
    pub fn walk(&self) -> Vec<&Component> {
        let mut out = vec![self];
        for c in &self.children {
            out.extend(c.walk());
        }
        out
    }
}

/// The text of `node`'s first `tag` child, trimmed, on one line: every control character
/// (a newline, a tab, `&#10;` decoded by the XML reader) becomes a space. Names and
/// designations end up in the mission's comments and warnings, where a newline would start a
/// line of TOML of the design's choosing; the values the importer needs never hold one.
fn child_text(node: roxmltree::Node<'_, '_>, tag: &str) -> Option<String> {
    node.children()
        .find(|c| c.has_tag_name(tag))
        .map(|c| one_line(c.text().unwrap_or("").trim()))
}

/// `text` with every control character replaced by a space.
pub(super) fn one_line(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect()
}

/// Axial length of a component for positioning, from its fields.
fn positioning_length(kind: Kind, c: &Component) -> Result<f64, OrkError> {
    Ok(match kind {
        Kind::TrapezoidFins | Kind::EllipticalFins => c.dim("rootchord")?,
        // The root chord: from the first outline point to the last (both on the body); a
        // swept tip may reach further aft.
        Kind::FreeFormFins => match (c.points.first(), c.points.last()) {
            (Some(a), Some(b)) => (b[0] - a[0]).abs(),
            _ => 0.0,
        },
        Kind::Parachute | Kind::Streamer | Kind::ShockCord | Kind::MassComponent => {
            c.dim_or("packedlength", 0.0)?
        }
        Kind::RailButton => c.dim_or("outerdiameter", 0.0)?,
        Kind::Stage => 0.0,
        // Set from its body parts before it is placed (`assembly_length`).
        Kind::PodSet => c.length,
        _ => c.dim_or("length", 0.0)?,
    })
}

const VERSIONS: [&str; 11] = [
    "1.0", "1.1", "1.2", "1.3", "1.4", "1.5", "1.6", "1.7", "1.8", "1.9", "1.10",
];

impl Design {
    /// Parses the OpenRocket document `text` of `file`.
    ///
    /// # Errors
    /// [`OrkError`]: malformed XML, an unknown version, no stage, parallel boosters, a value
    /// that is not a number.
    pub fn parse(file: &Path, text: &str) -> Result<Design, OrkError> {
        // The XML parser compares every attribute of an element with every other: a crowded
        // element is refused before it is parsed (as the thrust files' `.rse` reader does).
        if let Some((line, count)) = karman_propulsion::rse::crowded_element(text) {
            return Err(OrkError::Xml {
                file: file.to_owned(),
                message: format!(
                    "an element with {count} attributes at line {line} (at most {})",
                    karman_propulsion::rse::MAX_XML_ATTRIBUTES
                ),
            });
        }
        let doc = roxmltree::Document::parse(text).map_err(|e| OrkError::Xml {
            file: file.to_owned(),
            message: e.to_string(),
        })?;
        let root = doc.root_element();
        let container = |reason: &str| OrkError::Container {
            file: file.to_owned(),
            reason: reason.to_owned(),
        };
        if !root.has_tag_name("openrocket") {
            return Err(container(&format!(
                "the root element is <{}>, not <openrocket>",
                root.tag_name().name()
            )));
        }
        let version = root.attribute("version").unwrap_or("").to_owned();
        if !VERSIONS.contains(&version.as_str()) {
            return Err(OrkError::Version {
                file: file.to_owned(),
                version,
            });
        }
        let rocket = root
            .children()
            .find(|c| c.has_tag_name("rocket"))
            .ok_or_else(|| container("no <rocket> element"))?;
        let name = child_text(rocket, "name").unwrap_or_else(|| "OpenRocket design".to_owned());
        let stages: Vec<_> = rocket
            .children()
            .find(|c| c.has_tag_name("subcomponents"))
            .map(|s| s.children().filter(|c| c.is_element()).collect())
            .unwrap_or_default();
        if stages.is_empty() {
            return Err(container("a <rocket> without stages"));
        }
        let mut parsed: Vec<Component> = Vec::new();
        for node in &stages {
            let previous = parsed.last().map(|s| s.x + s.length);
            parsed.push(component(file, *node, None, previous)?);
        }
        resolve_automatic_radii(&mut parsed);
        let mut inactive: BTreeMap<String, Vec<usize>> = BTreeMap::new();
        for config in rocket
            .children()
            .filter(|c| c.has_tag_name("motorconfiguration"))
        {
            let id = config.attribute("configid").unwrap_or("").to_owned();
            let off = config
                .children()
                .filter(|s| s.has_tag_name("stage") && s.attribute("active") == Some("false"))
                .filter_map(|s| s.attribute("number").and_then(|n| n.parse().ok()))
                .collect();
            inactive.insert(id, off);
        }

        let mut simulations = Vec::new();
        if let Some(sims) = root.children().find(|c| c.has_tag_name("simulations")) {
            for s in sims.children().filter(|c| c.has_tag_name("simulation")) {
                let conditions_node = s.children().find(|c| c.has_tag_name("conditions"));
                let mut conditions = BTreeMap::new();
                if let Some(c) = conditions_node {
                    for e in c.children().filter(|e| e.is_element()) {
                        conditions.insert(
                            e.tag_name().name().to_owned(),
                            e.text().unwrap_or("").trim().to_owned(),
                        );
                    }
                }
                let config = conditions.get("configid").cloned().unwrap_or_default();
                simulations.push(Simulation {
                    name: child_text(s, "name").unwrap_or_default(),
                    inactive_stages: inactive.get(&config).cloned().unwrap_or_default(),
                    config,
                    conditions,
                });
            }
        }
        Ok(Design {
            name,
            stages: parsed,
            simulations,
        })
    }
}

/// How deep components may nest inside each other (stage, body tube, inner tube, ring, …).
pub const MAX_COMPONENT_DEPTH: usize = 64;

/// Reads one component element and its sub-components; `parent` is the parent's (top,
/// length) and `previous` the end of the previous body sibling (for `after` placement).
fn component(
    file: &Path,
    node: roxmltree::Node<'_, '_>,
    parent: Option<(f64, f64)>,
    previous: Option<f64>,
) -> Result<Component, OrkError> {
    let tag = node.tag_name().name();
    let name = child_text(node, "name").unwrap_or_else(|| tag.to_owned());
    let unsupported = |what: String| OrkError::Unsupported {
        file: file.to_owned(),
        component: name.clone(),
        what,
    };
    // The tree is walked recursively (here, in `Component::walk` and the mass model): a
    // crafted design nested thousands deep must end in an error, not overflow the stack.
    // Each component level is two XML levels (the element and its `<subcomponents>`).
    if node.ancestors().nth(2 * MAX_COMPONENT_DEPTH + 4).is_some() {
        return Err(unsupported(format!(
            "components nested more than {MAX_COMPONENT_DEPTH} deep (OpenRocket's own \
             designs nest a handful)"
        )));
    }
    let Some(kind) = Kind::from_tag(tag) else {
        let what = match tag {
            "parallelstage" => "a parallel booster set (side boosters with motors of their \
                                own, separated in flight; karman flies axial stages only)"
                .to_owned(),
            other => format!("a <{other}> component"),
        };
        return Err(unsupported(what));
    };
    let mut fields = BTreeMap::new();
    let mut material = None;
    let mut line_material = None;
    let mut fillet_material = None;
    let mut points = Vec::new();
    let mut motors = BTreeMap::new();
    let mut overhang = 0.0;
    let mut separations = BTreeMap::new();
    let mut deployments = BTreeMap::new();
    let mut axial = None;
    for e in node.children().filter(|e| e.is_element()) {
        let t = e.tag_name().name();
        let text = e.text().unwrap_or("").trim().to_owned();
        match t {
            "material" => {
                let d = e.attribute("density").and_then(|d| d.parse::<f64>().ok());
                material = d.map(|d| (d, e.attribute("type").unwrap_or("bulk").to_owned()));
            }
            "linematerial" => {
                line_material = e.attribute("density").and_then(|d| d.parse::<f64>().ok());
            }
            "radiusoffset" | "angleoffset" => {
                let method = e.attribute("method").unwrap_or("relative");
                fields.insert(format!("{t}method"), method.to_owned());
                fields.insert(t.to_owned(), text);
            }
            "filletmaterial" => {
                fillet_material = e.attribute("density").and_then(|d| d.parse::<f64>().ok());
            }
            "axialoffset" => {
                axial = Some((
                    e.attribute("method").unwrap_or("top").to_owned(),
                    text.clone(),
                ));
            }
            "finpoints" => points.extend(fin_points(file, &name, e)?),
            "motormount" => mount_motors(e, &mut overhang, &mut motors),
            "deploymentconfiguration" => {
                let id = e.attribute("configid").unwrap_or("").to_owned();
                let settings = e
                    .children()
                    .filter(|k| k.is_element())
                    .map(|k| {
                        (
                            k.tag_name().name().to_owned(),
                            k.text().unwrap_or("").trim().to_owned(),
                        )
                    })
                    .collect();
                deployments.insert(id, settings);
            }
            "separationconfiguration" => {
                let id = e.attribute("configid").unwrap_or("").to_owned();
                separations.insert(id, separation_of(e));
            }
            "subcomponents" | "appearance" | "insideappearance" | "motorconfiguration" => {}
            _ => {
                fields.insert(t.to_owned(), text);
            }
        }
    }
    let mut c = Component {
        kind,
        name: name.clone(),
        x: 0.0,
        length: 0.0,
        fields,
        material,
        line_material,
        fillet_material,
        points,
        motors,
        overhang,
        separations,
        deployments,
        children: Vec::new(),
        file: file.to_owned(),
    };
    if kind == Kind::Stage {
        c.separations.insert(String::new(), separation_of(node));
    }
    if kind == Kind::InnerTube {
        c.cluster()?;
    }
    if kind == Kind::PodSet {
        c.length = assembly_length(node);
    }
    c.length = positioning_length(kind, &c)?;
    c.x = axial_position(&c, axial.as_ref(), parent, previous)?;
    // Sub-components: body parts one after the other, the rest relative to this one.
    let mut end = None;
    if let Some(subs) = node.children().find(|s| s.has_tag_name("subcomponents")) {
        for s in subs.children().filter(|s| s.is_element()) {
            let child = component(file, s, Some((c.x, c.length)), end.or(Some(c.x)))?;
            if child.kind.is_body() {
                end = Some(child.x + child.length);
            }
            c.children.push(child);
        }
    }
    if kind == Kind::Stage {
        c.length = end.map_or(0.0, |e| e - c.x);
    }
    Ok(c)
}

/// The points of a free-form fin's `<finpoints>` element `e`, m.
///
/// # Errors
/// [`OrkError::Value`] for a point without finite `x` and `y`.
fn fin_points(
    file: &Path,
    component: &str,
    e: roxmltree::Node<'_, '_>,
) -> Result<Vec<[f64; 2]>, OrkError> {
    let mut points = Vec::new();
    for p in e.children().filter(|p| p.has_tag_name("point")) {
        let coordinate = |a: &str| {
            p.attribute(a)
                .and_then(|v| v.parse::<f64>().ok())
                .filter(|v| v.is_finite())
        };
        match (coordinate("x"), coordinate("y")) {
            (Some(x), Some(y)) => points.push([x, y]),
            _ => {
                return Err(OrkError::Value {
                    file: file.to_owned(),
                    component: component.to_owned(),
                    element: "finpoints".to_owned(),
                    problem: "a point without finite x and y".to_owned(),
                });
            }
        }
    }
    Ok(points)
}

/// The overhang and the motors of a `<motormount>` element `e`, each motor by its
/// configuration id, with the ignition event and delay of its configuration (else the
/// mount's, else OpenRocket's `automatic` at 0 s).
fn mount_motors(
    e: roxmltree::Node<'_, '_>,
    overhang: &mut f64,
    motors: &mut BTreeMap<String, MotorRef>,
) {
    if let Some(o) = child_text(e, "overhang").as_deref().and_then(number) {
        *overhang = o;
    }
    let ignition_of = |n: roxmltree::Node<'_, '_>| {
        (
            child_text(n, "ignitionevent"),
            child_text(n, "ignitiondelay").as_deref().and_then(number),
        )
    };
    let (default_event, default_delay) = ignition_of(e);
    for m in e.children().filter(|m| m.has_tag_name("motor")) {
        let id = m.attribute("configid").unwrap_or("").to_owned();
        let get = |t: &str| child_text(m, t).unwrap_or_default();
        let delay = child_text(m, "delay").and_then(|d| number(&d));
        let (event, ignition_delay) = e
            .children()
            .find(|c| {
                c.has_tag_name("ignitionconfiguration")
                    && c.attribute("configid") == Some(id.as_str())
            })
            .map_or((None, None), ignition_of);
        motors.insert(
            id,
            MotorRef {
                manufacturer: get("manufacturer"),
                designation: get("designation"),
                delay,
                diameter: number(&get("diameter")).unwrap_or(f64::NAN),
                length: number(&get("length")).unwrap_or(f64::NAN),
                ignition: (
                    event
                        .or_else(|| default_event.clone())
                        .unwrap_or_else(|| "automatic".to_owned()),
                    ignition_delay.or(default_delay).unwrap_or(0.0),
                ),
            },
        );
    }
}

/// The position of component `c` (its length known) from its `<axialoffset>` (`method`,
/// value; none: `after`), the parent's (top, length) and the end of the previous body sibling.
///
/// # Errors
/// An offset that is not a number or gives no finite position.
fn axial_position(
    c: &Component,
    axial: Option<&(String, String)>,
    parent: Option<(f64, f64)>,
    previous: Option<f64>,
) -> Result<f64, OrkError> {
    let (parent_top, parent_length) = parent.unwrap_or((0.0, 0.0));
    let (method, value) = match axial {
        Some((m, v)) => (
            m.as_str(),
            number(v)
                .ok_or_else(|| c.value_error("axialoffset", &format!("{v:?} is not a number")))?,
        ),
        None => ("after", 0.0),
    };
    let x = match method {
        "after" => previous.unwrap_or(parent_top) + value,
        "absolute" => value,
        "middle" => parent_top + 0.5 * parent_length - 0.5 * c.length + value,
        "bottom" => parent_top + parent_length - c.length + value,
        _ => parent_top + value,
    };
    if !x.is_finite() {
        return Err(c.value_error("axialoffset", "gives no finite position"));
    }
    Ok(x)
}

/// The length of a pod set: its body parts end to end (OpenRocket places them one after the
/// other from the pod's forward end), as needed to place the pod itself by its aft end or
/// middle.
fn assembly_length(node: roxmltree::Node<'_, '_>) -> f64 {
    node.children()
        .filter(|s| s.has_tag_name("subcomponents"))
        .flat_map(|s| s.children())
        .filter(|c| Kind::from_tag(c.tag_name().name()).is_some_and(Kind::is_body))
        .filter_map(|c| child_text(c, "length").as_deref().and_then(number))
        .sum()
}

/// The `<separationevent>` and `<separationdelay>` of a stage or one of its
/// `<separationconfiguration>`s (OpenRocket's default: at the ignition of the stage above).
fn separation_of(node: roxmltree::Node<'_, '_>) -> SeparationRef {
    SeparationRef {
        event: child_text(node, "separationevent").unwrap_or_else(|| "upperignition".to_owned()),
        delay: child_text(node, "separationdelay")
            .as_deref()
            .and_then(number)
            .unwrap_or(0.0),
    }
}

fn is_auto(c: &Component, element: &str) -> bool {
    c.text(element)
        .is_some_and(|t| t.trim_start().starts_with("auto"))
}

/// OpenRocket's automatic radii of the body (the parts of every stage, top to bottom): a tube or a transition end marked `auto` takes
/// the radius of the body part it joins (the previous part's aft end first, else the next
/// part's fore end), as OpenRocket resolves them when it opens the file; the value stored
/// after `auto` may be stale.
fn resolve_automatic_radii(stages: &mut [Component]) {
    let mut body: Vec<(usize, usize)> = Vec::new();
    for (s, stage) in stages.iter().enumerate() {
        for (i, c) in stage.children.iter().enumerate() {
            if c.kind.is_body() {
                body.push((s, i));
            }
        }
    }
    // (fore, aft, fore is auto, aft is auto) of each body part.
    let mut ends: Vec<(f64, f64, bool, bool)> = body
        .iter()
        .map(|&(s, i)| {
            let c = &stages[s].children[i];
            let get = |e: &str| c.text(e).and_then(number).unwrap_or(0.0);
            match c.kind {
                Kind::BodyTube => {
                    let a = is_auto(c, "radius");
                    (get("radius"), get("radius"), a, a)
                }
                Kind::NoseCone => (0.0, get("aftradius"), false, is_auto(c, "aftradius")),
                _ => (
                    get("foreradius"),
                    get("aftradius"),
                    is_auto(c, "foreradius"),
                    is_auto(c, "aftradius"),
                ),
            }
        })
        .collect();
    for _ in 0..ends.len() + 1 {
        for k in 0..ends.len() {
            let (s, i) = body[k];
            let tube = stages[s].children[i].kind == Kind::BodyTube;
            let previous = (k > 0 && !ends[k - 1].3).then(|| ends[k - 1].1);
            let next = (k + 1 < ends.len() && !ends[k + 1].2).then(|| ends[k + 1].0);
            if tube && ends[k].2 {
                if let Some(r) = previous.or(next) {
                    ends[k] = (r, r, false, false);
                }
                continue;
            }
            if ends[k].2 {
                if let Some(r) = previous {
                    ends[k].0 = r;
                    ends[k].2 = false;
                }
            }
            if ends[k].3 {
                if let Some(r) = next {
                    ends[k].1 = r;
                    ends[k].3 = false;
                }
            }
        }
    }
    for (k, &(s, i)) in body.iter().enumerate() {
        let c = &mut stages[s].children[i];
        let (fore, aft, _, _) = ends[k];
        match c.kind {
            Kind::BodyTube => {
                c.fields.insert("radius".to_owned(), fore.to_string());
            }
            Kind::NoseCone => {
                c.fields.insert("aftradius".to_owned(), aft.to_string());
            }
            _ => {
                c.fields.insert("foreradius".to_owned(), fore.to_string());
                c.fields.insert("aftradius".to_owned(), aft.to_string());
            }
        }
    }
}
