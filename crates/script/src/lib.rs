//! # karman-script
//!
//! The scripts a karman mission may carry, kept out of the flight engine:
//!
//! - [`expression`]: parachute trigger expressions (`trigger = { expression = "vz < 5.0 &&
//!   z > 300.0" }`), RocketPy's `trigger(p, h, y)` callables as one boolean expression of the
//!   common subset of Rhai and Python, parsed and type-checked once, evaluated without
//!   allocation.
//! - [`controller`]: air-brake controllers, RocketPy's `controller_function` written in Rhai
//!   (the `rhai` crate), compiled once per mission and run sandboxed
//!   ([`sandbox`]: no file, network, clock or module access; bounded operations, call depth
//!   and data sizes per call); a script of the controllers' common subset also compiled to a
//!   natively evaluated tree with Rhai's semantics, the interpreter making whatever that tree
//!   cannot decide (module `controller`, "Compiled calls").
//! - Air-brake controllers written in Rust ([`AirBrakeController`]), called by the flight
//!   exactly as the Rhai ones are ([`NativeController`]).
//!
//! ```
//! use karman_script::ControllerScript;
//! use std::path::Path;
//!
//! let script = ControllerScript::compile(
//!     Path::new("brakes.rhai"),
//!     "fn controller_function(time, sampling_rate, state, state_history, \
//!                             observed_variables, air_brakes) {
//!          air_brakes.deployment_level = if time > motor::burn_out_time { 1.0 } else { 0.0 };
//!          return [time, air_brakes.deployment_level];
//!      }",
//! )?;
//! assert_eq!(script.parameters(), 6);
//! # Ok::<(), karman_script::ScriptError>(())
//! ```

mod arguments;
mod compiled;
pub mod controller;
pub mod expression;
mod native;
pub mod sandbox;

pub use arguments::stored_level;
pub use controller::{
    AirBrakesSetup, Controller, ControllerRecord, ControllerScript, ControllerSetup,
    EnvironmentQuery, LevelRecord, ScriptError, SensorSetup,
};
pub use expression::{Expression, ExpressionError, SensorShape, TriggerInputs};
pub use native::{
    AirBrakeController, AirBrakesControl, ControlInputs, NativeController, NativeError,
    SensorReading,
};

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
