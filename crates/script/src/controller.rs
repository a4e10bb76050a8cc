//! Air-brake controllers written in Rhai: RocketPy's `controller_function` (docs/physics.md §16.5,
//! mission-format.md "The controller script").
//!
//! A [`ControllerScript`] is compiled once per mission; each flight makes its own
//! [`Controller`] from it (its deployment level, its record). The engine calls
//! [`Controller::call`] at every sampling instant with the state there and the last stored
//! solution row; the script sets `air_brakes.deployment_level` and returns what it wants
//! recorded (`()` records nothing), which comes back as `observed_variables[-1]` at the next
//! call.
//!
//! The scripts run sandboxed ([`crate::sandbox`]): no file, network, clock or module access,
//! and every call is bounded in operations, call depth and data size, so a runaway script ends
//! its flight with a located [`ScriptError`] instead of hanging. A flight is bounded too: its
//! interpreted calls together run at most [`sandbox::MAX_FLIGHT_OPERATIONS`] operations, and
//! what they return is kept (the record) up to [`sandbox::MAX_RECORD_VALUES`] values, each
//! nested at most [`sandbox::MAX_RECORD_DEPTH`] deep; past either budget the call is an error
//! naming the script file and the budget.
//!
//! ## Compiled calls
//!
//! A script within the controllers' common subset is also compiled, once (docs/performance.md,
//! "Controllers"), from the AST Rhai parsed and optimised, to a tree evaluated natively with Rhai's
//! semantics: numbers, booleans, `()` and array literals; `let`/`const`, assignment and arithmetic
//! op-assignment of locals and of `air_brakes.deployment_level`; `if`/`else` (also as an
//! expression) and `return`; the arithmetic, comparison and logical operators (floats as Rhai's
//! checked build computes them, its relative float comparisons included); `sqrt`, `exp`, `ln`,
//! `log`, `sin`, `cos`, `tan`, `abs`; `state[i]` and `state_history[-1][i]` at literal indices;
//! `time`, `sampling_rate`, `global::NAME`, `motor::NAME`; the air-brake handle's properties and
//! `drag_coefficient`; the environment's `elevation` and queries. A call the tree cannot decide
//! with certainty (integer arithmetic, a value of an unexpected type, an index out of range) has
//! had no effect outside it and is made again by the interpreter, which gives Rhai's result or its
//! located error; a script outside the subset runs interpreted throughout
//! ([`ControllerScript::interpreted_because`] says why). Without loops or script-function calls a
//! compiled call is bounded by the tree's size, far below the operation limit.

use crate::arguments::{AirBrakesHandle, EnvironmentHandle, SensorHandle};
pub use crate::arguments::{AirBrakesSetup, EnvironmentQuery, SensorSetup};
use crate::compiled::{self, Bound, Compiled, Inputs};
use crate::sandbox;
use rhai::{
    AST, Array, CallFnOptions, Dynamic, Engine, EvalAltResult, Map, Module, Position, Scope,
};
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicU8, AtomicU64, Ordering};
use thiserror::Error;

/// The function a controller script defines.
pub const CONTROLLER_FUNCTION: &str = "controller_function";

/// The namespace of a script's top-level constants inside its functions (`global::NAME`).
const GLOBAL: &str = "global";

/// A compile or run-time error of a script, located in the script file.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub struct ScriptError {
    /// The script file.
    pub file: PathBuf,
    /// Line and column (1-based) in the script, when known.
    pub position: Option<(usize, usize)>,
    /// What went wrong.
    pub message: String,
}

impl fmt::Display for ScriptError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.position {
            Some((line, column)) => write!(f, "{}:{line}:{column}: ", self.file.display())?,
            None => write!(f, "{}: ", self.file.display())?,
        }
        f.write_str(&self.message)
    }
}

fn located(file: &Path, position: Position, message: String) -> ScriptError {
    ScriptError {
        file: file.to_owned(),
        position: position
            .line()
            .map(|line| (line, position.position().unwrap_or(1))),
        message,
    }
}

