//! The Rhai engine scripts run in: the standard library without clock (`no_time`) and without
//! `sleep` (a call of it is an error: it would block the flight's thread unbounded by the
//! operation limits), no `curry` (each curried function pointer copies every argument curried
//! before, so a loop of a few thousand operations does quadratic work the limits do not
//! count), no module resolver (`import` fails), `eval` disabled, `print`/`debug` discarded,
//! strict variables (an
//! undefined name is a compile error), and limits on every call so that no script can hang or
//! exhaust memory; across the calls of one flight, a budget of interpreted operations
//! ([`MAX_FLIGHT_OPERATIONS`]) and of recorded values ([`MAX_RECORD_VALUES`]). The operations
//! are also counted by the controller itself, through the engine's progress callback, because
//! Rhai's own count runs on a copy inside a closure called by a native function (a `sort`
//! comparator) and its limit error is discarded there. What the engine adds: the `motor`
//! module, and the `AirBrakes`, `Environment` and `Sensor` types of the controller's arguments.

use crate::arguments::{AirBrakesHandle, EnvironmentHandle, SensorHandle};
use rhai::module_resolvers::DummyModuleResolver;
use rhai::packages::{Package, StandardPackage};
use rhai::{Array, Dynamic, Engine, EvalAltResult, FLOAT, INT, ImmutableString, Module, Shared};
use std::sync::OnceLock;

/// Operations one call may run (an operation is roughly one expression node or statement).
pub const MAX_OPERATIONS: u64 = 1_000_000;
/// Operations the interpreted calls of one flight may run together: a hundred calls at the
/// per-call limit, so that a loop just under that limit ends the flight within seconds
/// instead of running for tens of minutes, while a controller of a few thousand operations
/// a call at 100 Hz still flies for minutes (10⁴ calls × 10⁴ operations = 10⁸). Compiled
/// calls (module `controller`, "Compiled calls") are bounded by their tree and not counted.
pub const MAX_FLIGHT_OPERATIONS: u64 = 100_000_000;
/// Values the record of one flight (`observed_variables`, every non-`()` value the calls
/// returned) may hold, counting each number, boolean, array and map entry as one value and a
/// string or blob as one per 16 bytes: 32 MiB as Rhai values (16 bytes each), up to twice
/// that with the spare capacity of growing arrays, and as much again once converted to JSON
/// at the end of the flight (tests/hostile.rs measures the peak of such a flight).
pub const MAX_RECORD_VALUES: u64 = 2_000_000;
/// Nesting of arrays and maps in one returned value.
pub const MAX_RECORD_DEPTH: usize = 32;
/// Depth of nested function calls.
pub const MAX_CALL_LEVELS: usize = 48;
/// Nesting depth of expressions, at the top level and inside functions.
pub const MAX_EXPR_DEPTHS: (usize, usize) = (64, 48);
/// Characters of one string.
pub const MAX_STRING_SIZE: usize = 16_384;
/// Elements of one array (the total of nested arrays). Rhai measures a whole array after each
/// change to it, so a call growing one element by element costs the square of this limit:
/// 10,000 keeps such a call to a fraction of a second, far above what a controller keeps.
pub const MAX_ARRAY_SIZE: usize = 10_000;
/// Entries of one object map.
pub const MAX_MAP_SIZE: usize = 10_000;
/// Variables alive at once.
pub const MAX_VARIABLES: usize = 1_000;

/// Rhai's standard package, built once per process.
fn standard() -> Shared<Module> {
    static STANDARD: OnceLock<Shared<Module>> = OnceLock::new();
    STANDARD
        .get_or_init(|| StandardPackage::new().as_shared_module())
        .clone()
}

/// The `motor` module: `motor::burn_start_time` and `motor::burn_out_time`, s.
pub(crate) fn motor_module(burn_start: f64, burn_out: f64) -> Shared<Module> {
    let mut module = Module::new();
    module.set_var("burn_start_time", burn_start);
    module.set_var("burn_out_time", burn_out);
    module.into()
}

/// The error of a call of `sleep` (which the standard library has, and which would block the
/// flight's thread for as long as the script asks).
const NO_SLEEP: &str = "`sleep` is not available to a controller (a controller must not block)";

