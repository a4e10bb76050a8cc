//! Validation of a deserialized mission, without physics: required keys per model and kind,
//! keys that a model does not use, ranges of plain inputs, data files that must exist (and
//! curve files that must parse), dates, and the `[dispersion]` table. Every problem found is
//! returned, each located at its key.

use crate::document::Document;
use crate::error::{Problem, ProblemKind};
use crate::paths;
use crate::schema::{
    AtmosphereModel, AtmosphereSpec, Curve, DensitySpec, Discretize, MissionSpec, Mode, MotorKind,
    MotorSpec, ParachuteSpec, RocketSpec, SensorSpec, SoundingFormat, SurfaceSpec, Sweep,
    TankGeometryKind, TankGeometrySpec, TankKindName, TankSpec, Trigger, WeatherSource,
};
use karman_airframe::AirBrakesDrag;
use karman_math::{Extrapolation, Interpolation};
use std::path::Path;

/// Keys where `inf` is a valid value.
pub(crate) const ALLOW_INFINITE: &[&str] = &[
    "flight.max_time_step",
    // RocketPy's default: unbounded (`inf` is `[-inf, inf]`).
    "rocket.sensors.measurement_range",
];

/// Largest parachute and air-brake controller sampling rate, Hz (a barometer at 10 kHz already resolves far more than
/// any trigger needs; more only multiplies the sampling instants of a flight).
const MAX_SAMPLING_RATE: f64 = 10_000.0;

/// Largest 3-DOF weathercock coefficient, 1/s: the attitude then follows the relative wind
/// within a millisecond, faster than any rocket turns; a larger rate only makes the
/// equations stiff (at 10¹² 1/s the integrator's step limit ends the flight).
const MAX_WEATHERCOCK_COEFF: f64 = 1000.0;

/// Most fins (or tube fins) of one set: far more than any rocket carries; at 10⁹ the
/// interference factors make the flight too stiff to integrate.
const MAX_FINS: u32 = 1000;
const FIN_COUNT: &str = "needs 1 to 1000 fins";
const TUBE_COUNT: &str = "needs 1 to 1000 tubes";

/// Longest launch rail, m: a kilometre, far beyond any rail or tower.
const MAX_RAIL_LENGTH: f64 = 1000.0;

/// Range of the launch elevation, m: from below the Dead Sea shore to the Kármán line (a
/// launch from 10¹² m ends the flight in the integrator's step limit).
const ELEVATION_RANGE: (f64, f64) = (-1000.0, 100_000.0);

/// Longest flight time, s (a day; a descent under a drogue from 100 km takes under an hour).
pub(crate) const MAX_FLIGHT_TIME: f64 = 86_400.0;

/// Range of the integrator's relative tolerance: below 1e-12 round-off dominates the error
/// estimate; above 1e-2 the steps no longer resolve the flight (at 1 the step control accepts
/// anything and the states turn to NaN).
const RTOL_RANGE: (f64, f64) = (1e-12, 1e-2);

/// Largest absolute tolerance of a state (its SI unit: m, m/s, rad/s; the quaternion is
/// dimensionless).
const MAX_ATOL: f64 = 1.0;

/// Smallest absolute tolerance of a state component (`[flight] atol`): below it (1e-30 and
/// under) the error estimate asks for steps below the integrator's minimum at the first
/// instant, so the flight would fail whatever the mission; `rtol`'s lower bound too.
const MIN_ATOL: f64 = 1e-12;

/// Smallest `max_time_step`, s: a 600 s flight at 1e-4 s already takes six million steps.
const MIN_MAX_TIME_STEP: f64 = 1e-4;

/// Extensions a thrust curve file may have (parsing them is the propulsion crate's job).
const THRUST_EXTENSIONS: &[&str] = &["eng", "rse", "csv", "txt"];

/// Extensions of a netCDF weather grid.
const GRID_EXTENSIONS: &[&str] = &["nc", "nc4", "netcdf"];

struct Checker<'a> {
    dir: &'a Path,
    /// `--fetch` is about to download the atmosphere file a `source` names: it need not
    /// exist yet.
    fetching: bool,
    /// Whether data files are read and checked. Off for a Monte Carlo sample: its files are
    /// the nominal mission's, read and checked when the mission was loaded, and a sample's
    /// drawn curves are inline points (checked without reading anything).
    data: bool,
    /// Each problem by its whole dotted key, located by the caller.
    problems: Vec<(String, ProblemKind)>,
    /// While a `[[stages]]` entry is checked with the `[rocket]` and `[motor]` checks: its
    /// dotted path (`stages.0`), put before the keys they report.
    stage: Option<String>,
}

impl Checker<'_> {
    fn new(dir: &Path, fetching: bool, data: bool) -> Checker<'_> {
        Checker {
            dir,
            fetching,
            data,
            problems: Vec::new(),
            stage: None,
        }
    }

    fn report(&mut self, key: &str, kind: ProblemKind) {
        let key = match &self.stage {
            Some(stage) => format!("{stage}.{key}"),
            None => key.to_owned(),
        };
        self.problems.push((key, kind));
    }

    /// The problems found so far, located in `doc`.
    fn take_located(&mut self, doc: &Document<'_>) -> Vec<Problem> {
        self.problems
            .drain(..)
            .map(|(key, kind)| doc.problem(&key, kind))
            .collect()
    }

    /// `value` must satisfy `ok`, described by `expected`.
    fn range(&mut self, key: &str, value: f64, ok: bool, expected: &'static str) {
        if !ok && value.is_finite() {
            self.report(key, ProblemKind::OutOfRange { value, expected });
        }
    }

    fn positive(&mut self, key: &str, value: f64) {
        self.range(key, value, value > 0.0, "must be > 0");
    }

    fn non_negative(&mut self, key: &str, value: f64) {
        self.range(key, value, value >= 0.0, "must be >= 0");
    }

    fn required<T>(&mut self, key: &str, name: &'static str, value: Option<&T>, needed_by: &str) {
        if value.is_none() {
            self.report(
                key,
                ProblemKind::MissingKey {
                    key: name,
                    needed_by: needed_by.to_owned(),
                },
            );
        }
    }

    fn unused<T>(&mut self, key: &str, value: Option<&T>, model: &str) {
        if value.is_some() {
            self.report(
                key,
                ProblemKind::NotApplicable {
                    model: model.to_owned(),
                },
            );
        }
    }

    /// A data file must exist and have one of `extensions` (any, if empty).
    fn file(&mut self, key: &str, path: &Path, extensions: &'static [&'static str]) {
        if !self.data {
            return;
        }
        let resolved = self.dir.join(path);
        if let Err(source) = karman_math::files::check_data_file(&resolved) {
            self.report(
                key,
                ProblemKind::File {
                    path: resolved,
                    source,
                },
            );
            return;
        }
        let extension = resolved
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        if !extensions.is_empty() && !extension.is_some_and(|e| extensions.contains(&e.as_str())) {
            self.report(
                key,
                ProblemKind::FileExtension {
                    path: resolved,
                    expected: extensions,
                },
            );
        }
    }

    /// A curve: its file must exist and parse; inline points must make a table.
    /// A curve read with the format's default table (linear, end values held).
    fn curve(&mut self, key: &str, curve: &Curve) {
        self.curve_as(key, curve, Interpolation::Linear, Extrapolation::Constant);
    }

    fn curve_as(
        &mut self,
        key: &str,
        curve: &Curve,
        interpolation: Interpolation,
        extrapolation: Extrapolation,
    ) {
        if !self.data && curve.file_path(self.dir).is_some() {
            return;
        }
        match crate::curves::check(curve, self.dir, interpolation, extrapolation) {
            Ok(()) => {}
            Err(kind) => self.report(key, kind),
        }
    }
}

