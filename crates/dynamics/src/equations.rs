//! Right-hand sides of the flight phases (docs/physics.md §8): the 1-DOF rail slide (§8.1),
//! RocketPy's variable-mass 6-DOF "standard" equations (§8.2–§8.3, after Ceotto et al. 2021,
//! J. Aerosp. Eng. 34(6), and the RocketPy docs "Equations of Motion v1"), the 3-DOF
//! parachute descent with added mass (§8.4) and, in `point_mass`, RocketPy's 3-DOF
//! point-mass free flight (§8.5, `simulation_mode = "3 DOF"`).
//!
//! Each is a pure function of `(t, u)`, the flight's [`Configuration`] and the immutable
//! [`Equations`] context, and returns the state derivative together with the loads that
//! produced it, so the same code serves the integrator and the post-processing. The caller
//! passes the table cursors ([`Cursors`]) explicitly: they only shorten the searches, the
//! values never depend on them. Nothing here allocates.

use crate::state::{
    Mat3, State, Vec3, Vector, X, Y, add, angular_velocity, cross, derivative, dot, inverse,
    mat_t_vec, norm, position, quaternion, quaternion_rate, rotation, scale, sub, tensor, velocity,
};
use karman_model::{
    Air, AtmosphereModel, BodyFlow, Configuration, Cursor, LocalFlow, MAX_CONTROLS, MassFlowLaw,
    OffAxis, SurfaceModel, VehicleModel,
};

use crate::settings::EquationsForm;

mod point_mass;

/// State derivative and the loads behind it (body axes, about the CDM).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Derivative {
    /// `u̇` (docs/physics.md §3).
    pub u_dot: State,
    /// Aerodynamic force `(R1, R2, R3)` in body axes, N (parachute phase: drag in the
    /// inertial frame, as RocketPy reports it).
    pub force: Vec3,
    /// Aerodynamic moment `(M1, M2, M3)` about the CDM in body axes, N·m.
    pub moment: Vec3,
    /// Net thrust, N.
    pub net_thrust: f64,
}

/// The parachute currently inflated (docs/physics.md §8.4: the newest one replaces the older).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CanopyState {
    /// Drag coefficient times area, m².
    pub cd_s: f64,
    /// Canopy radius, m.
    pub radius: f64,
    /// Canopy height, m.
    pub height: f64,
    /// Added-mass coefficient.
    pub added_mass_coefficient: f64,
}

/// Immutable context of the equations of motion: the models plus constants read once.
#[derive(Debug)]
pub struct Equations<'a, A, V> {
    atmosphere: &'a A,
    vehicle: &'a V,
    earth_rotation: Vec3,
    burn_start: f64,
    burn_out: f64,
    nozzle: Vec3,
    nozzle_gyration: Mat3,
    dry_mass: f64,
    coast: Option<CoastMass>,
    /// The wind when it does not vary with height (read once; no per-height lookups then).
    uniform_wind: Option<[f64; 2]>,
    /// The sign of the lever arms: `+1` for RocketPy's CM→CDM and nozzle→CDM vectors, `−1`
    /// for the CDM→CM and CDM→nozzle vectors of the standard form ([`EquationsForm`]).
    lever_sign: f64,
    /// The mass flow of the form.
    law: MassFlowLaw,
    /// The forces' lines of action off the axis, when there are any (an aligned rocket adds
    /// nothing to its moments, bit for bit).
    off_axis: Option<OffAxis>,
}

/// The table cursors of the models' lookups, kept by the caller between evaluations so
/// that each search starts where the last one ended (heights, Mach numbers and times change
/// little between evaluations). Values never depend on them.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Cursors {
    /// Heights ([`AtmosphereModel::air_near`]).
    height: Cursor,
    /// Mach number ([`VehicleModel::axial_load`]).
    mach: Cursor,
    /// Times ([`VehicleModel::mass`], [`VehicleModel::thrust`]).
    time: [Cursor; 2],
}

