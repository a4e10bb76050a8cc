//! The trajectory of a flown mission as named series: every post-processed quantity at
//! every stored point (`trajectory.csv`, the Python package's arrays) and the flight path as
//! KML (latitude, longitude and absolute altitude for Google Earth).

use std::fmt::Write as _;

use karman_atmos::Environment;
use karman_dynamics::Sample;
use karman_math::PhysicalConstants;

use crate::assemble::flight::FlightRun;

/// What the series read of a flown body besides its samples: a single-stage flight
/// ([`FlightRun`]) or one body of a multi-stage flight
/// ([`crate::assemble::stages::BodyTrack`]).
pub trait Track {
    /// The launch environment (latitude and longitude of the points).
    fn environment(&self) -> &Environment;
    /// The static margin at `t` of the model flown then, calibers.
    fn static_margin(&self, t: f64) -> f64;
    /// The reference radius at `t` of the model flown then, m (the Reynolds number's length
    /// is its diameter).
    fn reference_radius(&self, t: f64) -> f64;
    /// The rail buttons of the body that left the rail, with its rail-exit time; `None` for
    /// a body that never was on the rail or a rocket without buttons.
    fn rail(&self) -> Option<RailArms>;
}

/// The rail buttons' lever arms from the centre of dry mass along the body axis, `D1` (upper
/// button) and `D2` (lower), m; their roll angle, rad; the rail-exit time, s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailArms {
    /// `(z_upper − z_CDM) csys`, m.
    pub upper: f64,
    /// `(z_lower − z_CDM) csys`, m.
    pub lower: f64,
    /// The buttons' angular position, rad.
    pub angle: f64,
    /// The rail-exit time, s.
    pub exit_time: f64,
}

impl RailArms {
    /// The arms of `rocket`'s buttons, off the rail at `exit_time`.
    #[must_use]
    pub fn of(rocket: &karman_airframe::Rocket, exit_time: f64) -> Option<Self> {
        let b = rocket.rail_buttons()?;
        let (cdm, csys) = (rocket.center_of_dry_mass(), rocket.csys());
        Some(RailArms {
            upper: (b.upper_position - cdm) * csys,
            lower: (b.lower_position - cdm) * csys,
            angle: b.angular_position_rad,
            exit_time,
        })
    }
}

impl Track for FlightRun {
    fn environment(&self) -> &Environment {
        &self.environment
    }
    fn static_margin(&self, t: f64) -> f64 {
        self.rocket.static_margin(t)
    }
    fn reference_radius(&self, _: f64) -> f64 {
        self.rocket.radius()
    }
    fn rail(&self) -> Option<RailArms> {
        RailArms::of(&self.rocket, self.flight.rail_exit?.0)
    }
}

/// One series of the trajectory: a name, its unit (empty for a pure number) and how it is
/// read from a flown point.
#[derive(Debug, Clone, Copy)]
pub struct Series {
    /// Name (`altitude_agl`).
    pub name: &'static str,
    /// Unit suffix (`m`, `mps`, `deg`, ...; empty when dimensionless).
    pub unit: &'static str,
    value: fn(&dyn Track, &Sample) -> f64,
}

impl Series {
    /// The column name of `trajectory.csv`: the name with its unit (`altitude_agl_m`).
    #[must_use]
    pub fn column(&self) -> String {
        if self.unit.is_empty() {
            self.name.to_owned()
        } else {
            format!("{}_{}", self.name, self.unit)
        }
    }

    /// The value at one point of `run`.
    #[must_use]
    pub fn value(&self, run: &dyn Track, sample: &Sample) -> f64 {
        (self.value)(run, sample)
    }
}

const fn series(
    name: &'static str,
    unit: &'static str,
    value: fn(&dyn Track, &Sample) -> f64,
) -> Series {
    Series { name, unit, value }
}

