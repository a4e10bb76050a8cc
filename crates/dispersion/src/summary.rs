//! `summary.json`, `dispersion.kml` and the plots of a complete study, computed from its
//! `samples.csv` (so a resumed or merged study summarizes exactly as an uninterrupted one).
//!
//! Which samples count where: the input statistics cover every sample (the draws do not
//! depend on how a flight ended); the output statistics, the ellipses, the landing points and
//! the histogram cover the completed flights only (status `ok`), the flights the study asked
//! for. Samples that ended early (`max_time`, `stuck_on_rail`) or failed are counted
//! separately and listed with their messages. A study of several bodies ([`crate::Points`])
//! gets the apogee and landing ellipses of each, in the order of its bodies.
//!
//! Memory does not grow without bound with the number of samples: the quantiles need every
//! value of a column, so columns are read in groups of at most `VALUES_PER_PASS` values
//! (64 MB), one pass over the file per group; the ellipses use running moments; the KML and
//! the scatter plot show at most the first `MAX_DRAWN_POINTS` landing points of each body.

use crate::csv::{Counts, Row};
use crate::error::DispersionError;
use crate::files::{
    self, HISTOGRAM_PLOT_FILE, KML_FILE, LANDING_PLOT_FILE, SAMPLES_FILE, STUDY_FILE, SUMMARY_FILE,
};
use crate::kml;
use crate::plot;
use crate::stats::{
    Ellipse, Moments, NORMAL_SIGMA_PROBABILITY, Statistics, k_sigma_probability, probability_scale,
};
use crate::study::{Record, Shard, Study};
use serde::Serialize;
use std::path::Path;

/// Values held in memory per pass over `samples.csv`.
const VALUES_PER_PASS: u64 = 8 * 1024 * 1024;
/// Samples that did not complete listed by index, status and message in `summary.json` (all
/// are counted).
const MAX_LISTED_FAILURES: usize = 100;
/// Landing points drawn in the KML file and the scatter plot.
const MAX_DRAWN_POINTS: usize = 10_000;

/// The summary of a complete study (`summary.json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// The study's seed.
    pub seed: u64,
    /// Number of samples.
    pub samples: u64,
    /// The samples by how they ended: completed, ended early (per status), failed.
    #[serde(flatten)]
    pub counts: Counts,
    /// The first samples that did not complete (at most 100), in index order.
    pub failures: Vec<Failure>,
    /// Statistics of the sampled inputs (all samples; a factor or offset column as drawn).
    pub inputs: Vec<Column>,
    /// Statistics of the outputs (completed flights where the quantity occurred).
    pub outputs: Vec<Column>,
    /// Apogee and landing ellipses of the completed flights, where the study names their
    /// outputs.
    pub ellipses: Vec<EllipseSummary>,
}

/// A sample that did not complete.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Failure {
    /// Sample index.
    pub index: u64,
    /// Its status: `failed`, or how it ended early (`max_time`, ...).
    pub status: String,
    /// The error or the explanation.
    pub error: String,
}

/// Statistics of one column (`count`, `mean`, `std` (population), `min`, `max`, `median`,
/// `p2_5`, `p97_5`); only the name when no value is finite.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Column {
    /// Column name.
    pub name: String,
    /// Its statistics.
    #[serde(flatten)]
    pub statistics: Option<Statistics>,
}

/// An ellipse in both conventions, 1σ/2σ/3σ.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EllipseSummary {
    /// `apogee` or `landing`.
    pub name: String,
    /// The body whose points these are, in a study of several ([`crate::Points::body`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// Output names of x (east) and y (north).
    pub outputs: [String; 2],
    /// Samples with both values.
    pub points: u64,
    /// Mean point (x, y), m.
    pub center_m: [f64; 2],
    /// Sample covariance (divisor N − 1), m².
    pub covariance_m2: [[f64; 2]; 2],
    /// Direction of the major axis, degrees counter-clockwise from east, in (−90, 90].
    pub orientation_deg: f64,
    /// RocketPy's k-σ contours, k = 1, 2, 3 (`normal_probability`: the share of a bivariate
    /// normal inside, 1 − exp(−k²/2): 39 %, 86 %, 99 %).
    pub k_sigma_rocketpy: Vec<Contour>,
    /// Probability-calibrated contours holding 68.27 %, 95.45 %, 99.73 % of a bivariate
    /// normal (the one-dimensional 1σ/2σ/3σ shares), `k = sqrt(−2 ln(1 − p))`.
    pub probability: Vec<Contour>,
}

