//! The rocket: airframe, motor, surfaces, parachutes and rail buttons, with the quantities the
//! equations of motion evaluate per step (RocketPy `Rocket`, docs/physics.md §2.5, §5, §7).

use std::f64::consts::PI;

use karman_math::{Cursor, Extrapolation, Interpolation, PhysicalConstants, Table1};

use crate::air_brakes::AirBrakes;
use crate::error::{AirframeError, finite, non_negative, positive};
use crate::mass::MassModel;
use crate::motor::{INERTIA_NAMES, MotorProperties};
use crate::recovery::{Parachute, RailButtons};
use crate::surfaces::{Geometry, Surface, SurfaceInput};
use karman_model::{MassSample, OffAxis, TriggerKind};

/// Orientation of the rocket's user axis (RocketPy `coordinate_system_orientation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CoordinateSystem {
    /// Positions grow toward the nose (csys_r = +1, the default).
    #[default]
    TailToNose,
    /// Positions grow toward the tail (csys_r = −1).
    NoseToTail,
}

impl CoordinateSystem {
    /// csys_r: +1 for tail-to-nose, −1 for nose-to-tail.
    #[must_use]
    pub fn sign(self) -> f64 {
        match self {
            CoordinateSystem::TailToNose => 1.0,
            CoordinateSystem::NoseToTail => -1.0,
        }
    }
}

/// Expands an inertia given as 3 `(I11, I22, I33)` or 6 `(…, I12, I13, I23)` components
/// (RocketPy's convention: products of inertia carry their minus sign).
///
/// # Errors
/// [`AirframeError::InertiaComponents`] for another count; [`AirframeError::NotFinite`].
pub fn inertia_components(component: &str, values: &[f64]) -> Result<[f64; 6], AirframeError> {
    let mut out = [0.0; 6];
    match values.len() {
        3 | 6 => out[..values.len()].copy_from_slice(values),
        got => {
            return Err(AirframeError::InertiaComponents {
                component: component.to_owned(),
                got,
            });
        }
    }
    for (v, name) in out.iter().zip(INERTIA_NAMES) {
        finite(component, name, *v)?;
    }
    Ok(out)
}

/// Everything needed to build a [`Rocket`] besides its motor.
#[derive(Debug, Clone, PartialEq)]
pub struct RocketInputs {
    /// Largest outer radius r, the reference radius of drag and margins (m).
    pub radius: f64,
    /// Mass without motor (kg).
    pub mass: f64,
    /// Inertia without motor about its own CM, `(I11, I22, I33, I12, I13, I23)` (kg·m²).
    pub inertia: [f64; 6],
    /// CM without motor, user coordinates (m).
    pub center_of_mass_without_motor: f64,
    /// Orientation of the user axis.
    pub coordinate_system: CoordinateSystem,
    /// Drag coefficient vs Mach with the motor off.
    pub power_off_drag: Table1,
    /// Drag coefficient vs Mach with the motor burning.
    pub power_on_drag: Table1,
    /// Position of the motor's coordinate origin, user coordinates (m).
    pub motor_position: f64,
    /// Aerodynamic surfaces, in the order the aerodynamic loads are summed.
    pub surfaces: Vec<SurfaceInput>,
    /// Parachutes, in the user's order (see [`Parachute::new`]).
    pub parachutes: Vec<Parachute>,
    /// Rail buttons, if any.
    pub rail_buttons: Option<RailButtons>,
    /// Offsets of the centre of mass, the centre of pressure and the thrust from the axis
    /// (all zero for an aligned rocket).
    pub eccentricities: Eccentricities,
}

