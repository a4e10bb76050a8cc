//! # karman-propulsion
//!
//! Rocket motors as RocketPy 1.13 models them (physics.md §5–§6; rocketpy/motors/*.py):
//!
//! - thrust data from RASP `.eng` ([`eng`]), RockSim `.rse` ([`rse`]) and two-column CSV
//!   ([`csv`]) files, inline tables or a constant ([`ThrustData`], [`ThrustSource`]);
//! - thrust-curve processing — burn interval, reshape, clipping, total impulse
//!   ([`ThrustCurve`]);
//! - the [`Motor`]: a solid motor with BATES grains ([`BatesGrains`]), a generic motor
//!   ([`CylindricalChamber`]) or no motor ([`Motor::empty`]), with its propellant mass,
//!   centre of mass and inertia tables and the derived motor mass properties.
//!
//! Motor types plug in through [`PropellantModel`], so hybrid and liquid motors can be added
//! without touching the thrust processing or the accessors. Everything is SI; tables are built
//! once and evaluated without allocation.

pub mod csv;
mod data;
pub mod eng;
mod error;
mod file;
mod generic;
mod motor;
mod propellant;
pub mod rse;
mod solid;
mod thrust;

pub use data::{MotorHeader, ThrustData, ThrustFormat};
pub use error::PropulsionError;
pub use generic::CylindricalChamber;
pub use motor::{CoordinateSystem, Motor, MotorKind, MotorStructure};
pub use propellant::{PropellantModel, PropellantTables};
pub use solid::{BatesGrains, GrainState};
pub use thrust::{BurnTime, ThrustCurve, ThrustOptions, ThrustSource};
