//! The vehicle the engine flies (docs/physics.md §5–§7, §9.4).

use std::fmt;
use std::sync::Arc;

use karman_math::Cursor;

use crate::{Configuration, MAX_CONTROLS, SurfaceModel};

/// Rail-button geometry in the rocket's user coordinates (docs/physics.md §2.5, §8.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailButtonGeometry {
    /// Axial position of the button nearer the nose, m.
    pub upper_position: f64,
    /// Axial position of the button nearer the nozzle, m.
    pub lower_position: f64,
    /// Angular position of the buttons, rad (from the user y axis).
    pub angular_position_rad: f64,
}

/// A parachute trigger decided from the whole sampled state, as RocketPy's callable trigger
/// `trigger(p, h, y)` (docs/physics.md §17): sampled at every instant while the parachute is
/// pending, ascent included.
pub trait TriggerCondition: fmt::Debug + Send + Sync {
    /// Whether the parachute fires at sampling instant `t` (s), with the noisy pressure
    /// signal `pressure` (Pa), the barometric height above ground derived from it `height`
    /// (m, docs/physics.md §4.4) and the 13-component `state` there.
    fn fires(&self, t: f64, pressure: f64, height: f64, state: &[f64; 13]) -> bool;

    /// The names of the flight's signals the condition also reads (the values other sampled
    /// processes publish, such as a sensor's readings: RocketPy's `trigger(p, h, y,
    /// sensors)`), in the order [`TriggerCondition::fires_reading`] takes their values; the
    /// flight does not start when one is not published. Default: none.
    fn signals(&self) -> &[String] {
        &[]
    }

    /// [`TriggerCondition::fires`] with the latest value of each of
    /// [`TriggerCondition::signals`], NaN for a signal not published yet. Default: `fires`,
    /// the signals unread.
    fn fires_reading(
        &self,
        t: f64,
        pressure: f64,
        height: f64,
        state: &[f64; 13],
        _signals: &[f64],
    ) -> bool {
        self.fires(t, pressure, height, state)
    }
}

/// What fires a parachute (docs/physics.md §9.4, §17).
#[derive(Debug, Clone)]
pub enum TriggerKind {
    /// Vertical velocity negative.
    Apogee,
    /// Descending and barometric height above ground below this value, m.
    HeightAboveGround(f64),
    /// A condition evaluated at every sampling instant, ascent included.
    Custom(Arc<dyn TriggerCondition>),
}

impl PartialEq for TriggerKind {
    /// Built-in triggers compare by value, custom conditions by identity.
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (TriggerKind::Apogee, TriggerKind::Apogee) => true,
            (TriggerKind::HeightAboveGround(a), TriggerKind::HeightAboveGround(b)) => {
                a.to_bits() == b.to_bits()
            }
            (TriggerKind::Custom(a), TriggerKind::Custom(b)) => Arc::ptr_eq(a, b),
            _ => false,
        }
    }
}

/// A parachute as the flight engine needs it (resolved defaults, docs/physics.md §1, §8.4, §9.4).
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
    /// Added-mass coefficient `C_a(porosity)` (docs/physics.md §8.4).
    pub added_mass_coefficient: f64,
}

/// Lines of action off the rocket's axis, body axes (m): the aerodynamic forces applied at
/// `cp = (x, y)` from the axis (RocketPy 1.13's `Rocket.add_cp_eccentricity`), the thrust at
/// `thrust = (x, y)` (`Rocket.add_thrust_eccentricity`). Their moments about the centre of dry
/// mass are the off-axis parts of `r × F` (docs/physics.md §7.7): `M₁ += c_y R₃ + t_y T`,
/// `M₂ −= c_x R₃ + t_x T`, `M₃ += c_x R₂ − c_y R₁`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OffAxis {
    /// Where the aerodynamic forces act, `(x, y)` from the axis, m.
    pub cp: [f64; 2],
    /// Where the thrust acts, `(x, y)` from the axis, m.
    pub thrust: [f64; 2],
}

impl OffAxis {
    /// Whether every offset is zero (the equations then add nothing, bit for bit).
    #[must_use]
    pub fn is_zero(&self) -> bool {
        self.cp.iter().chain(&self.thrust).all(|&v| v == 0.0)
    }
}