/// A rocket's misalignments, RocketPy 1.13's `Rocket.add_cm_eccentricity`,
/// `add_cp_eccentricity` and `add_thrust_eccentricity` (docs/physics.md §7.8), each `(x, y)` in
/// metres, `x` along the user axes' x (body x times the coordinate-system sign for the centre of
/// mass, as RocketPy places surfaces), `y` along body y:
///
/// - `center_of_mass`: the centre of dry mass off the geometric axis by `ε`: every surface's
///   centre of pressure then sits at `(−ε_x csys, −ε_y)` from it (its local stream sees the
///   rates about the offset centre), and the aerodynamic forces and the thrust act at `−ε`;
/// - `center_of_pressure`: the aerodynamic forces' line of action at `(x, y)` from the axis;
/// - `thrust`: the thrust's line of action at `(x, y)` from the axis.
///
/// RocketPy's `add_cm_eccentricity` sets the other two to `−ε`; karman adds them (the centre
/// of pressure at `e_cp − ε`, the thrust at `e_T − ε`), which is the same when only one is
/// given, and mission checks refuse the centre of mass together with either of the others.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Eccentricities {
    /// Centre-of-mass eccentricity `(x, y)`, m.
    pub center_of_mass: [f64; 2],
    /// Centre-of-pressure eccentricity `(x, y)`, m.
    pub center_of_pressure: [f64; 2],
    /// Thrust eccentricity `(x, y)`, m.
    pub thrust: [f64; 2],
}

impl Eccentricities {
    /// The lines of action the equations of motion use ([`OffAxis`]).
    #[must_use]
    pub fn off_axis(&self) -> OffAxis {
        let [ex, ey] = self.center_of_mass;
        let [cx, cy] = self.center_of_pressure;
        let [tx, ty] = self.thrust;
        OffAxis {
            cp: [cx - ex, cy - ey],
            thrust: [tx - ex, ty - ey],
        }
    }
}

/// Number of samples of RocketPy's static-margin spline on `[0, t_b1]`.
const STATIC_MARGIN_SAMPLES: usize = 200;

/// A complete rocket. Per-step methods are `#[inline]` and allocation-free.
#[derive(Debug, Clone, PartialEq)]
pub struct Rocket {
    radius: f64,
    csys: f64,
    coordinate_system: CoordinateSystem,
    motor_position: f64,
    rocket_center_of_mass: f64,
    power_off_drag: Table1,
    power_on_drag: Table1,
    mass: MassModel,
    surfaces: Vec<Surface>,
    /// `(r_s/r)²` per surface (area correction of the rocket CP, docs/physics.md §7.7).
    surface_weights: Vec<f64>,
    /// False when ΣCNα at Mach 0 vanishes: the CP is then 0, as in RocketPy.
    cp_defined: bool,
    parachutes: Vec<Parachute>,
    rail_buttons: Option<RailButtons>,
    nozzle_position: f64,
    nozzle_to_cdm: f64,
    nozzle_gyration: [f64; 3],
    static_margin: Option<Table1>,
    warnings: Vec<String>,
    air_brakes: Option<AirBrakes>,
    /// The forces' lines of action off the axis ([`Eccentricities::off_axis`]).
    off_axis: OffAxis,
}

/// How far a fin root may run past the nozzle exit before it is worth a warning, as a
/// fraction of the root chord: real rockets' fins end a few millimetres behind a nozzle that
/// sits inside a retainer (Halcyon's, 4 mm), and a mission states the nozzle, not the tube's
/// end. A fraction, so that the rule holds in any unit system.
const FIN_OVERHANG_ALLOWED: f64 = 0.1;

impl Rocket {
    /// The forces' lines of action off the axis (zero for an aligned rocket).
    #[must_use]
    pub fn off_axis(&self) -> OffAxis {
        self.off_axis
    }

    /// Builds the rocket with `motor` at `inputs.motor_position`, inputs in SI.
    ///
    /// # Errors
    /// [`AirframeError`] for impossible inputs (non-positive radius or mass, negative
    /// inertia, impossible surface geometry, bad motor data). Questionable but
    /// flyable inputs (no surfaces, a surface outside the body) are reported by
    /// [`Rocket::warnings`].
    pub fn new(inputs: RocketInputs, motor: MotorProperties) -> Result<Rocket, AirframeError> {
        Self::with_constants(inputs, motor, &PhysicalConstants::SI)
    }