/// A run-time error, located at the innermost position Rhai knows (inside a nested function
/// call, the statement that failed rather than the call).
/// An error Rhai does not locate (an operation limit reached inside a loop, say) is placed at
/// the definition of `controller_function`, `function`.
fn runtime(file: &Path, function: Option<(usize, usize)>, error: &EvalAltResult) -> ScriptError {
    let mut innermost = error;
    let mut position = error.position();
    while let EvalAltResult::ErrorInFunctionCall(_, _, inner, at) = innermost {
        if !at.is_none() {
            position = *at;
        }
        innermost = inner;
        if !innermost.position().is_none() {
            position = innermost.position();
        }
    }
    let message = match innermost {
        EvalAltResult::ErrorTooManyOperations(_) => call_budget(),
        // Rhai's text ends with "(line L, position C)": the error's own location says it.
        other => {
            let text = other.to_string();
            let suffix = format!(" ({})", other.position());
            match text.strip_suffix(&suffix) {
                Some(bare) if !other.position().is_none() => bare.to_owned(),
                _ => text,
            }
        }
    };
    let mut error = located(file, position, message);
    if error.position.is_none() {
        error.position = function;
        error.message = format!("in `{CONTROLLER_FUNCTION}`: {}", error.message);
    }
    error
}

/// No budget exceeded.
const WITHIN: u8 = 0;
/// The current call exceeded [`sandbox::MAX_OPERATIONS`].
const CALL_BUDGET: u8 = 1;
/// The flight's calls exceeded [`sandbox::MAX_FLIGHT_OPERATIONS`].
const FLIGHT_BUDGET: u8 = 2;

/// The operations of a flight's interpreted calls, counted one by one by the engine's
/// progress callback. Rhai counts operations itself, but a closure a native function calls
/// (a `sort` comparator) counts on a copy of that count and its limit error is discarded by
/// the native function, so an endless comparator would run to the per-call limit once per
/// comparison and the call would succeed; this count sees every operation, and once past a
/// budget the callback stops each further one (every later comparison included) and the call
/// is reported as over the budget whatever Rhai returns.
#[derive(Debug)]
struct Meter {
    /// The flight's budget of operations, [`sandbox::MAX_FLIGHT_OPERATIONS`] unless
    /// [`Controller::with_operation_budget`] set another.
    budget: AtomicU64,
    /// Operations of the current call.
    call: AtomicU64,
    /// Operations of the flight's finished calls.
    flight: AtomicU64,
    /// The budget the current call exceeded: [`WITHIN`], [`CALL_BUDGET`] or
    /// [`FLIGHT_BUDGET`].
    exceeded: AtomicU8,
}

impl Meter {
    /// The progress callback's step: counts one operation, and refuses it past a budget.
    fn operation(&self) -> Option<Dynamic> {
        let call = self.call.fetch_add(1, Ordering::Relaxed) + 1;
        let exceeded = if call > sandbox::MAX_OPERATIONS {
            CALL_BUDGET
        } else if self.flight.load(Ordering::Relaxed) + call > self.budget.load(Ordering::Relaxed) {
            FLIGHT_BUDGET
        } else {
            return None;
        };
        self.exceeded.store(exceeded, Ordering::Relaxed);
        Some(Dynamic::UNIT)
    }

    fn new() -> Self {
        Meter {
            budget: AtomicU64::new(sandbox::MAX_FLIGHT_OPERATIONS),
            call: AtomicU64::new(0),
            flight: AtomicU64::new(0),
            exceeded: AtomicU8::new(WITHIN),
        }
    }

    /// Starts a call.
    fn start(&self) {
        self.call.store(0, Ordering::Relaxed);
        self.exceeded.store(WITHIN, Ordering::Relaxed);
    }

    /// Ends a call: adds its operations to the flight's, and returns the budget it exceeded.
    fn finish(&self) -> u8 {
        self.flight
            .fetch_add(self.call.load(Ordering::Relaxed), Ordering::Relaxed);
        self.exceeded.load(Ordering::Relaxed)
    }
}

