//! Post-processing at the stored solution points (docs/physics.md §11) and the flight summary of
//! the mission contract (mission-format.md, "The summary").
//!
//! As in RocketPy, every derived quantity is computed at the stored points only, extremes are
//! arg-max over those points, and accelerations and loads come from re-evaluating each point's
//! own phase equations (rail points keep the clipped rail acceleration). One addition: the
//! largest acceleration also considers each phase's equations at its first instant, where a
//! canopy's inflation peak sits (see [`Flight::summary`]).

use serde::Serialize;

use karman_model::{AtmosphereModel, Cursor, MassFlowLaw, StabilityModel, VehicleModel};

use crate::equations::{Cursors, Equations};
use crate::flight::{Flight, PhaseKind, SolutionPoint, Termination, evaluate};
use crate::state::{State, mat_t_vec, norm, rotation};

/// One named event of the summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EventRecord {
    /// `rail_exit`, `burnout`, `apogee`, `parachute:<name>` or `impact`.
    pub name: String,
    /// Time, s.
    pub time_s: f64,
}

/// The flight summary (keys exactly as mission-format.md and `reference.json`); `None`
/// (JSON `null`) for what did not occur.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Apogee above the launch elevation, m.
    pub apogee_agl_m: Option<f64>,
    /// Apogee above sea level, m.
    pub apogee_asl_m: Option<f64>,
    /// Apogee time, s.
    pub apogee_time_s: Option<f64>,
    /// Apogee east of the pad, m.
    pub apogee_x_m: Option<f64>,
    /// Apogee north of the pad, m.
    pub apogee_y_m: Option<f64>,
    /// Rail exit time, s.
    pub out_of_rail_time_s: Option<f64>,
    /// Speed at rail exit, m/s.
    pub out_of_rail_velocity_mps: Option<f64>,
    /// Stability margin at rail exit (rail-exit Mach), calibers.
    pub out_of_rail_stability_margin: Option<f64>,
    /// Static margin at t = 0, calibers.
    pub initial_static_margin: f64,
    /// Static margin at burn-out, calibers.
    pub burnout_static_margin: f64,
    /// Largest speed over the stored points, m/s.
    pub max_speed_mps: f64,
    /// Largest Mach number over the stored points.
    pub max_mach: f64,
    /// Largest dynamic pressure over the stored points, Pa.
    pub max_dynamic_pressure_pa: f64,
    /// Largest acceleration magnitude over the stored points, m/s².
    pub max_acceleration_mps2: f64,
    /// Impact time, s.
    pub impact_time_s: Option<f64>,
    /// Impact point east of the pad, m.
    pub impact_x_m: Option<f64>,
    /// Impact point north of the pad, m.
    pub impact_y_m: Option<f64>,
    /// Speed at impact (magnitude), m/s.
    pub impact_velocity_mps: Option<f64>,
    /// Events in time order.
    pub events: Vec<EventRecord>,
    /// How the flight ended (`impact`, `apogee`, `max_time`, `stuck_on_rail`). Not one of
    /// the contract's summary keys, so it is not serialized with them; callers report it.
    #[serde(skip)]
    pub termination: Termination,
}

