//! # karman-dynamics
//!
//! The 6-DOF flight engine: equations of motion for the rail, free flight and parachute
//! phases, events, and the adaptive Runge–Kutta integrator with dense output. It reproduces
//! RocketPy 1.13's `Flight` (docs/physics.md §2–§3, §8–§11).
//!
//! - [`integrator`]: the Dormand–Prince pairs DOPRI5 and DOP853 with dense output, fixed-size
//!   state, no allocation.
//! - [`equations`]: rail, 6-DOF variable-mass, 3-DOF point-mass and parachute right-hand
//!   sides.
//! - The models it flies are the interfaces of karman-model ([`AtmosphereModel`],
//!   [`VehicleModel`], [`SurfaceModel`]), re-exported here; karman-atmos, karman-airframe and
//!   test mocks implement them.
//! - [`flight`]: phases, events, sampled processes and actions; [`simulate`] flies a rocket,
//!   [`simulate_from`] resumes a flight from a given state.
//! - [`output`]: post-processed samples and the [`Summary`] of the mission contract.

// The integration tests' analytic models (an exponential atmosphere, a stable 10 kg rocket),
// shared with the unit tests rather than copied; they name this crate.
#[cfg(test)]
extern crate self as karman_dynamics;
#[cfg(test)]
#[allow(dead_code)]
#[path = "../tests/mock.rs"]
mod mock;

pub mod equations;
mod error;
pub mod flight;
pub mod integrator;
pub mod noise;
pub mod output;
pub mod settings;
pub mod state;

pub use error::DynamicsError;
pub use flight::{
    Action, Connections, DenseOutput, Event, Flight, IntegrationStats, ParachuteEvent, PhaseKind,
    Probe, Record, SampledProcess, Signal, SignalId, Signals, SolutionPoint, StepBounds,
    Termination, simulate, simulate_from, simulate_with, simulate_with_events,
};
pub use karman_model::{
    Air, AtmosphereModel, BodyFlow, Configuration, Cursor, Loads, LocalFlow, MAX_CONTROLS,
    MassFlowLaw, MassSample, ParachuteSpec, RailButtonGeometry, StabilityModel, SurfaceModel,
    TriggerKind, VehicleModel, VehicleSetup,
};
pub use output::{EventRecord, Sample, Summary};
pub use settings::{DEFAULT_ATOL, EquationsForm, FlightSettings, SimulationMode};

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