/// The result of a metered call: `result` unless the call exceeded a budget (`exceeded`, of
/// `meter`), which is then the error, located where Rhai stopped or at `function`.
fn metered<T>(
    file: &Path,
    function: Option<(usize, usize)>,
    meter: &Meter,
    result: Result<T, Box<EvalAltResult>>,
) -> Result<T, ScriptError> {
    let exceeded = meter.finish();
    let message = match exceeded {
        CALL_BUDGET => call_budget(),
        FLIGHT_BUDGET => format!(
            "the controller exceeded its budget of {} operations per flight (at most {} per \
             call); make each call do less work",
            meter.budget.load(Ordering::Relaxed),
            sandbox::MAX_OPERATIONS
        ),
        _ => return result.map_err(|e| runtime(file, function, &e)),
    };
    let mut error = match &result {
        Err(e) => runtime(file, function, e),
        Ok(_) => ScriptError {
            file: file.to_owned(),
            position: function,
            message: String::new(),
        },
    };
    error.message = if error.position == function {
        format!("in `{CONTROLLER_FUNCTION}`: {message}")
    } else {
        message
    };
    Err(error)
}

/// The size of `value` as the record's budget counts it ([`sandbox::MAX_RECORD_VALUES`]): one
/// per number, boolean, `()`, array and map entry, one per 16 bytes of a string or blob; `None`
/// when it nests deeper than [`sandbox::MAX_RECORD_DEPTH`] (below `depth` levels already).
fn record_size(value: &Dynamic, depth: usize) -> Option<u64> {
    if depth > sandbox::MAX_RECORD_DEPTH {
        return None;
    }
    if let Some(array) = value.read_lock::<Array>() {
        let mut size = 1;
        for item in array.iter() {
            size += record_size(item, depth + 1)?;
        }
        return Some(size);
    }
    if let Some(map) = value.read_lock::<Map>() {
        let mut size = 1;
        for (key, item) in map.iter() {
            size += key.len() as u64 / 16 + record_size(item, depth + 1)?;
        }
        return Some(size);
    }
    if let Some(blob) = value.read_lock::<rhai::Blob>() {
        return Some(1 + blob.len() as u64 / 16);
    }
    if value.is_string() {
        let bytes = value.clone().into_immutable_string().map_or(0, |s| s.len());
        return Some(1 + bytes as u64 / 16);
    }
    Some(1)
}

/// The message of a call past [`sandbox::MAX_OPERATIONS`].
fn call_budget() -> String {
    format!(
        "the controller exceeded {} operations in one call (an endless loop, perhaps in a \
         `sort` comparator?)",
        sandbox::MAX_OPERATIONS
    )
}

/// Line and column of the definition `fn controller_function` in `source`.
fn definition(source: &str) -> Option<(usize, usize)> {
    source.lines().enumerate().find_map(|(index, line)| {
        let at = line.find("fn ")?;
        let rest = line[at + 3..].trim_start();
        rest.strip_prefix(CONTROLLER_FUNCTION)
            .filter(|after| after.trim_start().starts_with('('))
            .map(|_| (index + 1, line[..at].chars().count() + 1))
    })
}

/// A controller script, compiled and checked.
#[derive(Debug, Clone)]
pub struct ControllerScript {
    file: PathBuf,
    ast: AST,
    parameters: usize,
    definition: Option<(usize, usize)>,
    constants: Vec<(String, f64)>,
    /// `controller_function` compiled (module documentation), or why the interpreter runs it.
    compiled: Result<Compiled, String>,
}