/// Every series, in the column order of `trajectory.csv`. Positions are those of the centre
/// of dry mass in the launch frame (x east, y north, z up); body-frame quantities carry the
/// indices 1, 2, 3 of RocketPy's body axes.
pub const SERIES: &[Series] = &[
    series("time", "s", |_, s| s.t),
    series("x", "m", |_, s| s.x),
    series("y", "m", |_, s| s.y),
    series("z_asl", "m", |_, s| s.z),
    series("altitude_agl", "m", |_, s| s.altitude_agl),
    series("latitude", "deg", |r, s| {
        r.environment().geodetic(s.x, s.y).0
    }),
    series("longitude", "deg", |r, s| {
        r.environment().geodetic(s.x, s.y).1
    }),
    series("vx", "mps", |_, s| s.vx),
    series("vy", "mps", |_, s| s.vy),
    series("vz", "mps", |_, s| s.vz),
    series("ax", "mps2", |_, s| s.ax),
    series("ay", "mps2", |_, s| s.ay),
    series("az", "mps2", |_, s| s.az),
    series("e0", "", |_, s| s.e[0]),
    series("e1", "", |_, s| s.e[1]),
    series("e2", "", |_, s| s.e[2]),
    series("e3", "", |_, s| s.e[3]),
    series("omega1", "radps", |_, s| s.omega[0]),
    series("omega2", "radps", |_, s| s.omega[1]),
    series("omega3", "radps", |_, s| s.omega[2]),
    series("alpha1", "radps2", |_, s| s.omega_dot[0]),
    series("alpha2", "radps2", |_, s| s.omega_dot[1]),
    series("alpha3", "radps2", |_, s| s.omega_dot[2]),
    series("speed", "mps", |_, s| s.speed),
    series("free_stream_speed", "mps", |_, s| s.free_stream_speed),
    series("mach", "", |_, s| s.mach),
    series("dynamic_pressure", "pa", |_, s| s.dynamic_pressure),
    series("angle_of_attack", "deg", |_, s| s.angle_of_attack_deg),
    series("path_angle", "deg", |_, s| s.path_angle_deg),
    series("attitude_angle", "deg", |_, s| s.attitude_angle_deg),
    series("precession", "deg", |_, s| s.euler_deg[0]),
    series("nutation", "deg", |_, s| s.euler_deg[1]),
    series("spin", "deg", |_, s| s.euler_deg[2]),
    series("static_margin", "cal", |r, s| r.static_margin(s.t)),
    series("stability_margin", "cal", |_, s| s.stability_margin),
    series("aero_force_r1", "n", |_, s| s.force[0]),
    series("aero_force_r2", "n", |_, s| s.force[1]),
    series("aero_force_r3", "n", |_, s| s.force[2]),
    series("aero_moment_m1", "nm", |_, s| s.moment[0]),
    series("aero_moment_m2", "nm", |_, s| s.moment[1]),
    series("aero_moment_m3", "nm", |_, s| s.moment[2]),
    series("net_thrust", "n", |_, s| s.net_thrust),
    series("mass", "kg", |_, s| s.mass),
    // RocketPy 1.13's further `Flight` attributes (docs/flight-outputs.md), after the columns
    // above so that a reader of the earlier columns by position is unaffected.
    series("vx_body", "mps", |_, s| s.velocity_body[0]),
    series("vy_body", "mps", |_, s| s.velocity_body[1]),
    series("vz_body", "mps", |_, s| s.velocity_body[2]),
    series("ax_body", "mps2", |_, s| s.acceleration_body[0]),
    series("ay_body", "mps2", |_, s| s.acceleration_body[1]),
    series("az_body", "mps2", |_, s| s.acceleration_body[2]),
    series("attitude_vector_x", "", |_, s| s.axis[0]),
    series("attitude_vector_y", "", |_, s| s.axis[1]),
    series("attitude_vector_z", "", |_, s| s.axis[2]),
    series("axial_acceleration", "mps2", |_, s| {
        s.ax * s.axis[0] + s.ay * s.axis[1] + s.az * s.axis[2]
    }),
    series("horizontal_speed", "mps", |_, s| s.vx.hypot(s.vy)),
    series("partial_angle_of_attack", "deg", |_, s| {
        // RocketPy: the stream's opposite (the rocket's motion through the air) in the
        // body's y-z plane, against the axis.
        (-s.stream_body[1]).atan2(-s.stream_body[2]).to_degrees()
    }),
    series("angle_of_sideslip", "deg", |_, s| {
        (-s.stream_body[0]).atan2(-s.stream_body[2]).to_degrees()
    }),
    series("pressure", "pa", |_, s| s.pressure),
    series("density", "kgpm3", |_, s| s.density),
    series("dynamic_viscosity", "pas", |_, s| s.dynamic_viscosity),
    series("reynolds_number", "", |r, s| {
        s.density * s.free_stream_speed / s.dynamic_viscosity * (2.0 * r.reference_radius(s.t))
    }),
    series("total_pressure", "pa", |_, s| {
        // The isentropic stagnation pressure of air (γ = 1.4), RocketPy's
        // `p (1 + 0.2 M²)^3.5` at every Mach number.
        s.pressure * (1.0 + 0.2 * s.mach * s.mach).powf(3.5)
    }),
    series("aerodynamic_lift", "n", |_, s| s.force[0].hypot(s.force[1])),
    series("aerodynamic_drag", "n", |_, s| -s.force[2]),
    series("aerodynamic_bending_moment", "nm", |_, s| {
        s.moment[0].hypot(s.moment[1])
    }),
    series("aerodynamic_spin_moment", "nm", |_, s| s.moment[2]),
    series("rotational_energy", "j", |_, s| rotational_energy(s)),
    series("translational_energy", "j", |_, s| translational_energy(s)),
    series("kinetic_energy", "j", |_, s| {
        rotational_energy(s) + translational_energy(s)
    }),
    series("potential_energy", "j", |r, s| potential_energy(r, s)),
    series("total_energy", "j", |r, s| {
        rotational_energy(s) + translational_energy(s) + potential_energy(r, s)
    }),
    series("thrust_power", "w", |_, s| s.net_thrust * s.speed),
    series("drag_power", "w", |_, s| s.force[2] * s.speed),
    series("thrust_to_weight", "", |_, s| {
        // RocketPy's `Rocket.thrust_to_weight`: thrust over the weight at standard gravity.
        s.net_thrust / (PhysicalConstants::SI.standard_gravity * s.mass)
    }),
    series("rail_button1_normal_force", "n", |r, s| {
        rail_button_forces(r, s)[0]
    }),
    series("rail_button1_shear_force", "n", |r, s| {
        rail_button_forces(r, s)[1]
    }),
    series("rail_button2_normal_force", "n", |r, s| {
        rail_button_forces(r, s)[2]
    }),
    series("rail_button2_shear_force", "n", |r, s| {
        rail_button_forces(r, s)[3]
    }),
    series("drift", "m", |_, s| s.x.hypot(s.y)),
    series("bearing", "deg", |_, s| {
        // Clockwise from north, in (0°, 360°] as RocketPy writes it (`2π − atan2(−x, y)`).
        (2.0 * std::f64::consts::PI - (-s.x).atan2(s.y)).to_degrees()
    }),
];