/// Derived quantities at one stored point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// East position of the CDM, m.
    pub x: f64,
    /// North position, m.
    pub y: f64,
    /// Height above sea level, m.
    pub z: f64,
    /// Height above the launch elevation, m.
    pub altitude_agl: f64,
    /// Inertial velocity, m/s.
    pub vx: f64,
    /// North velocity, m/s.
    pub vy: f64,
    /// Vertical velocity, m/s.
    pub vz: f64,
    /// Inertial acceleration, m/s².
    pub ax: f64,
    /// North acceleration, m/s².
    pub ay: f64,
    /// Vertical acceleration, m/s².
    pub az: f64,
    /// Quaternion `e0..e3`.
    pub e: [f64; 4],
    /// Body angular rates `ω1, ω2, ω3`, rad/s.
    pub omega: [f64; 3],
    /// Body angular accelerations, rad/s².
    pub omega_dot: [f64; 3],
    /// Speed `‖v‖`, m/s.
    pub speed: f64,
    /// Free-stream speed `‖w − v‖`, m/s.
    pub free_stream_speed: f64,
    /// Mach number.
    pub mach: f64,
    /// Dynamic pressure `½ρ‖w − v‖²`, Pa.
    pub dynamic_pressure: f64,
    /// Total angle of attack, degrees.
    pub angle_of_attack_deg: f64,
    /// Flight-path angle, degrees.
    pub path_angle_deg: f64,
    /// Attitude (rocket-axis elevation) angle, degrees.
    pub attitude_angle_deg: f64,
    /// 3-1-3 Euler angles (precession, nutation, spin), degrees.
    pub euler_deg: [f64; 3],
    /// Stability margin at the point's Mach, calibers.
    pub stability_margin: f64,
    /// Aerodynamic force `(R1, R2, R3)`, N.
    pub force: [f64; 3],
    /// Aerodynamic moment `(M1, M2, M3)`, N·m.
    pub moment: [f64; 3],
    /// Net thrust, N.
    pub net_thrust: f64,
    /// Total mass, kg (dry mass under canopy).
    pub mass: f64,
    /// Inertia `(I11, I22, I33)` about the centre of dry mass at the point's time, kg·m²
    /// (RocketPy's `Rocket.I_11`, `I_22`, `I_33`).
    pub inertia: [f64; 3],
    /// Air pressure at the point's height, Pa.
    pub pressure: f64,
    /// Air density, kg/m³.
    pub density: f64,
    /// Dynamic viscosity of the air, Pa·s.
    pub dynamic_viscosity: f64,
    /// Velocity in body axes `Kᵀ v`, m/s.
    pub velocity_body: [f64; 3],
    /// Acceleration in body axes `Kᵀ a`, m/s².
    pub acceleration_body: [f64; 3],
    /// Free-stream velocity `w − v` in body axes, m/s (RocketPy's
    /// `stream_velocity_body_frame`).
    pub stream_body: [f64; 3],
    /// Unit vector of the rocket's axis in the launch frame (RocketPy's `attitude_vector_*`).
    pub axis: [f64; 3],
}

/// Derived quantities of one point; rail points report the loads of the free-flight
/// equations `free` at their state (RocketPy's `udot_rail1(post_processing=True)`).
fn sample<A: AtmosphereModel, V: VehicleModel + StabilityModel>(
    eq: &Equations<'_, A, V>,
    elevation: f64,
    point: &SolutionPoint,
    free: &PhaseKind,
    cursors: &mut Cursors,
) -> Sample {
    let atm = eq.atmosphere();
    let veh = eq.vehicle();
    let (kind, configuration) = (&point.phase, &point.configuration);
    let (t, u) = (point.t, &point.state);
    let d = evaluate(eq, kind, configuration, t, u, cursors);
    let (force, moment, net_thrust) = match (kind, free) {
        (PhaseKind::Rail, PhaseKind::PointMass { .. }) => {
            let f = evaluate(eq, free, configuration, t, u, cursors);
            (f.force, f.moment, f.net_thrust)
        }
        (PhaseKind::Rail, _) => eq.rail_loads(t, u, configuration, cursors),
        _ => (d.force, d.moment, d.net_thrust),
    };
    let z = u[2];
    let v = [u[3], u[4], u[5]];
    let wind = atm.wind(z);
    let free = [wind[0] - v[0], wind[1] - v[1], -v[2]];
    let free_speed = norm(free);
    let mach = free_speed / atm.speed_of_sound(z);
    let k = rotation([u[6], u[7], u[8], u[9]]);
    let axis = [k[0][2], k[1][2], k[2][2]];
    let aoa = if free_speed < 1e-6 {
        0.0
    } else {
        let c = -(axis[0] * free[0] + axis[1] * free[1] + axis[2] * free[2]) / free_speed;
        c.clamp(-1.0, 1.0).acos().to_degrees()
    };
    let (e0, e1, e2, e3) = (u[6], u[7], u[8], u[9]);
    let a1 = e3.atan2(e0);
    let a2 = (-e2).atan2(-e1);
    let properties = veh.mass(
        t,
        MassFlowLaw::ThrustOverExhaustVelocity,
        &mut [Cursor::default(); 2],
    );
    let mass = match kind {
        PhaseKind::Parachute(_) => eq.dry_mass(),
        _ => properties.total_mass,
    };
    let body = |w: [f64; 3]| mat_t_vec(&k, w);
    let a = [d.u_dot[3], d.u_dot[4], d.u_dot[5]];
    Sample {
        t,
        x: u[0],
        y: u[1],
        z,
        altitude_agl: z - elevation,
        vx: v[0],
        vy: v[1],
        vz: v[2],
        ax: d.u_dot[3],
        ay: d.u_dot[4],
        az: d.u_dot[5],
        e: [e0, e1, e2, e3],
        omega: [u[10], u[11], u[12]],
        omega_dot: [d.u_dot[10], d.u_dot[11], d.u_dot[12]],
        speed: norm(v),
        free_stream_speed: free_speed,
        mach,
        dynamic_pressure: 0.5 * atm.density(z) * free_speed * free_speed,
        angle_of_attack_deg: aoa,
        path_angle_deg: v[2].atan2(v[0].hypot(v[1])).to_degrees(),
        attitude_angle_deg: axis[2].atan2(axis[0].hypot(axis[1])).to_degrees(),
        euler_deg: [
            (a1 + a2).to_degrees(),
            (2.0 * (-(e1 * e1 + e2 * e2).sqrt()).asin()).to_degrees(),
            (a1 - a2).to_degrees(),
        ],
        stability_margin: veh.stability_margin(mach, t),
        force,
        moment,
        net_thrust,
        mass,
        inertia: [
            properties.inertia[0],
            properties.inertia[1],
            properties.inertia[2],
        ],
        pressure: atm.pressure(z),
        density: atm.density(z),
        dynamic_viscosity: atm.dynamic_viscosity(z),
        velocity_body: body(v),
        acceleration_body: body(a),
        stream_body: body(free),
        axis,
    }
}