    /// [`Rocket::new`] for inputs in the unit system of `constants` (which holds the time
    /// step of the numerical second derivative of the CM offset).
    ///
    /// # Errors
    /// As [`Rocket::new`].
    pub fn with_constants(
        inputs: RocketInputs,
        motor: MotorProperties,
        constants: &PhysicalConstants,
    ) -> Result<Rocket, AirframeError> {
        const C: &str = "rocket";
        let radius = positive(C, "radius", inputs.radius)?;
        let rocket_mass = positive(C, "mass", inputs.mass)?;
        for (v, name) in inputs.inertia.iter().zip(INERTIA_NAMES) {
            finite(C, name, *v)?;
        }
        for v in &inputs.inertia[..3] {
            non_negative(C, "inertia", *v)?;
        }
        let rocket_com = finite(
            C,
            "center_of_mass_without_motor",
            inputs.center_of_mass_without_motor,
        )?;
        let motor_position = finite(C, "motor_position", inputs.motor_position)?;
        motor.validate()?;
        let csys = inputs.coordinate_system.sign();
        let mut warnings = Vec::new();
        let mass = MassModel::new(
            csys,
            rocket_mass,
            rocket_com,
            inputs.inertia,
            motor_position,
            motor,
            constants.time_difference_step,
            &mut warnings,
        )?;
        let cdm = mass.cdm;

        let eccentricities = inputs.eccentricities;
        for (name, pair) in [
            ("center_of_mass_eccentricity", eccentricities.center_of_mass),
            (
                "center_of_pressure_eccentricity",
                eccentricities.center_of_pressure,
            ),
            ("thrust_eccentricity", eccentricities.thrust),
        ] {
            for v in pair {
                finite(C, name, v)?;
            }
        }
        let mut surfaces = Vec::with_capacity(inputs.surfaces.len());
        for input in &inputs.surfaces {
            let (mut surface, w) = Surface::build(input, radius, csys, cdm, constants)?;
            let [ex, ey] = eccentricities.center_of_mass;
            if ex != 0.0 || ey != 0.0 {
                // RocketPy's `surfaces_cp_to_cdm`: the surface's origin `(0 − ε_x) csys`,
                // `0 − ε_y` from the offset centre.
                surface.cp_body[0] = -ex * csys;
                surface.cp_body[1] = -ey;
            }
            warnings.extend(w);
            surfaces.push(surface);
        }
        // A pod surface counts once per pod.
        let surface_weights: Vec<f64> = surfaces
            .iter()
            .map(|s| match s.pod {
                None => (s.radius / radius).powi(2),
                Some(pod) => (s.radius / radius).powi(2) * pod.factor(),
            })
            .collect();
        let total0: f64 = surfaces
            .iter()
            .zip(&surface_weights)
            .map(|(s, k)| k * s.cn_alpha(0.0))
            .sum();
        let cp_defined = total0.abs() > 1e-12;
        if surfaces.is_empty() {
            warnings.push(
                "rocket: no aerodynamic surfaces; there is no restoring moment and the centre \
                 of pressure is taken at the user origin (RocketPy's convention)"
                    .to_owned(),
            );
        } else if !cp_defined {
            warnings.push(
                "rocket: the surfaces' normal-force slopes cancel at Mach 0; the centre of \
                 pressure is taken at the user origin (RocketPy's convention)"
                    .to_owned(),
            );
        }

        let parachutes = inputs.parachutes;

        let m = mass.motor();
        let nozzle_position = mass.motor_to_user(m.nozzle_position);
        let nozzle_to_cdm = -csys * (nozzle_position - cdm);
        let s33 = 0.5 * m.nozzle_radius * m.nozzle_radius;
        let s11 = 0.5 * s33 + 0.25 * nozzle_to_cdm * nozzle_to_cdm;
        let burn_out = m.burn_out;

        let mut rocket = Rocket {
            radius,
            csys,
            coordinate_system: inputs.coordinate_system,
            motor_position,
            rocket_center_of_mass: rocket_com,
            power_off_drag: inputs.power_off_drag,
            power_on_drag: inputs.power_on_drag,
            mass,
            surfaces,
            surface_weights,
            cp_defined,
            parachutes,
            rail_buttons: inputs.rail_buttons,
            nozzle_position,
            nozzle_to_cdm,
            nozzle_gyration: [s11, s11, s33],
            static_margin: None,
            warnings,
            air_brakes: None,
            off_axis: eccentricities.off_axis(),
        };
        rocket.check_layout();
        if burn_out > 0.0 {
            // The CP at Mach 0 does not depend on time: located once for all the samples.
            let cp = rocket.cp_position(0.0);
            let table = Table1::sample(
                |t| rocket.margin_from(t, cp),
                0.0,
                burn_out,
                STATIC_MARGIN_SAMPLES,
                Interpolation::Spline,
                Extrapolation::Constant,
            )
            .map_err(|source| AirframeError::Table {
                component: C.to_owned(),
                quantity: "static margin",
                error: source,
            })?;
            rocket.static_margin = Some(table);
        }
        Ok(rocket)
    }