/// Checks everything that can be checked without building models.
pub(crate) fn validate(
    spec: &MissionSpec,
    doc: &Document<'_>,
    dir: &Path,
    fetching: bool,
) -> Vec<Problem> {
    let mut c = Checker::new(dir, fetching, true);
    environment(&mut c, spec);
    motor(&mut c, spec);
    rocket(&mut c, spec);
    air_brakes(&mut c, spec);
    sensors(&mut c, spec);
    flight(&mut c, spec);
    let mut problems = c.take_located(doc);
    problems.extend(dispersion(spec, doc));
    stages(&mut c, spec);
    extra_motors(&mut c, spec);
    problems.extend(c.take_located(doc));
    problems
}

/// The checks of [`validate`] on a Monte Carlo sample's mission (`spec`, the nominal mission
/// with the sample's drawn values applied), without reading data files: the same ranges as
/// the file and `--set` get, so that a draw outside them fails its sample instead of flying
/// it. Each problem by its dotted key. The `[dispersion]` table is the study's, not the
/// sample's, and is not checked again.
pub(crate) fn validate_drawn(spec: &MissionSpec, dir: &Path) -> Vec<(String, ProblemKind)> {
    let mut c = Checker::new(dir, false, false);
    environment(&mut c, spec);
    motor(&mut c, spec);
    rocket(&mut c, spec);
    air_brakes(&mut c, spec);
    sensors(&mut c, spec);
    flight(&mut c, spec);
    stages(&mut c, spec);
    extra_motors(&mut c, spec);
    c.problems
}

/// The `[[extra_motors]]` entries: each motor with the checks of `[motor]`, its ignition
/// delay, and what a combination of motors needs (linear thrust curves, no pressure-thrust
/// correction, a single-stage rocket): everything the flight's combination would refuse.
fn extra_motors(c: &mut Checker<'_>, spec: &MissionSpec) {
    if spec.extra_motors.is_empty() {
        return;
    }
    if !spec.stages.is_empty() {
        c.report(
            "extra_motors",
            ProblemKind::Unsupported {
                what: "`[[extra_motors]]` on a multi-stage rocket".to_owned(),
            },
        );
    }
    let motors = std::iter::once(("motor".to_owned(), &spec.motor)).chain(
        spec.extra_motors
            .iter()
            .enumerate()
            .map(|(index, e)| (format!("extra_motors.{index}.motor"), &e.motor)),
    );
    for (key, m) in motors {
        if m.interpolation != crate::schema::InterpolationKind::Linear {
            c.report(
                &format!("{key}.interpolation"),
                ProblemKind::Unsupported {
                    what: format!(
                        "a thrust curve interpolated as `{}` in a rocket of several motors \
                         (their thrust curves are summed on the union of their times: \
                         `interpolation = \"linear\"`)",
                        m.interpolation
                    ),
                },
            );
        }
        if m.reference_pressure.is_some() {
            c.report(
                &format!("{key}.reference_pressure"),
                ProblemKind::Unsupported {
                    what: "the pressure-thrust correction (`reference_pressure`) in a rocket of \
                           several motors"
                        .to_owned(),
                },
            );
        }
    }
    for (index, extra) in spec.extra_motors.iter().enumerate() {
        let mut alone = spec.clone();
        alone.motor = extra.motor.clone();
        alone.extra_motors.clear();
        c.stage = Some(format!("extra_motors.{index}"));
        motor(c, &alone);
        c.stage = None;
        // Within the longest flight: a later ignition never happens (and at 1e15 s the
        // thrust curve's times no longer resolve its burn).
        c.range(
            &format!("extra_motors.{index}.ignition_delay"),
            extra.ignition_delay,
            (0.0..=MAX_FLIGHT_TIME).contains(&extra.ignition_delay),
            "must be in [0, 86400] s",
        );
    }
}

/// The `[[stages]]` entries: each stage's airframe and motor with the checks of `[rocket]`
/// and `[motor]` (a stage may weigh nothing), its separation trigger, and what a stack must
/// share (one coordinate system, distinct surface and parachute names).
fn stages(c: &mut Checker<'_>, spec: &MissionSpec) {
    if spec.stages.is_empty() {
        return;
    }
    if spec.rocket.air_brakes.is_some() {
        c.report(
            "rocket.air_brakes",
            ProblemKind::Unsupported {
                what: "air brakes on a multi-stage rocket".to_owned(),
            },
        );
    }
    let mut surfaces: Vec<&str> = spec.rocket.surfaces.keys().map(String::as_str).collect();
    let mut parachutes: Vec<&str> = spec.rocket.parachutes.keys().map(String::as_str).collect();
    for (index, stage) in spec.stages.iter().enumerate() {
        let at = |k: &str| format!("stages.{index}.{k}");
        let mut alone = spec.clone();
        alone.rocket = stage.rocket.clone();
        alone.stages.clear();
        c.stage = Some(format!("stages.{index}"));
        if let Some(motor_spec) = &stage.motor {
            alone.motor = motor_spec.clone();
            motor(c, &alone);
        }
        rocket(c, &alone);
        c.stage = None;
        if stage.rocket.air_brakes.is_some() {
            c.report(
                &at("rocket.air_brakes"),
                ProblemKind::NotApplicable {
                    model: "a lower stage".to_owned(),
                },
            );
        }
        if stage.rocket.coordinate_system != spec.rocket.coordinate_system {
            c.report(
                &at("rocket.coordinate_system"),
                ProblemKind::Stage {
                    reason: "every stage is placed in the coordinates of [rocket]: the \
                             coordinate systems must be the same"
                        .to_owned(),
                },
            );
        }
        for name in stage.rocket.surfaces.keys() {
            if surfaces.contains(&name.as_str()) {
                c.report(
                    &at(&format!("rocket.surfaces.{name}")),
                    ProblemKind::Stage {
                        reason: format!("a surface `{name}` is already on the stack above"),
                    },
                );
            }
            surfaces.push(name);
        }
        for name in stage.rocket.parachutes.keys() {
            if parachutes.contains(&name.as_str()) {
                c.report(
                    &at(&format!("rocket.parachutes.{name}")),
                    ProblemKind::Stage {
                        reason: format!("a parachute `{name}` is already on the stack above"),
                    },
                );
            }
            parachutes.push(name);
        }
        match &stage.separation {
            Trigger::HeightAboveGround(h) => c.non_negative(&at("separation"), *h),
            Trigger::Launch(delay) | Trigger::Burnout(delay) => {
                c.non_negative(&at("separation"), *delay);
            }
            Trigger::Expression(text) => {
                if let Err(source) = karman_script::Expression::parse(text) {
                    c.report(
                        &at("separation.expression"),
                        ProblemKind::Expression {
                            text: text.clone(),
                            source,
                        },
                    );
                }
            }
            Trigger::Apogee => {}
        }
        // A stage without a motor cannot lift what is above it: it and every stage below it
        // leave on the pad.
        let on_pad =
            |s: &crate::schema::StageSpec| matches!(s.separation, Trigger::Launch(d) if d <= 0.0);
        let motorless_above = spec.stages[..index].iter().any(|s| s.motor.is_none());
        if (stage.motor.is_none() || motorless_above) && !on_pad(stage) {
            c.report(
                &at("separation"),
                ProblemKind::Stage {
                    reason: "a stage without a motor cannot lift the stack: it and the stages \
                             below it separate at launch (`separation = \"launch + 0\"`), or it \
                             needs `[stages.motor]`"
                        .to_owned(),
                },
            );
        }
        c.range(
            &at("sampling_rate"),
            stage.sampling_rate,
            stage.sampling_rate > 0.0 && stage.sampling_rate <= MAX_SAMPLING_RATE,
            "must be in (0, 10000] Hz",
        );
        c.range(
            &at("ignition_delay"),
            stage.ignition_delay,
            (0.0..=MAX_FLIGHT_TIME).contains(&stage.ignition_delay),
            "must be in [0, 86400] s",
        );
        if let Some(area) = stage.tumble_drag_area {
            c.positive(&at("tumble_drag_area"), area);
        }
        let (interpolation, extrapolation) = (
            stage.rocket.interpolation.into(),
            stage.rocket.extrapolation.into(),
        );
        for (key, curve) in [
            ("stack_power_off_drag", &stage.stack_power_off_drag),
            ("stack_power_on_drag", &stage.stack_power_on_drag),
        ] {
            if !curve.is_estimate() {
                c.curve_as(&at(key), curve, interpolation, extrapolation);
            }
        }
    }
}

