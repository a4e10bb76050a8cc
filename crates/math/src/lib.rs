//! # karman-math
//!
//! The mathematical bottom layer of karman: everything the physics crates need to turn
//! tabulated data and formulas into functions they can evaluate cheaply in the equations of
//! motion (the role of RocketPy's `Function` class, Ceotto et al. 2021, §"Function").
//!
//! - [`constants`]: every physical constant of the model, in one [`PhysicalConstants`] value
//!   that can be expressed in a scaled unit system ([`Units`]) for dimensional-analysis tests.
//! - [`Table1`]: a tabulated function of one variable with linear, natural cubic spline, Akima
//!   or polynomial interpolation and constant, natural or zero extrapolation; allocation-free
//!   `O(log n)` evaluation.
//!
//! All quantities are SI `f64`.

pub mod constants;
mod error;
mod table;

pub use constants::{PhysicalConstants, Units};
pub use error::MathError;
pub use table::{Extrapolation, Interpolation, Table1, linspace};