    /// Warns about surfaces outside the body, overhanging its tail or wider than the rocket
    /// radius.
    fn check_layout(&mut self) {
        let csys = self.csys;
        let cdm = self.mass.cdm;
        let body = |z: f64| csys * (z - cdm);
        let tip = self
            .surfaces
            .iter()
            .filter(|s| matches!(s.geometry, Geometry::Nose { .. }) && s.pod.is_none())
            .map(|s| body(s.position))
            .fold(None, |acc: Option<f64>, z| {
                Some(acc.map_or(z, |a| a.max(z)))
            });
        let nozzle = body(self.nozzle_position);
        // Rounding allowance on positions, relative to the rocket's size.
        let tol = 1e-9 * self.radius;
        for s in &self.surfaces {
            let front = body(s.position);
            if let Some(tip) = tip {
                if front > tip + tol {
                    self.warnings.push(format!(
                        "{}: lies {:.4} m ahead of the nose tip, outside the body",
                        s.name,
                        front - tip
                    ));
                }
            }
            if front < nozzle - tol {
                self.warnings.push(format!(
                    "{}: starts {:.4} m aft of the nozzle exit, outside the body",
                    s.name,
                    nozzle - front
                ));
            } else if let Geometry::Fins { root_chord, .. } = s.geometry {
                // The root is attached to the body: a root running past the tail (the nozzle
                // exit, the aftmost point of the airframe) is a fin hanging in the air.
                let overhang = nozzle - (front - root_chord);
                if overhang > FIN_OVERHANG_ALLOWED * root_chord {
                    self.warnings.push(format!(
                        "{}: the fin root runs {overhang:.4} m past the tail (the nozzle exit), \
                         where there is no body to hold it",
                        s.name
                    ));
                }
            }
            let widest = match s.geometry {
                Geometry::Fins { body_radius, .. } | Geometry::TubeFins { body_radius, .. } => {
                    body_radius
                }
                ref g => g.max_radius(),
            };
            if widest > self.radius * (1.0 + 1e-9) {
                self.warnings.push(format!(
                    "{}: radius {widest} m exceeds the rocket radius {} m (the largest outer \
                     radius)",
                    s.name, self.radius
                ));
            }
        }
    }

    /// Reference radius r (m).
    #[inline]
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Reference area π r² (m²).
    #[inline]
    #[must_use]
    pub fn reference_area(&self) -> f64 {
        PI * self.radius * self.radius
    }

    /// csys_r: +1 tail-to-nose, −1 nose-to-tail.
    #[inline]
    #[must_use]
    pub fn csys(&self) -> f64 {
        self.csys
    }

    /// The user axis orientation.
    #[must_use]
    pub fn coordinate_system(&self) -> CoordinateSystem {
        self.coordinate_system
    }

    /// Motor origin in user coordinates (m).
    #[must_use]
    pub fn motor_position(&self) -> f64 {
        self.motor_position
    }

