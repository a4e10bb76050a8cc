//! # karman-dynamics
//!
//! The 6-DOF flight engine: equations of motion for the rail, free flight and parachute
//! phases, events, and the adaptive Runge–Kutta integrator with dense output. It reproduces
//! RocketPy 1.13's `Flight` (physics.md §2–§3, §8–§11).
//!
//! - [`integrator`]: the Dormand–Prince pairs DOPRI5 and DOP853 with dense output, fixed-size
//!   state, no allocation.
//! - [`equations`]: rail, 6-DOF variable-mass and parachute right-hand sides.
//! - [`model`]: the [`AtmosphereModel`] / [`VehicleModel`] traits the engine evaluates
//!   (implemented for karman-atmos' `Environment` and karman-airframe's `Rocket` in
//!   [`adapters`]).
//! - [`flight`]: phases, time nodes and events; [`simulate`] flies a rocket.
//! - [`output`]: post-processed samples and the [`Summary`] of the mission contract.

// The integration tests' analytic models (an exponential atmosphere, a stable 10 kg rocket),
// shared with the unit tests rather than copied; they name this crate.
#[cfg(test)]
extern crate self as karman_dynamics;
#[cfg(test)]
#[allow(dead_code)]
#[path = "../tests/mock.rs"]
mod mock;

pub mod adapters;
pub mod equations;
mod error;
pub mod flight;
pub mod integrator;
pub mod model;
pub mod noise;
pub mod output;
pub mod settings;
pub mod state;

pub use error::DynamicsError;
pub use flight::{
    Flight, IntegrationStats, ParachuteEvent, PhaseKind, SolutionPoint, Termination, simulate,
};
pub use model::{
    Air, AtmosphereModel, MassSample, ParachuteSpec, RailButtonGeometry, SurfaceModel, TriggerKind,
    VehicleModel,
};
pub use output::{EventRecord, Sample, Summary};
pub use settings::{DEFAULT_ATOL, FlightSettings};