fn environment(c: &mut Checker<'_>, spec: &MissionSpec) {
    let env = &spec.environment;
    c.range(
        "environment.latitude",
        env.latitude_deg,
        (-90.0..=90.0).contains(&env.latitude_deg),
        "must be within [-90, 90] deg",
    );
    c.range(
        "environment.elevation",
        env.elevation,
        (ELEVATION_RANGE.0..=ELEVATION_RANGE.1).contains(&env.elevation),
        "must be within [-1000, 100000] m",
    );
    c.range(
        "environment.longitude",
        env.longitude_deg,
        (-180.0..=360.0).contains(&env.longitude_deg),
        "must be within [-180, 360] deg",
    );
    if let Some(date) = &env.date {
        if date.date.is_none() || date.time.is_none() || date.offset.is_none() {
            c.report(
                "environment.date",
                ProblemKind::Date {
                    date: date.to_string(),
                },
            );
        }
    }
    if let Some(g) = env.gravity {
        c.positive("environment.gravity", g);
    }
    if let Some(h) = env.max_expected_height {
        c.range(
            "environment.max_expected_height",
            h,
            h > env.elevation,
            "must be above the launch elevation",
        );
    }
    let atm = &env.atmosphere;
    let model = atm.model;
    let what = format!("the {model} atmosphere");
    let grid = matches!(
        model,
        AtmosphereModel::Reanalysis | AtmosphereModel::Forecast | AtmosphereModel::Ensemble
    );
    let custom = model == AtmosphereModel::Custom;
    if matches!(model, AtmosphereModel::Standard | AtmosphereModel::Custom) {
        c.unused("environment.atmosphere.file", atm.file.as_ref(), &what);
    } else {
        c.required(
            "environment.atmosphere.file",
            "file",
            atm.file.as_ref(),
            &what,
        );
        if let Some(file) = &atm.file {
            let extensions = match model {
                _ if grid => GRID_EXTENSIONS,
                AtmosphereModel::OpenMeteo => &["json"],
                _ => &[],
            };
            if !(c.fetching && atm.source.is_some()) {
                c.file("environment.atmosphere.file", file, extensions);
            }
        }
        c.required("environment.date", "date", env.date.as_ref(), &what);
    }
    if model == AtmosphereModel::Sounding {
        c.required(
            "environment.atmosphere.format",
            "format",
            atm.format.as_ref(),
            &what,
        );
    } else {
        c.unused("environment.atmosphere.format", atm.format.as_ref(), &what);
    }
    if !grid {
        c.unused(
            "environment.atmosphere.dictionary",
            atm.dictionary.as_ref(),
            &what,
        );
    }
    if !matches!(
        model,
        AtmosphereModel::Ensemble | AtmosphereModel::OpenMeteo
    ) {
        c.unused("environment.atmosphere.member", atm.member.as_ref(), &what);
    }
    source(c, atm, &what);
    let curves = [
        ("pressure", &atm.pressure),
        ("temperature", &atm.temperature),
        ("wind_u", &atm.wind_u),
        ("wind_v", &atm.wind_v),
    ];
    for (name, curve) in curves {
        let key = format!("environment.atmosphere.{name}");
        match curve {
            Some(curve) if custom => c.curve(&key, curve),
            _ => c.unused(&key, curve.as_ref(), &what),
        }
    }
}

/// `source` must be a service that sends what `model` reads; `station` goes with Wyoming.
fn source(c: &mut Checker<'_>, atm: &AtmosphereSpec, what: &str) {
    let wyoming = atm.source == Some(WeatherSource::Wyoming);
    if wyoming {
        c.required(
            "environment.atmosphere.station",
            "station",
            atm.station.as_ref(),
            what,
        );
    } else {
        c.unused(
            "environment.atmosphere.station",
            atm.station.as_ref(),
            "a source other than \"wyoming\"",
        );
    }
    let Some(source) = atm.source else {
        return;
    };
    let fits = match source {
        WeatherSource::OpenMeteo => atm.model == AtmosphereModel::OpenMeteo,
        WeatherSource::Gfs => atm.model == AtmosphereModel::Forecast,
        WeatherSource::Wyoming => {
            atm.model == AtmosphereModel::Sounding && atm.format != Some(SoundingFormat::NoaaRuc)
        }
    };
    if !fits {
        let needs = match source {
            WeatherSource::OpenMeteo => "model = \"open_meteo\"",
            WeatherSource::Gfs => "model = \"forecast\"",
            WeatherSource::Wyoming => "model = \"sounding\" with format = \"wyoming\"",
        };
        c.report(
            "environment.atmosphere.source",
            ProblemKind::Schema {
                message: format!("source \"{source}\" sends files read with {needs}"),
            },
        );
    }
}

/// `[motor]`: its thrust, mounting and cluster, then the keys its kind needs and refuses, then
/// the values of those keys.
fn motor(c: &mut Checker<'_>, spec: &MissionSpec) {
    let m = &spec.motor;
    let what = format!("a {} motor", m.kind);
    motor_thrust_and_mounting(c, m);
    motor_kind_keys(c, m, &what);
    motor_kind_values(c, m, &what);
}