/// Mass properties after burn-out, when they no longer change (docs/physics.md §8.2 remarks:
/// `m_p = 0`, `c = ċ = 0`, `İ = 0`): read once instead of at every evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
struct CoastMass {
    mass: f64,
    /// `1/m`, the same number as computed per evaluation.
    inverse_mass: f64,
    com_to_cdm: f64,
    inertia: Mat3,
    inverse_cm_inertia: Mat3,
}

/// Mass properties at one instant as the 6-DOF equations use them (docs/physics.md §8.2).
#[derive(Debug, Clone, Copy, PartialEq)]
struct MassState {
    mass: f64,
    inverse_mass: f64,
    c: f64,
    c_dot: f64,
    c_ddot: f64,
    inertia: Mat3,
    inertia_dot: Mat3,
    inverse_cm_inertia: Mat3,
}

/// Whether a rocket on the rail without thrust, `travelled` metres along it at `speed`, still
/// reaches rail exit (`travel` metres) against gravity alone: its coast `v²/(2 g sin i)` covers
/// the rest (`gravity_along_rail` is `g sin i`; drag would only shorten the coast). The rail
/// equation (docs/physics.md §8.1) clips the acceleration at zero, so after burn-out RocketPy's
/// rocket keeps its speed and creeps off the rail however long that takes; one that this
/// coast cannot carry off would stop and slide back: it is stuck on the rail. The engine
/// (at burn-out, [`crate::Termination::StuckOnRail`]) and the mission's launch check apply
/// this one rule.
#[must_use]
pub fn coasts_off_rail(travelled: f64, speed: f64, travel: f64, gravity_along_rail: f64) -> bool {
    travelled + speed * speed / (2.0 * gravity_along_rail) >= travel
}

/// `I_CM⁻¹` with `I_CM = I − m(|r|² 𝟙 − r rᵀ)`, `r = (0, 0, c)` (docs/physics.md §8.2); NaN when
/// singular, so the integrator reports the failure.
#[inline]
fn inverse_cm_inertia(inertia: &Mat3, mass: f64, c: f64) -> Mat3 {
    let r = [0.0, 0.0, c];
    let r2 = c * c;
    let mut i_cm = *inertia;
    for (i, row) in i_cm.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            let delta = if i == j { r2 } else { 0.0 };
            *x -= mass * (delta - r[i] * r[j]);
        }
    }
    inverse(&i_cm).unwrap_or([[f64::NAN; 3]; 3])
}

/// [`CoastMass`] when the mass tables are constant after burn-out (checked at two times far
/// apart, to 1e-12 relative); `None` otherwise.
fn coast_mass<V: VehicleModel>(vehicle: &V, burn_out: f64) -> Option<CoastMass> {
    let b1 = burn_out;
    let cursors = &mut [Cursor::default(); 2];
    let law = MassFlowLaw::ThrustOverExhaustVelocity;
    let p1 = vehicle.mass(b1 + 1.0, law, cursors);
    let p2 = vehicle.mass(b1 + 1e4, law, cursors);
    let (m1, c1, i1) = (p1.total_mass, p1.com_to_cdm, p1.inertia);
    let (m2, c2, i2) = (p2.total_mass, p2.com_to_cdm, p2.inertia);
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs());
    let rates = p1.inertia_rate;
    let constant = same(m1, m2)
        && same(c1, c2)
        && i1.iter().zip(&i2).all(|(a, b)| same(*a, *b))
        && rates.iter().all(|r| r.abs() <= f64::MIN_POSITIVE)
        && p1.com_to_cdm_rate.abs() <= f64::MIN_POSITIVE;
    constant.then(|| CoastMass {
        mass: m1,
        inverse_mass: 1.0 / m1,
        com_to_cdm: c1,
        inertia: tensor(i1),
        inverse_cm_inertia: inverse_cm_inertia(&tensor(i1), m1, c1),
    })
}

