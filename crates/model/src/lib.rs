//! # karman-model
//!
//! The interfaces the flight engine (karman-dynamics) flies: the crates that
//! own the physical models (karman-atmos, karman-airframe, or a test's analytic mock) implement
//! them, and the engine depends on this crate only.
//!
//! - [`AtmosphereModel`]: air, wind, gravity and Earth rotation at a height (docs/physics.md §4).
//! - [`VehicleModel`]: a [`VehicleSetup`] read once (burn window, thrust knots, rail buttons,
//!   recovery devices, dry mass, nozzle), and the per-step quantities: mass properties (or
//!   the total mass alone), thrust, the axial aerodynamic load given the flow and the
//!   [`Configuration`] (docs/physics.md §5–§7).
//! - [`StabilityModel`]: the stability margin the flight's reports read (§7.7); the
//!   equations never call it.
//! - [`SurfaceModel`]: one aerodynamic surface whose force law lives in the surface:
//!   [`SurfaceModel::loads`] turns the [`LocalFlow`] at its centre of pressure into
//!   [`Loads`] (docs/physics.md §7.2, §7.6), so a surface with its own coefficient tables is one
//!   more implementation.
//! - [`Configuration`]: what can change during a flight without changing the equations'
//!   form — control inputs (an air-brake deployment level) and the recovery devices deployed.
//! - [`PropellantPart`]: the one piece of plain data shared by the motor crate, which makes
//!   it, and the vehicle crate, which sums it (neither may depend on the other).
//!
//! Contract of every per-step method: no allocation, and a value that depends on its
//! arguments only. Table lookups take a [`Cursor`] that the caller keeps between evaluations
//! (updated by the lookup); the values are the same whatever it holds, only the search is
//! shorter when successive arguments are close.
//!
//! ```
//! use karman_model::{Configuration, LocalFlow, Loads, SurfaceModel};
//!
//! /// A surface with a constant normal-force slope on the rocket axis, 0.5 m aft of the CDM.
//! struct Fin;
//! impl SurfaceModel for Fin {
//!     fn cp_body(&self) -> [f64; 3] {
//!         [0.0, 0.0, -0.5]
//!     }
//!     fn loads(&self, flow: &LocalFlow) -> Loads {
//!         Loads::normal_force(flow, 0.01, 2.0, -0.5)
//!     }
//! }
//! let flow = LocalFlow {
//!     stream: [1.0, 0.0, -50.0],
//!     speed: 50.01,
//!     mach: 0.147,
//!     density: 1.2,
//!     roll_rate: 0.0,
//! };
//! let loads = Fin.loads(&flow);
//! assert!(loads.force[0] > 0.0 && loads.moment[1] < 0.0);
//! assert_eq!(Configuration::default().control(0), 0.0);
//! ```

mod atmosphere;
mod configuration;
mod propellant;
mod surface;
mod vehicle;

pub use atmosphere::{Air, AtmosphereModel};
pub use configuration::{Configuration, MAX_CONTROLS};
pub use karman_math::Cursor;
pub use propellant::PropellantPart;
pub use surface::{Loads, LocalFlow, SurfaceModel};
pub use vehicle::{
    BodyFlow, MassFlowLaw, MassSample, OffAxis, ParachuteSpec, RailButtonGeometry, StabilityModel,
    TriggerCondition, TriggerKind, VehicleModel, VehicleSetup,
};

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
