//! # karman-dispersion
//!
//! Monte Carlo dispersion: reproducible sampling of uncertain inputs, many flights in
//! parallel, statistics and 1σ/2σ/3σ apogee and landing ellipses (docs/physics.md §12). The crate
//! knows nothing of rockets: the caller describes the varied inputs ([`VariedInput`]: a
//! name, what it is, a [`Variation`]) and the scalar outputs, and supplies a function that
//! flies one sample from its sampled values.
//!
//! ```
//! use karman_dispersion::{run, Distribution, Outcome, ProgressMode, RunOptions, Study, Target,
//!     Variation, VariedInput};
//!
//! let inputs = vec![
//!     VariedInput::new("mass", Target::Number(10.0), Variation::Std(0.1)),
//!     VariedInput::new("drag", Target::Curve,
//!         Variation::Factor(Distribution::Normal { mean: 1.0, std: 0.05 })),
//! ];
//! let study = Study::new(42, 100, inputs, vec!["apogee_m".to_owned()]);
//! let dir = std::env::temp_dir().join(format!("karman-doc-{}", std::process::id()));
//! let options = RunOptions { threads: Some(2), progress: ProgressMode::Hidden, ..Default::default() };
//! let report = run(&study, &dir, &options, |_index, values: &[f64]| {
//!     let (mass, drag_factor) = (values[0], values[1]);
//!     Ok(Outcome::new(vec![Some(1000.0 / (mass * drag_factor))]))
//! })?;
//! assert_eq!(report.flown, 100);
//! # std::fs::remove_dir_all(&dir).ok();
//! # Ok::<(), karman_dispersion::DispersionError>(())
//! ```
//!
//! Output directory (see [`files`]): `study.lock` (held by the one run writing it),
//! `study.json` (format version, seed, samples, inputs, outputs, data files and fingerprint),
//! `samples.csv` (one row per sample in index order with its status: completed, ended early,
//! failed, and the row's digest keyed by the fingerprint, which resume and merge check),
//! `summary.json`, `dispersion.kml`, `landing.svg`, `apogee_histogram.svg`, each written
//! atomically.
//!
//! - Reproducible: sample `i` draws from streams keyed by (seed, i) ([`sampling`]); the
//!   results are byte-identical for any thread count, shard split or interruption.
//! - Resumable: rerunning [`run`] in the same directory keeps the complete rows (dropping a
//!   partial last line), refuses a different study or an edited row (its digest:
//!   [`DispersionError::TamperedRow`]), removes the temporary files of a killed run, and
//!   flies the rest.
//! - Shardable: [`RunOptions::shard`] `K/N` flies the samples with `index % N == K − 1`;
//!   [`merge`] joins the shard directories into the files of a single run.

pub mod convergence;
mod csv;
mod distribution;
mod error;
pub mod files;
mod kml;
mod merge;
mod plot;
mod progress;
mod regular;
mod runner;
pub mod sampling;
mod sensitivity;
mod sobol;
mod stats;
mod study;
mod summary;
mod tolerance;

pub use csv::{Counts, Row, Status, parse as parse_row};
pub use distribution::{
    Distribution, Meaning, TRUNCATION_MIN_SHARE, Target, Variation, VariedInput,
};
pub use error::DispersionError;
pub use kml::offset_to_lat_lon;
pub use merge::merge;
pub use plot::sensitivity_bars;
pub use progress::ProgressMode;
pub use runner::{
    MAX_THREADS_PER_CORE, MemoryRun, Outcome, RunOptions, RunReport, WINDOW_PER_THREAD, run,
    run_in_memory, run_until, sample_lines, samples_header,
};
pub use sensitivity::{
    InputShare, OutputSensitivity, Sensitivity, Skipped, decompose, sensitivity,
    sensitivity_of_rows,
};
pub use sobol::{OutputIndices, SobolIndices, saltelli_design, sobol, sobol_indices, sobol_study};
pub use stats::{
    Ellipse, Moments, NORMAL_SIGMA_PROBABILITY, Statistics, k_sigma_probability, probability_scale,
    quantile,
};
pub use study::{BodyPoints, DataFile, Points, Shard, Site, Study};
pub use summary::{Column, Contour, EllipseSummary, Failure, Summary, summarize, summarize_rows};
pub use tolerance::{
    ToleranceBounds, bounds_of, samples_needed, tolerance, tolerance_of_rows, wilks_rank,
};

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