/// One contour of an ellipse.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Contour {
    /// Level, 1 to 3.
    pub sigma: u32,
    /// Scale on the square roots of the eigenvalues.
    pub k: f64,
    /// Share of a bivariate normal inside the contour.
    pub normal_probability: f64,
    /// Semi-major axis `k√λ1`, m (RocketPy's width is twice it).
    pub semi_major_m: f64,
    /// Semi-minor axis `k√λ2`, m.
    pub semi_minor_m: f64,
}

impl EllipseSummary {
    fn new(name: &str, body: Option<&str>, outputs: &[String; 2], ellipse: &Ellipse) -> Self {
        let contour = |sigma: u32, k: f64, normal_probability: f64| {
            let [semi_major_m, semi_minor_m] = ellipse.semi_axes(k);
            Contour {
                sigma,
                k,
                normal_probability,
                semi_major_m,
                semi_minor_m,
            }
        };
        EllipseSummary {
            name: name.to_owned(),
            body: body.map(str::to_owned),
            outputs: outputs.clone(),
            points: ellipse.count,
            center_m: ellipse.center,
            covariance_m2: ellipse.covariance,
            orientation_deg: ellipse.orientation_deg,
            k_sigma_rocketpy: (1..=3)
                .map(|s| contour(s, f64::from(s), k_sigma_probability(f64::from(s))))
                .collect(),
            probability: NORMAL_SIGMA_PROBABILITY
                .iter()
                .zip(1..)
                .map(|(&p, s)| contour(s, probability_scale(p), p))
                .collect(),
        }
    }
}

/// Computes the summary of the complete study in `dir` and writes `summary.json`,
/// `dispersion.kml` (when the study has a site and landing points), `landing.svg` and
/// `apogee_histogram.svg` (when the study names those outputs).
pub fn summarize(dir: &Path) -> Result<Summary, DispersionError> {
    let record =
        Record::read(&dir.join(STUDY_FILE))?.ok_or_else(|| DispersionError::MissingStudy {
            dir: dir.to_owned(),
        })?;
    if record.shard != Shard::WHOLE {
        return Err(DispersionError::InvalidStudy {
            reason: format!(
                "{} holds shard {} only; merge the shards to summarize the study",
                dir.display(),
                record.shard
            ),
        });
    }
    let samples_path = dir.join(SAMPLES_FILE);
    let scan = files::scan(&samples_path, &record)?;
    if !files::shard_is_complete(&scan, &record) {
        return Err(DispersionError::InvalidStudy {
            reason: format!(
                "{} has {} of {} samples; run the study again to finish it",
                samples_path.display(),
                scan.rows,
                record.samples
            ),
        });
    }
    let study = record.study();
    let (n_inputs, n_outputs) = (study.inputs.len(), study.outputs.len());
    let computed = compute(&study, &mut |f| {
        files::for_each_row(&samples_path, n_inputs, n_outputs, |row| f(&row))
    })?;
    let summary = computed.summary;
    let mut json = serde_json::to_string_pretty(&summary).unwrap_or_default();
    json.push('\n');
    files::write_atomic(&dir.join(SUMMARY_FILE), json.as_bytes())?;

    if let Some((name, values)) = &computed.histogram {
        plot::histogram(
            &dir.join(HISTOGRAM_PLOT_FILE),
            &format!("{name}: {} samples", values.len()),
            name,
            values,
        )?;
    }
    let title = if study.context.is_empty() {
        format!("Dispersion, {} samples, seed {}", study.samples, study.seed)
    } else {
        format!(
            "{}: {} samples, seed {}",
            study.context, study.samples, study.seed
        )
    };
    let landed: Vec<&Body> = computed
        .bodies
        .iter()
        .filter(|b| b.landing_names.is_some())
        .collect();
    if !landed.is_empty() {
        let points: Vec<Vec<[f64; 2]>> = landed
            .iter()
            .map(|b| b.drawn.iter().map(|(_, p)| *p).collect())
            .collect();
        let ellipses: Vec<Option<Ellipse>> = landed.iter().map(|b| b.landing.ellipse()).collect();
        let drawn: Vec<plot::Landings<'_>> = landed
            .iter()
            .zip(&points)
            .zip(&ellipses)
            .map(|((b, points), ellipse)| plot::Landings {
                body: b.name.as_deref(),
                points,
                ellipse: ellipse.as_ref(),
            })
            .collect();
        plot::landing(&dir.join(LANDING_PLOT_FILE), &title, &drawn)?;
        if let Some(site) = &study.site {
            let bodies: Vec<kml::Body<'_>> = landed
                .iter()
                .map(|b| kml::Body {
                    name: b.name.as_deref(),
                    ellipses: &b.kml_ellipses,
                    points: &b.drawn,
                    points_total: b.landing.count(),
                })
                .collect();
            let document = kml::document(&title, site, &bodies);
            files::write_atomic(&dir.join(KML_FILE), document.as_bytes())?;
        }
    }
    Ok(summary)
}