impl<'a, A: AtmosphereModel, V: VehicleModel> Equations<'a, A, V> {
    /// Reads the constant model quantities once; the 6-DOF equations take the given form.
    pub fn new(atmosphere: &'a A, vehicle: &'a V, form: EquationsForm) -> Self {
        let setup = vehicle.setup();
        let s = setup.nozzle_gyration;
        let (lever_sign, law) = match form {
            EquationsForm::RocketPy113 => (1.0, MassFlowLaw::ThrustOverExhaustVelocity),
            EquationsForm::Standard => (-1.0, MassFlowLaw::MassDerivative),
        };
        Self {
            atmosphere,
            vehicle,
            earth_rotation: atmosphere.earth_rotation_enu(),
            burn_start: setup.burn_start,
            burn_out: setup.burn_out,
            nozzle: [0.0, 0.0, lever_sign * setup.nozzle_to_cdm],
            nozzle_gyration: [[s[0], 0.0, 0.0], [0.0, s[1], 0.0], [0.0, 0.0, s[2]]],
            dry_mass: setup.dry_mass,
            coast: coast_mass(vehicle, setup.burn_out),
            uniform_wind: atmosphere.uniform_wind(),
            lever_sign,
            law,
            off_axis: Some(setup.off_axis).filter(|o| !o.is_zero()),
        }
    }

