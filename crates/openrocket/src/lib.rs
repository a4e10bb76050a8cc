//! # karman-openrocket
//!
//! OpenRocket designs for karman: the `.ork` file read ([`read_document`], [`Design`]), turned
//! into a karman mission's TOML text ([`import`]), and the flights OpenRocket stored in it read
//! as reference figures ([`StoredFlight`]) with the acceptance karman's flight of the import is
//! held to ([`OpenRocketComparison`], [`StagedComparison`], [`DesignResult`]).
//!
//! ## Sources
//!
//! The file format is OpenRocket's, as its own reader and writer define it: the element and
//! attribute names of OpenRocket's document (the `OpenRocketSaver` writer and the `importt`
//! readers of `core` in <https://github.com/openrocket/openrocket>, format versions 1.0 to
//! 1.10, release 24.12), read for the element names and units only; no OpenRocket code or text
//! is copied (OpenRocket is GPLv3). The stored flights are the `reference.json` of each folder
//! of `fixtures/openrocket` (its README), extracted from the simulations the `.ork` stores.
//!
//! ## Contract
//!
//! - A file is read only when it is a regular file (a FIFO or `/dev/zero` is refused), its
//!   document at most [`MAX_DOCUMENT_BYTES`] (64 MiB, compressed or decompressed: a zip bomb
//!   stops there), its component tree at most [`MAX_COMPONENT_DEPTH`] (64) deep; the element
//!   text written into the mission is sanitised to one line. Arbitrary bytes give a design or
//!   an [`OrkError`] naming the file and the component, never a panic (the fuzz target
//!   `fuzz/fuzz_targets/ork.rs`).
//! - The mission text is deterministic: the same design, options and thrust curves give the
//!   same bytes.
//! - Nothing here flies a mission: karman-mission flies the import and compares it with the
//!   stored flight (`report::openrocket::compare_folder`); this crate depends on
//!   karman-airframe (body profile shapes) and karman-propulsion (thrust-curve files) only.
//!
//! ## The import
//!
//! [`import`] reads a design ([`read_document`], [`Design::parse`]) and writes the mission for
//! one of its stored simulations ([`ImportOptions`], [`Imported`]). It maps
//! - the body (nose cone, body tubes, transitions) onto a `"nose"` surface and `"tail"`
//!   surfaces, trapezoidal, elliptical and free-form fin sets onto fin surfaces and tube fin
//!   sets onto `"tube_fins"`;
//! - every component's mass, centre of mass and inertia, with OpenRocket's mass and CG
//!   overrides, onto the rocket's mass, centre of mass and inertia without motor
//!   (module `mass`);
//! - parachutes onto `[rocket.parachutes]`, the chosen simulation's launch conditions onto
//!   `[environment]` and `[flight]`, its motor onto a generic `[motor]` whose thrust curve is
//!   found by designation among the given files and folders;
//! - the drag onto `power_off_drag = "estimate"` with `[rocket.drag_estimate]` (finish, fin
//!   thickness and edges, launch lugs, rail buttons).
//!
//! - a design of several stages onto `[[stages]]`: the top stage as `[rocket]` and `[motor]`,
//!   each stage below with its own airframe, motor and drag-estimate table, and OpenRocket's
//!   separation and ignition events (with their delays) as `separation = "burnout + X"` and
//!   `ignition_delay` (module `write`); a motor OpenRocket never lights is carried as mass, and
//!   a stage without a lit motor rides on the stage below (at the bottom, on the stage above
//!   while its separation never fires).
//!
//! - a clustered inner tube onto `[motor] cluster_count` and `cluster_radius`, its copies'
//!   masses with their offsets (`Component::cluster`).
//!
//! - several motor mounts in one stage of a single-stage design onto `[motor]` (the mount lit
//!   first) and `[[extra_motors]]` (each with its ignition delay after launch, OpenRocket's
//!   `automatic`/`launch` events; the launch stage's `burnout`/`ejection` never fire, and those
//!   motors are carried as mass like any motor OpenRocket never lights).
//!
//! - pod sets onto `[rocket.pods]` (their surfaces, and their masses at the pods' offset).
//!
//! Powered pods, parallel boosters and staging events the format cannot express are refused,
//! naming the component; what is mapped approximately is listed in [`Imported::warnings`].

mod acceptance;
mod design;
mod import;
mod mass;
mod stored;
mod write;

pub use acceptance::{
    APOGEE, CD_SUBSONIC, CD_TRANSONIC, CP_FRACTION, Compared, DesignResult, KNOWN_REFUSALS,
    MARGIN_CALIBERS, MAX_SPEED, OpenRocketComparison, Problem, SEPARATION_TIME, STAGED_APOGEE,
    STAGED_APOGEE_EXCEPTIONS, SimulationResult, StagedComparison, known_refusal,
    staged_apogee_exception,
};
pub use design::{
    Component, Design, Kind, MAX_COMPONENT_DEPTH, MotorRef, SeparationRef, Simulation,
};
pub use import::{
    ImportOptions, Imported, MAX_DOCUMENT_BYTES, OrkError, document_text, import, import_bytes,
    read_document,
};
pub use stored::{
    Ascent, RodExit, StoredFlight, design_folders, each_imported_simulation, stage_count,
    stored_flights,
};

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
