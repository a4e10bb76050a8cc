//! # karman-atmos
//!
//! The launch environment: atmosphere (pressure, temperature, density, speed of sound,
//! viscosity), wind and gravity as functions of height above sea level, from the ISA
//! (ISO 2533), custom profiles, soundings and reanalysis/forecast grids.
