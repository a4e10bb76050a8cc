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
/// (docs/physics.md §16.3). Every controller's write goes through it, whatever its language.
pub fn stored_level(clamp: bool, value: f64) -> f64 {
    if clamp { value.clamp(0.0, 1.0) } else { value }
}

/// The `environment` argument.
#[derive(Clone)]
pub(crate) struct EnvironmentHandle(pub(crate) Arc<dyn EnvironmentQuery>);

/// What a controller knows of one of the rocket's sensors before the flight: its name, its
/// kind's name (`"accelerometer"`, `"gyroscope"`, `"barometer"`, `"gnss"`) and the number of
/// components of its reading (1 for a barometer, 3 otherwise).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SensorSetup {
    /// The sensor's name (unique in the flight).
    pub name: String,
    /// Its kind's name.
    pub kind: String,
    /// Components of a reading, 1 to 3.
    pub components: usize,
}

/// One sensor as the `sensors` argument holds it: its setup and its latest reading, written
/// by the engine before each call ([`crate::Controller::set_sensor`]) and shared by every
/// copy of the handle, so that the array of handles is built once per flight. The time is
/// NaN before the sensor's first reading.
#[derive(Debug)]
pub(crate) struct SensorSlot {
    pub(crate) name: rhai::ImmutableString,
    pub(crate) kind: rhai::ImmutableString,
    pub(crate) components: usize,
    /// The bits of `[t, v₀, v₁, v₂]`.
    cells: [AtomicU64; 4],
}

/// The handle of one sensor in the `sensors` argument (the Rhai type `Sensor`).
#[derive(Debug, Clone)]
pub(crate) struct SensorHandle(pub(crate) Arc<SensorSlot>);

impl SensorHandle {
    pub(crate) fn new(setup: &SensorSetup) -> Self {
        let nan = f64::NAN.to_bits();
        SensorHandle(Arc::new(SensorSlot {
            name: setup.name.as_str().into(),
            kind: setup.kind.as_str().into(),
            components: setup.components.clamp(1, 3),
            cells: [
                AtomicU64::new(nan),
                AtomicU64::new(nan),
                AtomicU64::new(nan),
                AtomicU64::new(nan),
            ],
        }))
    }

    /// Stores the reading `values` taken at `t`.
    pub(crate) fn set(&self, t: f64, values: [f64; 3]) {
        let cells = &self.0.cells;
        cells[0].store(t.to_bits(), Ordering::Relaxed);
        for (cell, v) in cells[1..].iter().zip(values) {
            cell.store(v.to_bits(), Ordering::Relaxed);
        }
    }

    /// The instant of the latest reading, `None` before the first.
    pub(crate) fn time(&self) -> Option<f64> {
        let t = f64::from_bits(self.0.cells[0].load(Ordering::Relaxed));
        (!t.is_nan()).then_some(t)
    }

    /// Component `i` of the latest reading.
    pub(crate) fn value(&self, i: usize) -> f64 {
        f64::from_bits(self.0.cells[1 + i].load(Ordering::Relaxed))
    }
}
