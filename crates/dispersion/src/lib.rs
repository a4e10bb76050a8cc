//! # karman-dispersion
//!
//! Monte Carlo dispersion: reproducible sampling of uncertain inputs, many flights in
//! parallel, statistics and 1σ/2σ/3σ apogee and landing ellipses.
