//! # karman-math
//!
//! The mathematical bottom layer of karman: everything the physics crates need to turn
//! tabulated data and formulas into functions they can evaluate cheaply in the equations of
//! motion (the role of RocketPy's `Function` class, Ceotto et al. 2021, §"Function").
//! It depends on no other karman crate.
//!
//! - [`constants`]: every physical constant of the model, in one [`PhysicalConstants`] value
//!   that can be expressed in a scaled unit system ([`Units`]) for dimensional-analysis tests.
//! - [`dimensions`]: test support for those tests (random unit systems, dimensions, scaled
//!   comparisons); nothing in it runs during a simulation.
//! - [`Table1`] (module `table`): a tabulated function of one variable with linear, natural
//!   cubic spline, Akima (1970, RocketPy 1.13's `"akima"`), or polynomial interpolation and
//!   constant, natural or zero extrapolation; repeated abscissae for linear tables
//!   ([`Table1::linear_stepwise`]); allocation-free `O(log n)` evaluation, or `O(1)` along
//!   monotone query sequences with a [`Cursor`]; exact derivatives, integrals and inverse.
//! - [`Function`] (module `function`): a constant, a table, a closure or an expression of
//!   those with `+ − × ÷` (`std::ops`, owned or borrowed, with `f64` on either side),
//!   composition, derivative, integral, minimum/maximum.
//! - [`quadrature`]: adaptive Gauss–Kronrod (21-point) quadrature, QUADPACK style.
//! - [`RegularGrid`] and [`ScatteredTable`] (module `grid`): functions of several variables
//!   (multilinear on a grid; inverse-distance weighting on scattered points).
//! - [`TriangulatedTable`] (module `triangulated`): scattered data of two variables, linear on
//!   the Delaunay triangulation and a thin-plate spline outside the hull (RocketPy's linear
//!   two-variable `Function`, used for fluid densities).
//! - [`geodesy`]: latitude/longitude of an east/north offset (great-circle destination).
//! - [`text`]: user text and numbers as error messages quote them (cut to one line).
//! - [`csv`]: numeric columns and `[x, y]` curves from text files, with errors that name the
//!   file, line, column and text ([`CsvError`]).
//! - [`files`]: data files given as bytes ([`files::FileSet`]), read instead of the file
//!   system while installed on a thread (a browser page has no file system).
//!
//! Linear algebra (the Vandermonde solve of polynomial interpolation, the thin-plate spline) uses `nalgebra`'s LU
//! decomposition with partial pivoting. All quantities are SI `f64`.
//!
//! ```
//! use karman_math::{Extrapolation, Function, Interpolation, Table1};
//!
//! // A thrust curve: linear, zero outside the burn.
//! let thrust = Table1::new(
//!     vec![0.0, 0.1, 2.0, 2.5],
//!     vec![0.0, 1500.0, 1200.0, 0.0],
//!     Interpolation::Linear,
//!     Extrapolation::Zero,
//! )?;
//! let impulse = thrust.integral(0.0, 2.5); // exact trapezoid: 2 940 N·s
//! assert!((impulse - 2940.0).abs() < 1e-9);
//! // Mass flow −T/v̄_e (folds into a table) and the propellant burnt, 1.47 kg.
//! let mdot = -Function::table(thrust) / 2000.0;
//! assert!((mdot.eval(2.0) + 0.6).abs() < 1e-12);
//! assert!((mdot.integral(0.0, 2.5)?.value + 1.47).abs() < 1e-12);
//! // Expressions of tables and closures: integrated by Gauss–Kronrod, split at the nodes.
//! let weighted = &mdot * Function::analytic(|t| t);
//! let peak = mdot.minimum(0.0, 2.5)?; // the most negative flow, at t = 0.1 s
//! assert!((peak.x - 0.1).abs() < 1e-12 && weighted.integral(0.0, 2.5)?.value < 0.0);
//! # Ok::<(), karman_math::MathError>(())
//! ```

pub mod constants;
pub mod csv;
pub mod dimensions;
mod error;
pub mod files;
mod function;
pub mod geodesy;
mod grid;
pub mod quadrature;
mod table;
pub mod text;
mod triangulated;

pub use constants::{PhysicalConstants, Units};
pub use csv::{CurveRows, read_columns, read_curve, read_data_file, read_rows};
pub use error::{CsvError, MathError};
pub use function::{Extremum, Function};
pub use grid::{MAX_GRID_DIMENSIONS, RegularGrid, ScatteredTable};
pub use quadrature::{Quadrature, QuadratureOptions, integrate};
pub use table::{
    Cursor, Extrapolation, Interpolation, Location, Piece, PointOrder, Table1, interpolate_clamped,
    linspace,
};
pub use triangulated::TriangulatedTable;

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
