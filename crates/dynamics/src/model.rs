//! What the flight engine needs from the atmosphere and the vehicle, as two small traits.
//!
//! The engine evaluates its models only through [`AtmosphereModel`] and [`VehicleModel`]
//! (implemented for `karman_atmos::Environment` and `karman_airframe::Rocket` in
//! [`crate::adapters`]), so the equations of motion can be unit-tested against hand-built
//! models and the model crates can evolve behind one adapter. Every per-step method must be
//! allocation-free; the methods documented "once" are called when a flight is set up. The
//! `*_near` methods take table cursors ([`Cursor`]) that the engine keeps between
//! evaluations, so that a model's lookups start where the previous ones ended.

pub use karman_math::Cursor;

/// The atmosphere at one height, as the equations of motion use it
/// ([`AtmosphereModel::air`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Air {
    /// Air pressure, Pa.
    pub pressure: f64,
    /// Air density, kg/m³.
    pub density: f64,
    /// Speed of sound, m/s.
    pub speed_of_sound: f64,
    /// Gravity, m/s².
    pub gravity: f64,
}

/// Atmosphere, gravity and Earth rotation at the launch site (physics.md §4). Heights are
/// geometric, metres above sea level.
pub trait AtmosphereModel {
    /// Launch elevation, m ASL (once).
    fn elevation(&self) -> f64;
    /// Air pressure, Pa.
    fn pressure(&self, z: f64) -> f64;
    /// Air density, kg/m³.
    fn density(&self, z: f64) -> f64;
    /// Speed of sound, m/s.
    fn speed_of_sound(&self, z: f64) -> f64;
    /// Dynamic viscosity, Pa·s.
    fn dynamic_viscosity(&self, z: f64) -> f64;
    /// Horizontal wind `(east, north)`, m/s.
    fn wind(&self, z: f64) -> [f64; 2];
    /// The wind when it is the same at every height, bit for bit what
    /// [`AtmosphereModel::wind`] returns (once): the engine then skips the per-height lookups.
    /// `None` (the default) when it varies with height.
    fn uniform_wind(&self) -> Option<[f64; 2]> {
        None
    }
    /// Gravity, m/s².
    fn gravity(&self, z: f64) -> f64;
    /// Pressure, density, speed of sound and gravity at once, equal to the individual
    /// methods; a model overrides it to share the height lookups.
    #[inline]
    fn air(&self, z: f64) -> Air {
        Air {
            pressure: self.pressure(z),
            density: self.density(z),
            speed_of_sound: self.speed_of_sound(z),
            gravity: self.gravity(z),
        }
    }
    /// [`AtmosphereModel::air`] with the height located from `cursor`, which the engine
    /// keeps between evaluations (updated): the same values whatever it holds. A model with
    /// tables overrides it to start its search where the last one ended; the default
    /// ignores it.
    #[inline]
    fn air_near(&self, z: f64, _cursor: &mut Cursor) -> Air {
        self.air(z)
    }
    /// Earth rotation vector in the ENU launch frame, rad/s (once).
    fn earth_rotation_enu(&self) -> [f64; 3];
    /// Barometric height `h_baro(P)` of a (noisy) pressure, m ASL (physics.md §4.4).
    fn barometric_height(&self, pressure: f64) -> f64;
}

/// One aerodynamic surface as the equations of motion see it (physics.md §7.2, §7.6).
pub trait SurfaceModel {
    /// Centre of pressure in body axes, measured from the centre of dry mass, m.
    fn cp_body(&self) -> [f64; 3];
    /// Reference area `π r_s²`, m².
    fn reference_area(&self) -> f64;
    /// Reference length `d = 2 r_s`, m (roll moments).
    fn reference_length(&self) -> f64;
    /// Normal-force slope `CNα(Mach)`, 1/rad, on [`SurfaceModel::reference_area`].
    fn cn_alpha(&self, mach: f64) -> f64;
    /// Whether the surface produces roll moments (fin sets); the roll coefficients of other
    /// surfaces are not evaluated.
    fn rolls(&self) -> bool;
    /// Roll-forcing coefficient `C_lf,δ(Mach)·δ` (0 for surfaces that do not roll).
    fn roll_forcing(&self, mach: f64) -> f64;
    /// Roll-damping coefficient `C_ld,ω(Mach)` (0 for surfaces that do not roll).
    fn roll_damping(&self, mach: f64) -> f64;
    /// `[CNα, roll forcing, roll damping]` at one Mach number, what the equations of motion
    /// evaluate per surface; a model overrides it to share the Mach-dependent work.
    #[inline]
    fn coefficients(&self, mach: f64) -> [f64; 3] {
        if self.rolls() {
            [
                self.cn_alpha(mach),
                self.roll_forcing(mach),
                self.roll_damping(mach),
            ]
        } else {
            [self.cn_alpha(mach), 0.0, 0.0]
        }
    }
}