impl ControllerScript {
    /// Compiles `source` (read from `file`, which names it in errors) and checks that it
    /// defines `controller_function` with 6, 7 or 8 parameters (RocketPy's forms without and
    /// with `sensors` and `environment`).
    ///
    /// # Errors
    /// [`ScriptError`] at the position of a syntax error, an undefined variable or module, a
    /// missing or misshapen `controller_function`.
    pub fn compile(file: &Path, source: &str) -> Result<Self, ScriptError> {
        let engine = sandbox::engine(&sandbox::motor_module(0.0, 0.0));
        let ast = engine
            .compile(source)
            .map_err(|e| located(file, e.position(), e.err_type().to_string()))?;
        let definitions: Vec<usize> = ast
            .iter_functions()
            .filter(|f| f.name == CONTROLLER_FUNCTION)
            .map(|f| f.params.len())
            .collect();
        let parameters = match definitions.as_slice() {
            [n @ 6..=8] => *n,
            [] => {
                return Err(ScriptError {
                    file: file.to_owned(),
                    position: None,
                    message: format!(
                        "the script defines no `{CONTROLLER_FUNCTION}(time, sampling_rate, state, \
                         state_history, observed_variables, air_brakes[, sensors[, environment]])`"
                    ),
                });
            }
            _ => {
                return Err(ScriptError {
                    file: file.to_owned(),
                    position: None,
                    message: format!(
                        "`{CONTROLLER_FUNCTION}` must be defined once, with 6, 7 or 8 parameters \
                         (found {})",
                        definitions
                            .iter()
                            .map(usize::to_string)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                });
            }
        };
        let constants = ast
            .iter_literal_variables(true, false)
            .filter_map(|(name, _, value)| value.as_float().ok().map(|v| (name.to_owned(), v)))
            .collect();
        let compiled = compiled::compile(&ast, CONTROLLER_FUNCTION);
        Ok(ControllerScript {
            file: file.to_owned(),
            ast,
            parameters,
            definition: definition(source),
            constants,
            compiled,
        })
    }

    /// The script file.
    #[must_use]
    pub fn file(&self) -> &Path {
        &self.file
    }

    /// Number of parameters of its `controller_function` (6, 7 or 8).
    #[must_use]
    pub fn parameters(&self) -> usize {
        self.parameters
    }

    /// Why the calls of this script run in Rhai's interpreter rather than compiled (the
    /// script uses something outside the compiled subset of the module documentation), or
    /// `None` when they run compiled. Either way the results are the same; the interpreter
    /// is slower.
    #[must_use]
    pub fn interpreted_because(&self) -> Option<&str> {
        self.compiled.as_ref().err().map(String::as_str)
    }

    /// This script with its calls always made by the interpreter (the reference the
    /// compiled calls are tested against).
    #[must_use]
    pub fn interpreted(&self) -> Self {
        Self {
            compiled: Err("interpretation asked for".to_owned()),
            ..self.clone()
        }
    }

    /// The script's top-level `const NAME = <float>;` declarations, in order: the constants a
    /// mission may set (`[rocket.air_brakes.constants]`).
    #[must_use]
    pub fn constants(&self) -> &[(String, f64)] {
        &self.constants
    }
}

/// Everything a flight's controller is made from besides its script.
#[derive(Clone)]
pub struct ControllerSetup {
    /// Calls per second.
    pub sampling_rate: f64,
    /// The air brakes it drives.
    pub air_brakes: AirBrakesSetup,
    /// `motor::burn_start_time`, s.
    pub burn_start: f64,
    /// `motor::burn_out_time`, s.
    pub burn_out: f64,
    /// The environment queries of the `environment` argument.
    pub environment: Arc<dyn EnvironmentQuery>,
    /// The record's first entry (`initial_observed_variables`), if given.
    pub initial_observed_variables: Option<Vec<f64>>,
    /// Values replacing the script's top-level constants of these names.
    pub constants: Vec<(String, f64)>,
}

/// One call of a controller: its instant and the deployment level after it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevelRecord {
    /// The sampling instant, s.
    pub time: f64,
    /// The deployment level the call left.
    pub level: f64,
}

/// What a flight's controller recorded.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ControllerRecord {
    /// RocketPy's `observed_variables`: `initial_observed_variables` when given, then every
    /// value other than `()` the script returned, in call order.
    pub observed_variables: Vec<serde_json::Value>,
    /// The level after each call, in call order.
    pub levels: Vec<LevelRecord>,
}

impl ControllerRecord {
    /// The record as JSON: `{"calls": [[time, level], ...], "observed_variables": [...]}`,
    /// one `calls` row per call with the level it left, the observed variables in record
    /// order (what `simulate --json` and `controller.json` hold).
    #[must_use]
    pub fn to_json(&self) -> serde_json::Value {
        let number =
            |v: f64| serde_json::Number::from_f64(v).map_or(serde_json::Value::Null, Into::into);
        serde_json::json!({
            "calls": self
                .levels
                .iter()
                .map(|r| serde_json::Value::Array(vec![number(r.time), number(r.level)]))
                .collect::<Vec<_>>(),
            "observed_variables": self.observed_variables,
        })
    }
}