    /// The motor data the rocket was built with.
    #[must_use]
    pub fn motor(&self) -> &MotorProperties {
        self.mass.motor()
    }

    /// Mass without motor (kg).
    #[must_use]
    pub fn rocket_mass(&self) -> f64 {
        self.mass.rocket_mass()
    }

    /// CM without motor, user coordinates (m).
    #[must_use]
    pub fn rocket_center_of_mass(&self) -> f64 {
        self.rocket_center_of_mass
    }

    /// Total mass m(t) (kg).
    #[inline]
    #[must_use]
    pub fn total_mass(&self, t: f64) -> f64 {
        self.mass.total_mass(t)
    }

    /// [`Rocket::total_mass`] with the time located from `cursor` (on the propellant tables'
    /// times; updated): the same value, found faster when successive times are close.
    #[inline]
    #[must_use]
    pub fn total_mass_near(&self, t: f64, cursor: &mut Cursor) -> f64 {
        self.mass.total_mass_near(t, cursor)
    }

    /// Signed total mass flow rate ṁ(t) = −T(t)/v̄_e (kg/s), docs/physics.md §6.2.
    #[inline]
    #[must_use]
    pub fn mass_flow_rate(&self, t: f64) -> f64 {
        self.mass.mass_flow_rate(t)
    }

    /// m̈(t) (kg/s²): segment slope of ṁ (RocketPy complex step; the left segment at a node).
    #[inline]
    #[must_use]
    pub fn mass_flow_rate_derivative(&self, t: f64) -> f64 {
        self.mass.mass_flow_rate_derivative(t)
    }

    /// c(t) = −csys (z_pc − z_CDM) m_p/m (m): RocketPy's CM→CDM offset, docs/physics.md §5.4.
    #[inline]
    #[must_use]
    pub fn com_to_cdm(&self, t: f64) -> f64 {
        self.mass.com_to_cdm(t)
    }

    /// ċ(t) (m/s), RocketPy's complex-step derivative of c.
    #[inline]
    #[must_use]
    pub fn com_to_cdm_rate(&self, t: f64) -> f64 {
        self.mass.com_to_cdm_rate(t)
    }

    /// c̈(t) (m/s²): RocketPy's second derivative of c — 0 for the piecewise-linear table of
    /// a solid motor (docs/physics.md §5.4), a central difference with step
    /// 1e-6 for the pointwise formula of mixed grids (generic motors).
    #[inline]
    #[must_use]
    pub fn com_to_cdm_accel(&self, t: f64) -> f64 {
        self.mass.com_to_cdm_accel(t)
    }

    /// Inertia about the CDM in body axes, `(I11, I22, I33, I12, I13, I23)` (kg·m²).
    #[inline]
    #[must_use]
    pub fn inertia(&self, t: f64) -> [f64; 6] {
        self.mass.inertia(t)
    }

    /// İ(t), same layout (kg·m²/s).
    #[inline]
    #[must_use]
    pub fn inertia_rate(&self, t: f64) -> [f64; 6] {
        self.mass.inertia_rate(t)
    }

    /// Every time-dependent mass quantity at `t` at once (what the equations of motion
    /// evaluate per step), each equal to the method of the same name (the mass flow is
    /// `−T/v̄_e`, [`karman_model::MassFlowLaw::ThrustOverExhaustVelocity`]); the tables that
    /// share a time grid are searched once.
    #[inline]
    #[must_use]
    pub fn mass_properties(&self, t: f64) -> MassSample {
        self.mass.properties_near(t, &mut [Cursor::default(); 2])
    }

    /// [`Rocket::mass_properties`] with the time located from `cursors` (on the thrust
    /// curve's and on the propellant tables' times; updated): the same values, found faster
    /// when successive times are close, as along an integration.
    #[inline]
    #[must_use]
    pub fn mass_properties_near(&self, t: f64, cursors: &mut [Cursor; 2]) -> MassSample {
        self.mass.properties_near(t, cursors)
    }