/// `½ (I11 ω1² + I22 ω2² + I33 ω3²)` about the centre of dry mass (RocketPy's
/// `Flight.rotational_energy`), J.
fn rotational_energy(s: &Sample) -> f64 {
    let [i1, i2, i3] = s.inertia;
    let [w1, w2, w3] = s.omega;
    0.5 * (i1 * w1 * w1 + i2 * w2 * w2 + i3 * w3 * w3)
}

/// The forces on the rail buttons while the rocket is on the rail (RocketPy 1.13's
/// `Flight.rail_button1_normal_force` …): the transverse aerodynamic loads `(R1, R2)` and
/// moments `(M1, M2)` about the centre of dry mass shared by the two buttons as a beam on two
/// supports at `D1` (upper) and `D2` (lower) from it, `F1 = (R1 D2 − M2, R2 D2 + M1)/(D1 + D2)`,
/// `F2 = (R1 D1 + M2, R2 D1 − M1)/(D1 + D2)`, each resolved along the buttons' angular position
/// φ into normal `F·(cos φ, sin φ)` and shear `F·(−sin φ, cos φ)`: `[normal 1, shear 1,
/// normal 2, shear 2]`, N; zero off the rail and without buttons.
fn rail_button_forces(r: &dyn Track, s: &Sample) -> [f64; 4] {
    let Some(arms) = r.rail().filter(|a| s.t <= a.exit_time) else {
        return [0.0; 4];
    };
    let ([r1, r2, _], [m1, m2, _]) = (s.force, s.moment);
    let (d1, d2) = (arms.upper, arms.lower);
    let span = d1 + d2;
    if !(span.abs() > 0.0 && span.is_finite()) {
        // Buttons placed symmetrically about the centre of dry mass: no beam to share.
        return [0.0; 4];
    }
    let upper = [(r1 * d2 - m2) / span, (r2 * d2 + m1) / span];
    let lower = [(r1 * d1 + m2) / span, (r2 * d1 - m1) / span];
    let (sin, cos) = arms.angle.sin_cos();
    [
        upper[0] * cos + upper[1] * sin,
        -upper[0] * sin + upper[1] * cos,
        lower[0] * cos + lower[1] * sin,
        -lower[0] * sin + lower[1] * cos,
    ]
}

