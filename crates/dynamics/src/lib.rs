//! # karman-dynamics
//!
//! The 6-DOF flight engine: equations of motion for the rail, free flight and parachute
//! phases, events, and the adaptive Runge–Kutta integrator with dense output.