impl Flight {
    /// Derived quantities at every stored point (docs/physics.md §11).
    #[must_use]
    pub fn samples<A: AtmosphereModel, V: VehicleModel + StabilityModel>(
        &self,
        atmosphere: &A,
        vehicle: &V,
    ) -> Vec<Sample> {
        let eq = Equations::new(atmosphere, vehicle, self.equations);
        let mut cursors = Cursors::default();
        // The free flight's equations: those of the first point flown with them.
        let free = self
            .points
            .iter()
            .map(|p| p.phase)
            .find(|k| matches!(k, PhaseKind::SixDof | PhaseKind::PointMass { .. }))
            .unwrap_or(PhaseKind::SixDof);
        self.points
            .iter()
            .map(|p| sample(&eq, self.elevation, p, &free, &mut cursors))
            .collect()
    }

    /// The flight summary of the mission contract.
    #[must_use]
    pub fn summary<A: AtmosphereModel, V: VehicleModel + StabilityModel>(
        &self,
        atmosphere: &A,
        vehicle: &V,
    ) -> Summary {
        let static_margins = vehicle.setup().static_margins;
        let mut max_speed: f64 = 0.0;
        let mut max_mach: f64 = 0.0;
        let mut max_q: f64 = 0.0;
        // The points follow the trajectory: each height search starts where the last ended.
        let mut cursor = Cursor::default();
        for p in &self.points {
            let u = &p.state;
            let z = u[2];
            let v = [u[3], u[4], u[5]];
            let wind = atmosphere.wind(z);
            let free = norm([wind[0] - v[0], wind[1] - v[1], -v[2]]);
            let air = atmosphere.air_near(z, &mut cursor);
            max_speed = max_speed.max(norm(v));
            max_mach = max_mach.max(free / air.speed_of_sound);
            max_q = max_q.max(0.5 * air.density * free * free);
        }
        let elevation = self.elevation;
        let (apogee_t, apogee_y) = match self.apogee {
            Some((t, y)) => (Some(t), Some(y)),
            None => (None, None),
        };
        let rail = self.rail_exit.map(|(t, u)| {
            let wind = atmosphere.wind(u[2]);
            let free = norm([wind[0] - u[3], wind[1] - u[4], -u[5]]);
            let mach = free / atmosphere.speed_of_sound(u[2]);
            (
                t,
                norm([u[3], u[4], u[5]]),
                vehicle.stability_margin(mach, t),
            )
        });

        let mut events = Vec::new();
        if let Some((t, _, _)) = rail {
            events.push(EventRecord {
                name: "rail_exit".into(),
                time_s: t,
            });
        }
        if self.burn_out <= self.t_final {
            events.push(EventRecord {
                name: "burnout".into(),
                time_s: self.burn_out,
            });
        }
        if let Some(t) = apogee_t {
            events.push(EventRecord {
                name: "apogee".into(),
                time_s: t,
            });
        }
        for p in &self.parachute_events {
            events.push(EventRecord {
                name: format!("parachute:{}", p.name),
                time_s: p.trigger_time,
            });
        }
        if let Some(t) = self.tumble {
            events.push(EventRecord {
                name: "tumble".into(),
                time_s: t,
            });
        }
        if let Some((t, _)) = self.impact {
            events.push(EventRecord {
                name: "impact".into(),
                time_s: t,
            });
        }
        events.sort_by(|a, b| a.time_s.total_cmp(&b.time_s));

        Summary {
            apogee_agl_m: apogee_y.map(|u: State| u[2] - elevation),
            apogee_asl_m: apogee_y.map(|u: State| u[2]),
            apogee_time_s: apogee_t,
            apogee_x_m: apogee_y.map(|u: State| u[0]),
            apogee_y_m: apogee_y.map(|u: State| u[1]),
            out_of_rail_time_s: rail.map(|r| r.0),
            out_of_rail_velocity_mps: rail.map(|r| r.1),
            out_of_rail_stability_margin: rail.map(|r| r.2),
            initial_static_margin: static_margins[0],
            burnout_static_margin: static_margins[1],
            max_speed_mps: max_speed,
            max_mach,
            max_dynamic_pressure_pa: max_q,
            max_acceleration_mps2: self.max_acceleration,
            impact_time_s: self.impact.map(|(t, _)| t),
            impact_x_m: self.impact.map(|(_, u)| u[0]),
            impact_y_m: self.impact.map(|(_, u)| u[1]),
            impact_velocity_mps: self.impact.map(|(_, u)| norm([u[3], u[4], u[5]])),
            events,
            termination: self.termination,
        }
    }
}