/// `½ m |v|²`, J.
fn translational_energy(s: &Sample) -> f64 {
    0.5 * s.mass * s.speed * s.speed
}

/// `GM m (1/(R + z) − 1/R)` with the datum's local radius `R` and the height above sea level
/// `z` (RocketPy's `Flight.potential_energy`), J.
fn potential_energy(r: &dyn Track, s: &Sample) -> f64 {
    let gm = PhysicalConstants::SI.earth_gravitational_parameter;
    let radius = r.environment().datum_radius();
    gm * s.mass * (1.0 / (s.z + radius) - 1.0 / radius)
}

/// The series called `name`.
#[must_use]
pub fn series_named(name: &str) -> Option<&'static Series> {
    SERIES.iter().find(|s| s.name == name)
}

/// `trajectory.csv`: a header of [`Series::column`] names, then one row per point (numbers in
/// Rust's shortest round-trip form).
#[must_use]
pub fn csv(run: &dyn Track, samples: &[Sample]) -> String {
    let header: Vec<String> = SERIES.iter().map(Series::column).collect();
    let mut csv = header.join(",");
    csv.push('\n');
    for sample in samples {
        for (i, series) in SERIES.iter().enumerate() {
            if i > 0 {
                csv.push(',');
            }
            let _ = write!(csv, "{}", series.value(run, sample));
        }
        csv.push('\n');
    }
    csv
}

/// Escapes text for XML.
fn xml_escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The flight path named `name` as a KML LineString with absolute altitudes.
#[must_use]
pub fn kml(run: &dyn Track, name: &str, samples: &[Sample]) -> String {
    let name = xml_escape(name);
    let mut coords = String::new();
    for s in samples {
        let (lat, lon) = run.environment().geodetic(s.x, s.y);
        let _ = writeln!(coords, "          {lon:.8},{lat:.8},{:.2}", s.z);
    }
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2">
  <Document>
    <name>{name}</name>
    <Style id="path"><LineStyle><color>ff0000ff</color><width>3</width></LineStyle></Style>
    <Placemark>
      <name>{name} trajectory</name>
      <styleUrl>#path</styleUrl>
      <LineString>
        <altitudeMode>absolute</altitudeMode>
        <coordinates>
{coords}        </coordinates>
      </LineString>
    </Placemark>
  </Document>
</kml>
"#
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_columns_carry_units() {
        let mut names: Vec<&str> = SERIES.iter().map(|s| s.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), SERIES.len());
        assert_eq!(
            series_named("altitude_agl").map(Series::column).as_deref(),
            Some("altitude_agl_m")
        );
        assert_eq!(
            series_named("mach").map(Series::column).as_deref(),
            Some("mach")
        );
        assert!(series_named("nothing").is_none());
    }

    #[test]
    fn escapes_xml() {
        assert_eq!(xml_escape("a<b>&c"), "a&lt;b&gt;&amp;c");
    }
}
