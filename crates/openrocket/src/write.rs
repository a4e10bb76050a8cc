//! The imported design as a commented mission file.

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::design::{Component, Design, Kind, MotorRef, SeparationRef, Simulation};
use crate::mass::{self, MassProps};
use crate::{ImportOptions, Imported, OrkError};

/// Significant digits of a number the importer writes: the design's values pass through unit
/// conversions and sums (inches and grams to metres and kilograms, component masses summed)
/// whose last bits are rounding noise, so `0.15239999999999998` (6 in) is written `0.1524`.
/// Twelve digits keep every figure of an OpenRocket file (which stores at most about ten)
/// and change a value by at most 5·10⁻¹³ of itself.
const SIGNIFICANT_DIGITS: usize = 12;

/// A TOML number: `v` rounded to [`SIGNIFICANT_DIGITS`], in the shortest form that reads
/// back to that rounded `f64`.
fn n(v: f64) -> String {
    let rounded = if v.is_finite() {
        format!("{v:.prec$e}", prec = SIGNIFICANT_DIGITS - 1)
            .parse::<f64>()
            .unwrap_or(v)
    } else {
        v
    };
    let s = format!("{rounded:?}");
    if s.contains('.') || s.contains('e') || s.contains("inf") || s.contains("NaN") {
        s
    } else {
        format!("{s}.0")
    }
}

fn quoted(s: &str) -> String {
    let mut out = String::from("\"");
    for ch in s.chars() {
        match ch {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A table key from a component name: lower case, `[a-z0-9_]`, unique.
fn key(name: &str, used: &mut BTreeSet<String>) -> String {
    let mut k: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    k = k.trim_matches('_').to_owned();
    while k.contains("__") {
        k = k.replace("__", "_");
    }
    if k.is_empty() {
        k = "part".to_owned();
    }
    let mut unique = k.clone();
    let mut i = 2;
    while used.contains(&unique) {
        unique = format!("{k}_{i}");
        i += 1;
    }
    used.insert(unique.clone());
    unique
}

/// The header line of a RASP `.eng` file: designation, diameter (mm), length (mm),
/// propellant and total mass (kg), manufacturer.
struct EngHeader {
    designation: String,
    manufacturer: String,
    diameter: f64,
    length: f64,
    propellant: f64,
    total: f64,
}

impl EngHeader {
    /// The length and diameter (m) of `motor`: those the design stores, else this file's.
    fn size_of(&self, motor: &MotorRef) -> (f64, f64) {
        let pick = |stored: f64, file: f64| if stored.is_finite() { stored } else { file };
        (
            pick(motor.length, self.length),
            pick(motor.diameter, self.diameter),
        )
    }
}

fn eng_header(path: &Path) -> Option<EngHeader> {
    let text = match karman_math::files::installed_read(path) {
        Some(bytes) => String::from_utf8(bytes.ok()?).ok()?,
        None => std::fs::read_to_string(path).ok()?,
    };
    let line = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with(';'))?;
    let f: Vec<&str> = line.split_whitespace().collect();
    if f.len() < 7 {
        return None;
    }
    let num = |s: &str| s.parse::<f64>().ok().filter(|v| v.is_finite());
    Some(EngHeader {
        designation: f[0].to_owned(),
        diameter: num(f[1])? / 1000.0,
        length: num(f[2])? / 1000.0,
        propellant: num(f[4])?,
        total: num(f[5])?,
        manufacturer: f[6].to_owned(),
    })
}

/// Designations match without case and separators, and an `.eng` name may carry the delay
/// (`C6-5`) where the design has `C6`.
fn same_designation(a: &str, b: &str) -> bool {
    let norm = |s: &str| -> String {
        s.chars()
            .filter(|c| c.is_ascii_alphanumeric())
            .map(|c| c.to_ascii_lowercase())
            .collect()
    };
    let (a, b) = (norm(a), norm(b));
    a == b
        || (a.len() < b.len()
            && b.starts_with(&a)
            && !b[a.len()..].starts_with(|c: char| c.is_ascii_alphabetic()))
}

fn find_motor(
    file: &Path,
    motor: &MotorRef,
    options: &ImportOptions,
) -> Result<(PathBuf, EngHeader), OrkError> {
    let mut places: Vec<PathBuf> = options.motors.clone();
    // A bare file name's parent is the empty path: the current folder.
    let design_dir = file
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    places.push(design_dir);
    let mut candidates = Vec::new();
    for p in &places {
        if p.is_dir() {
            let mut entries: Vec<PathBuf> = std::fs::read_dir(p)
                .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
                .unwrap_or_default();
            entries.sort();
            candidates.extend(entries.into_iter().filter(|e| {
                e.extension()
                    .and_then(|x| x.to_str())
                    .is_some_and(|x| x.eq_ignore_ascii_case("eng"))
            }));
        } else {
            candidates.push(p.clone());
        }
    }
    for c in candidates {
        if let Some(h) = eng_header(&c) {
            let maker = h.manufacturer.to_ascii_lowercase();
            let wanted = motor.manufacturer.to_ascii_lowercase();
            let maker_ok = maker.contains(&wanted) || wanted.contains(&maker) || wanted.is_empty();
            if maker_ok && same_designation(&motor.designation, &h.designation) {
                return Ok((c, h));
            }
        }
    }
    Err(OrkError::Motor {
        file: file.to_owned(),
        manufacturer: motor.manufacturer.clone(),
        designation: motor.designation.clone(),
        searched: places
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", "),
    })
}

/// `path` relative to `base` when it lies below it, else as given.
fn relative(path: &Path, base: Option<&Path>) -> String {
    let absolute = |p: &Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
    let shown = base
        .and_then(|b| {
            let (p, b) = (absolute(path), absolute(b));
            pathdiff(&p, &b)
        })
        .unwrap_or_else(|| absolute(path));
    shown.display().to_string()
}

/// `path` relative to the folder `base` (both absolute), with `..` steps.
fn pathdiff(path: &Path, base: &Path) -> Option<PathBuf> {
    let p: Vec<_> = path.components().collect();
    let b: Vec<_> = base.components().collect();
    let common = p.iter().zip(&b).take_while(|(x, y)| x == y).count();
    // Only the root in common: the absolute path reads better.
    if common <= 1 {
        return None;
    }
    let mut out = PathBuf::new();
    for _ in common..b.len() {
        out.push("..");
    }
    for c in &p[common..] {
        out.push(c);
    }
    Some(out)
}

fn condition(sim: &Simulation, key: &str, default: f64) -> f64 {
    sim.conditions
        .get(key)
        .and_then(|t| t.parse::<f64>().ok())
        .filter(|v| v.is_finite())
        .unwrap_or(default)
}

/// One body of the imported flight: consecutive OpenRocket stages, top first, flown as one
/// airframe with the one motor among them that OpenRocket lights (a stage without a lit
/// motor in the chosen configuration rides on the stage below it, or, at the bottom of the
/// rocket, on the stage above it when its separation never fires).
struct Group<'a> {
    /// The OpenRocket stages, top first.
    stages: Vec<&'a Component>,
    /// OpenRocket's number of the first (0: the top stage).
    number: usize,
    /// The motor mount of the stage with the lit motor.
    mount: &'a Component,
    /// Its motor in the configuration.
    motor: &'a MotorRef,
    /// The index in `stages` of the stage with the lit motor.
    powered: usize,
    /// The further motors lit in a single-stage design's one stage, with their mounts, in
    /// the order of their ignition (`[[extra_motors]]`).
    extra: Vec<(&'a Component, &'a MotorRef)>,
    /// The motors of its stages that OpenRocket never lights in the configuration, with
    /// their mounts: carried as mass.
    unlit: Vec<(&'a Component, &'a MotorRef)>,
}

impl Group<'_> {
    fn name(&self) -> &str {
        &self.stages[0].name
    }

    /// Every component of its stages.
    fn all(&self) -> Vec<&Component> {
        self.stages.iter().flat_map(|s| s.walk()).collect()
    }

    /// The body parts (nose cone, tubes, transitions) of its stages, top first.
    fn body(&self) -> Vec<&Component> {
        self.stages
            .iter()
            .flat_map(|s| s.children.iter().filter(|c| c.kind.is_body()))
            .collect()
    }
}