/// The thrust curve (or constant thrust and its burn time), reshaping, dry mass, nozzle,
/// cluster and reference pressure of any motor.
fn motor_thrust_and_mounting(c: &mut Checker<'_>, m: &MotorSpec) {
    match &m.thrust {
        Curve::File(path) => c.file("motor.thrust", path, THRUST_EXTENSIONS),
        Curve::Constant(value) => {
            c.non_negative("motor.thrust", *value);
            if m.burn_time.is_none() && m.reshape_thrust_curve.is_none() {
                c.required(
                    "motor.burn_time",
                    "burn_time",
                    m.burn_time.as_ref(),
                    "a constant thrust",
                );
            }
        }
        points @ Curve::Points(_) => c.curve("motor.thrust", points),
    }
    if let Some(burn) = m.burn_time {
        c.range(
            "motor.burn_time",
            burn.end,
            burn.start >= 0.0 && burn.end > burn.start,
            "needs 0 <= start < end",
        );
    }
    if let Some([time, impulse]) = m.reshape_thrust_curve {
        c.positive("motor.reshape_thrust_curve", time);
        c.positive("motor.reshape_thrust_curve", impulse);
    }
    c.non_negative("motor.dry_mass", m.dry_mass);
    c.positive("motor.nozzle_radius", m.nozzle_radius);
    if let Some(n) = m.cluster_count {
        c.range(
            "motor.cluster_count",
            f64::from(n),
            n >= 1,
            "needs at least 1 motor",
        );
    }
    if let Some(r) = m.cluster_radius {
        c.non_negative("motor.cluster_radius", r);
    }
    if let Some(p) = m.reference_pressure {
        c.positive("motor.reference_pressure", p);
    }
}

