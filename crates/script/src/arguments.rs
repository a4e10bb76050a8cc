//! The arguments a controller receives besides the state: the air brakes it drives and the
//! environment it may query (RocketPy's `AirBrakes` and `Environment` objects), as the
//! mission crate describes them ([`AirBrakesSetup`], [`EnvironmentQuery`]) and as the
//! scripts hold them (the handles the sandbox registers as Rhai types). Both the
//! interpreter ([`crate::sandbox`]) and the compiled fast path read them here.

use std::fmt;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

/// Environment functions of height a controller may query (RocketPy's `Environment`), heights
/// in m above sea level.
pub trait EnvironmentQuery: Send + Sync {
    /// Launch elevation, m.
    fn elevation(&self) -> f64;
    /// Eastward wind, m/s.
    fn wind_velocity_x(&self, height: f64) -> f64;
    /// Northward wind, m/s.
    fn wind_velocity_y(&self, height: f64) -> f64;
    /// Speed of sound, m/s.
    fn speed_of_sound(&self, height: f64) -> f64;
    /// Air density, kg/m³.
    fn density(&self, height: f64) -> f64;
    /// Air pressure, Pa.
    fn pressure(&self, height: f64) -> f64;
    /// Air temperature, K.
    fn temperature(&self, height: f64) -> f64;
    /// Dynamic viscosity, Pa·s.
    fn dynamic_viscosity(&self, height: f64) -> f64;
    /// Gravity, m/s².
    fn gravity(&self, height: f64) -> f64;
}

/// The air brakes as a controller sees them (RocketPy's `AirBrakes` object).
#[derive(Clone)]
pub struct AirBrakesSetup {
    /// Whether a level written outside `[0, 1]` is clipped to it.
    pub clamp: bool,
    /// Whether the brakes' curve replaces the rocket's drag while deployed.
    pub override_rocket_drag: bool,
    /// Reference area of the curve, m².
    pub reference_area: f64,
    /// The level at `t = 0`.
    pub initial_level: f64,
    /// The drag-coefficient curve `Cd(level, Mach)`.
    pub drag_coefficient: Arc<dyn Fn(f64, f64) -> f64 + Send + Sync>,
}

impl fmt::Debug for AirBrakesSetup {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("AirBrakesSetup")
            .field("clamp", &self.clamp)
            .field("override_rocket_drag", &self.override_rocket_drag)
            .field("reference_area", &self.reference_area)
            .field("initial_level", &self.initial_level)
            .finish_non_exhaustive()
    }
}

/// The `air_brakes` argument: its level is shared by every copy, so a write inside the
/// script is seen by the engine.
#[derive(Clone)]
pub(crate) struct AirBrakesHandle {
    level: Arc<AtomicU64>,
    pub(crate) setup: AirBrakesSetup,
}

impl AirBrakesHandle {
    /// A handle on `setup`'s brakes at their initial level (clipped when they clamp).
    pub(crate) fn new(setup: AirBrakesSetup) -> Self {
        let handle = AirBrakesHandle {
            level: Arc::new(AtomicU64::new(0.0f64.to_bits())),
            setup,
        };
        handle.set_level(handle.setup.initial_level);
        handle
    }

    /// The deployment level stored last.
    pub(crate) fn level(&self) -> f64 {
        f64::from_bits(self.level.load(Ordering::Relaxed))
    }

    /// Stores `value`, clipped to `[0, 1]` when the brakes clamp (docs/physics.md §16.3).
    pub(crate) fn set_level(&self, value: f64) {
        let stored = stored_level(self.setup.clamp, value);
        self.level.store(stored.to_bits(), Ordering::Relaxed);
    }
}

/// The level a write of `value` stores: clipped to `[0, 1]` when the brakes clamp
/// (docs/physics.md §16.3).
pub(crate) fn stored_level(clamp: bool, value: f64) -> f64 {
    if clamp { value.clamp(0.0, 1.0) } else { value }
}

/// The `environment` argument.
#[derive(Clone)]
pub(crate) struct EnvironmentHandle(pub(crate) Arc<dyn EnvironmentQuery>);
