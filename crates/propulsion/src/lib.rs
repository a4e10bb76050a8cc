//! # karman-propulsion
//!
//! Rocket motors as RocketPy 1.13 models them (docs/physics.md §5–§6; rocketpy/motors/*.py):
//!
//! - thrust data from RASP `.eng` ([`eng`]), RockSim `.rse` ([`rse`]) and two-column CSV
//!   ([`csv`]) files, inline tables or a constant ([`ThrustData`], [`ThrustSource`]);
//! - thrust-curve processing — burn interval, reshape, clipping, total impulse
//!   ([`ThrustCurve`]);
//! - tanks ([`Tank`]): fluids ([`Fluid`]) in a geometry ([`TankGeometry`]: cylinders with or
//!   without spherical caps, spheres, custom profiles) given by their flows, ullage, level or
//!   masses ([`TankKind`]), with liquid and gas masses, heights, centre of mass and inertia
//!   over time (docs/physics.md §15);
//! - the [`Motor`]: a solid motor with BATES grains ([`BatesGrains`]), a generic motor
//!   ([`CylindricalChamber`]), a liquid motor (tanks, [`PositionedTank`]), a hybrid motor (a
//!   grain and tanks) or no motor ([`Motor::empty`]), with its propellant mass, centre of mass
//!   and inertia tables and the derived motor mass properties.
//!
//! Motor types plug in through [`PropellantModel`], without touching the thrust processing or
//! the accessors. Everything is SI; tables are built
//! once and evaluated without allocation.

pub mod csv;
mod data;
pub mod eng;
mod error;
mod file;
mod fluid;
mod generic;
mod hybrid;
mod liquid;
mod motor;
mod propellant;
pub mod rse;
mod solid;
mod tank;
mod tank_geometry;
mod thrust;

pub use data::{MotorHeader, ThrustData, ThrustFormat};
pub use error::PropulsionError;
pub use fluid::{Density, Fluid};
pub use generic::CylindricalChamber;
pub use liquid::PositionedTank;
pub use motor::{CoordinateSystem, Motor, MotorKind, MotorStructure};
pub use propellant::{PropellantModel, PropellantTables};
pub use solid::{BatesGrains, GrainState};
pub use tank::{
    DEFAULT_DISCRETIZE, DEFAULT_PRESSURE, DEFAULT_TEMPERATURE, Tank, TankCurve, TankKind, TankSpec,
};
pub use tank_geometry::{TankGeometry, TankShape};
pub use thrust::{BurnTime, ThrustCurve, ThrustOptions, ThrustSource};

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