/// A flight's controller: the compiled script bound to its air brakes and environment.
pub struct Controller {
    engine: Engine,
    ast: AST,
    file: PathBuf,
    parameters: usize,
    definition: Option<(usize, usize)>,
    sampling_rate: f64,
    air_brakes: AirBrakesHandle,
    environment: EnvironmentHandle,
    observed: Vec<Dynamic>,
    /// The size of `observed` as its budget counts it ([`record_size`]).
    observed_size: u64,
    levels: Vec<LevelRecord>,
    /// The operations of the interpreted calls, and the budgets they exceeded.
    meter: Arc<Meter>,
    /// The scope the calls run in, kept between calls for its storage: a call pushes the
    /// arguments and its local variables and the scope is rewound to empty after it.
    scope: Scope<'static>,
    /// The compiled calls, when the script is in the compiled subset.
    fast: Option<Bound>,
    /// Calls made compiled.
    compiled_calls: usize,
    /// The `sensors` argument: one handle per sensor, in the mission's order, built once
    /// ([`Controller::with_sensors`]); each call hands the script a copy of the array.
    sensors: Array,
    /// The handles of `sensors`, which [`Controller::set_sensor`] writes.
    sensor_handles: Vec<SensorHandle>,
}

impl fmt::Debug for Controller {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Controller")
            .field("file", &self.file)
            .field("sampling_rate", &self.sampling_rate)
            .field("level", &self.air_brakes.level())
            .field("calls", &self.levels.len())
            .finish_non_exhaustive()
    }
}

impl Controller {
    /// A controller flying `script` with `setup`; the level starts at the setup's initial
    /// level (clipped when the brakes clamp).
    ///
    /// # Errors
    /// [`ScriptError`] when a constant of `setup` is not one of the script's top-level
    /// constants.
    pub fn new(script: &ControllerScript, setup: ControllerSetup) -> Result<Self, ScriptError> {
        let mut engine = sandbox::engine(&sandbox::motor_module(setup.burn_start, setup.burn_out));
        for (name, _) in &setup.constants {
            if !script.constants.iter().any(|(n, _)| n == name) {
                return Err(ScriptError {
                    file: script.file.clone(),
                    position: None,
                    message: format!(
                        "the mission sets the constant `{name}`, which the script does not \
                         declare (`const {name} = ...;` at its top level)"
                    ),
                });
            }
        }
        let meter = Arc::new(Meter::new());
        let counter = Arc::clone(&meter);
        engine.on_progress(move |_| counter.operation());
        // The top-level statements run once per flight; the constants they leave are what
        // `global::NAME` reads inside functions, the mission's values replacing the script's.
        let mut scope = Scope::new();
        meter.start();
        let result = engine.run_ast_with_scope(&mut scope, &script.ast);
        metered(&script.file, None, &meter, result)?;
        let mut globals = Module::new();
        for (name, constant, value) in scope.iter() {
            if constant {
                globals.set_var(name, value);
            }
        }
        for (name, value) in &setup.constants {
            globals.set_var(name.as_str(), *value);
        }
        let (burn_start, burn_out) = (setup.burn_start, setup.burn_out);
        let fast = script.compiled.as_ref().ok().and_then(|compiled| {
            compiled.bind(|namespace, name| match (namespace, name) {
                (GLOBAL, _) => globals.get_var(name),
                ("motor", "burn_start_time") => Some(Dynamic::from_float(burn_start)),
                ("motor", "burn_out_time") => Some(Dynamic::from_float(burn_out)),
                _ => None,
            })
        });
        engine.register_static_module(GLOBAL, globals.into());
        let ast = script.ast.clone_functions_only();
        let air_brakes = AirBrakesHandle::new(setup.air_brakes);
        let observed: Vec<Dynamic> = setup
            .initial_observed_variables
            .map(|values| {
                values
                    .into_iter()
                    .map(Dynamic::from_float)
                    .collect::<Array>()
                    .into()
            })
            .into_iter()
            .collect();
        Ok(Controller {
            engine,
            ast,
            file: script.file.clone(),
            parameters: script.parameters,
            definition: script.definition,
            sampling_rate: setup.sampling_rate,
            air_brakes,
            environment: EnvironmentHandle(setup.environment),
            observed_size: observed
                .iter()
                .map(|v| record_size(v, 0).unwrap_or(0))
                .sum(),
            observed,
            levels: Vec::new(),
            meter,
            scope: Scope::new(),
            fast,
            compiled_calls: 0,
            sensors: Array::new(),
            sensor_handles: Vec::new(),
        })
    }