/// Rail-button geometry in the rocket's user coordinates (physics.md §2.5, §8.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailButtonGeometry {
    /// Axial position of the button nearer the nose, m.
    pub upper_position: f64,
    /// Axial position of the button nearer the nozzle, m.
    pub lower_position: f64,
    /// Angular position of the buttons, rad (from the user y axis).
    pub angular_position_rad: f64,
}

/// What fires a parachute (physics.md §9.4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TriggerKind {
    /// Vertical velocity negative.
    Apogee,
    /// Descending and barometric height above ground below this value, m.
    HeightAboveGround(f64),
}

/// A parachute as the flight engine needs it (resolved defaults, physics.md §1, §8.4, §9.4).
#[derive(Debug, Clone, PartialEq)]
pub struct ParachuteSpec {
    /// The user's name for it (event `parachute:<name>`).
    pub name: String,
    /// Drag coefficient times reference area, m².
    pub cd_s: f64,
    /// Trigger condition.
    pub trigger: TriggerKind,
    /// Trigger sampling rate, Hz.
    pub sampling_rate: f64,
    /// Delay between trigger and full inflation, s.
    pub lag: f64,
    /// Pressure-signal noise `(mean, std, correlation)`, Pa, Pa, –.
    pub noise: [f64; 3],
    /// Canopy radius, m.
    pub radius: f64,
    /// Canopy height, m.
    pub height: f64,
    /// Added-mass coefficient `C_a(porosity)` (physics.md §8.4).
    pub added_mass_coefficient: f64,
}

/// Every time-dependent mass quantity at one instant ([`VehicleModel::mass_sample`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassSample {
    /// Total mass `m(t)`, kg.
    pub total_mass: f64,
    /// Signed mass-flow rate `ṁ(t)`, kg/s.
    pub mass_flow_rate: f64,
    /// `m̈(t)`, kg/s².
    pub mass_flow_rate_derivative: f64,
    /// CM→CDM offset `c(t)`, m.
    pub com_to_cdm: f64,
    /// `ċ(t)`, m/s.
    pub com_to_cdm_rate: f64,
    /// `c̈(t)`, m/s².
    pub com_to_cdm_accel: f64,
    /// Inertia about the CDM `(I11, I22, I33, I12, I13, I23)`, kg·m².
    pub inertia: [f64; 6],
    /// Its time derivative, kg·m²/s.
    pub inertia_rate: [f64; 6],
}

/// The rocket as the equations of motion see it (physics.md §5–§7). Times are seconds from
/// motor ignition reference `t = 0`; positions are SI.
pub trait VehicleModel {
    /// The aerodynamic-surface type.
    type Surface: SurfaceModel;

