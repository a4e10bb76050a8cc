//! # karman-airframe
//!
//! The rocket: mass properties with its motor, Barrowman aerodynamics of its surfaces
//! (Barrowman 1967), centre of pressure, static and stability margins, parachutes.