    /// The derivative of the total mass `dm/dt` (kg/s) and its rate (kg/s²) at `t`, with the
    /// time located from `cursor` (on the propellant tables' times; updated): the motor's
    /// mass-flow table when it has one, else the slopes of its propellant-mass table.
    #[inline]
    #[must_use]
    pub fn mass_rate_near(&self, t: f64, cursor: &mut Cursor) -> (f64, f64) {
        self.mass.mass_rate_near(t, cursor)
    }

    /// Dry inertia about the CDM (rocket + unloaded motor), same layout (kg·m²).
    #[must_use]
    pub fn dry_inertia(&self) -> [f64; 6] {
        self.mass.dry_inertia
    }

    /// Dry mass: rocket + motor dry mass (kg).
    #[inline]
    #[must_use]
    pub fn dry_mass(&self) -> f64 {
        self.mass.dry_mass
    }

    /// Centre of dry mass z_CDM, user coordinates (m).
    #[inline]
    #[must_use]
    pub fn center_of_dry_mass(&self) -> f64 {
        self.mass.cdm
    }

    /// Nozzle exit, user coordinates (m).
    #[must_use]
    pub fn nozzle_position(&self) -> f64 {
        self.nozzle_position
    }

    /// d_n = −csys (z_noz − z_CDM) (m), docs/physics.md §5.6.
    #[inline]
    #[must_use]
    pub fn nozzle_to_cdm(&self) -> f64 {
        self.nozzle_to_cdm
    }

    /// Nozzle gyration tensor diagonal `(S11, S22, S33)` (m²), docs/physics.md §5.6 **\[RP\]**.
    #[inline]
    #[must_use]
    pub fn nozzle_gyration(&self) -> [f64; 3] {
        self.nozzle_gyration
    }

    /// Propellant CM in user coordinates z_pc(t) (m).
    #[must_use]
    pub fn propellant_position(&self, t: f64) -> f64 {
        self.mass.propellant_position(t)
    }

    /// Raw thrust T(t) (N).
    #[inline]
    #[must_use]
    pub fn thrust(&self, t: f64) -> f64 {
        self.mass.motor().thrust.eval(t)
    }

    /// Net thrust with the nozzle-pressure correction, clamped at 0 (docs/physics.md §6.3).
    #[inline]
    #[must_use]
    pub fn net_thrust(&self, t: f64, ambient_pressure: f64) -> f64 {
        self.net_thrust_near(t, ambient_pressure, &mut Cursor::default())
    }

    /// [`Rocket::net_thrust`] with the time located on the thrust curve from `cursor`
    /// (updated; the first cursor of [`Rocket::mass_properties_near`] serves): the same value.
    #[inline]
    #[must_use]
    pub fn net_thrust_near(&self, t: f64, ambient_pressure: f64, cursor: &mut Cursor) -> f64 {
        let m = self.mass.motor();
        let mut thrust = m.thrust.eval_with(t, cursor);
        if let Some(p_ref) = m.reference_pressure {
            thrust += (p_ref - ambient_pressure) * PI * m.nozzle_radius * m.nozzle_radius;
        }
        thrust.max(0.0)
    }

    /// Burn start t_b0 (s).
    #[inline]
    #[must_use]
    pub fn burn_start(&self) -> f64 {
        self.mass.motor().burn_start
    }

    /// Burn-out t_b1 (s).
    #[inline]
    #[must_use]
    pub fn burn_out(&self) -> f64 {
        self.mass.motor().burn_out
    }

    /// Drag coefficient at `mach`, power-on or power-off curve (docs/physics.md §7.1).
    #[inline]
    #[must_use]
    pub fn drag_coefficient(&self, power_on: bool, mach: f64) -> f64 {
        self.drag_coefficient_near(power_on, mach, &mut Cursor::default())
    }