/// A sandboxed engine with the controller's types and `motor`.
pub(crate) fn engine(motor: &Shared<Module>) -> Engine {
    let mut engine = Engine::new_raw();
    engine.register_global_module(standard());
    engine.register_static_module("motor", motor.clone());
    engine.set_module_resolver(DummyModuleResolver::new());
    engine.disable_symbol("eval");
    engine.disable_symbol("curry");
    engine.register_fn("sleep", |_: FLOAT| -> Result<(), Box<EvalAltResult>> {
        Err(NO_SLEEP.into())
    });
    engine.register_fn("sleep", |_: INT| -> Result<(), Box<EvalAltResult>> {
        Err(NO_SLEEP.into())
    });
    engine.on_print(|_| {});
    engine.on_debug(|_, _, _| {});
    engine.set_strict_variables(true);
    engine.set_max_operations(MAX_OPERATIONS);
    engine.set_max_call_levels(MAX_CALL_LEVELS);
    engine.set_max_expr_depths(MAX_EXPR_DEPTHS.0, MAX_EXPR_DEPTHS.1);
    engine.set_max_string_size(MAX_STRING_SIZE);
    engine.set_max_array_size(MAX_ARRAY_SIZE);
    engine.set_max_map_size(MAX_MAP_SIZE);
    engine.set_max_variables(MAX_VARIABLES);
    engine.set_max_modules(0);

    engine.register_type_with_name::<AirBrakesHandle>("AirBrakes");
    engine.register_get_set(
        "deployment_level",
        |brakes: &mut AirBrakesHandle| -> FLOAT { brakes.level() },
        |brakes: &mut AirBrakesHandle, value: FLOAT| brakes.set_level(value),
    );
    engine.register_get("clamp", |brakes: &mut AirBrakesHandle| brakes.setup.clamp);
    engine.register_get("override_rocket_drag", |brakes: &mut AirBrakesHandle| {
        brakes.setup.override_rocket_drag
    });
    engine.register_get("reference_area", |brakes: &mut AirBrakesHandle| {
        brakes.setup.reference_area
    });
    engine.register_fn(
        "drag_coefficient",
        |brakes: &mut AirBrakesHandle, level: FLOAT, mach: FLOAT| -> FLOAT {
            (brakes.setup.drag_coefficient)(level, mach)
        },
    );

    engine.register_type_with_name::<EnvironmentHandle>("Environment");
    engine.register_get("elevation", |env: &mut EnvironmentHandle| env.0.elevation());
    macro_rules! of_height {
        ($($name:ident),*) => {$(
            engine.register_fn(stringify!($name), |env: &mut EnvironmentHandle, h: FLOAT| {
                env.0.$name(h)
            });
        )*};
    }
    of_height!(
        wind_velocity_x,
        wind_velocity_y,
        speed_of_sound,
        density,
        pressure,
        temperature,
        dynamic_viscosity,
        gravity
    );
    // RocketPy's `Sensor.measurement`: `()` (RocketPy's `None`) before the first reading, a
    // number for a barometer, an array of three numbers otherwise; `time`, the instant of
    // that reading (RocketPy's `measured_data[-1][0]`), also `()` before it.
    engine.register_type_with_name::<SensorHandle>("Sensor");
    engine.register_get("name", |s: &mut SensorHandle| -> ImmutableString {
        s.0.name.clone()
    });
    engine.register_get("kind", |s: &mut SensorHandle| -> ImmutableString {
        s.0.kind.clone()
    });
    engine.register_get("time", |s: &mut SensorHandle| -> Dynamic {
        s.time().map_or(Dynamic::UNIT, Dynamic::from_float)
    });
    engine.register_get("measurement", |s: &mut SensorHandle| -> Dynamic {
        if s.time().is_none() {
            return Dynamic::UNIT;
        }
        if s.0.components == 1 {
            return Dynamic::from_float(s.value(0));
        }
        (0..s.0.components)
            .map(|i| Dynamic::from_float(s.value(i)))
            .collect::<Array>()
            .into()
    });
    engine
}
