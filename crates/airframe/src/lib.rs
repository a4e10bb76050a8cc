//! # karman-airframe
//!
//! The rocket: mass properties with its motor, Barrowman aerodynamics of its surfaces
//! (Barrowman 1967), centre of pressure, static and stability margins, parachutes.
//!
//! Reproduces RocketPy 1.13's `Rocket`, `NoseCone`, `TrapezoidalFins`, `EllipticalFins`,
//! `FreeFormFins`, `Tail`, `Parachute` and `RailButtons` (see `docs/physics.md` §2.5, §5, §7,
//! §8.4), including its **\[RP\]** conventions: the CM→CDM offset sign, the nozzle gyration
//! tensor, the piecewise compressibility factor of the fin slope and the node-wise
//! construction of time tables.
//!
//! Build a [`Rocket`] from [`RocketInputs`] and the motor's [`MotorProperties`]; the per-step
//! methods the equations of motion call are `#[inline]` and allocation-free.
//!
//! ```
//! use karman_airframe::*;
//! use karman_math::{Extrapolation, Interpolation, Table1};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let grid = vec![0.0, 1.0, 2.0];
//! let table = |ys: Vec<f64>, e| Table1::new(grid.clone(), ys, Interpolation::Linear, e);
//! let motor = MotorProperties {
//!     thrust: table(vec![200.0, 200.0, 200.0], Extrapolation::Zero)?,
//!     burn_start: 0.0,
//!     burn_out: 2.0,
//!     exhaust_velocity: 2000.0,
//!     propellant_mass: table(vec![0.2, 0.1, 0.0], Extrapolation::Constant)?,
//!     mass_flow: None,
//!     propellant_center_of_mass: table(vec![0.15; 3], Extrapolation::Constant)?,
//!     propellant_i11: table(vec![1e-3, 5e-4, 0.0], Extrapolation::Constant)?,
//!     propellant_i33: table(vec![1e-4, 5e-5, 0.0], Extrapolation::Constant)?,
//!     propellant_parts: Vec::new(),
//!     dry_mass: 0.3,
//!     center_of_dry_mass: 0.15,
//!     dry_inertia: [1e-3, 1e-3, 1e-4, 0.0, 0.0, 0.0],
//!     nozzle_position: 0.0,
//!     nozzle_radius: 0.015,
//!     coordinate_system_sign: 1.0,
//!     reference_pressure: None,
//! };
//! let fins = TrapezoidalFinsSpec {
//!     n: 3, root_chord: 0.1, tip_chord: 0.05, span: 0.06, sweep: Sweep::Default,
//!     cant_angle_deg: 0.0, angular_position_deg: 0.0, radius: None, airfoil: None,
//! };
//! let nose = NoseConeSpec { length: 0.25, kind: NoseKind::Ogive, base_radius: None, bluffness: 0.0 };
//! let rocket = Rocket::new(
//!     RocketInputs {
//!         radius: 0.04,
//!         mass: 2.0,
//!         inertia: inertia_components("rocket", &[0.3, 0.3, 0.002])?,
//!         center_of_mass_without_motor: 0.6,
//!         coordinate_system: CoordinateSystem::TailToNose,
//!         power_off_drag: Table1::linear(vec![0.0, 1.0], vec![0.45, 0.55])?,
//!         power_on_drag: Table1::linear(vec![0.0, 1.0], vec![0.40, 0.50])?,
//!         motor_position: 0.0,
//!         surfaces: vec![
//!             SurfaceInput { name: "nose".into(), position: 1.3, spec: SurfaceSpec::Nose(nose), pod: None },
//!             SurfaceInput { name: "fins".into(), position: 0.12, spec: SurfaceSpec::TrapezoidalFins(fins), pod: None },
//!         ],
//!         parachutes: Vec::new(),
//!         rail_buttons: None,
//!         eccentricities: Eccentricities::default(),
//!     },
//!     motor,
//! )?;
//! assert!(rocket.warnings().is_empty());
//! assert!(rocket.static_margin(0.0) > 0.0, "stable: CP aft of the CM");
//! assert!((rocket.total_mass(0.0) - 2.5).abs() < 1e-12);
//! # Ok(())
//! # }
//! ```

pub mod air_brakes;
pub mod drag;
mod error;
mod mass;
mod model;
mod motor;
mod recovery;
mod rigid;
mod rocket;
pub mod surfaces;

pub use air_brakes::{AIR_BRAKES_CONTROL, AirBrakes, AirBrakesDrag, AirBrakesSpec};
pub use drag::{
    BodyLift, BodySegment, DragComponents, DragEstimate, DragGeometry, DragModel, FinCrossSection,
    FinSetDrag, FlowReference, LaunchLug, PodDrag, Profile, RailButtonDrag, TubeFinSetDrag,
};
pub use error::AirframeError;
/// What fires a parachute: the engine's own trigger kind (one definition, karman-model).
pub use karman_model::TriggerKind;
pub use motor::MotorProperties;
pub use recovery::{
    DEFAULT_CANOPY_DRAG_COEFFICIENT, DEFAULT_POROSITY, DEFAULT_SAMPLING_RATE, Parachute,
    ParachuteSpec, RailButtons,
};
pub use rigid::RigidMass;
pub use rocket::{CoordinateSystem, Eccentricities, Rocket, RocketInputs, inertia_components};
pub use surfaces::{
    Airfoil, AngleUnit, EllipticalFinsSpec, FinAerodynamics, FreeFormFinsSpec, Geometry,
    NoseConeSpec, NoseKind, PodPlacement, Surface, SurfaceInput, SurfaceSpec, Sweep, TailSpec,
    TrapezoidalFinsSpec, TubeFinsSpec,
};

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
