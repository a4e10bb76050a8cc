//! The imported design as a commented mission file.

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::design::{Component, Design, Kind, MotorRef, Simulation};
use super::mass::{self, MassProps};
use super::{ImportOptions, Imported, OrkError};

/// A TOML number that reads back to the same `f64`.
fn n(v: f64) -> String {
    let s = format!("{v:?}");
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

fn eng_header(path: &Path) -> Option<EngHeader> {
    let text = std::fs::read_to_string(path).ok()?;
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
    let design_dir = file
        .parent()
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

/// Builds the mission text of `design` for the simulation chosen by `options`.
pub(super) fn mission(
    file: &Path,
    design: &Design,
    options: &ImportOptions,
) -> Result<Imported, OrkError> {
    let mut warnings = Vec::new();
    let sim = match &options.simulation {
        Some(name) => design.simulations.iter().find(|s| &s.name == name),
        None => design.simulations.first(),
    };
    let Some(sim) = sim else {
        return Err(OrkError::Simulation {
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
        });
    };
    let stage = &design.stage;
    let all = stage.walk();

    // Body: the nose first, then tubes and transitions.
    let body: Vec<&Component> = stage.children.iter().filter(|c| c.kind.is_body()).collect();
    let Some(nose) = body.first().filter(|c| c.kind == Kind::NoseCone) else {
        return Err(OrkError::Unsupported {
            file: file.to_owned(),
            component: body
                .first()
                .map_or_else(|| stage.name.clone(), |c| c.name.clone()),
            what: "a body that does not start with a nose cone".to_owned(),
        });
    };
    let mut radius: f64 = 0.0;
    for b in &body {
        for e in ["radius", "aftradius", "foreradius"] {
            if b.fields.contains_key(e) {
                radius = radius.max(b.dim(e)?);
            }
        }
    }
    if radius <= 0.0 {
        return Err(nose.value_error("aftradius", "the body has no positive radius"));
    }
    let body_length = body.last().map_or(0.0, |b| b.x + b.length);
    for c in &all {
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
        let aft = w[0].num_or("aftradius", w[0].num_or("radius", 0.0)?)?;
        let fore = w[1].num_or("foreradius", w[1].num_or("radius", 0.0)?)?;
        if (aft - fore).abs() > 1e-6 {
            warnings.push(format!(
                "`{}` → `{}`: a step in radius ({aft} m → {fore} m) without a transition; \
                 the drag estimate's body keeps the radius",
                w[0].name, w[1].name
            ));
        }
    }

    // Mass without motor.
    let props: MassProps = mass::subtree(stage, 0.0, radius)?;

    // Motor of the simulation's configuration.
    let mounts: Vec<&Component> = all
        .iter()
        .copied()
        .filter(|c| c.motors.contains_key(&sim.config))
        .collect();
    if mounts.len() > 1 {
        return Err(OrkError::Unsupported {
            file: file.to_owned(),
            component: mounts
                .iter()
                .map(|m| m.name.clone())
                .collect::<Vec<_>>()
                .join(", "),
            what: "several motors in one flight".to_owned(),
        });
    }
    let Some(mount) = mounts.first() else {
        return Err(OrkError::Unsupported {
            file: file.to_owned(),
            component: sim.name.clone(),
            what: "a simulation without a motor".to_owned(),
        });
    };
    let motor = &mount.motors[&sim.config];
    let (eng_path, eng) = find_motor(file, motor, options)?;
    let motor_length = if motor.length.is_finite() {
        motor.length
    } else {
        eng.length
    };
    let motor_diameter = if motor.diameter.is_finite() {
        motor.diameter
    } else {
        eng.diameter
    };
    let nozzle_at = mount.x + mount.length + mount.overhang;
    let dry = (eng.total - eng.propellant).max(0.0);

    let mut t = String::new();
    let w = &mut t;
    let _ = writeln!(
        w,
        "# {} — imported from {} by `karman import`.",
        design.name,
        file.file_name()
            .map_or_else(String::new, |f| f.to_string_lossy().into_owned())
    );
    let _ = writeln!(
        w,
        "# Simulation {:?}: motor {} {}; OpenRocket's masses, overrides and launch",
        sim.name, motor.manufacturer, motor.designation
    );
    let _ = writeln!(
        w,
        "# conditions; drag estimated from the geometry. Rocket coordinates: nose tip at 0,"
    );
    let _ = writeln!(w, "# positions grow toward the tail (m).");
    let _ = writeln!(w, "name = {}", quoted(&design.name));
    let _ = writeln!(w);

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

    let _ = writeln!(
        w,
        "# {} {} from {}: RASP masses {} kg propellant, {} kg total; the propellant is",
        motor.manufacturer,
        motor.designation,
        eng_path.display(),
        eng.propellant,
        eng.total
    );
    let _ = writeln!(
        w,
        "# a cylinder filling the motor case, and leaves in proportion to the impulse."
    );
    let _ = writeln!(
        w,
        "[motor]\nkind = \"generic\"\nthrust = {}",
        quoted(&relative(&eng_path, options.output_dir.as_deref()))
    );
    let _ = writeln!(
        w,
        "dry_mass = {}\ncenter_of_dry_mass_position = {}",
        n(dry),
        n(0.5 * motor_length)
    );
    let _ = writeln!(
        w,
        "nozzle_radius = {}\npropellant_initial_mass = {}",
        n(0.25 * motor_diameter),
        n(eng.propellant)
    );
    let _ = writeln!(
        w,
        "chamber_radius = {}\nchamber_height = {}\nchamber_position = {}",
        n(0.5 * motor_diameter),
        n(motor_length),
        n(0.5 * motor_length)
    );
    let _ = writeln!(w, "coordinate_system = \"nozzle_to_combustion_chamber\"\n");

    let _ = writeln!(
        w,
        "# Mass properties without motor, summed over the components (with OpenRocket's overrides)."
    );
    let _ = writeln!(
        w,
        "[rocket]\nradius = {}\nmass = {}",
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
    let _ = writeln!(
        w,
        "power_off_drag = \"estimate\"\npower_on_drag = \"estimate\""
    );
    let _ = writeln!(
        w,
        "motor_position = {}                # nozzle exit: the mount's aft end plus overhang\n",
        n(nozzle_at)
    );

    // Drag-estimate geometry.
    let finishes: Vec<&str> = body.iter().filter_map(|b| b.text("finish")).collect();
    let finish = finishes
        .iter()
        .copied()
        .max_by_key(|f| finishes.iter().filter(|g| *g == f).count())
        .unwrap_or("normal");
    let mut used = BTreeSet::new();
    let mut surfaces = String::new();
    let mut fins = String::new();
    let mut lugs = String::new();
    let mut buttons = None;
    let mut overrides = String::new();
    let nose_key = key(&nose.name, &mut used);
    if let Some(cd) = nose
        .fields
        .get("overridecd")
        .and_then(|t| super::design::number(t))
    {
        let _ = writeln!(overrides, "{nose_key} = {}", n(cd));
    }
    let _ = write!(
        surfaces,
        "[rocket.surfaces.{nose_key}]\ntype = \"nose\"\nlength = {}\n",
        n(nose.length)
    );
    let shape = nose.text("shape").unwrap_or("conical");
    let parameter = nose.num_or("shapeparameter", 1.0)?;
    let kind = match shape {
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
    };
    let _ = writeln!(surfaces, "kind = \"{kind}\"");
    if kind == "powerseries" {
        let _ = writeln!(surfaces, "power = {}", n(parameter));
    }
    let _ = write!(
        surfaces,
        "position = 0.0\nbase_radius = {}\n\n",
        n(nose.dim("aftradius")?)
    );
    for b in &body[1..] {
        if b.kind == Kind::Transition {
            if b.text("shape") != Some("conical") {
                warnings.push(format!(
                    "`{}`: a {} transition is flown (normal force, CP and drag) as a conical one",
                    b.name,
                    b.text("shape").unwrap_or("?")
                ));
            }
            let tail_key = key(&b.name, &mut used);
            if let Some(cd) = b
                .fields
                .get("overridecd")
                .and_then(|t| super::design::number(t))
            {
                let _ = writeln!(overrides, "{tail_key} = {}", n(cd));
            }
            let _ = write!(
                surfaces,
                "[rocket.surfaces.{tail_key}]\ntype = \"tail\"\ntop_radius = {}\nbottom_radius = {}\nlength = {}\nposition = {}\n\n",
                n(b.dim("foreradius")?),
                n(b.dim("aftradius")?),
                n(b.length),
                n(b.x)
            );
        }
    }
    for parent in &body {
        let tube_radius = parent.num_or("radius", parent.num_or("aftradius", radius)?)?;
        for c in &parent.children {
            match c.kind {
                Kind::TrapezoidFins | Kind::EllipticalFins | Kind::FreeFormFins => {
                    let name = key(&c.name, &mut used);
                    let count = c.num_or("fincount", 1.0)?;
                    let cant = c.num_or("cant", 0.0)?;
                    let common = format!(
                        "n = {}\nposition = {}\ncant_angle = {}\nradius = {}\n",
                        count as u32,
                        n(c.x),
                        n(cant),
                        n(tube_radius)
                    );
                    match c.kind {
                        Kind::TrapezoidFins => {
                            let _ = write!(
                                surfaces,
                                "[rocket.surfaces.{name}]\ntype = \"trapezoidal_fins\"\nroot_chord = {}\ntip_chord = {}\nspan = {}\nsweep_length = {}\n{common}\n",
                                n(c.dim("rootchord")?),
                                n(c.dim("tipchord")?),
                                n(c.dim("height")?),
                                n(c.num("sweeplength")?)
                            );
                        }
                        Kind::EllipticalFins => {
                            let _ = write!(
                                surfaces,
                                "[rocket.surfaces.{name}]\ntype = \"elliptical_fins\"\nroot_chord = {}\nspan = {}\n{common}\n",
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
                                "[rocket.surfaces.{name}]\ntype = \"free_form_fins\"\nshape_points = [{}]\n{common}\n",
                                points.join(", ")
                            );
                        }
                    }
                    let section = c.text("crosssection").unwrap_or("square");
                    let _ = write!(
                        fins,
                        "[rocket.drag_estimate.fins.{name}]\nthickness = {}\ncross_section = \"{section}\"\n",
                        n(c.dim("thickness")?)
                    );
                    if let Some(f) = c.text("finish") {
                        if f != finish {
                            let _ = writeln!(fins, "finish = \"{f}\"");
                        }
                    }
                    fins.push('\n');
                }
                Kind::LaunchLug => {
                    let r = c.dim("radius")?;
                    let _ = write!(
                        lugs,
                        "[rocket.drag_estimate.launch_lugs.{}]\nouter_radius = {}\ninner_radius = {}\nlength = {}\ncount = {}\n\n",
                        key(&c.name, &mut used),
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
    let _ = writeln!(
        w,
        "[rocket.drag_estimate]\nbody_length = {}\nfinish = \"{finish}\"\n",
        n(body_length)
    );
    if !overrides.is_empty() {
        let _ = writeln!(
            w,
            "# OpenRocket's drag-coefficient overrides (on the reference area)."
        );
        let _ = writeln!(w, "[rocket.drag_estimate.overrides]\n{overrides}");
    }
    w.push_str(&fins);
    w.push_str(&lugs);
    if let Some((upper, lower, od, id, h, inner)) = buttons {
        let _ = writeln!(
            w,
            "[rocket.drag_estimate.rail_buttons]\nouter_diameter = {}\ninner_diameter = {}\nheight = {}\ninner_height = {}\n",
            n(od),
            n(id),
            n(h),
            n(inner)
        );
        let _ = writeln!(
            w,
            "[rocket.rail_buttons]\nupper_position = {}\nlower_position = {}\n",
            n(upper),
            n(lower.max(upper + 1e-3))
        );
    }
    w.push_str(&surfaces);

    // Recovery.
    for c in &all {
        match c.kind {
            Kind::Parachute => {
                let d = c.dim("diameter")?;
                let cd = c.num_or("cd", 0.8)?;
                let area = std::f64::consts::PI * 0.25 * d * d;
                let event = c.text("deployevent").unwrap_or("ejection");
                let delay = c.num_or("deploydelay", 0.0)?;
                // OpenRocket's deployment events, each then delayed by `deploydelay` (the lag).
                let trigger = match event {
                    "apogee" => "\"apogee\"".to_owned(),
                    "altitude" => n(c.num("deployaltitude")?),
                    "launch" => "\"launch + 0\"".to_owned(),
                    "never" => continue,
                    // The motor's ejection charge fires its delay after burn-out.
                    "ejection" => match motor.delay {
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
                    "[rocket.parachutes.{}]\ncd_s = {}              # Cd {cd} × π ({d} m)² / 4\ntrigger = {trigger}\nlag = {}\nsampling_rate = 100\n\n",
                    key(&c.name, &mut used),
                    n(cd * area),
                    n(delay)
                );
            }
            Kind::Streamer => warnings.push(format!("`{}`: streamers are not modelled", c.name)),
            _ => {}
        }
    }

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
    if !warnings.is_empty() {
        let mut head = String::new();
        for warning in &warnings {
            let _ = writeln!(head, "# note: {warning}");
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
