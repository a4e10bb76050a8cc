//! # karman-propulsion
//!
//! Rocket motors: thrust curves (RASP `.eng`, RockSim `.rse`, CSV, tables), and the mass,
//! centre of mass and inertia of solid, generic, hybrid and liquid motors over time.