/// What the engine reads of a vehicle once, when a flight is set up
/// ([`VehicleModel::setup`]). Times are seconds from the motor-ignition reference `t = 0`,
/// positions in the rocket's user coordinates unless stated.
#[derive(Debug, Clone, PartialEq)]
pub struct VehicleSetup {
    /// `+1` for a `tail_to_nose` rocket, `−1` for `nose_to_tail`.
    pub csys: f64,
    /// Start of the burn, s.
    pub burn_start: f64,
    /// End of the burn, s.
    pub burn_out: f64,
    /// Abscissae of the thrust curve's knots, s, where the thrust has kinks.
    pub thrust_knots: Vec<f64>,
    /// Rail buttons, if any.
    pub rail_buttons: Option<RailButtonGeometry>,
    /// Parachutes in insertion order.
    pub parachutes: Vec<ParachuteSpec>,
    /// Rocket + motor dry mass, kg.
    pub dry_mass: f64,
    /// Nozzle exit position, m.
    pub nozzle_position: f64,
    /// Nozzle-to-CDM distance `d_n` (docs/physics.md §5.6), m.
    pub nozzle_to_cdm: f64,
    /// Nozzle gyration tensor diagonal `(S11, S22, S33)`, m².
    pub nozzle_gyration: [f64; 3],
    /// Static margin (CP at Mach 0) at `t = 0` and at burn-out, calibers (post-processing).
    pub static_margins: [f64; 2],
    /// The control inputs at launch (e.g. an air brake's initial deployment level).
    pub initial_controls: [f64; MAX_CONTROLS],
    /// The forces' lines of action off the axis ([`OffAxis`]; zero for an aligned rocket).
    pub off_axis: OffAxis,
}

/// Which mass-flow rate [`VehicleModel::mass`] gives (docs/physics.md §6.2, §15.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MassFlowLaw {
    /// RocketPy 1.13's `ṁ = −T/v̄_e` for every motor, whatever its mass table.
    ThrustOverExhaustVelocity,
    /// The time derivative of the vehicle's mass `dm/dt` (of the motor's mass-flow table when
    /// it has one, e.g. from its tanks), consistent with the mass the equations fly.
    MassDerivative,
}

/// Every time-dependent mass quantity at one instant ([`VehicleModel::mass`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassSample {
    /// Total mass `m(t)`, kg.
    pub total_mass: f64,
    /// Signed mass-flow rate `ṁ(t)` of the requested [`MassFlowLaw`], kg/s.
    pub mass_flow_rate: f64,
    /// `m̈(t)` of [`MassSample::mass_flow_rate`], kg/s².
    pub mass_flow_rate_derivative: f64,
    /// CM→CDM offset `c(t)` with RocketPy's sign (docs/physics.md §5.4), m.
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

/// The free stream of the vehicle as a whole (at its centre of dry mass), what its axial
/// aerodynamic load depends on (docs/physics.md §7.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyFlow {
    /// Whether the motor is burning (power-on drag).
    pub power_on: bool,
    /// Free-stream speed `|w − v|`, m/s.
    pub speed: f64,
    /// Its Mach number.
    pub mach: f64,
    /// Air density, kg/m³.
    pub density: f64,
}

/// The rocket as the equations of motion see it (docs/physics.md §5–§7): a [`VehicleSetup`] read
/// once, and the quantities evaluated along the flight, which allocate nothing. The cursor
/// arguments are the caller's table cursors (see the crate overview).
pub trait VehicleModel {
    /// The aerodynamic-surface type.
    type Surface: SurfaceModel;

    /// The constants of the vehicle (once).
    fn setup(&self) -> VehicleSetup;
    /// Aerodynamic surfaces in insertion order.
    fn surfaces(&self) -> &[Self::Surface];
    /// Every time-dependent mass quantity at `t`, the mass flow by `law`, with the time
    /// located from `cursors`.
    fn mass(&self, t: f64, law: MassFlowLaw, cursors: &mut [Cursor; 2]) -> MassSample;
    /// The total mass `m(t)` alone, kg, equal to [`VehicleModel::mass`]'s
    /// [`MassSample::total_mass`], with the time located from `cursor` (the second of
    /// [`VehicleModel::mass`]'s): for the equations that need no other mass quantity (the
    /// rail slide, the point-mass flight).
    fn total_mass(&self, t: f64, cursor: &mut Cursor) -> f64;
    /// Net thrust at `t` with the nozzle-pressure correction for the ambient pressure,
    /// clamped at 0, N (docs/physics.md §6.3); `cursor` is the first of [`VehicleModel::mass`]'s.
    fn thrust(&self, t: f64, ambient_pressure: f64, cursor: &mut Cursor) -> f64;
    /// Axial aerodynamic force `R3` in body axes (drag, negative forward), N, in the flow
    /// and the configuration (e.g. air brakes deployed) of the instant, with the Mach number
    /// located from `cursor` (docs/physics.md §7.1).
    fn axial_load(
        &self,
        flow: &BodyFlow,
        configuration: &Configuration,
        cursor: &mut Cursor,
    ) -> f64;
    /// The names of the vehicle's control channels, in the order of
    /// [`Configuration::controls`] (at most [`crate::MAX_CONTROLS`]): channel `i` is control
    /// input `i`. A process finds a channel by name instead of assuming an index. Default:
    /// none declared.
    fn control_channels(&self) -> &[&str] {
        &[]
    }
}

/// The static stability a flight's report reads along the trajectory (docs/physics.md §7.7). It
/// is no force law and the equations of motion never call it, so it is a trait of its own
/// beside [`VehicleModel`]: the reports ask for both, the engine's step loop for the vehicle
/// alone.
pub trait StabilityModel {
    /// Stability margin at a Mach number and time, calibers.
    fn stability_margin(&self, mach: f64, t: f64) -> f64;
}