fn unsupported(file: &Path, component: &str, what: String) -> OrkError {
    OrkError::Unsupported {
        file: file.to_owned(),
        component: component.to_owned(),
        what,
    }
}

/// A time after an OpenRocket event, for messages.
fn after(event: &str, delay: f64) -> String {
    if delay == 0.0 {
        format!("at {event}")
    } else {
        format!("{delay} s after {event}")
    }
}

/// Whether OpenRocket lights the motor `motor` of stage `number` (0: the top) of a rocket
/// whose bottom stage is `bottom`, given `below`, whether the stage under it has a lit motor
/// and that motor's ejection delay (`None`: plugged). OpenRocket's ignition events
/// (`IgnitionEvent`, read for the method): `launch` at launch; `automatic` at launch in the
/// bottom stage, elsewhere as `ejection`; `ejection` and `burnout` at the ejection charge or
/// burn-out of a motor in the stage directly below; `never` never. An event this reader
/// does not know counts as lit, for the staging to refuse it by name.
fn lit(motor: &MotorRef, number: usize, bottom: usize, below: Option<Option<f64>>) -> bool {
    match motor.ignition.0.as_str() {
        "launch" => true,
        "automatic" if number == bottom => true,
        "automatic" | "ejection" => below.is_some_and(|delay| delay.is_some()),
        "burnout" => below.is_some(),
        "never" => false,
        _ => true,
    }
}

/// Why OpenRocket never lights `motor` (`bottom`: its stage is the bottom one; `below` as
/// for [`lit`]), for the import's note.
fn unlit_reason(motor: &MotorRef, bottom: bool, below: Option<Option<f64>>) -> String {
    let (event, _) = &motor.ignition;
    match event.as_str() {
        "never" => "its ignition event is `never`".to_owned(),
        _ if bottom => format!(
            "its ignition event `{event}` waits for a stage below it, and it is the bottom stage"
        ),
        _ if below.is_none() => {
            format!(
                "its ignition event `{event}` waits for a motor of the stage below, which has none lit"
            )
        }
        _ => format!(
            "its ignition event `{event}` waits for the ejection charge of the stage below, \
             whose motor is plugged"
        ),
    }
}

/// Whether the separation of stage `number` (a stage without a lit motor) from the stage
/// above fires in the flight: OpenRocket's separation events at the ignition, burn-out or
/// ejection of the stage's own motor never do; `upperignition` does when the stage above
/// has a lit motor (`above_lit`); `launch`, `apogee` and the altitudes do.
fn separation_fires(separation: &SeparationRef, above_lit: bool) -> bool {
    match separation.event.as_str() {
        "never" | "ignition" | "burnout" | "ejection" => false,
        "upperignition" => above_lit,
        _ => true,
    }
}

/// A stage's motor mount with the motor the configuration puts in it.
type Mount<'a> = (&'a Component, &'a MotorRef);

/// Each stage's motor mount in the configuration of `sim` (none for a stage without one; the
/// first lit of a single-stage design with several), and the other mounts of such a design.
///
/// # Errors
/// A stage the simulation leaves inactive; several motors in one stage of a multi-stage
/// rocket.
fn stage_mounts<'a>(
    file: &Path,
    design: &'a Design,
    sim: &Simulation,
) -> Result<(Vec<Option<Mount<'a>>>, Vec<Mount<'a>>), OrkError> {
    let mut mounts: Vec<Option<Mount<'a>>> = Vec::new();
    let mut others: Vec<Mount<'a>> = Vec::new();
    for (number, stage) in design.stages.iter().enumerate() {
        if sim.inactive_stages.contains(&number) {
            return Err(unsupported(
                file,
                &stage.name,
                format!("a stage left inactive by simulation {:?}", sim.name),
            ));
        }
        let found: Vec<&Component> = stage
            .walk()
            .into_iter()
            .filter(|c| c.motors.contains_key(&sim.config))
            .collect();
        match found.as_slice() {
            [] => mounts.push(None),
            [mount] => mounts.push(Some((*mount, &mount.motors[&sim.config]))),
            several if design.stages.len() == 1 => {
                // A single-stage design: the motors lit (at launch plus their delays) first,
                // in the order of their ignition, then those never lit; the first is
                // `[motor]`, the other lit ones `[[extra_motors]]`.
                let mut all: Vec<(&'a Component, &'a MotorRef)> = several
                    .iter()
                    .map(|m| (*m, &m.motors[&sim.config]))
                    .collect();
                all.sort_by(|a, b| {
                    let key =
                        |(_, m): &(&Component, &MotorRef)| (!lit(m, 0, 0, None), m.ignition.1);
                    let (ka, kb) = (key(a), key(b));
                    ka.0.cmp(&kb.0).then(ka.1.total_cmp(&kb.1))
                });
                mounts.push(Some(all[0]));
                others = all[1..].to_vec();
            }
            several => {
                let names: Vec<String> = several.iter().map(|m| m.name.clone()).collect();
                return Err(unsupported(
                    file,
                    &names.join(", "),
                    "several motors in one stage of a multi-stage rocket".to_owned(),
                ));
            }
        }
    }
    Ok((mounts, others))
}

/// Which of the stages' mounts OpenRocket lights, from the bottom stage (`bottom`) up (an
/// upper motor lit by the ejection charge below it); a warning for each it never lights.
fn lit_mounts(
    mounts: &[Option<Mount<'_>>],
    bottom: usize,
    warnings: &mut Vec<String>,
) -> Vec<bool> {
    let mut lit_motor: Vec<bool> = vec![false; mounts.len()];
    for number in (0..mounts.len()).rev() {
        if let Some((mount, motor)) = mounts[number] {
            let below = (number < bottom && lit_motor[number + 1])
                .then(|| mounts[number + 1].and_then(|(_, m)| m.delay));
            lit_motor[number] = lit(motor, number, bottom, below);
            if !lit_motor[number] {
                warnings.push(format!(
                    "`{}`: OpenRocket never lights its {} {} in this configuration ({}); it is \
                     carried as mass (its full mass from the thrust curve)",
                    mount.name,
                    motor.manufacturer,
                    motor.designation,
                    unlit_reason(motor, number == bottom, below)
                ));
            }
        }
    }
    lit_motor
}

/// The design's stages grouped into the bodies karman flies ([`Group`]) for `sim`.
fn groups<'a>(
    file: &Path,
    design: &'a Design,
    sim: &Simulation,
    warnings: &mut Vec<String>,
) -> Result<Vec<Group<'a>>, OrkError> {
    let (mounts, others) = stage_mounts(file, design, sim)?;
    let bottom = design.stages.len() - 1;
    let lit_motor = lit_mounts(&mounts, bottom, warnings);

    let mut out: Vec<Group<'a>> = Vec::new();
    let mut pending: Vec<&Component> = Vec::new();
    let mut unlit = Vec::new();
    let mut first = 0;
    for (number, stage) in design.stages.iter().enumerate() {
        if pending.is_empty() {
            first = number;
        }
        pending.push(stage);
        match mounts[number] {
            Some((mount, motor)) if lit_motor[number] => {
                out.push(Group {
                    powered: pending.len() - 1,
                    stages: std::mem::take(&mut pending),
                    number: first,
                    mount,
                    motor,
                    extra: Vec::new(),
                    unlit: std::mem::take(&mut unlit),
                });
            }
            Some(dead) => unlit.push(dead),
            None => {}
        }
    }
    if out.is_empty() {
        return Err(unsupported(
            file,
            &sim.name,
            "a simulation without a motor lit".to_owned(),
        ));
    }
    // The other motors of a single-stage design: those OpenRocket lights fly as extra
    // motors, the others are carried as mass.
    if let Some(group) = out.first_mut() {
        for (mount, motor) in others {
            if lit(motor, 0, 0, None) {
                group.extra.push((mount, motor));
            } else {
                warnings.push(format!(
                    "`{}`: OpenRocket never lights its {} {} in this configuration ({}); it is \
                     carried as mass (its full mass from the thrust curve)",
                    mount.name,
                    motor.manufacturer,
                    motor.designation,
                    unlit_reason(motor, true, None)
                ));
                group.unlit.push((mount, motor));
            }
        }
    }
    // Stages below the last lit motor ride on the body above while their separation never
    // fires.
    if let Some(last) = out.last_mut() {
        for (k, stage) in pending.iter().enumerate() {
            let number = first + k;
            let separation = separation(&sim.config, stage);
            if separation_fires(&separation, lit_motor[number - 1]) {
                return Err(unsupported(
                    file,
                    &stage.name,
                    format!(
                        "a stage without a motor lit below the last stage with one, separated {}",
                        after(&separation.event, separation.delay)
                    ),
                ));
            }
            warnings.push(format!(
                "`{}` has no motor lit in this configuration and its separation (OpenRocket: \
                 {}) never fires: it flies attached to `{}`",
                stage.name,
                after(&separation.event, separation.delay),
                design.stages[number - 1].name
            ));
            last.stages.push(stage);
        }
        last.unlit.append(&mut unlit);
    }
    for group in &out {
        for pair in group.stages[..=group.powered].windows(2) {
            let separation = separation(&sim.config, pair[1]);
            warnings.push(format!(
                "`{}` has no motor lit in this configuration and flies on `{}` as one body: \
                 karman's stages each carry a motor, so its separation (OpenRocket: {}) is \
                 not flown",
                pair[0].name,
                pair[1].name,
                after(&separation.event, separation.delay)
            ));
        }
    }
    Ok(out)
}