/// Decimals a person reads for a figure of `unit`: 0.1 m, 0.01 s, 0.1 m/s, 0.01 calibre, 1 Pa
/// (full precision stays in the JSON summary).
fn decimals(unit: &str) -> usize {
    match unit {
        "m" | "m/s" | "m/s²" => 1,
        "Pa" => 0,
        _ => 2,
    }
}

/// Writes one aligned `label  value unit` row; `None` prints as `—`.
fn row(
    f: &mut std::fmt::Formatter<'_>,
    label: &str,
    value: Option<f64>,
    unit: &str,
) -> std::fmt::Result {
    let gap = if unit.is_empty() { "" } else { " " };
    match value {
        Some(v) => writeln!(
            f,
            "  {label:<32}{v:>12.prec$}{gap}{unit}",
            prec = decimals(unit)
        ),
        None => writeln!(f, "  {label:<32}{:>12}{gap}{unit}", "—"),
    }
}

impl std::fmt::Display for Summary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "Flight summary (termination: {:?})", self.termination)?;
        row(f, "apogee AGL", self.apogee_agl_m, "m")?;
        row(f, "apogee ASL", self.apogee_asl_m, "m")?;
        row(f, "apogee time", self.apogee_time_s, "s")?;
        row(f, "apogee x (east)", self.apogee_x_m, "m")?;
        row(f, "apogee y (north)", self.apogee_y_m, "m")?;
        row(f, "out-of-rail time", self.out_of_rail_time_s, "s")?;
        row(
            f,
            "out-of-rail velocity",
            self.out_of_rail_velocity_mps,
            "m/s",
        )?;
        row(
            f,
            "out-of-rail stability margin",
            self.out_of_rail_stability_margin,
            "cal",
        )?;
        row(
            f,
            "initial static margin",
            Some(self.initial_static_margin),
            "cal",
        )?;
        row(
            f,
            "burn-out static margin",
            Some(self.burnout_static_margin),
            "cal",
        )?;
        row(f, "max speed", Some(self.max_speed_mps), "m/s")?;
        row(f, "max Mach", Some(self.max_mach), "")?;
        row(
            f,
            "max dynamic pressure",
            Some(self.max_dynamic_pressure_pa),
            "Pa",
        )?;
        row(
            f,
            "max acceleration",
            Some(self.max_acceleration_mps2),
            "m/s²",
        )?;
        row(f, "impact time", self.impact_time_s, "s")?;
        row(f, "impact x (east)", self.impact_x_m, "m")?;
        row(f, "impact y (north)", self.impact_y_m, "m")?;
        row(f, "impact velocity", self.impact_velocity_mps, "m/s")?;
        writeln!(f, "Events")?;
        // The label column widens for long event names (parachute names are the user's).
        let width = self
            .events
            .iter()
            .map(|e| e.name.chars().count() + 2)
            .max()
            .unwrap_or(0)
            .max(32);
        for e in &self.events {
            writeln!(f, "  {:<width$}{:>12.2} s", e.name, e.time_s)?;
        }
        Ok(())
    }
}