    /// Aerodynamic surfaces in insertion order.
    fn surfaces(&self) -> &[Self::Surface];
    /// Reference area `π r²`, m².
    fn reference_area(&self) -> f64;
    /// Reference radius `r`, m.
    fn radius(&self) -> f64;
    /// `+1` for a `tail_to_nose` rocket, `−1` for `nose_to_tail` (once).
    fn csys(&self) -> f64;
    /// Total mass `m(t)`, kg.
    fn total_mass(&self, t: f64) -> f64;
    /// Signed total mass-flow rate `ṁ(t) = −T/v̄_e`, kg/s.
    fn mass_flow_rate(&self, t: f64) -> f64;
    /// `m̈(t)`, kg/s².
    fn mass_flow_rate_derivative(&self, t: f64) -> f64;
    /// RocketPy's CM→CDM offset `c(t)` (physics.md §5.4), m.
    fn com_to_cdm(&self, t: f64) -> f64;
    /// `ċ(t)`, m/s.
    fn com_to_cdm_rate(&self, t: f64) -> f64;
    /// `c̈(t)`, m/s².
    fn com_to_cdm_accel(&self, t: f64) -> f64;
    /// Inertia about the CDM in body axes `(I11, I22, I33, I12, I13, I23)`, kg·m².
    fn inertia(&self, t: f64) -> [f64; 6];
    /// Time derivative of [`VehicleModel::inertia`], kg·m²/s.
    fn inertia_rate(&self, t: f64) -> [f64; 6];
    /// Every time-dependent mass quantity at once, equal to the individual methods; a model
    /// overrides it to share the table lookups.
    #[inline]
    fn mass_sample(&self, t: f64) -> MassSample {
        MassSample {
            total_mass: self.total_mass(t),
            mass_flow_rate: self.mass_flow_rate(t),
            mass_flow_rate_derivative: self.mass_flow_rate_derivative(t),
            com_to_cdm: self.com_to_cdm(t),
            com_to_cdm_rate: self.com_to_cdm_rate(t),
            com_to_cdm_accel: self.com_to_cdm_accel(t),
            inertia: self.inertia(t),
            inertia_rate: self.inertia_rate(t),
        }
    }
    /// [`VehicleModel::mass_sample`] with the time located from `cursors`, which the engine
    /// keeps between evaluations (updated): the same values whatever they hold. The default
    /// ignores them.
    #[inline]
    fn mass_sample_near(&self, t: f64, _cursors: &mut [Cursor; 2]) -> MassSample {
        self.mass_sample(t)
    }
    /// Nozzle-to-CDM distance `d_n` (physics.md §5.6), m (once).
    fn nozzle_to_cdm(&self) -> f64;
    /// Nozzle gyration tensor diagonal `(S11, S22, S33)`, m² (once).
    fn nozzle_gyration(&self) -> [f64; 3];
    /// Raw thrust `T(t)`, N.
    fn thrust(&self, t: f64) -> f64;
    /// Net thrust with the pressure correction, clamped at 0, N (physics.md §6.3).
    fn net_thrust(&self, t: f64, ambient_pressure: f64) -> f64;
    /// [`VehicleModel::net_thrust`] with the time located from `cursor` (updated; the first
    /// cursor of [`VehicleModel::mass_sample_near`]): the same value. The default ignores it.
    #[inline]
    fn net_thrust_near(&self, t: f64, ambient_pressure: f64, _cursor: &mut Cursor) -> f64 {
        self.net_thrust(t, ambient_pressure)
    }
    /// Abscissae of the thrust curve's knots, s, where the thrust has kinks (once).
    fn thrust_knots(&self) -> Vec<f64>;
    /// Start of the burn, s (once).
    fn burn_start(&self) -> f64;
    /// End of the burn, s (once).
    fn burn_out(&self) -> f64;
    /// Drag coefficient (power on or off) at a Mach number.
    fn drag_coefficient(&self, power_on: bool, mach: f64) -> f64;
    /// [`VehicleModel::drag_coefficient`] with the Mach number located from `cursor`
    /// (updated): the same value. The default ignores it.
    #[inline]
    fn drag_coefficient_near(&self, power_on: bool, mach: f64, _cursor: &mut Cursor) -> f64 {
        self.drag_coefficient(power_on, mach)
    }
    /// Rocket + motor dry mass, kg (once).
    fn dry_mass(&self) -> f64;
    /// Centre of dry mass, user coordinates, m (once).
    fn center_of_dry_mass(&self) -> f64;
    /// Nozzle exit position, user coordinates, m (once).
    fn nozzle_position(&self) -> f64;
    /// Rail buttons, if any (once).
    fn rail_buttons(&self) -> Option<RailButtonGeometry>;
    /// Parachutes in insertion order (once).
    fn parachutes(&self) -> Vec<ParachuteSpec>;
    /// Static margin at time `t` (CP at Mach 0), calibers (post-processing).
    fn static_margin(&self, t: f64) -> f64;
    /// Stability margin at a Mach number and time, calibers (post-processing).
    fn stability_margin(&self, mach: f64, t: f64) -> f64;
}