    /// This controller with the rocket's sensors as its `sensors` argument, in order (each a
    /// `Sensor` with `name`, `kind`, `measurement` and `time`; mission-format.md, "The
    /// controller script"); without this call `sensors` is empty. A script that reads
    /// `sensors` runs in the interpreter (module documentation, "Compiled calls").
    #[must_use]
    pub fn with_sensors(mut self, sensors: &[SensorSetup]) -> Self {
        self.sensor_handles = sensors.iter().map(SensorHandle::new).collect();
        self.sensors = self
            .sensor_handles
            .iter()
            .map(|h| Dynamic::from(h.clone()))
            .collect();
        self
    }

    /// Number of sensors of the `sensors` argument.
    #[must_use]
    pub fn sensor_count(&self) -> usize {
        self.sensor_handles.len()
    }

    /// Stores the latest reading of sensor `index` (of [`Controller::with_sensors`]'s list),
    /// taken at `time`: what the next calls see as its `measurement` (the first
    /// `components` of `values`) and `time`. Before the first store a sensor's `measurement`
    /// and `time` are `()`, as RocketPy's `measurement` is `None` before the sensor's first
    /// reading. An index past the list is ignored. Allocation-free.
    pub fn set_sensor(&mut self, index: usize, time: f64, values: [f64; 3]) {
        if let Some(handle) = self.sensor_handles.get(index) {
            handle.set(time, values);
        }
    }

    /// This controller with a budget of `operations` for its flight's interpreted calls
    /// instead of [`sandbox::MAX_FLIGHT_OPERATIONS`] (the per-call limit still applies).
    #[must_use]
    pub fn with_operation_budget(self, operations: u64) -> Self {
        self.meter.budget.store(operations, Ordering::Relaxed);
        self
    }

    /// Calls per second.
    #[must_use]
    pub fn sampling_rate(&self) -> f64 {
        self.sampling_rate
    }

    /// How many calls so far ran compiled (module documentation), the others in Rhai's
    /// interpreter.
    #[must_use]
    pub fn compiled_calls(&self) -> usize {
        self.compiled_calls
    }

    /// The current deployment level.
    #[must_use]
    pub fn level(&self) -> f64 {
        self.air_brakes.level()
    }

    /// Calls the script at sampling instant `time` with the state there and the last stored
    /// solution row `[t, x, …, wz]`; returns the deployment level it leaves. A script of the
    /// compiled subset runs compiled (module documentation), any call the compiled form cannot
    /// decide (and every call of another script) in Rhai's interpreter, with the same result.
    ///
    /// # Errors
    /// [`ScriptError`] located in the script for any run-time error (a type error, a limit of
    /// the sandbox such as its operation count).
    pub fn call(
        &mut self,
        time: f64,
        state: &[f64; 13],
        last_row: &[f64; 14],
    ) -> Result<f64, ScriptError> {
        if let Some(fast) = &mut self.fast {
            let inputs = Inputs {
                time,
                sampling_rate: self.sampling_rate,
                state,
                last_row,
                air_brakes: &self.air_brakes.setup,
                environment: &*self.environment.0,
            };
            if let Ok((returned, level)) = fast.call(&inputs, self.air_brakes.level()) {
                self.air_brakes.set_level(level);
                self.compiled_calls += 1;
                return self.recorded(time, returned);
            }
        }
        self.interpret(time, state, last_row)
    }