/// The summary of a complete study whose rows, in index order, are in memory (as
/// [`crate::run_in_memory`] keeps them): the [`summarize`] of the same rows in a directory,
/// without its files.
pub fn summarize_rows(study: &Study, rows: &[Row]) -> Summary {
    let Ok(computed) = compute::<std::convert::Infallible>(study, &mut |f| {
        rows.iter().for_each(&mut *f);
        Ok(())
    });
    computed.summary
}

/// The summary and what its figures draw.
struct Computed {
    summary: Summary,
    /// The histogram's output and its values (completed flights).
    histogram: Option<(String, Vec<f64>)>,
    /// The bodies' points, the study's first body first.
    bodies: Vec<Body>,
}

/// The apogee and landing points of one body of a study, as the rows are read.
struct Body {
    /// Its name; none in a study of one body.
    name: Option<String>,
    apogee_names: Option<[String; 2]>,
    landing_names: Option<[String; 2]>,
    /// The output indices of the apogee's and the landing's (x, y).
    apogee_pair: Option<(usize, usize)>,
    landing_pair: Option<(usize, usize)>,
    apogee: Moments,
    /// Moments of every landing point.
    landing: Moments,
    /// The landing points drawn (at most [`MAX_DRAWN_POINTS`]) with their sample indices.
    drawn: Vec<(u64, [f64; 2])>,
    /// The ellipses with their KML labels.
    kml_ellipses: Vec<(&'static str, Ellipse)>,
}

/// A pass over a study's rows: calls the function given on every row, in index order.
type RowPass<'a, E> = dyn FnMut(&mut dyn FnMut(&Row)) -> Result<(), E> + 'a;

/// Computes the summary of `study` from its rows, read by `rows` as many times as needed
/// (once per group of columns, plus one).
fn compute<E>(study: &Study, rows: &mut RowPass<'_, E>) -> Result<Computed, E> {
    let (n_inputs, n_outputs) = (study.inputs.len(), study.outputs.len());
    let output_index = |name: &String| study.outputs.iter().position(|o| o == name);
    let pair = |names: &Option<[String; 2]>| {
        names
            .as_ref()
            .and_then(|[x, y]| Some((output_index(x)?, output_index(y)?)))
    };
    let points = &study.points;
    let first = (points.body.clone(), &points.apogee, &points.landing);
    let others = points
        .bodies
        .iter()
        .map(|b| (Some(b.name.clone()), &b.apogee, &b.landing));
    let mut bodies: Vec<Body> = std::iter::once(first)
        .chain(others)
        .map(|(name, apogee, landing)| Body {
            name,
            apogee_names: apogee.clone(),
            landing_names: landing.clone(),
            apogee_pair: pair(apogee),
            landing_pair: pair(landing),
            apogee: Moments::default(),
            landing: Moments::default(),
            drawn: Vec::new(),
            kml_ellipses: Vec::new(),
        })
        .collect();
    let histogram_column = study
        .points
        .histogram
        .as_ref()
        .and_then(output_index)
        .map(|i| n_inputs + i);

    // First pass: counts, failures, moments, landing points.
    let mut failures = Vec::new();
    let mut counts = Counts::default();
    let value = |row: &Row, i: usize| row.outputs.get(i).copied().flatten();
    rows(&mut |row| {
        counts.add(&row.status);
        if !row.status.is_completed() {
            if failures.len() < MAX_LISTED_FAILURES {
                failures.push(Failure {
                    index: row.index,
                    status: row.status.label().to_owned(),
                    error: row.status.message().to_owned(),
                });
            }
            return;
        }
        for body in &mut bodies {
            if let Some((x, y)) = body.apogee_pair
                && let (Some(x), Some(y)) = (value(row, x), value(row, y))
            {
                body.apogee.push(x, y);
            }
            if let Some((x, y)) = body.landing_pair
                && let (Some(x), Some(y)) = (value(row, x), value(row, y))
            {
                body.landing.push(x, y);
                if body.drawn.len() < MAX_DRAWN_POINTS && x.is_finite() && y.is_finite() {
                    body.drawn.push((row.index, [x, y]));
                }
            }
        }
    })?;

    // Column statistics, a group of columns per pass.
    let columns = n_inputs + n_outputs;
    let per_pass = (VALUES_PER_PASS / study.samples.max(1)).max(1) as usize;
    let mut statistics = Vec::with_capacity(columns);
    let mut histogram = None;
    for first in (0..columns).step_by(per_pass) {
        let group = first..(first + per_pass).min(columns);
        let mut values: Vec<Vec<f64>> = group.clone().map(|_| Vec::new()).collect();
        rows(&mut |row| {
            let completed = row.status.is_completed();
            for (column, slot) in group.clone().zip(values.iter_mut()) {
                let v = if column < n_inputs {
                    row.inputs.get(column).copied()
                } else if completed {
                    value(row, column - n_inputs)
                } else {
                    None
                };
                slot.extend(v);
            }
        })?;
        for (column, mut column_values) in group.zip(values) {
            statistics.push(Statistics::of(&mut column_values));
            if Some(column) == histogram_column {
                histogram = Some((study.outputs[column - n_inputs].clone(), column_values));
            }
        }
    }
    let names = study
        .inputs
        .iter()
        .map(|i| i.column())
        .chain(study.outputs.iter().cloned());
    let mut columns: Vec<Column> = names
        .zip(statistics)
        .map(|(name, statistics)| Column { name, statistics })
        .collect();
    let outputs = columns.split_off(n_inputs);

    let mut ellipses = Vec::new();
    for body in &mut bodies {
        for (name, label, moments, names) in [
            ("apogee", "Apogee", &body.apogee, &body.apogee_names),
            ("landing", "Landing", &body.landing, &body.landing_names),
        ] {
            if let (Some(ellipse), Some(names)) = (moments.ellipse(), names) {
                ellipses.push(EllipseSummary::new(
                    name,
                    body.name.as_deref(),
                    names,
                    &ellipse,
                ));
                body.kml_ellipses.push((label, ellipse));
            }
        }
    }
    let summary = Summary {
        seed: study.seed,
        samples: study.samples,
        counts,
        failures,
        inputs: columns,
        outputs,
        ellipses,
    };
    Ok(Computed {
        summary,
        histogram,
        bodies,
    })
}