/// The keys a motor of `m.kind` needs (each named as missing) and those it does not use
/// (each named as unused), the tanks of a hybrid or liquid motor checked one by one.
fn motor_kind_keys(c: &mut Checker<'_>, m: &MotorSpec, what: &str) {
    let solid = [
        (
            "motor.grain_number",
            "grain_number",
            m.grain_number.map(f64::from),
        ),
        (
            "motor.grain_separation",
            "grain_separation",
            m.grain_separation,
        ),
        ("motor.grain_density", "grain_density", m.grain_density),
        (
            "motor.grain_outer_radius",
            "grain_outer_radius",
            m.grain_outer_radius,
        ),
        (
            "motor.grain_initial_inner_radius",
            "grain_initial_inner_radius",
            m.grain_initial_inner_radius,
        ),
        (
            "motor.grain_initial_height",
            "grain_initial_height",
            m.grain_initial_height,
        ),
        (
            "motor.grains_center_of_mass_position",
            "grains_center_of_mass_position",
            m.grains_center_of_mass_position,
        ),
    ];
    let generic = [
        (
            "motor.propellant_initial_mass",
            "propellant_initial_mass",
            m.propellant_initial_mass,
        ),
        ("motor.chamber_radius", "chamber_radius", m.chamber_radius),
        ("motor.chamber_height", "chamber_height", m.chamber_height),
        (
            "motor.chamber_position",
            "chamber_position",
            m.chamber_position,
        ),
    ];
    let none: [(&str, &'static str, Option<f64>); 0] = [];
    let (needed, foreign): (&[_], Vec<_>) = match m.kind {
        MotorKind::Solid | MotorKind::Hybrid => (&solid[..], generic.to_vec()),
        MotorKind::Generic => (&generic[..], solid.to_vec()),
        MotorKind::Liquid => (&none[..], solid.iter().chain(&generic).copied().collect()),
    };
    match m.kind {
        MotorKind::Hybrid | MotorKind::Liquid => {
            if m.tanks.is_empty() {
                c.required("motor.tanks", "tanks", None::<&()>, what);
            }
            for (index, tank) in m.tanks.iter().enumerate() {
                tank_checks(c, index, tank);
            }
        }
        MotorKind::Solid | MotorKind::Generic => {
            c.unused("motor.tanks", m.tanks.first(), what);
        }
    }
    if matches!(m.kind, MotorKind::Generic | MotorKind::Liquid) {
        c.unused("motor.only_radial_burn", m.only_radial_burn.as_ref(), what);
    }
    for (key, name, value) in needed {
        c.required(key, name, value.as_ref(), what);
    }
    for (key, _, value) in foreign {
        c.unused(key, value.as_ref(), what);
    }
}

/// The values of the kind's own keys: grain and throat sizes of a solid or hybrid motor, the
/// chamber of a generic one.
fn motor_kind_values(c: &mut Checker<'_>, m: &MotorSpec, what: &str) {
    match m.kind {
        MotorKind::Solid | MotorKind::Hybrid => {
            c.required(
                "motor.center_of_dry_mass_position",
                "center_of_dry_mass_position",
                m.center_of_dry_mass_position.as_ref(),
                what,
            );
            if let Some(n) = m.grain_number {
                c.range(
                    "motor.grain_number",
                    f64::from(n),
                    n >= 1,
                    "needs at least 1 grain",
                );
            }
            let positives = [
                ("motor.grain_density", m.grain_density),
                ("motor.grain_outer_radius", m.grain_outer_radius),
                ("motor.grain_initial_height", m.grain_initial_height),
                ("motor.throat_radius", m.throat_radius),
            ];
            for (key, value) in positives {
                if let Some(value) = value {
                    c.positive(key, value);
                }
            }
            if let Some(gap) = m.grain_separation {
                c.non_negative("motor.grain_separation", gap);
            }
            if let (Some(inner), Some(outer)) = (m.grain_initial_inner_radius, m.grain_outer_radius)
            {
                c.range(
                    "motor.grain_initial_inner_radius",
                    inner,
                    (0.0..outer).contains(&inner),
                    "must be >= 0 and below grain_outer_radius",
                );
            }
        }
        MotorKind::Liquid => {
            c.unused("motor.throat_radius", m.throat_radius.as_ref(), what);
        }
        MotorKind::Generic => {
            c.unused("motor.throat_radius", m.throat_radius.as_ref(), what);
            let positives = [
                ("motor.propellant_initial_mass", m.propellant_initial_mass),
                ("motor.chamber_radius", m.chamber_radius),
                ("motor.chamber_height", m.chamber_height),
            ];
            for (key, value) in positives {
                if let Some(value) = value {
                    c.positive(key, value);
                }
            }
        }
    }
}

/// `[rocket.pods]`: at least one pod, every surface named exists and belongs to one pod,
/// at most one nose cone per pod.
fn pods(c: &mut Checker<'_>, r: &RocketSpec) {
    let mut owner: std::collections::BTreeMap<&str, &str> = std::collections::BTreeMap::new();
    for (pod, p) in &r.pods {
        let key = |k: &str| format!("rocket.pods.{pod}.{k}");
        c.range(
            &key("count"),
            f64::from(p.count),
            p.count >= 1,
            "needs at least 1 pod",
        );
        if let Some(l) = p.body_length {
            c.positive(&key("body_length"), l);
        }
        let mut noses = 0;
        for name in &p.surfaces {
            match r.surfaces.get(name) {
                None => c.report(
                    &key("surfaces"),
                    ProblemKind::UnknownPath {
                        path: key("surfaces"),
                        reason: format!("there is no surface [rocket.surfaces.{name}]"),
                    },
                ),
                Some(SurfaceSpec::Nose(_)) => noses += 1,
                Some(_) => {}
            }
            if let Some(other) = owner.insert(name.as_str(), pod.as_str()) {
                c.report(
                    &key("surfaces"),
                    ProblemKind::Schema {
                        message: format!(
                            "surface `{name}` is already carried by pod `{other}`; a surface belongs to one pod set"
                        ),
                    },
                );
            }
        }
        if noses > 1 {
            c.report(
                &key("surfaces"),
                ProblemKind::OutOfRange {
                    value: f64::from(noses),
                    expected: "a pod has at most one nose cone",
                },
            );
        }
    }
}

/// `[rocket.drag_estimate]`: dimensions in range, every fin table names a fin set.
fn drag_estimate(c: &mut Checker<'_>, d: &crate::schema::DragEstimateSpec, r: &RocketSpec) {
    const K: &str = "rocket.drag_estimate";
    if let Some(l) = d.body_length {
        c.positive(&format!("{K}.body_length"), l);
    }
    if let Some(k) = d.roughness {
        c.non_negative(&format!("{K}.roughness"), k);
    }
    for (name, f) in &d.fins {
        let key = format!("{K}.fins.{name}");
        let is_fin_set = r.surfaces.get(name).is_some_and(|s| {
            matches!(
                s,
                SurfaceSpec::TrapezoidalFins(_)
                    | SurfaceSpec::EllipticalFins(_)
                    | SurfaceSpec::FreeFormFins(_)
            )
        });
        if !is_fin_set {
            c.report(
                &key,
                ProblemKind::UnknownPath {
                    path: key.clone(),
                    reason: format!("there is no fin set [rocket.surfaces.{name}]"),
                },
            );
        }
        c.non_negative(&format!("{key}.thickness"), f.thickness);
    }
    for name in d.overrides.keys() {
        let body_part = r
            .surfaces
            .get(name)
            .is_some_and(|s| matches!(s, SurfaceSpec::Nose(_) | SurfaceSpec::Tail(_)));
        if !body_part {
            let key = format!("{K}.overrides.{name}");
            c.report(
                &key,
                ProblemKind::UnknownPath {
                    path: key.clone(),
                    reason: format!("there is no nose or tail [rocket.surfaces.{name}]"),
                },
            );
        }
    }
    for (name, l) in &d.launch_lugs {
        let key = format!("{K}.launch_lugs.{name}");
        c.positive(&format!("{key}.outer_radius"), l.outer_radius);
        c.non_negative(&format!("{key}.inner_radius"), l.inner_radius);
        c.non_negative(&format!("{key}.length"), l.length);
    }
    if let Some(b) = &d.rail_buttons {
        let key = format!("{K}.rail_buttons");
        c.required(
            &key,
            "rocket.rail_buttons",
            r.rail_buttons.as_ref(),
            "the rail-button drag",
        );
        for (k, v) in [
            ("outer_diameter", b.outer_diameter),
            ("inner_diameter", b.inner_diameter),
            ("height", b.height),
            ("inner_height", b.inner_height),
        ] {
            c.non_negative(&format!("{key}.{k}"), v);
        }
    }
}

/// A tank without resampling (`discretize = false`, RocketPy's `discretize=None`): RocketPy
/// 1.13 builds it only from tables, which keep their own points — the ullage, the liquid
/// height, or the liquid and gas masses given at the same times — and builds no
/// mass-flow-rate tank so.
fn own_points_checks(c: &mut Checker<'_>, index: usize, t: &TankSpec) {
    let key = |name: &str| format!("motor.tanks.{index}.{name}");
    let schema = |message: &str| ProblemKind::Schema {
        message: message.to_owned(),
    };
    let curves: &[(&str, Option<&Curve>)] = match t.kind {
        TankKindName::MassFlowRate => {
            c.report(
                &key("discretize"),
                schema(
                    "a mass_flow_rate tank needs resampling (discretize = N): RocketPy 1.13 \
                     builds none with discretize=None",
                ),
            );
            return;
        }
        TankKindName::Ullage => &[("ullage", t.ullage.as_ref())],
        TankKindName::Level => &[("liquid_height", t.liquid_height.as_ref())],
        TankKindName::Mass => &[
            ("liquid_mass", t.liquid_mass.as_ref()),
            ("gas_mass", t.gas_mass.as_ref()),
        ],
    };
    for (name, curve) in curves {
        if let Some(Curve::Constant(_)) = curve {
            c.report(
                &key(name),
                schema(
                    "must be a table of time with discretize = false (the tank keeps the \
                     curve's own points)",
                ),
            );
        }
    }
    if let [
        (_, Some(liquid @ Curve::Points(_))),
        (_, Some(gas @ Curve::Points(_))),
    ] = curves
    {
        let times = |curve: &Curve| -> Vec<f64> {
            curve
                .sorted_points()
                .unwrap_or_default()
                .iter()
                .map(|p| p[0])
                .collect()
        };
        if times(liquid) != times(gas) {
            c.report(
                &key("gas_mass"),
                schema(
                    "must be given at the times of liquid_mass with discretize = false \
                     (RocketPy 1.13 adds the two tables point by point)",
                ),
            );
        }
    }
}

/// One `[[motor.tanks]]` entry: the keys its kind needs and uses, its geometry, fluids, flux
/// time and curves (the contents are checked against the volume when the tank is built).
fn tank_checks(c: &mut Checker<'_>, index: usize, t: &TankSpec) {
    let key = |name: &str| format!("motor.tanks.{index}.{name}");
    let what = format!("a {} tank", t.kind);
    tank_geometry(c, &key, &t.geometry);
    tank_fluids(c, index, t, &key);
    tank_kind_keys(c, t, &key, &what);
}

/// The tank's radius (a number or a curve by kind) and height (needed by a cylinder, unused
/// by the others).
fn tank_geometry(c: &mut Checker<'_>, key: &dyn Fn(&str) -> String, g: &TankGeometrySpec) {
    match (&g.kind, &g.radius) {
        (TankGeometryKind::Cylindrical | TankGeometryKind::Spherical, Curve::Constant(r)) => {
            c.positive(&key("geometry.radius"), *r);
        }
        (TankGeometryKind::Cylindrical | TankGeometryKind::Spherical, _) => c.report(
            &key("geometry.radius"),
            ProblemKind::OutOfRange {
                value: f64::NAN,
                expected: "must be a number for a cylindrical or spherical tank",
            },
        ),
        (TankGeometryKind::Custom, radius) => c.curve(&key("geometry.radius"), radius),
    }
    match g.kind {
        TankGeometryKind::Cylindrical => {
            let geometry = "a cylindrical tank";
            c.required(
                &key("geometry.height"),
                "height",
                g.height.as_ref(),
                geometry,
            );
            if let Some(h) = g.height {
                c.positive(&key("geometry.height"), h);
                if let (true, Curve::Constant(r)) = (g.spherical_caps, &g.radius) {
                    c.range(
                        &key("geometry.height"),
                        h,
                        h >= 2.0 * r,
                        "must be at least twice the radius with spherical caps",
                    );
                }
            }
        }
        TankGeometryKind::Spherical | TankGeometryKind::Custom => {
            let geometry = format!("a {} tank", g.kind);
            c.unused(&key("geometry.height"), g.height.as_ref(), &geometry);
            if g.spherical_caps {
                c.unused(&key("geometry.spherical_caps"), Some(&()), &geometry);
            }
        }
    }
}

/// The tank's flux time, its fluids' densities and its discretisation.
fn tank_fluids(c: &mut Checker<'_>, index: usize, t: &TankSpec, key: &dyn Fn(&str) -> String) {
    c.range(
        &key("flux_time"),
        t.flux_time.end,
        t.flux_time.start >= 0.0 && t.flux_time.end > t.flux_time.start,
        "needs 0 <= start < end",
    );
    for (name, fluid) in [("liquid", &t.liquid), ("gas", &t.gas)] {
        let at = key(&format!("{name}.density"));
        match &fluid.density {
            DensitySpec::Constant(rho) => c.positive(&at, *rho),
            DensitySpec::Rows(rows) => {
                if rows.is_empty() {
                    c.report(
                        &at,
                        ProblemKind::OutOfRange {
                            value: 0.0,
                            expected: "needs at least one [temperature, pressure, density] row",
                        },
                    );
                }
                for row in rows {
                    c.positive(&at, row[2]);
                }
            }
            DensitySpec::File(path) => c.file(&at, path, &[]),
        }
    }
    match t.discretize {
        Some(Discretize::Nodes(n)) => c.range(
            &key("discretize"),
            f64::from(n),
            n >= 2,
            "needs at least 2 grid nodes",
        ),
        Some(Discretize::Flag(false)) => own_points_checks(c, index, t),
        None | Some(Discretize::Flag(true)) => {}
    }
}

/// The tank's curves, and the mass and flow keys its kind needs (each named as missing) and
/// does not use (each named as unused).
fn tank_kind_keys(c: &mut Checker<'_>, t: &TankSpec, key: &dyn Fn(&str) -> String, what: &str) {
    let curves = [
        ("temperature", t.temperature.as_ref()),
        ("pressure", t.pressure.as_ref()),
        (
            "liquid_mass_flow_rate_in",
            t.liquid_mass_flow_rate_in.as_ref(),
        ),
        (
            "liquid_mass_flow_rate_out",
            t.liquid_mass_flow_rate_out.as_ref(),
        ),
        ("gas_mass_flow_rate_in", t.gas_mass_flow_rate_in.as_ref()),
        ("gas_mass_flow_rate_out", t.gas_mass_flow_rate_out.as_ref()),
        ("ullage", t.ullage.as_ref()),
        ("liquid_height", t.liquid_height.as_ref()),
        ("liquid_mass", t.liquid_mass.as_ref()),
        ("gas_mass", t.gas_mass.as_ref()),
    ];
    for (name, curve) in curves {
        if let Some(curve) = curve {
            c.curve(&key(name), curve);
        }
    }
    let masses = [
        ("initial_liquid_mass", t.initial_liquid_mass),
        ("initial_gas_mass", t.initial_gas_mass),
    ];
    let (needed, used): (&[&str], &[&str]) = match t.kind {
        TankKindName::MassFlowRate => (
            &["initial_liquid_mass", "initial_gas_mass"],
            &[
                "initial_liquid_mass",
                "initial_gas_mass",
                "liquid_mass_flow_rate_in",
                "liquid_mass_flow_rate_out",
                "gas_mass_flow_rate_in",
                "gas_mass_flow_rate_out",
            ],
        ),
        TankKindName::Ullage => (&["ullage"], &["ullage"]),
        TankKindName::Level => (&["liquid_height"], &["liquid_height"]),
        TankKindName::Mass => (&["liquid_mass", "gas_mass"], &["liquid_mass", "gas_mass"]),
    };
    let present = |name: &str| {
        masses.iter().any(|(n, v)| *n == name && v.is_some())
            || curves.iter().any(|(n, v)| *n == name && v.is_some())
    };
    for name in needed {
        if !present(name) {
            c.report(
                &key(name),
                ProblemKind::MissingKey {
                    key: tank_key_name(name),
                    needed_by: what.to_owned(),
                },
            );
        }
    }
    let all = masses
        .iter()
        .map(|(n, _)| *n)
        .chain(curves[2..].iter().map(|(n, _)| *n));
    for name in all {
        if present(name) && !used.contains(&name) {
            c.report(
                &key(name),
                ProblemKind::NotApplicable {
                    model: what.to_owned(),
                },
            );
        }
    }
    for (name, value) in masses {
        if let Some(v) = value {
            c.non_negative(&key(name), v);
        }
    }
}

/// The `'static` name of a tank key (for [`ProblemKind::MissingKey`]).
fn tank_key_name(name: &str) -> &'static str {
    [
        "initial_liquid_mass",
        "initial_gas_mass",
        "ullage",
        "liquid_height",
        "liquid_mass",
        "gas_mass",
    ]
    .into_iter()
    .find(|n| *n == name)
    .unwrap_or("tank curve")
}

fn rocket(c: &mut Checker<'_>, spec: &MissionSpec) {
    let r = &spec.rocket;
    c.positive("rocket.radius", r.radius);
    if c.stage.is_some() {
        // A lower stage may be massless (a stack that equals the stage above).
        c.non_negative("rocket.mass", r.mass);
    } else {
        c.positive("rocket.mass", r.mass);
    }
    let (interpolation, extrapolation) = (r.interpolation.into(), r.extrapolation.into());
    for (key, curve) in [
        ("rocket.power_off_drag", &r.power_off_drag),
        ("rocket.power_on_drag", &r.power_on_drag),
    ] {
        if !curve.is_estimate() {
            c.curve_as(key, curve, interpolation, extrapolation);
        }
    }
    if let Some(d) = &r.drag_estimate {
        drag_estimate(c, d, r);
    }
    pods(c, r);
    eccentricities(c, spec);
    for (name, surface) in &r.surfaces {
        surface_checks(c, name, surface);
    }
    for (name, chute) in &r.parachutes {
        parachute_checks(c, name, chute, &r.sensors);
    }
}

/// `cm_eccentricity`, `cp_eccentricity`, `thrust_eccentricity`: finite offsets within the body
/// radius, the centre of mass not together with either of the others (RocketPy's
/// `add_cm_eccentricity` sets both), none on a rocket with stages.
fn eccentricities(c: &mut Checker<'_>, spec: &MissionSpec) {
    let r = &spec.rocket;
    let given = [
        ("rocket.cm_eccentricity", r.cm_eccentricity),
        ("rocket.cp_eccentricity", r.cp_eccentricity),
        ("rocket.thrust_eccentricity", r.thrust_eccentricity),
    ];
    for (key, value) in given {
        let Some([x, y]) = value else { continue };
        if c.stage.is_some() || !spec.stages.is_empty() {
            c.report(
                key,
                ProblemKind::Unsupported {
                    what: "an eccentricity on a multi-stage rocket".to_owned(),
                },
            );
            continue;
        }
        let offset = x.hypot(y);
        c.range(
            key,
            offset,
            offset < r.radius,
            "must lie within the body radius (|[x, y]| < rocket.radius)",
        );
    }
    if r.cm_eccentricity.is_some() {
        for (key, value) in &given[1..] {
            if value.is_some() {
                c.report(
                    key,
                    ProblemKind::Schema {
                        message: "cm_eccentricity already puts the aerodynamic forces and the \
                                  thrust off the axis (RocketPy's add_cm_eccentricity): give \
                                  it alone, or cp_eccentricity and thrust_eccentricity"
                            .to_owned(),
                    },
                );
            }
        }
    }
}

/// A fin or tube count `n` of `1..=MAX_FINS`, refused with `expected` otherwise.
fn fin_count(c: &mut Checker<'_>, key: &str, n: u32, expected: &'static str) {
    c.range(key, f64::from(n), (1..=MAX_FINS).contains(&n), expected);
}

/// A fin set's optional body radius: not negative (0: fins on no body, a pod's phantom tube).
fn fin_body_radius(c: &mut Checker<'_>, key: &str, radius: Option<f64>) {
    if let Some(radius) = radius {
        c.non_negative(key, radius);
    }
}

/// One `[rocket.surfaces.NAME]`: the sizes of its kind, its fin count, its airfoil curve.
fn surface_checks(c: &mut Checker<'_>, name: &str, surface: &SurfaceSpec) {
    let key = |k: &str| format!("rocket.surfaces.{name}.{k}");
    match surface {
        SurfaceSpec::Nose(s) => {
            c.positive(&key("length"), s.length);
            if let Some(b) = s.bluffness {
                c.range(
                    &key("bluffness"),
                    b,
                    (0.0..1.0).contains(&b),
                    "must be in [0, 1)",
                );
            }
            if let Some(p) = s.power {
                c.range(&key("power"), p, p > 0.0 && p <= 1.0, "must be in (0, 1]");
            }
            if let Some(radius) = s.base_radius {
                c.positive(&key("base_radius"), radius);
            }
        }
        SurfaceSpec::TrapezoidalFins(s) => {
            fin_count(c, &key("n"), s.n, FIN_COUNT);
            c.positive(&key("span"), s.span);
            c.positive(&key("root_chord"), s.root_chord);
            c.non_negative(&key("tip_chord"), s.tip_chord);
            if let Some(Sweep::AngleDeg(angle)) = s.sweep {
                c.range(
                    &key("sweep_angle"),
                    angle,
                    angle.abs() < 90.0,
                    "must be within (-90, 90) deg",
                );
            }
            fin_body_radius(c, &key("radius"), s.radius);
        }
        SurfaceSpec::EllipticalFins(s) => {
            fin_count(c, &key("n"), s.n, FIN_COUNT);
            c.positive(&key("span"), s.span);
            c.positive(&key("root_chord"), s.root_chord);
            fin_body_radius(c, &key("radius"), s.radius);
        }
        SurfaceSpec::FreeFormFins(s) => {
            fin_count(c, &key("n"), s.n, FIN_COUNT);
            if s.shape_points.len() < 3 {
                c.report(
                    &key("shape_points"),
                    ProblemKind::OutOfRange {
                        value: s.shape_points.len() as f64,
                        expected: "a fin planform needs at least 3 points",
                    },
                );
            }
            fin_body_radius(c, &key("radius"), s.radius);
        }
        SurfaceSpec::Tail(s) => {
            c.positive(&key("top_radius"), s.top_radius);
            // 0: a cone closing to a point (a pod's tail).
            c.non_negative(&key("bottom_radius"), s.bottom_radius);
            c.positive(&key("length"), s.length);
        }
        SurfaceSpec::TubeFins(s) => {
            fin_count(c, &key("n"), s.n, TUBE_COUNT);
            c.positive(&key("length"), s.length);
            c.positive(&key("outer_radius"), s.outer_radius);
            c.positive(&key("inner_radius"), s.inner_radius);
            c.range(
                &key("inner_radius"),
                s.inner_radius,
                s.inner_radius < s.outer_radius,
                "must be smaller than outer_radius",
            );
            if let Some(radius) = s.radius {
                c.positive(&key("radius"), radius);
            }
        }
    }
    if let Some(airfoil) = surface.airfoil() {
        c.curve(&key("airfoil"), &airfoil.lift);
    }
}

/// One `[rocket.parachutes.NAME]`: its drag area, trigger (an expression parsed with the
/// rocket's sensors readable), sampling rate, lag, noise and canopy sizes.
fn parachute_checks(
    c: &mut Checker<'_>,
    name: &str,
    chute: &ParachuteSpec,
    sensors: &[SensorSpec],
) {
    let key = |k: &str| format!("rocket.parachutes.{name}.{k}");
    c.positive(&key("cd_s"), chute.cd_s);
    match &chute.trigger {
        Trigger::HeightAboveGround(h) => c.non_negative(&key("trigger"), *h),
        Trigger::Launch(delay) | Trigger::Burnout(delay) => {
            c.non_negative(&key("trigger"), *delay);
        }
        Trigger::Expression(text) => {
            // The rocket's sensors are readable (`sensors[i]`, `sensors.NAME`).
            let shapes = crate::assemble::sensors::shapes(sensors);
            if let Err(source) = karman_script::Expression::parse_with(text, &shapes) {
                c.report(
                    &key("trigger.expression"),
                    ProblemKind::Expression {
                        text: text.clone(),
                        source,
                    },
                );
            }
        }
        Trigger::Apogee => {}
    }
    c.range(
        &key("sampling_rate"),
        chute.sampling_rate,
        chute.sampling_rate > 0.0 && chute.sampling_rate <= MAX_SAMPLING_RATE,
        "must be in (0, 10000] Hz",
    );
    c.non_negative(&key("lag"), chute.lag);
    c.non_negative(&key("noise"), chute.noise[1]);
    for (k, v) in [("radius", chute.radius), ("height", chute.height)] {
        if let Some(v) = v {
            c.positive(&key(k), v);
        }
    }
    if let Some(p) = chute.porosity {
        c.range(
            &key("porosity"),
            p,
            (0.0..=1.0).contains(&p),
            "must be in [0, 1]",
        );
    }
}

fn air_brakes(c: &mut Checker<'_>, spec: &MissionSpec) {
    let Some(ab) = &spec.rocket.air_brakes else {
        return;
    };
    let key = |k: &str| format!("rocket.air_brakes.{k}");
    c.range(
        &key("sampling_rate"),
        ab.sampling_rate,
        ab.sampling_rate > 0.0 && ab.sampling_rate <= MAX_SAMPLING_RATE,
        "must be in (0, 10000] Hz",
    );
    if let Some(area) = ab.reference_area {
        c.positive(&key("reference_area"), area);
    }
    if !c.data {
        // The drag table and the controller script are data files (a drawn table only
        // scales the nominal one's values).
        return;
    }
    match ab.drag_coefficient_curve.to_drag(c.dir) {
        Ok(AirBrakesDrag::Table(rows)) if rows.is_empty() => c.report(
            &key("drag_coefficient_curve"),
            ProblemKind::OutOfRange {
                value: 0.0,
                expected: "the table needs at least one [level, mach, cd] row",
            },
        ),
        Ok(_) => {}
        Err(source) => c.report(
            &key("drag_coefficient_curve"),
            ProblemKind::Curve { source },
        ),
    }
    let file = c.dir.join(&ab.controller);
    let text = karman_math::read_data_file(&file).and_then(|bytes| {
        String::from_utf8(bytes).map_err(|_| {
            std::io::Error::new(std::io::ErrorKind::InvalidData, "not a UTF-8 text file")
        })
    });
    let source = match text {
        Ok(source) => source,
        Err(source) => {
            c.report(&key("controller"), ProblemKind::File { path: file, source });
            return;
        }
    };
    match karman_script::ControllerScript::compile(&file, &source) {
        Ok(script) => {
            for name in ab.constants.keys() {
                if !script.constants().iter().any(|(n, _)| n == name) {
                    c.report(
                        &format!("rocket.air_brakes.constants.{name}"),
                        ProblemKind::Script {
                            source: Box::new(karman_script::ScriptError {
                                file: file.clone(),
                                position: None,
                                message: format!(
                                    "the script declares no top-level `const {name} = <number>;`"
                                ),
                            }),
                        },
                    );
                }
            }
        }
        Err(source) => c.report(
            &key("controller"),
            ProblemKind::Script {
                source: Box::new(source),
            },
        ),
    }
}

/// `[[rocket.sensors]]` (docs/physics.md §29): a unique name usable in a file name, a rate in
/// `(0, MAX_SENSOR_SAMPLING_RATE]`, the kind's own keys only, parameters in their domains.
/// Whether each sensor lies on the rocket is checked when the rocket is built
/// (`assemble::sensors::build`).
fn sensors(c: &mut Checker<'_>, spec: &MissionSpec) {
    use crate::assemble::sensors::MAX_SENSOR_SAMPLING_RATE;
    let sensors = &spec.rocket.sensors;
    if !sensors.is_empty() && !spec.stages.is_empty() {
        c.report(
            "rocket.sensors",
            ProblemKind::Unsupported {
                what: "sensors on a multi-stage rocket".to_owned(),
            },
        );
    }
    for (i, s) in sensors.iter().enumerate() {
        let key = |k: &str| format!("rocket.sensors.{i}.{k}");
        let sensor = |reason: String| ProblemKind::Sensor { reason };
        let good_name = !s.name.is_empty()
            && s.name.len() <= 64
            && s.name
                .chars()
                .all(|ch| ch.is_ascii_alphanumeric() || ch == '_' || ch == '-');
        if !good_name {
            c.report(
                &key("name"),
                sensor(format!(
                    "`{}`: a sensor name is 1 to 64 letters, digits, `_` or `-` (its readings go \
                     to sensor_<name>.csv)",
                    s.name.escape_debug()
                )),
            );
        }
        if sensors[..i].iter().any(|other| other.name == s.name) {
            c.report(
                &key("name"),
                sensor(format!("a sensor `{}` is already defined above", s.name)),
            );
        }
        c.range(
            &key("sampling_rate"),
            s.sampling_rate,
            s.sampling_rate > 0.0 && s.sampling_rate <= MAX_SENSOR_SAMPLING_RATE,
            "must be in (0, 10000] Hz",
        );
        let kind = format!("a {} sensor", s.kind.as_str());
        for k in s.keys_not_for_kind() {
            c.report(
                &key(k),
                ProblemKind::NotApplicable {
                    model: kind.clone(),
                },
            );
        }
        for k in s.per_axis_keys_on_scalar() {
            c.report(
                &key(k),
                sensor(format!(
                    "{kind} has one axis: give one number, not [x, y, z]"
                )),
            );
        }
        for (k, v) in [
            ("noise_density", s.noise_density),
            ("noise_variance", s.noise_variance),
            ("random_walk_density", s.random_walk_density),
            ("random_walk_variance", s.random_walk_variance),
        ] {
            if let Some(v) = v {
                for x in v.values() {
                    c.non_negative(&key(k), x);
                }
            }
        }
        for (k, v) in [
            ("resolution", s.resolution),
            ("position_accuracy", s.position_accuracy),
            ("altitude_accuracy", s.altitude_accuracy),
        ] {
            if let Some(v) = v {
                c.non_negative(&key(k), v);
            }
        }
        if let Some(t) = s.operating_temperature {
            c.range(
                &key("operating_temperature"),
                t,
                t > 0.0,
                "must be > 0 K (a temperature in kelvin)",
            );
        }
        if let Some(x) = s.cross_axis_sensitivity {
            c.range(
                &key("cross_axis_sensitivity"),
                x,
                (0.0..=100.0).contains(&x),
                "must be in [0, 100] %",
            );
        }
        if let Some(r) = s.measurement_range {
            let [lo, hi] = r.0;
            if lo.is_nan() || hi.is_nan() || lo >= hi {
                c.report(
                    &key("measurement_range"),
                    sensor(format!(
                        "[{lo}, {hi}]: the range must be [low, high] with low < high (a single \
                         number m is [-m, m], m > 0)"
                    )),
                );
            }
        }
    }
}

fn flight(c: &mut Checker<'_>, spec: &MissionSpec) {
    let f = &spec.flight;
    c.range(
        "flight.rail_length",
        f.rail_length,
        f.rail_length > 0.0 && f.rail_length <= MAX_RAIL_LENGTH,
        "must be in (0, 1000] m",
    );
    c.range(
        "flight.inclination",
        f.inclination_deg,
        f.inclination_deg > 0.0 && f.inclination_deg < 180.0,
        "must be in (0, 180) deg (past 90 the rail leans toward heading + 180)",
    );
    c.range(
        "flight.max_time",
        f.max_time,
        f.max_time > 0.0 && f.max_time <= MAX_FLIGHT_TIME,
        "must be in (0, 86400] s",
    );
    c.range(
        "flight.rtol",
        f.rtol,
        (RTOL_RANGE.0..=RTOL_RANGE.1).contains(&f.rtol),
        "must be in [1e-12, 1e-2]",
    );
    if let Some(atol) = f.atol {
        for value in atol.per_state() {
            c.range(
                "flight.atol",
                value,
                (MIN_ATOL..=MAX_ATOL).contains(&value),
                "every component must be in [1e-12, 1]",
            );
        }
    }
    c.range(
        "flight.max_time_step",
        f.max_time_step,
        f.max_time_step >= MIN_MAX_TIME_STEP,
        "must be at least 1e-4 s",
    );
    match f.simulation_mode {
        Mode::ThreeDof => {
            if let Some(w) = f.weathercock_coeff {
                c.range(
                    "flight.weathercock_coeff",
                    w,
                    (0.0..=MAX_WEATHERCOCK_COEFF).contains(&w),
                    "must be in [0, 1000] 1/s",
                );
            }
        }
        Mode::SixDof => c.unused(
            "flight.weathercock_coeff",
            f.weathercock_coeff.as_ref(),
            "the \"6 DOF\" simulation mode",
        ),
    }
}

fn dispersion(spec: &MissionSpec, doc: &Document<'_>) -> Vec<Problem> {
    let mut problems = Vec::new();
    let Some(d) = &spec.dispersion else {
        return problems;
    };
    if d.samples < 1 {
        problems.push(doc.problem(
            "dispersion.samples",
            ProblemKind::OutOfRange {
                value: f64::from(d.samples),
                expected: "needs at least 1 sample",
            },
        ));
    }
    for (path, distribution) in &d.vary {
        let key = format!("dispersion.vary.{path}");
        let problem = match paths::resolve(spec, path) {
            Ok(paths::Input::Curve(curve)) if curve.is_estimate() && !spec.stages.is_empty() => {
                Some(
                    "the estimated drag of a multi-stage rocket takes no `factor` or `offset` \
                     yet; give the curve as points or a file"
                        .to_owned(),
                )
            }
            Ok(input) => paths::check_distribution(&input, distribution).err(),
            Err(error) => Some(error.to_string()),
        };
        if let Some(reason) = problem {
            problems.push(vary_problem(doc, &key, path, reason));
        }
    }
    problems
}

/// A problem of a `[dispersion.vary]` entry, located at its key (whose name has dots, so
/// the located path is `dispersion.vary` plus the whole quoted key).
fn vary_problem(doc: &Document<'_>, key: &str, path: &str, reason: String) -> Problem {
    let span = doc.span_of(&["dispersion", "vary", path]);
    Problem {
        location: doc.location(span.start),
        key: key.to_owned(),
        kind: ProblemKind::Distribution { reason },
    }
}