/// Pods that hold a motor mount (OpenRocket's powered pods) are refused: their motors
/// would be a cluster at each pod's offset, lit with the core's or on their own event,
/// which the import does not write.
fn refuse_powered_pods(file: &Path, design: &Design) -> Result<(), OrkError> {
    for stage in &design.stages {
        for pod in stage.walk().into_iter().filter(|c| c.kind == Kind::PodSet) {
            if let Some(mount) = pod.walk().into_iter().find(|c| !c.motors.is_empty()) {
                return Err(unsupported(
                    file,
                    &pod.name,
                    format!(
                        "a powered pod set (motor mount `{}`: its motors would fly as a second \
                         cluster, at the pods' offset, beside the core's motor; karman imports \
                         unpowered pods)",
                        mount.name
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// karman's nose `kind` for OpenRocket's `shape` and shape parameter of `nose`, with a
/// warning where the shape is approximated.
fn nose_kind(
    nose: &Component,
    shape: &str,
    parameter: f64,
    warnings: &mut Vec<String>,
) -> Result<String, OrkError> {
    Ok(match shape {
        "conical" => "conical".to_owned(),
        "ogive" => {
            if parameter < 0.999 {
                warnings.push(format!(
                    "`{}`: a secant ogive (parameter {parameter}) is flown as a tangent ogive",
                    nose.name
                ));
            }
            "tangent".to_owned()
        }
        "ellipsoid" => "elliptical".to_owned(),
        "power" => "powerseries".to_owned(),
        "parabolic" => {
            if parameter < 0.999 {
                warnings.push(format!(
                    "`{}`: a {parameter} parabolic series is flown as a full parabola",
                    nose.name
                ));
            }
            "parabolic".to_owned()
        }
        "haack" => {
            if parameter > 1.0 / 6.0 {
                "lvhaack".to_owned()
            } else {
                "von karman".to_owned()
            }
        }
        other => return Err(nose.value_error("shape", &format!("unknown shape {other:?}"))),
    })
}

/// The text a pod set adds to the mission: its surfaces (`[<rocket>.surfaces.*]`), its
/// fins' drag tables and its `[<rocket>.pods.<name>]` table.
struct PodText {
    surfaces: String,
    fins: String,
    pod: String,
}

/// The largest of a component's radii (`radius`, `aftradius`, `foreradius`, whichever it
/// has), 0 when it has none.
///
/// # Errors
/// An unreadable radius.
fn largest_radius(c: &Component) -> Result<f64, OrkError> {
    let mut r: f64 = 0.0;
    for e in ["radius", "aftradius", "foreradius"] {
        if c.fields.contains_key(e) {
            r = r.max(c.dim(e)?);
        }
    }
    Ok(r)
}

/// The surfaces of a pod's body (its nose cone, and its tail cones and transitions as conical
/// tails) appended to `surfaces`, their keys to `names`; returns the aft end of the body
/// (from the pod's position `pod_x`), m.
///
/// # Errors
/// An unreadable dimension or a nose shape the mission cannot describe.
fn pod_body_text(
    pod_x: f64,
    body: &[&Component],
    rocket_key: &str,
    used: &mut BTreeSet<String>,
    warnings: &mut Vec<String>,
    surfaces: &mut String,
    names: &mut Vec<String>,
) -> Result<f64, OrkError> {
    let mut body_end = pod_x;
    for (i, b) in body.iter().enumerate() {
        body_end = body_end.max(b.x + b.length);
        if largest_radius(b)? <= 0.0 {
            continue;
        }
        let flipped = b.text("isflipped") == Some("true");
        let section = |k: &str| format!("[{rocket_key}.surfaces.{k}]");
        match b.kind {
            Kind::NoseCone if i == 0 && !flipped => {
                let k = key(&b.name, used);
                let shape = b.text("shape").unwrap_or("conical");
                let kind = nose_kind(b, shape, b.num_or("shapeparameter", 1.0)?, warnings)?;
                let _ = write!(
                    surfaces,
                    "{}
type = \"nose\"\nlength = {}\nkind = \"{kind}\"\n",
                    section(&k),
                    n(b.length)
                );
                if kind == "powerseries" {
                    let _ = writeln!(surfaces, "power = {}", n(b.num_or("shapeparameter", 1.0)?));
                }
                let _ = write!(
                    surfaces,
                    "position = {}\nbase_radius = {}\n\n",
                    n(b.x),
                    n(b.dim("aftradius")?)
                );
                names.push(k);
            }
            // A nose cone turned aft (the pod's tail) or a transition: a conical tail.
            Kind::NoseCone | Kind::Transition => {
                let (fore, aft) = if b.kind == Kind::NoseCone {
                    (b.dim("aftradius")?, 0.0)
                } else {
                    (b.dim("foreradius")?, b.dim("aftradius")?)
                };
                let shape = b.text("shape").unwrap_or("conical");
                if shape != "conical" {
                    warnings.push(format!(
                        "`{}`: a {shape} pod {} is flown (normal force, CP and drag) as a conical one",
                        b.name,
                        if b.kind == Kind::NoseCone { "tail cone" } else { "transition" }
                    ));
                }
                if (fore - aft).abs() <= 1e-12 {
                    continue;
                }
                let k = key(&b.name, used);
                let _ = write!(
                    surfaces,
                    "{}\ntype = \"tail\"\ntop_radius = {}\nbottom_radius = {}\nlength = {}\nposition = {}\n\n",
                    section(&k),
                    n(fore),
                    n(aft),
                    n(b.length),
                    n(b.x)
                );
                names.push(k);
            }
            _ => {}
        }
    }
    Ok(body_end)
}

/// The surfaces, fin drag tables and pod table of pod set `pod` under `rocket_key`, sitting
/// on a body of outer radius `parent_radius`.
#[allow(clippy::too_many_arguments)]
fn pod_text(
    file: &Path,
    pod: &Component,
    parent_radius: f64,
    rocket_key: &str,
    finish: &str,
    used: &mut BTreeSet<String>,
    warnings: &mut Vec<String>,
) -> Result<PodText, OrkError> {
    let (count, distance, angle) = pod.pod_placement(parent_radius)?;
    let body: Vec<&Component> = pod.children.iter().filter(|c| c.kind.is_body()).collect();
    if let Some(c) = pod
        .children
        .iter()
        .find(|c| !c.kind.is_body() && (c.kind.is_aerodynamic() || c.kind == Kind::PodSet))
    {
        return Err(unsupported(
            file,
            &c.name,
            "a pod's part other than a nose cone, body tube, transition or fin set".to_owned(),
        ));
    }
    let mut pod_radius: f64 = 0.0;
    for b in &body {
        pod_radius = pod_radius.max(largest_radius(b)?);
    }
    let mut surfaces = String::new();
    let mut names = Vec::new();
    let has_body = pod_radius > 0.0;
    if has_body {
        match body.first() {
            Some(first)
                if first.kind == Kind::NoseCone && first.text("isflipped") != Some("true") => {}
            Some(first) => {
                return Err(unsupported(
                    file,
                    &first.name,
                    "a pod body that does not start with a nose cone (a blunt front)".to_owned(),
                ));
            }
            None => {}
        }
    }
    let body_end = pod_body_text(
        pod.x,
        &body,
        rocket_key,
        used,
        warnings,
        &mut surfaces,
        &mut names,
    )?;
    let mut fins = String::new();
    for b in &body {
        let tube_radius = b.dim_or("radius", b.dim_or("aftradius", 0.0)?)?;
        for c in &b.children {
            if c.kind.is_fins() {
                let (k, surface, drag) = fin_tables(c, rocket_key, tube_radius, finish, used)?;
                surfaces.push_str(&surface);
                fins.push_str(&drag);
                names.push(k);
            } else if c.kind == Kind::PodSet {
                return Err(unsupported(
                    file,
                    &c.name,
                    "a pod set inside a pod".to_owned(),
                ));
            } else if c.kind.is_aerodynamic() {
                return Err(unsupported(
                    file,
                    &c.name,
                    "a pod's part other than a nose cone, body tube, transition or fin set"
                        .to_owned(),
                ));
            }
        }
    }
    let pod_key = key(&pod.name, used);
    let mut t = String::new();
    let _ = writeln!(
        t,
        "# OpenRocket's pod set `{}`: {count} pod(s), their axes {} m from the rocket's axis\n\
         # (mass and inertia above include them{}).",
        pod.name,
        (distance * 1e4).round() / 1e4,
        if count > 1 {
            ""
        } else {
            ", the pitch and yaw inertias averaged"
        }
    );
    let _ = writeln!(
        t,
        "[{rocket_key}.pods.{pod_key}]\ncount = {count}\nangular_position = {}",
        n(angle.to_degrees())
    );
    let quoted_names: Vec<String> = names.iter().map(|k| quoted(k)).collect();
    let _ = writeln!(t, "surfaces = [{}]", quoted_names.join(", "));
    if has_body {
        let tip = body.first().map_or(pod.x, |b| b.x);
        let _ = writeln!(t, "body_length = {}", n(body_end - tip));
    } else {
        let _ = writeln!(
            t,
            "# A body of radius 0 (OpenRocket's \"phantom\" tube): fins only, no pod body."
        );
    }
    t.push('\n');
    Ok(PodText {
        surfaces,
        fins,
        pod: t,
    })
}

/// The `[<rocket>.surfaces.<key>]` table of fin set `c` on a tube of radius `tube_radius`,
/// and its `[<rocket>.drag_estimate.fins.<key>]` table.
fn fin_tables(
    c: &Component,
    rocket_key: &str,
    tube_radius: f64,
    finish: &str,
    used: &mut BTreeSet<String>,
) -> Result<(String, String, String), OrkError> {
    let name = key(&c.name, used);
    let mut surfaces = String::new();
    let mut fins = String::new();
    let count = c.count_or("fincount", 1.0, 1.0)?;
    let cant = c.num_or("cant", 0.0)?;
    // OpenRocket's fin-set rotation: the first fin's roll position.
    let rotation = c.num_or("rotation", 0.0)?;
    let common = format!(
        "n = {}\nposition = {}\ncant_angle = {}\nangular_position = {}\nradius = {}\n",
        count as u32,
        n(c.x),
        n(cant),
        n(rotation),
        n(tube_radius)
    );
    let table = format!("{rocket_key}.surfaces.{name}");
    match c.kind {
        Kind::TrapezoidFins => {
            let _ = write!(
                surfaces,
                "[{table}]\ntype = \"trapezoidal_fins\"\nroot_chord = {}\ntip_chord = {}\nspan = {}\nsweep_length = {}\n{common}\n",
                n(c.dim("rootchord")?),
                n(c.dim("tipchord")?),
                n(c.dim("height")?),
                n(c.num("sweeplength")?)
            );
        }
        Kind::EllipticalFins => {
            let _ = write!(
                surfaces,
                "[{table}]\ntype = \"elliptical_fins\"\nroot_chord = {}\nspan = {}\n{common}\n",
                n(c.dim("rootchord")?),
                n(c.dim("height")?)
            );
        }
        _ => {
            let points: Vec<String> = c
                .points
                .iter()
                .map(|p| format!("[{}, {}]", n(p[0]), n(p[1])))
                .collect();
            let _ = write!(
                surfaces,
                "[{table}]\ntype = \"free_form_fins\"\nshape_points = [{}]\n{common}\n",
                points.join(", ")
            );
        }
    }
    let section = c.text("crosssection").unwrap_or("square");
    let _ = write!(
        fins,
        "[{rocket_key}.drag_estimate.fins.{name}]\nthickness = {}\ncross_section = \"{section}\"\n",
        n(c.dim("thickness")?)
    );
    if let Some(f) = c.text("finish") {
        if f != finish {
            let _ = writeln!(fins, "finish = \"{f}\"");
        }
    }
    fins.push('\n');
    Ok((name, surfaces, fins))
}

/// The separation of `stage` in configuration `config`.
fn separation(config: &str, stage: &Component) -> SeparationRef {
    stage
        .separations
        .get(config)
        .or_else(|| stage.separations.get(""))
        .cloned()
        .unwrap_or(SeparationRef {
            event: "upperignition".to_owned(),
            delay: 0.0,
        })
}

/// The `separation` trigger and `ignition_delay` of lower body `lower` under `upper`:
/// OpenRocket's separation event of the lower body's top stage and the ignition event of the
/// upper body's motor, both as times after the lower motor's burn-out.
fn staging(
    file: &Path,
    config: &str,
    upper: &Group,
    lower: &Group,
) -> Result<(f64, f64), OrkError> {
    let plugged = |what: &str| {
        unsupported(
            file,
            &lower.mount.name,
            format!("{what} at the ejection charge of a plugged motor (it never fires)"),
        )
    };
    let ejection = lower.motor.delay;
    let (event, delay) = &upper.motor.ignition;
    let ignition = match event.as_str() {
        "burnout" => *delay,
        // OpenRocket's `automatic` above the bottom stage: the ejection charge below.
        "automatic" | "ejection" => ejection.ok_or_else(|| plugged("an ignition"))? + delay,
        other => {
            return Err(unsupported(
                file,
                &upper.mount.name,
                format!(
                    "an upper-stage ignition at {other:?} (karman lights a stage's motor at \
                     or after the separation below it)"
                ),
            ));
        }
    };
    let sep = separation(config, lower.stages[0]);
    let separate = match sep.event.as_str() {
        "burnout" => sep.delay,
        "ejection" => ejection.ok_or_else(|| plugged("a separation"))? + sep.delay,
        "upperignition" => ignition + sep.delay,
        other => {
            return Err(unsupported(
                file,
                lower.name(),
                format!(
                    "a stage separation at {other:?} (karman separates a stage at or after \
                     its motor's burn-out)"
                ),
            ));
        }
    };
    if ignition < separate {
        return Err(unsupported(
            file,
            upper.name(),
            format!(
                "a motor that ignites {} s before the stage below separates",
                separate - ignition
            ),
        ));
    }
    Ok((separate, ignition - separate))
}

/// The text of one body: its `[motor]` table and its `[rocket]` tables (under the dotted
/// names `motor_key` and `rocket_key`).
struct BodyText {
    motor: String,
    rocket: String,
}

/// The drag of a spent lower stage flying alone, on its own largest radius: a body with a
/// blunt front (no nose cone, so no geometry estimate), its stagnation pressure on the front
/// face, 0.85 (1 + M²/4 + M⁴/40), and its base drag, 0.12 + 0.13 M² (OpenRocket's forms,
/// Niskanen 2009 §3.4.3 and §3.4.4), each on its area; skin friction and fins are left out.
/// It concerns the spent stage's own path only.
fn spent_stage_drag(front: f64, base: f64, radius: f64) -> String {
    let (f, b) = ((front / radius).powi(2), (base / radius).powi(2));
    let points: Vec<String> = [0.0, 0.3, 0.6, 0.9]
        .iter()
        .map(|&m: &f64| {
            let cd = 0.85 * (1.0 + m * m / 4.0 + m.powi(4) / 40.0) * f + (0.12 + 0.13 * m * m) * b;
            format!("[{}, {}]", n(m), n((cd * 1e4).round() / 1e4))
        })
        .collect();
    format!("[{}]", points.join(", "))
}

/// The motor table `[motor_key]` of `motor` in `mount` (a generic motor from its RASP file,
/// with the mount's cluster) and the rocket coordinate of its nozzle exit: the mount's aft end
/// plus its overhang.
fn motor_text(
    file: &Path,
    mount: &Component,
    motor: &MotorRef,
    motor_key: &str,
    options: &ImportOptions,
) -> Result<(String, f64), OrkError> {
    let (eng_path, eng) = find_motor(file, motor, options)?;
    let (motor_length, motor_diameter) = eng.size_of(motor);
    let nozzle_at = mount.x + mount.length + mount.overhang;
    let dry = (eng.total - eng.propellant).max(0.0);

    let mut m = String::new();
    let _ = writeln!(
        m,
        "# {} {} from {}: RASP masses {} kg propellant, {} kg total; the propellant is",
        motor.manufacturer,
        motor.designation,
        crate::design::one_line(&eng_path.display().to_string()),
        eng.propellant,
        eng.total
    );
    let _ = writeln!(
        m,
        "# a cylinder filling the motor case, and leaves in proportion to the impulse."
    );
    let _ = writeln!(
        m,
        "[{motor_key}]\nkind = \"generic\"\nthrust = {}",
        quoted(&relative(&eng_path, options.output_dir.as_deref()))
    );
    let _ = writeln!(
        m,
        "dry_mass = {}\ncenter_of_dry_mass_position = {}",
        n(dry),
        n(0.5 * motor_length)
    );
    let _ = writeln!(
        m,
        "nozzle_radius = {}\npropellant_initial_mass = {}",
        n(0.25 * motor_diameter),
        n(eng.propellant)
    );
    let _ = writeln!(
        m,
        "chamber_radius = {}\nchamber_height = {}\nchamber_position = {}",
        n(0.5 * motor_diameter),
        n(motor_length),
        n(0.5 * motor_length)
    );
    let (cluster_count, cluster_radius) = mount.cluster()?;
    if cluster_count > 1 {
        let _ = writeln!(
            m,
            "# OpenRocket's {} cluster: {cluster_count} motors lit together, their axes {} m from\n\
             # the rocket's axis (root mean square).\ncluster_count = {cluster_count}\ncluster_radius = {}",
            mount.text("clusterconfiguration").unwrap_or(""),
            (cluster_radius * 1e4).round() / 1e4,
            n(cluster_radius)
        );
    }
    let _ = writeln!(m, "coordinate_system = \"nozzle_to_combustion_chamber\"\n");
    Ok((m, nozzle_at))
}

/// The time after launch of the first ejection charge among the motors of `group` (each
/// fires its delay after its own burn-out, the end of its thrust curve, OpenRocket's
/// `EJECTION_CHARGE` event); `None` when every motor is plugged.
fn first_ejection(
    file: &Path,
    group: &Group,
    options: &ImportOptions,
) -> Result<Option<f64>, OrkError> {
    let mut first: Option<f64> = None;
    for (mount, motor) in
        std::iter::once((group.mount, group.motor)).chain(group.extra.iter().copied())
    {
        let Some(charge) = motor.delay else { continue };
        let (path, _) = find_motor(file, motor, options)?;
        let end = karman_propulsion::ThrustData::load(&path)
            .ok()
            .and_then(|d| d.times.last().copied())
            .ok_or_else(|| {
                unsupported(
                    file,
                    &mount.name,
                    format!("a thrust curve {} that cannot be read", path.display()),
                )
            })?;
        let t = motor.ignition.1 + end + charge;
        first = Some(first.map_or(t, |f| f.min(t)));
    }
    Ok(first)
}

#[allow(clippy::too_many_arguments)]
fn body_text(
    file: &Path,
    config: &str,
    group: &Group,
    top: bool,
    rocket_key: &str,
    motor_key: &str,
    options: &ImportOptions,
    used: &mut BTreeSet<String>,
    warnings: &mut Vec<String>,
) -> Result<BodyText, OrkError> {
    let all = group.all();
    let body = group.body();
    let nose = body.first().filter(|c| c.kind == Kind::NoseCone);
    if top && nose.is_none() {
        return Err(unsupported(
            file,
            &body
                .first()
                .map_or_else(|| group.name().to_owned(), |c| c.name.clone()),
            "a body that does not start with a nose cone".to_owned(),
        ));
    }
    let Some(first) = body.first() else {
        return Err(unsupported(
            file,
            group.name(),
            "a stage without body tubes".to_owned(),
        ));
    };
    let radius = reference_radius(first, &body, &all)?;
    let body_end = body.last().map_or(0.0, |b| b.x + b.length);
    unmodelled_drag_warnings(&all, &body, warnings)?;

    // Mass without motor, with the motors OpenRocket never lights carried whole.
    let props = mass_without_motor(file, group, radius, options)?;

    // Motor of the simulation's configuration.
    let (m, nozzle_at) = motor_text(file, group.mount, group.motor, motor_key, options)?;

    let mut t = String::new();
    let w = &mut t;
    let _ = writeln!(
        w,
        "# Mass properties without motor, summed over the components (with OpenRocket's overrides)."
    );
    let _ = writeln!(
        w,
        "[{rocket_key}]\nradius = {}\nmass = {}",
        n(radius),
        n(props.mass)
    );
    let _ = writeln!(
        w,
        "inertia = [{}, {}, {}]",
        n(props.i_long),
        n(props.i_long),
        n(props.i_rot)
    );
    let _ = writeln!(
        w,
        "center_of_mass_without_motor = {}\ncoordinate_system = \"nose_to_tail\"",
        n(props.cg)
    );
    if top {
        let _ = writeln!(
            w,
            "power_off_drag = \"estimate\"\npower_on_drag = \"estimate\""
        );
    } else {
        let front = first.dim_or("foreradius", first.dim_or("radius", radius)?)?;
        let base = match body.last() {
            Some(b) => b.dim_or("aftradius", b.dim_or("radius", radius)?)?,
            None => radius,
        };
        let drag = spent_stage_drag(front, base, radius);
        let _ = writeln!(
            w,
            "# The spent stage alone (blunt front, no geometry estimate): stagnation pressure on\n\
             # its front and base drag, OpenRocket's forms; friction and fins left out."
        );
        let _ = writeln!(w, "power_off_drag = {drag}\npower_on_drag = {drag}");
    }
    let _ = writeln!(
        w,
        "motor_position = {}                # nozzle exit: the mount's aft end plus overhang\n",
        n(nozzle_at)
    );

    // Drag-estimate geometry.
    let finish = body_finish(&body);
    let Attached {
        surfaces,
        pod_surfaces,
        pods,
        fins,
        lugs,
        buttons,
        overrides,
    } = attached_text(
        file, nose, &body, rocket_key, radius, finish, used, warnings,
    )?;
    if !top {
        let _ = writeln!(
            w,
            "# The drag estimate of the stack while this stage is its bottom: the body from the\n\
             # sustainer's nose tip to this stage's aft end."
        );
    }
    let _ = writeln!(
        w,
        "[{rocket_key}.drag_estimate]\nbody_length = {}\nfinish = \"{finish}\"\n",
        n(body_end)
    );
    if !overrides.is_empty() {
        let _ = writeln!(
            w,
            "# OpenRocket's drag-coefficient overrides (on the reference area)."
        );
        let _ = writeln!(w, "[{rocket_key}.drag_estimate.overrides]\n{overrides}");
    }
    w.push_str(&fins);
    w.push_str(&lugs);
    if let Some(buttons) = buttons {
        rail_buttons_text(w, rocket_key, buttons);
    }
    w.push_str(&surfaces);
    w.push_str(&pods);
    w.push_str(&pod_surfaces);

    recovery_text(
        w, file, config, group, &all, rocket_key, options, used, warnings,
    )?;
    Ok(BodyText {
        motor: m,
        rocket: t,
    })
}

/// The finish most of a body's components have (OpenRocket's `finish`), `normal` when none says.
fn body_finish<'a>(body: &[&'a Component]) -> &'a str {
    let finishes: Vec<&str> = body.iter().filter_map(|b| b.text("finish")).collect();
    finishes
        .iter()
        .copied()
        .max_by_key(|f| finishes.iter().filter(|g| *g == f).count())
        .unwrap_or("normal")
}

/// The rail buttons' drag-estimate table and their positions on the rail, appended to `w`:
/// `(upper, lower, outer diameter, inner diameter, height, inner height)`, m.
fn rail_buttons_text(
    w: &mut String,
    rocket_key: &str,
    (upper, lower, od, id, h, inner): (f64, f64, f64, f64, f64, f64),
) {
    let _ = writeln!(
        w,
        "[{rocket_key}.drag_estimate.rail_buttons]\nouter_diameter = {}\ninner_diameter = {}\nheight = {}\ninner_height = {}\n",
        n(od),
        n(id),
        n(h),
        n(inner)
    );
    let _ = writeln!(
        w,
        "[{rocket_key}.rail_buttons]\nupper_position = {}\nlower_position = {}\n",
        n(upper),
        n(lower.max(upper + 1e-3))
    );
}

/// The line of component `c`'s OpenRocket drag-coefficient override (`overridecd`, on the
/// reference area) under its surface key `key`, appended to `overrides`, if it has one.
fn drag_override(overrides: &mut String, c: &Component, key: &str) {
    if let Some(cd) = c
        .fields
        .get("overridecd")
        .and_then(|t| crate::design::number(t))
    {
        let _ = writeln!(overrides, "{key} = {}", n(cd));
    }
}

/// The nose cone's surface table appended to `surfaces` (its OpenRocket drag override to
/// `overrides`).
///
/// # Errors
/// An unreadable dimension or a nose shape the mission cannot describe.
fn nose_text(
    nose: &Component,
    rocket_key: &str,
    used: &mut BTreeSet<String>,
    warnings: &mut Vec<String>,
    surfaces: &mut String,
    overrides: &mut String,
) -> Result<(), OrkError> {
    let nose_key = key(&nose.name, used);
    drag_override(overrides, nose, &nose_key);
    let _ = write!(
        surfaces,
        "[{rocket_key}.surfaces.{nose_key}]\ntype = \"nose\"\nlength = {}\n",
        n(nose.length)
    );
    let shape = nose.text("shape").unwrap_or("conical");
    let parameter = nose.num_or("shapeparameter", 1.0)?;
    let kind = nose_kind(nose, shape, parameter, warnings)?;
    let _ = writeln!(surfaces, "kind = \"{kind}\"");
    if kind == "powerseries" {
        let _ = writeln!(surfaces, "power = {}", n(parameter));
    }
    let _ = write!(
        surfaces,
        "position = {}\nbase_radius = {}\n\n",
        n(nose.x),
        n(nose.dim("aftradius")?)
    );
    Ok(())
}

/// The reference radius of a body: its largest radius, pods included (OpenRocket's reference
/// radius is the largest body radius of the rocket).
///
/// # Errors
/// A component's unreadable radius; no positive radius at all (named at `first`).
fn reference_radius(
    first: &Component,
    body: &[&Component],
    all: &[&Component],
) -> Result<f64, OrkError> {
    let mut radius: f64 = 0.0;
    for b in body {
        radius = radius.max(largest_radius(b)?);
    }
    if radius <= 0.0 {
        return Err(first.value_error("radius", "the body has no positive radius"));
    }
    for pod in all.iter().filter(|c| c.kind == Kind::PodSet) {
        for b in pod.children.iter().filter(|c| c.kind.is_body()) {
            radius = radius.max(largest_radius(b)?);
        }
    }
    Ok(radius)
}

/// Warnings for the drag inputs of the design the drag estimate does not model: a
/// drag-coefficient override on a component whose drag is estimated as a whole, and a step in
/// radius without a transition.
///
/// # Errors
/// A component's unreadable radius.
fn unmodelled_drag_warnings(
    all: &[&Component],
    body: &[&Component],
    warnings: &mut Vec<String>,
) -> Result<(), OrkError> {
    for c in all {
        let overridden = c.fields.contains_key("overridecd");
        let mapped = matches!(c.kind, Kind::NoseCone | Kind::Transition)
            && c.text("overridesubcomponentscd") != Some("true");
        if overridden && !mapped {
            warnings.push(format!(
                "`{}`: its drag-coefficient override is not modelled; the estimate includes its drag",
                c.name
            ));
        }
    }
    // Radius steps without a transition: the estimate's implied body has none.
    for w in body.windows(2).filter(|w| w[1].kind == Kind::BodyTube) {
        let aft = w[0].dim_or("aftradius", w[0].dim_or("radius", 0.0)?)?;
        let fore = w[1].dim_or("foreradius", w[1].dim_or("radius", 0.0)?)?;
        if (aft - fore).abs() > 1e-6 {
            warnings.push(format!(
                "`{}` → `{}`: a step in radius ({aft} m → {fore} m) without a transition; \
                 the drag estimate's body keeps the radius",
                w[0].name, w[1].name
            ));
        }
    }
    Ok(())
}

/// The mass properties of a group without its motor, summed over its components (with
/// OpenRocket's overrides), the motors OpenRocket never lights carried whole.
///
/// # Errors
/// A component's unreadable dimensions; an unlit motor's thrust file that cannot be found.
fn mass_without_motor(
    file: &Path,
    group: &Group,
    radius: f64,
    options: &ImportOptions,
) -> Result<MassProps, OrkError> {
    let mut props = MassProps::default();
    for stage in &group.stages {
        props = props.add(mass::subtree(stage, 0.0, radius)?);
    }
    for (mount, motor) in &group.unlit {
        let (_, eng) = find_motor(file, motor, options)?;
        let (length, diameter) = eng.size_of(motor);
        props = props.add(mass::unlit_motor(
            mount.x + mount.length + mount.overhang,
            length,
            0.5 * diameter,
            eng.total,
            mount.cluster()?,
        ));
    }
    Ok(props)
}

/// The mission tables of the surfaces and drag-estimate parts of a body: each a string of
/// TOML tables, in the order [`body_text`] writes them.
struct Attached {
    surfaces: String,
    pod_surfaces: String,
    pods: String,
    fins: String,
    lugs: String,
    /// The first rail-button set: upper and lower positions, outer and inner diameters,
    /// height and inner height, m.
    buttons: Option<(f64, f64, f64, f64, f64, f64)>,
    overrides: String,
}

/// The nose, the transitions (tails) and what each body component carries (fins, pods, tube
/// fins, launch lugs, rail buttons) as mission tables under `rocket_key`, the names taken
/// unique through `used`.
///
/// # Errors
/// A component's unreadable dimensions or a shape the mission cannot describe.
#[allow(clippy::too_many_arguments)]
fn attached_text(
    file: &Path,
    nose: Option<&&Component>,
    body: &[&Component],
    rocket_key: &str,
    radius: f64,
    finish: &str,
    used: &mut BTreeSet<String>,
    warnings: &mut Vec<String>,
) -> Result<Attached, OrkError> {
    let mut surfaces = String::new();
    let mut pod_surfaces = String::new();
    let mut pods = String::new();
    let mut fins = String::new();
    let mut lugs = String::new();
    let mut buttons = None;
    let mut overrides = String::new();
    if let Some(nose) = nose {
        nose_text(
            nose,
            rocket_key,
            used,
            warnings,
            &mut surfaces,
            &mut overrides,
        )?;
    }
    for b in body {
        if b.kind == Kind::Transition {
            // Equal radii (automatic ends between tubes of one radius): a piece of tube,
            // which the drag estimate's body already has; no tail.
            if (b.dim("foreradius")? - b.dim("aftradius")?).abs() <= 1e-9 {
                if b.fields.contains_key("overridecd") {
                    warnings.push(format!(
                        "`{}`: a transition between equal radii is a piece of tube; its \
                         drag-coefficient override is not modelled",
                        b.name
                    ));
                }
                continue;
            }
            if b.text("shape") != Some("conical") {
                warnings.push(format!(
                    "`{}`: a {} transition is flown (normal force, CP and drag) as a conical one",
                    b.name,
                    b.text("shape").unwrap_or("?")
                ));
            }
            let tail_key = key(&b.name, used);
            drag_override(&mut overrides, b, &tail_key);
            let _ = write!(
                surfaces,
                "[{rocket_key}.surfaces.{tail_key}]\ntype = \"tail\"\ntop_radius = {}\nbottom_radius = {}\nlength = {}\nposition = {}\n\n",
                n(b.dim("foreradius")?),
                n(b.dim("aftradius")?),
                n(b.length),
                n(b.x)
            );
        }
    }
    for parent in body {
        let tube_radius = parent.dim_or("radius", parent.dim_or("aftradius", radius)?)?;
        for c in &parent.children {
            match c.kind {
                Kind::TrapezoidFins | Kind::EllipticalFins | Kind::FreeFormFins => {
                    let (_, surface, drag) = fin_tables(c, rocket_key, tube_radius, finish, used)?;
                    surfaces.push_str(&surface);
                    fins.push_str(&drag);
                }
                Kind::PodSet => {
                    let p = pod_text(file, c, tube_radius, rocket_key, finish, used, warnings)?;
                    pod_surfaces.push_str(&p.surfaces);
                    fins.push_str(&p.fins);
                    pods.push_str(&p.pod);
                }
                Kind::TubeFins => {
                    let (outer, inner) = c.tube_fin_radii(tube_radius)?;
                    let _ = write!(
                        surfaces,
                        "[{rocket_key}.surfaces.{}]\ntype = \"tube_fins\"\nn = {}\nlength = {}\nouter_radius = {}\ninner_radius = {}\nposition = {}\nradius = {}\n\n",
                        key(&c.name, used),
                        c.count_or("fincount", 1.0, 1.0)? as u32,
                        n(c.length),
                        n(outer),
                        n(inner),
                        n(c.x),
                        n(tube_radius)
                    );
                }
                Kind::LaunchLug => {
                    let r = c.dim("radius")?;
                    let _ = write!(
                        lugs,
                        "[{rocket_key}.drag_estimate.launch_lugs.{}]\nouter_radius = {}\ninner_radius = {}\nlength = {}\ncount = {}\n\n",
                        key(&c.name, used),
                        n(r),
                        n((r - c.dim("thickness")?).max(0.0)),
                        n(c.length),
                        c.num_or("instancecount", 1.0)? as u32
                    );
                }
                Kind::RailButton => {
                    if buttons.is_some() {
                        warnings.push(format!(
                            "`{}`: only the first rail-button set is modelled",
                            c.name
                        ));
                        continue;
                    }
                    let od = c.dim("outerdiameter")?;
                    let h = c.dim("height")?;
                    let inner =
                        (h - c.num_or("baseheight", 0.0)? - c.num_or("flangeheight", 0.0)?)
                            .max(0.0);
                    let separation = c.num_or("instanceseparation", 0.0)?;
                    let upper = c.x + 0.5 * od;
                    buttons = Some((
                        upper,
                        upper + separation,
                        od,
                        c.dim("innerdiameter")?,
                        h,
                        inner,
                    ));
                }
                _ => {}
            }
        }
    }
    Ok(Attached {
        surfaces,
        pod_surfaces,
        pods,
        fins,
        lugs,
        buttons,
        overrides,
    })
}

/// The recovery devices of a group as `[<rocket_key>.parachutes.<name>]` tables appended to
/// `w`: each parachute with the chosen configuration's deployment settings (else the
/// device's own) and OpenRocket's deployment event as a trigger; streamers are not modelled.
///
/// # Errors
/// A parachute's unreadable dimensions; a motor's thrust file that cannot be found.
#[allow(clippy::too_many_arguments)]
fn recovery_text(
    w: &mut String,
    file: &Path,
    config: &str,
    group: &Group,
    all: &[&Component],
    rocket_key: &str,
    options: &ImportOptions,
    used: &mut BTreeSet<String>,
    warnings: &mut Vec<String>,
) -> Result<(), OrkError> {
    for c in all {
        match c.kind {
            Kind::Parachute => {
                // The chosen configuration's deployment settings, else the device's own.
                let mut c = (*c).clone();
                if let Some(settings) = c.deployments.get(config) {
                    c.fields.extend(settings.clone());
                }
                let d = c.dim("diameter")?;
                let cd = c.positive_or("cd", 0.8)?;
                let area = std::f64::consts::PI * 0.25 * d * d;
                let event = c.text("deployevent").unwrap_or("ejection");
                let delay = c.dim_or("deploydelay", 0.0)?;
                // OpenRocket's deployment events, each then delayed by `deploydelay` (the lag).
                let trigger = match event {
                    "apogee" => "\"apogee\"".to_owned(),
                    "altitude" => n(c.dim("deployaltitude")?),
                    "launch" => "\"launch + 0\"".to_owned(),
                    "never" => continue,
                    // The motor's ejection charge fires its delay after burn-out.
                    // Several motors: the first charge of any of them, a time after launch.
                    "ejection" if !group.extra.is_empty() => {
                        match first_ejection(file, group, options)? {
                            Some(t) => format!("\"launch + {}\"", n(t)),
                            None => {
                                warnings.push(format!(
                                    "`{}`: deployed by the ejection charges of plugged motors in OpenRocket, so never deployed; left out",
                                    c.name
                                ));
                                continue;
                            }
                        }
                    }
                    "ejection" => match group.motor.delay {
                        Some(charge) => format!("\"burnout + {}\"", n(charge)),
                        None => {
                            warnings.push(format!(
                                "`{}`: deployed by the ejection charge of a plugged motor in OpenRocket, so never deployed; left out",
                                c.name
                            ));
                            continue;
                        }
                    },
                    other => {
                        warnings.push(format!(
                            "`{}`: deployment event {other:?} flown as apogee",
                            c.name
                        ));
                        "\"apogee\"".to_owned()
                    }
                };
                let _ = write!(
                    w,
                    "[{rocket_key}.parachutes.{}]\ncd_s = {}              # Cd {} × π ({} m)² / 4\ntrigger = {trigger}\nlag = {}\nsampling_rate = 100\n\n",
                    key(&c.name, used),
                    n(cd * area),
                    n(cd),
                    n(d),
                    n(delay)
                );
            }
            Kind::Streamer => warnings.push(format!("`{}`: streamers are not modelled", c.name)),
            _ => {}
        }
    }
    Ok(())
}

/// Builds the mission text of `design` for the simulation chosen by `options`: the top body
/// as `[rocket]` and `[motor]`, the bodies below it as `[[stages]]`, bottom last.
pub(super) fn mission(
    file: &Path,
    design: &Design,
    options: &ImportOptions,
) -> Result<Imported, OrkError> {
    let mut warnings = Vec::new();
    let sim = chosen_simulation(file, design, options)?;
    refuse_powered_pods(file, design)?;
    let groups = groups(file, design, sim, &mut warnings)?;
    let bottom = &groups[groups.len() - 1];
    if !matches!(bottom.motor.ignition.0.as_str(), "automatic" | "launch")
        || bottom.motor.ignition.1 != 0.0
    {
        return Err(unsupported(
            file,
            &bottom.mount.name,
            format!(
                "a first motor lit {} (karman lights it at launch)",
                after(&bottom.motor.ignition.0, bottom.motor.ignition.1)
            ),
        ));
    }
    let mut staging_of = Vec::new();
    for pair in groups.windows(2) {
        staging_of.push(staging(file, &sim.config, &pair[0], &pair[1])?);
    }
    let mut used = BTreeSet::new();
    let top = body_text(
        file,
        &sim.config,
        &groups[0],
        true,
        "rocket",
        "motor",
        options,
        &mut used,
        &mut warnings,
    )?;
    let mut lower = Vec::new();
    for group in &groups[1..] {
        lower.push(body_text(
            file,
            &sim.config,
            group,
            false,
            "stages.rocket",
            "stages.motor",
            options,
            &mut used,
            &mut warnings,
        )?);
    }

    let mut t = String::new();
    let w = &mut t;
    header_text(w, file, design, sim, &groups);

    environment_text(w, sim);
    w.push_str(&top.motor);
    w.push_str(&top.rocket);

    flight_text(w, sim);
    extra_motors_text(w, file, &groups[0], options)?;
    stages_text(w, sim, &groups, &lower, &staging_of);
    let t = t.trim_end().to_owned() + "\n";
    let mut t = t;
    if !warnings.is_empty() {
        let mut head = String::new();
        for warning in &warnings {
            // A warning can quote a file name, which may hold any character.
            let _ = writeln!(head, "# note: {}", crate::design::one_line(warning));
        }
        t = t.replacen(
            &format!("name = {}", quoted(&design.name)),
            &format!("{head}name = {}", quoted(&design.name)),
            1,
        );
    }
    Ok(Imported {
        mission: t,
        warnings,
    })
}

/// The stored simulation `options` names (the design's first by default).
///
/// # Errors
/// [`OrkError::Simulation`] naming the simulations the design has when none matches.
fn chosen_simulation<'a>(
    file: &Path,
    design: &'a Design,
    options: &ImportOptions,
) -> Result<&'a Simulation, OrkError> {
    let sim = match &options.simulation {
        Some(name) => design.simulations.iter().find(|s| &s.name == name),
        None => design.simulations.first(),
    };
    sim.ok_or_else(|| OrkError::Simulation {
        file: file.to_owned(),
        name: options.simulation.clone().unwrap_or_default(),
        available: if design.simulations.is_empty() {
            "none".to_owned()
        } else {
            design
                .simulations
                .iter()
                .map(|s| format!("{:?}", s.name))
                .collect::<Vec<_>>()
                .join(", ")
        },
    })
}

/// The mission's opening comments (the design, its file, the simulation, its motors and
/// stages) and its `name`, appended to `w`.
fn header_text(w: &mut String, file: &Path, design: &Design, sim: &Simulation, groups: &[Group]) {
    let _ = writeln!(
        w,
        "# {} — imported from {} by `karman import`.",
        design.name,
        file.file_name()
            .map_or_else(String::new, |f| crate::design::one_line(
                &f.to_string_lossy()
            ))
    );
    let motors: Vec<String> = groups
        .iter()
        .flat_map(|g| std::iter::once(g.motor).chain(g.extra.iter().map(|(_, m)| *m)))
        .map(|m| format!("{} {}", m.manufacturer, m.designation))
        .collect();
    let _ = writeln!(
        w,
        "# Simulation {:?}: motor{} {}; OpenRocket's masses, overrides and launch",
        sim.name,
        if motors.len() > 1 { "s" } else { "" },
        motors.join(" + ")
    );
    let _ = writeln!(
        w,
        "# conditions; drag estimated from the geometry. Rocket coordinates: nose tip at 0,"
    );
    let _ = writeln!(w, "# positions grow toward the tail (m).");
    if groups.len() > 1 {
        let names: Vec<&str> = groups.iter().map(Group::name).collect();
        let _ = writeln!(
            w,
            "# Stages, top first: {} ([rocket] and [motor], then [[stages]]).",
            names.join(", ")
        );
    }
    let _ = writeln!(w, "name = {}", quoted(&design.name));
    let _ = writeln!(w);
}

/// The `[environment]` of the simulation's launch conditions (site and OpenRocket's average
/// wind as a constant wind), appended to `w`.
fn environment_text(w: &mut String, sim: &Simulation) {
    let lat = condition(sim, "launchlatitude", 0.0);
    let lon = condition(sim, "launchlongitude", 0.0);
    let alt = condition(sim, "launchaltitude", 0.0);
    let _ = writeln!(
        w,
        "[environment]\nlatitude = {}\nlongitude = {}\nelevation = {}\n",
        n(lat),
        n(lon),
        n(alt)
    );
    let speed = condition(sim, "windaverage", 0.0);
    let from = condition(sim, "winddirection", 0.0);
    let (u, v) = (-speed * from.sin(), -speed * from.cos());
    let _ = writeln!(
        w,
        "# OpenRocket's average wind, {speed} m/s from {:.1}° (its gusts are not modelled).",
        from.to_degrees()
    );
    let _ = writeln!(
        w,
        "[environment.atmosphere]\nmodel = \"custom\"\nwind_u = {}\nwind_v = {}\n",
        n(u),
        n(v)
    );
}

/// The `[flight]` table of the simulation's launch rod and time limit, appended to `w`.
fn flight_text(w: &mut String, sim: &Simulation) {
    let rod = condition(sim, "launchrodlength", 1.0);
    let angle = condition(sim, "launchrodangle", 0.0);
    let heading = condition(sim, "launchroddirection", 90.0);
    let max_time = condition(sim, "maxtime", 600.0);
    let _ = writeln!(
        w,
        "[flight]\nrail_length = {}\ninclination = {}\nheading = {}\nmax_time = {}",
        n(rod),
        n(90.0 - angle),
        n(heading),
        n(max_time)
    );
}

/// The further motor mounts of a single-stage rocket as `[[extra_motors]]` entries, each lit
/// its delay after launch, appended to `w`.
///
/// # Errors
/// A motor's thrust file that cannot be found or read.
fn extra_motors_text(
    w: &mut String,
    file: &Path,
    group: &Group,
    options: &ImportOptions,
) -> Result<(), OrkError> {
    for (mount, motor) in &group.extra {
        let (text, nozzle_at) = motor_text(file, mount, motor, "extra_motors.motor", options)?;
        let _ = writeln!(
            w,
            "\n# `{}`: {} {}, lit {} (OpenRocket: {}).",
            mount.name,
            motor.manufacturer,
            motor.designation,
            after("launch", motor.ignition.1),
            after(&motor.ignition.0, motor.ignition.1)
        );
        let _ = writeln!(
            w,
            "[[extra_motors]]\nname = {}\nmotor_position = {}                # nozzle exit: the mount's aft end plus overhang\nignition_delay = {}\n",
            quoted(&mount.name),
            n(nozzle_at),
            n(motor.ignition.1)
        );
        w.push_str(&text);
    }
    Ok(())
}

/// The bodies below the top one as `[[stages]]` entries (their separation and the ignition of
/// the stage above, their airframe and motor texts `lower`), appended to `w`.
fn stages_text(
    w: &mut String,
    sim: &Simulation,
    groups: &[Group],
    lower: &[BodyText],
    staging_of: &[(f64, f64)],
) {
    // Stage names as reports show them, made unique by OpenRocket's stage number.
    let title = |g: &Group| {
        if groups.iter().filter(|o| o.name() == g.name()).count() > 1 {
            format!("{} {}", g.name(), g.number)
        } else {
            g.name().to_owned()
        }
    };
    for (k, (group, text)) in groups[1..].iter().zip(lower).enumerate() {
        let (separate, ignition_delay) = staging_of[k];
        let upper = &groups[k];
        let sep = separation(&sim.config, group.stages[0]);
        let _ = writeln!(
            w,
            "\n# {} (OpenRocket's stage {}): separated {}; `{}` above lights {}.",
            title(group),
            group.number,
            after(&sep.event, sep.delay),
            upper.mount.name,
            after(&upper.motor.ignition.0, upper.motor.ignition.1)
        );
        let _ = writeln!(
            w,
            "[[stages]]\nname = {}\nseparation = \"burnout + {}\"\nignition_delay = {}",
            quoted(&title(group)),
            n(separate),
            n(ignition_delay)
        );
        let _ = writeln!(
            w,
            "stack_power_off_drag = \"estimate\"\nstack_power_on_drag = \"estimate\"\n"
        );
        w.push_str(&text.motor);
        w.push_str(&text.rocket);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_written_without_rounding_noise() {
        assert_eq!(n(6.0 * 0.0254), "0.1524");
        assert_eq!(n(0.013049999999999999), "0.01305");
        assert_eq!(n(0.40800000000000003), "0.408");
        assert_eq!(n(2.0), "2.0");
        assert_eq!(n(1.0 / 3.0), "0.333333333333");
        assert_eq!(n(-1.5e-7), "-1.5e-7");
        assert_eq!(n(f64::INFINITY), "inf");
    }
}