    /// The atmosphere model.
    #[must_use]
    pub fn atmosphere(&self) -> &'a A {
        self.atmosphere
    }

    /// The vehicle model.
    #[must_use]
    pub fn vehicle(&self) -> &'a V {
        self.vehicle
    }

    /// The vehicle's dry mass, kg (the mass under a canopy, docs/physics.md §8.4).
    #[must_use]
    pub fn dry_mass(&self) -> f64 {
        self.dry_mass
    }

    /// The horizontal wind at time `t` and position `p` ([`AtmosphereModel::wind_at`]),
    /// without a lookup when it is uniform.
    #[inline]
    fn wind(&self, t: f64, p: Vec3) -> [f64; 2] {
        match self.uniform_wind {
            Some(w) => w,
            None => self.atmosphere.wind_at(t, p),
        }
    }

    /// Whether the motor is burning at `t` (strict `t_b0 < t < t_b1`, docs/physics.md §6.3).
    #[inline]
    #[must_use]
    pub fn powered(&self, t: f64) -> bool {
        self.burn_start < t && t < self.burn_out
    }

    /// Rail phase (docs/physics.md §8.1): 1-DOF slide along the rocket axis, power-on drag,
    /// gravity times `K33`, acceleration clipped at zero, attitude frozen, no Coriolis.
    #[inline]
    #[must_use]
    pub fn rail(
        &self,
        t: f64,
        u: &State,
        configuration: &Configuration,
        cursors: &mut Cursors,
    ) -> Derivative {
        let (e0, e1, e2, e3) = (u[6], u[7], u[8], u[9]);
        let atm = self.atmosphere;
        let veh = self.vehicle;
        let wind = self.wind(t, position(u));
        let free = [wind[0] - u[3], wind[1] - u[4], -u[5]];
        let speed = norm(free);
        let air = atm.air_at(t, position(u), &mut cursors.height);
        let mach = speed / air.speed_of_sound;
        let flow = BodyFlow {
            power_on: true,
            speed,
            mach,
            density: air.density,
        };
        // Control inputs (air brakes) do not act on the rail (RocketPy's rail equations).
        let on_rail = Configuration {
            controls: [0.0; MAX_CONTROLS],
            ..*configuration
        };
        let r3 = veh.axial_load(&flow, &on_rail, &mut cursors.mach);
        let net_thrust = veh.thrust(t, air.pressure, &mut cursors.time[0]);
        let mass = veh.total_mass(t, &mut cursors.time[1]);
        let a3 = (r3 + net_thrust) / mass - (e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3) * air.gravity;
        let (ax, ay, az) = if a3 > 0.0 {
            (
                2.0 * (e1 * e3 + e0 * e2) * a3,
                2.0 * (e2 * e3 - e0 * e1) * a3,
                (1.0 - 2.0 * (e1 * e1 + e2 * e2)) * a3,
            )
        } else if a3.is_nan() {
            // A NaN must reach the integrator (and fail the flight), not be clipped to rest.
            (f64::NAN, f64::NAN, f64::NAN)
        } else {
            (0.0, 0.0, 0.0)
        };
        Derivative {
            u_dot: [
                u[3], u[4], u[5], ax, ay, az, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
            ],
            force: [0.0, 0.0, r3],
            moment: [0.0; 3],
            net_thrust,
        }
    }

    /// Aerodynamic force and moment in body axes about the CDM, plus the net thrust
    /// (docs/physics.md §7.1, §7.2, §7.6, §8.3 steps 1–5); `power_on_drag` picks the drag curve
    /// (the 6-DOF equations: while the motor burns; the 3-DOF ones: before burn-out).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn loads(
        &self,
        t: f64,
        u: &State,
        k: &Mat3,
        air: &Air,
        power_on_drag: bool,
        configuration: &Configuration,
        cursors: &mut Cursors,
    ) -> (Vec3, Vec3, f64) {
        let atm = self.atmosphere;
        let veh = self.vehicle;
        let z = u[2];
        let v = [u[3], u[4], u[5]];
        let w = [u[10], u[11], u[12]];
        let rho = air.density;
        let wind = self.wind(t, position(u));
        let a = air.speed_of_sound;
        let free = [wind[0] - v[0], wind[1] - v[1], -v[2]];
        let speed = norm(free);
        let mach = speed / a;
        let powered = self.powered(t);
        let net_thrust = if powered {
            veh.thrust(t, air.pressure, &mut cursors.time[0])
        } else {
            0.0
        };
        let flow = BodyFlow {
            power_on: power_on_drag,
            speed,
            mach,
            density: rho,
        };
        let mut r = [
            0.0,
            0.0,
            veh.axial_load(&flow, configuration, &mut cursors.mach),
        ];
        let mut m = [0.0; 3];
        let v_body = mat_t_vec(k, v);
        // The wind in body axes at each surface's height: once when it is uniform.
        let uniform_wind_body = self
            .uniform_wind
            .map(|wc| mat_t_vec(k, [wc[0], wc[1], 0.0]));
        // The Mach number of each surface's stream: one division for all.
        let inverse_a = 1.0 / a;
        for surface in veh.surfaces() {
            let cp = surface.cp_body();
            let vb = add(v_body, cross(w, cp));
            let wb = match uniform_wind_body {
                Some(wb) => wb,
                None => {
                    let at = [
                        u[X] + dot(k[0], cp),
                        u[Y] + dot(k[1], cp),
                        z + dot(k[2], cp),
                    ];
                    let wc = atm.wind_at(t, at);
                    mat_t_vec(k, [wc[0], wc[1], 0.0])
                }
            };
            let stream = sub(wb, vb);
            let speed = norm(stream);
            let flow = LocalFlow {
                stream,
                speed,
                mach: speed * inverse_a,
                density: rho,
                roll_rate: w[2],
            };
            // The surfaces' zero components are −0, so they add nothing (karman_model::Loads).
            let loads = surface.loads(&flow);
            for i in 0..3 {
                r[i] += loads.force[i];
                m[i] += loads.moment[i];
            }
        }
        if let Some(o) = &self.off_axis {
            // The off-axis parts of r × F (karman_model::OffAxis), RocketPy 1.13's order.
            let ([cx, cy], [tx, ty]) = (o.cp, o.thrust);
            m[0] += cy * r[2] + ty * net_thrust;
            m[1] -= cx * r[2] + tx * net_thrust;
            m[2] += cx * r[1] - cy * r[0];
        }
        (r, m, net_thrust)
    }

    /// Rail-phase loads for post-processing: the 6-DOF aerodynamic loads at the rail state
    /// (RocketPy's `udot_rail1(post_processing=True)` reports those).
    #[must_use]
    pub fn rail_loads(
        &self,
        t: f64,
        u: &State,
        configuration: &Configuration,
        cursors: &mut Cursors,
    ) -> (Vec3, Vec3, f64) {
        let k = rotation(quaternion(u));
        let air = self.atmosphere.air_at(t, position(u), &mut cursors.height);
        self.loads(t, u, &k, &air, self.powered(t), configuration, cursors)
    }

    /// 6-DOF variable-mass flight (docs/physics.md §8.2, RocketPy's `u_dot_generalized`), with the
    /// RocketPy sign of the CM offset (§5.4) and nozzle terms (§5.6), Coriolis (§4.5).
    #[inline]
    #[must_use]
    pub fn six_dof(
        &self,
        t: f64,
        u: &State,
        configuration: &Configuration,
        cursors: &mut Cursors,
    ) -> Derivative {
        let atm = self.atmosphere;
        let veh = self.vehicle;
        let v = velocity(u);
        let e = quaternion(u);
        let w = angular_velocity(u);
        let k = rotation(e);

        // After burn-out c ≡ 0 and nothing changes; a finite-difference c̈ of a spline table
        // (RocketPy's, §5.4) straddling the burn-out kink would otherwise spike within 1e-6 s
        // of it, exactly where steps stop. ṁ = −T/v̄_e vanishes outside the burn
        // (zero-extrapolated thrust); gating it with the thrust makes the burn-out instant
        // itself, where integration steps stop, the unpowered limit instead of a mix (thrust
        // off but the last segment's m̈ on). Powered implies t < t_b1, so the coast branch
        // never needs it.
        let coasting = self.coast.is_some() && t >= self.burn_out;
        let (ms, mdot, mddot) = match &self.coast {
            Some(k) if coasting => (
                MassState {
                    mass: k.mass,
                    inverse_mass: k.inverse_mass,
                    c: k.com_to_cdm,
                    c_dot: 0.0,
                    c_ddot: 0.0,
                    inertia: k.inertia,
                    inertia_dot: [[0.0; 3]; 3],
                    inverse_cm_inertia: k.inverse_cm_inertia,
                },
                0.0,
                0.0,
            ),
            _ => {
                let p = veh.mass(t, self.law, &mut cursors.time);
                let (mass, c) = (p.total_mass, p.com_to_cdm);
                let inertia = tensor(p.inertia);
                let c_ddot = if t < self.burn_out {
                    p.com_to_cdm_accel
                } else {
                    0.0
                };
                let (mdot, mddot) = if self.powered(t) {
                    (p.mass_flow_rate, p.mass_flow_rate_derivative)
                } else {
                    (0.0, 0.0)
                };
                let state = MassState {
                    mass,
                    inverse_mass: 1.0 / mass,
                    c,
                    c_dot: p.com_to_cdm_rate,
                    c_ddot,
                    inertia,
                    inertia_dot: tensor(p.inertia_rate),
                    inverse_cm_inertia: inverse_cm_inertia(&inertia, mass, c),
                };
                (state, mdot, mddot)
            }
        };
        let MassState {
            mass,
            inverse_mass,
            c,
            c_dot,
            c_ddot,
            inertia,
            inertia_dot,
            inverse_cm_inertia: i_cm_inv,
        } = ms;
        // RocketPy's `c` is the CM→CDM offset (docs/physics.md §5.4); the standard form flies the
        // CDM→CM vector, its opposite (`I_CM` depends on `c²` only).
        let s = self.lever_sign;
        let r_cm = [0.0, 0.0, s * c];
        let r_cm_dot = [0.0, 0.0, s * c_dot];
        let r_cm_ddot = [0.0, 0.0, s * c_ddot];

        let air = atm.air_at(t, position(u), &mut cursors.height);
        let (force, moment, net_thrust) =
            self.loads(t, u, &k, &air, self.powered(t), configuration, cursors);
        let weight = Vector([0.0, 0.0, -mass * air.gravity]).by_t(&k);

        let (w, r_cm) = (Vector(w), Vector(r_cm));
        let (force_v, moment_v) = (Vector(force), Vector(moment));
        let t00 = mass * r_cm;
        let (t20, t21) = if coasting {
            // The variable-mass terms t03, t04 and t05 vanish (ṁ = m̈ = ċ = c̈ = T = 0, İ = 0):
            // adding their zeros changes no value, so they are left out.
            (
                w.cross(t00).cross(w) + weight + force_v,
                w.by(&inertia).cross(w) + (moment_v - weight.cross(r_cm)),
            )
        } else {
            let (r_cm_dot, r_cm_ddot) = (Vector(r_cm_dot), Vector(r_cm_ddot));
            let noz_minus_r = Vector(self.nozzle) - r_cm;
            let t03 = (2.0 * mdot) * noz_minus_r - (2.0 * mass) * r_cm_dot;
            let t04 = Vector([0.0, 0.0, net_thrust]) - mass * r_cm_ddot - (2.0 * mdot) * r_cm_dot
                + mddot * noz_minus_r;
            let mut t05 = inertia_dot;
            for (i, row) in t05.iter_mut().enumerate() {
                for (j, x) in row.iter_mut().enumerate() {
                    *x = mdot * self.nozzle_gyration[i][j] - *x;
                }
            }
            (
                w.cross(t00).cross(w) + w.cross(t03) + (t04 + weight) + force_v,
                w.by(&inertia).cross(w) + w.by(&t05) + (moment_v - weight.cross(r_cm)),
            )
        };
        let rhs = t21 + t20.cross(r_cm);
        let w_dot = rhs.by(&i_cm_inv);
        let e_dot = quaternion_rate(e, w.0);
        let body_acc = inverse_mass * t20 - r_cm.cross(w_dot);
        let v_dot = body_acc.by(&k) - 2.0 * Vector(self.earth_rotation).cross(Vector(v));
        Derivative {
            u_dot: derivative(v, v_dot.0, e_dot, w_dot.0),
            force,
            moment,
            net_thrust,
        }
    }

    /// Parachute descent (docs/physics.md §8.4): point mass at the dry mass, quadratic drag of the
    /// newest canopy relative to the wind, hemispheroid added mass dividing drag and weight,
    /// Coriolis; attitude frozen.
    #[inline]
    #[must_use]
    pub fn parachute(
        &self,
        t: f64,
        u: &State,
        canopy: &CanopyState,
        cursors: &mut Cursors,
    ) -> Derivative {
        let atm = self.atmosphere;
        let v = [u[3], u[4], u[5]];
        let air = atm.air_at(t, position(u), &mut cursors.height);
        let rho = air.density;
        let wind = self.wind(t, position(u));
        let mass = self.dry_mass;
        let added = canopy.added_mass_coefficient
            * rho
            * (2.0 / 3.0)
            * std::f64::consts::PI
            * canopy.radius
            * canopy.radius
            * canopy.height;
        let rel = [v[0] - wind[0], v[1] - wind[1], v[2]];
        let pseudo = -0.5 * rho * canopy.cd_s * norm(rel);
        let drag = scale(pseudo, rel);
        let total = mass + added;
        let coriolis = scale(2.0, cross(self.earth_rotation, v));
        let a = [
            drag[0] / total - coriolis[0],
            drag[1] / total - coriolis[1],
            (drag[2] - mass * air.gravity) / total - coriolis[2],
        ];
        Derivative {
            u_dot: [
                v[0], v[1], v[2], a[0], a[1], a[2], 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
            ],
            force: drag,
            moment: [0.0; 3],
            net_thrust: 0.0,
        }
    }
}