    /// [`Rocket::drag_coefficient`] with the Mach number located from `cursor` (updated):
    /// the same value, found faster when successive Mach numbers are close.
    #[inline]
    #[must_use]
    pub fn drag_coefficient_near(&self, power_on: bool, mach: f64, cursor: &mut Cursor) -> f64 {
        if power_on {
            self.power_on_drag.eval_with(mach, cursor)
        } else {
            self.power_off_drag.eval_with(mach, cursor)
        }
    }

    /// The aerodynamic surfaces in insertion order.
    #[inline]
    #[must_use]
    pub fn surfaces(&self) -> &[Surface] {
        &self.surfaces
    }

    /// Centre of mass z_CM(t), user coordinates (m).
    #[inline]
    #[must_use]
    pub fn center_of_mass(&self, t: f64) -> f64 {
        self.mass.center_of_mass(t)
    }

    /// Rocket CP at `mach`, user coordinates (m): the `(r_s/r)²·CNα`-weighted mean of the
    /// surface CPs (docs/physics.md §7.7).
    #[inline]
    #[must_use]
    pub fn cp_position(&self, mach: f64) -> f64 {
        if !self.cp_defined {
            return 0.0;
        }
        let (mut num, mut den) = (0.0, 0.0);
        for (s, k) in self.surfaces.iter().zip(&self.surface_weights) {
            let c = k * s.cn_alpha(mach);
            num += c * s.cp_user(self.csys);
            den += c;
        }
        num / den
    }

    /// Sum of the area-corrected slopes `Σ (r_s/r)² CNα_s(Mach)` (per rad, area π r²).
    #[must_use]
    pub fn total_cn_alpha(&self, mach: f64) -> f64 {
        self.surfaces
            .iter()
            .zip(&self.surface_weights)
            .map(|(s, k)| k * s.cn_alpha(mach))
            .sum()
    }

    fn margin_at(&self, t: f64, mach: f64) -> f64 {
        self.margin_from(t, self.cp_position(mach))
    }

    /// Margin (calibres) at time `t` of the CP at `cp` (user coordinates).
    fn margin_from(&self, t: f64, cp: f64) -> f64 {
        self.csys * (self.center_of_mass(t) - cp) / (2.0 * self.radius)
    }

    /// Static margin (calibres) at time `t`: CP at Mach 0; RocketPy's 200-point spline on
    /// `[0, t_b1]` (docs/physics.md §7.7).
    #[must_use]
    pub fn static_margin(&self, t: f64) -> f64 {
        match &self.static_margin {
            Some(table) => table.eval(t),
            None => self.margin_at(t, 0.0),
        }
    }

    /// Stability margin (calibres) at `mach` and time `t` (docs/physics.md §7.7).
    #[inline]
    #[must_use]
    pub fn stability_margin(&self, mach: f64, t: f64) -> f64 {
        self.margin_at(t, mach)
    }

    /// The parachutes in the user's order.
    #[inline]
    #[must_use]
    pub fn parachutes(&self) -> &[Parachute] {
        &self.parachutes
    }

    /// The rocket with the parachute called `name` fired by `trigger` instead (a trigger
    /// written in a host language, such as a Python function); `None` when the rocket has no
    /// parachute of that name.
    #[must_use]
    pub fn with_parachute_trigger(mut self, name: &str, trigger: TriggerKind) -> Option<Self> {
        let parachute = self.parachutes.iter_mut().find(|p| p.name == name)?;
        parachute.trigger = trigger;
        Some(self)
    }

    /// The rocket with `air_brakes` (RocketPy's `add_air_brakes`; docs/physics.md §16).
    #[must_use]
    pub fn with_air_brakes(mut self, air_brakes: AirBrakes) -> Self {
        self.air_brakes = Some(air_brakes);
        self
    }

    /// The air brakes, if any.
    #[inline]
    #[must_use]
    pub fn air_brakes(&self) -> Option<&AirBrakes> {
        self.air_brakes.as_ref()
    }

    /// The rail buttons, if any.
    #[inline]
    #[must_use]
    pub fn rail_buttons(&self) -> Option<RailButtons> {
        self.rail_buttons
    }

    /// Warnings about questionable but flyable inputs.
    #[must_use]
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }
}