    /// The record of a call that returned `returned`: the level it left.
    ///
    /// # Errors
    /// [`ScriptError`] at the definition of `controller_function` when `returned` nests
    /// deeper than [`sandbox::MAX_RECORD_DEPTH`] or the record would exceed
    /// [`sandbox::MAX_RECORD_VALUES`]; the record is left as it was.
    fn recorded(&mut self, time: f64, returned: Dynamic) -> Result<f64, ScriptError> {
        if !returned.is_unit() {
            let fail = |message: String| ScriptError {
                file: self.file.clone(),
                position: self.definition,
                message: format!("in `{CONTROLLER_FUNCTION}`: {message}"),
            };
            let Some(size) = record_size(&returned, 0) else {
                return Err(fail(format!(
                    "the call at t = {time} s returned arrays or maps nested deeper than {} levels",
                    sandbox::MAX_RECORD_DEPTH
                )));
            };
            let total = self.observed_size.saturating_add(size);
            if total > sandbox::MAX_RECORD_VALUES {
                return Err(fail(format!(
                    "the values the controller returned exceed the record's budget of {} values \
                     per flight at t = {time} s (call {}, which returned {size}); every value \
                     returned is kept for the whole flight, so return only what must be kept",
                    sandbox::MAX_RECORD_VALUES,
                    self.levels.len() + 1
                )));
            }
            self.observed_size = total;
            self.observed.push(returned);
        }
        let level = self.air_brakes.level();
        self.levels.push(LevelRecord { time, level });
        Ok(level)
    }

    /// [`Controller::call`] in Rhai's interpreter.
    fn interpret(
        &mut self,
        time: f64,
        state: &[f64; 13],
        last_row: &[f64; 14],
    ) -> Result<f64, ScriptError> {
        let floats = |values: &[f64]| -> Dynamic {
            values
                .iter()
                .map(|&v| Dynamic::from_float(v))
                .collect::<Array>()
                .into()
        };
        let history: Array = vec![floats(last_row)];
        let observed: Array = self.observed.last().cloned().into_iter().collect();
        let mut args: Vec<Dynamic> = vec![
            Dynamic::from_float(time),
            Dynamic::from_float(self.sampling_rate),
            floats(state),
            history.into(),
            observed.into(),
            Dynamic::from(self.air_brakes.clone()),
        ];
        if self.parameters >= 7 {
            args.push(self.sensors.clone().into());
        }
        if self.parameters >= 8 {
            args.push(Dynamic::from(self.environment.clone()));
        }
        self.meter.start();
        let result = self.engine.call_fn_with_options::<Dynamic>(
            CallFnOptions::new().eval_ast(false).rewind_scope(true),
            &mut self.scope,
            &self.ast,
            CONTROLLER_FUNCTION,
            args,
        );
        let returned = metered(&self.file, self.definition, &self.meter, result)?;
        self.recorded(time, returned)
    }

    /// What the controller recorded so far.
    #[must_use]
    pub fn record(&self) -> ControllerRecord {
        ControllerRecord {
            observed_variables: self.observed.iter().map(to_json).collect(),
            levels: self.levels.clone(),
        }
    }
}

/// A recorded value as JSON: numbers, booleans, strings, arrays and maps (keys sorted, as Rhai
/// keeps them); a non-finite number or another type becomes `null` or its text.
#[must_use]
pub fn to_json(value: &Dynamic) -> serde_json::Value {
    use serde_json::Value;
    if value.is_unit() {
        return Value::Null;
    }
    if let Ok(v) = value.as_float() {
        return serde_json::Number::from_f64(v).map_or(Value::Null, Value::Number);
    }
    if let Ok(v) = value.as_int() {
        return Value::from(v);
    }
    if let Ok(v) = value.as_bool() {
        return Value::Bool(v);
    }
    if let Ok(v) = value.as_char() {
        return Value::String(v.to_string());
    }
    if value.is_string() {
        return Value::String(value.to_string());
    }
    if let Some(array) = value.read_lock::<Array>() {
        return Value::Array(array.iter().map(to_json).collect());
    }
    if let Some(map) = value.read_lock::<Map>() {
        return Value::Object(
            map.iter()
                .map(|(k, v)| (k.to_string(), to_json(v)))
                .collect(),
        );
    }
    Value::String(value.to_string())
}
