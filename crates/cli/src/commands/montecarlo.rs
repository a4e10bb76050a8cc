//! `karman montecarlo MISSION [--samples N] [--seed S] [--threads T] [--out DIR]
//! [--shard K/N] [--set PATH=VALUE]...`: a Monte Carlo dispersion study of a mission
//! (docs/montecarlo.md).
//!
//! Writes `study.json` and `samples.csv` into DIR (rows flushed in index order as samples
//! finish); a whole study also gets `summary.json`, `dispersion.kml`, `landing.svg` and
//! `apogee_histogram.svg`. Rerunning the same command resumes an interrupted study.
//!
//! Exit code: 0 when at least one sample of the shard flown (the whole study without
//! `--shard`) completed its flight; 1 when none did (every sample failed or ended early), after
//! writing the files, and on any error.

use super::MissionArgs;
use anyhow::{Result, bail};
use clap::Args;
use karman_mission::dispersion::{self, ProgressMode, RunOptions, Shard, Summary};
use karman_mission::montecarlo::{MonteCarlo, StudyOverrides};
use std::io::Write;
use std::path::PathBuf;

/// Arguments of `karman montecarlo`.
#[derive(Debug, Args)]
pub struct MonteCarloArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
    #[command(flatten)]
    pub fetch: super::FetchFlag,
    /// Number of samples (default: the mission's `[dispersion] samples`).
    #[arg(long, value_name = "N")]
    pub samples: Option<u64>,
    /// Seed of the random streams (default: the mission's `[dispersion] seed`).
    #[arg(long, value_name = "S")]
    pub seed: Option<u64>,
    /// Worker threads (default: one per core; at most 4 per core).
    #[arg(long, value_name = "T")]
    pub threads: Option<usize>,
    /// Output directory; rerun with the same directory to resume.
    #[arg(long, value_name = "DIR", default_value = "montecarlo")]
    pub out: PathBuf,
    /// Fly only shard K of N (samples with index % N == K - 1); join shards with
    /// `karman merge`.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<Shard>,
    /// No progress output on stderr.
    #[arg(long)]
    pub quiet: bool,
}

/// Runs (or resumes) the study and prints what it did.
pub fn run(args: &MonteCarloArgs) -> Result<()> {
    args.fetch.run(&args.mission)?;
    let mission = args.mission.load()?;
    let overrides = StudyOverrides {
        samples: args.samples,
        seed: args.seed,
    };
    let study = MonteCarlo::new(&mission, overrides)?;
    let options = RunOptions {
        threads: args.threads,
        shard: args.shard,
        progress: if args.quiet {
            ProgressMode::Hidden
        } else {
            ProgressMode::Auto
        },
    };
    let report = dispersion::run(study.study(), &args.out, &options, |index, values| {
        study.fly(index, values)
    })?;
    let mut out = std::io::stdout().lock();
    writeln!(
        out,
        "{} samples (shard {}): {} resumed, {} flown in {:.1} s ({:.1} flights/s on {} threads); {}",
        report.shard_samples,
        report.shard,
        report.resumed,
        report.flown,
        report.elapsed.as_secs_f64(),
        report.rate(),
        report.threads,
        report.counts
    )?;
    match &report.summary {
        Some(summary) => print_summary(&mut out, summary)?,
        None => writeln!(
            out,
            "shard written to {}; join the shards with `karman merge OUT DIR...`",
            args.out.display()
        )?,
    }
    writeln!(
        out,
        "seed {}; results in {}",
        study.study().seed,
        args.out.display()
    )?;
    if report.counts.completed == 0 {
        bail!(
            "no sample of shard {} completed its flight ({}); see samples.csv in {}",
            report.shard,
            report.counts,
            args.out.display()
        );
    }
    Ok(())
}

/// A few lines of the summary: apogee, impact, ellipses (each body's, named, in a study of
/// several).
pub fn print_summary(out: &mut impl Write, summary: &Summary) -> Result<()> {
    writeln!(out, "{} samples: {}", summary.samples, summary.counts)?;
    for failure in summary.failures.iter().take(3) {
        writeln!(
            out,
            "  sample {} {}: {}",
            failure.index, failure.status, failure.error
        )?;
    }
    let width = summary
        .outputs
        .iter()
        .map(|c| c.name.chars().count())
        .fold(28, usize::max);
    writeln!(
        out,
        "{:<width$} {:>12} {:>10} {:>12} {:>12}",
        "output", "mean", "std", "2.5 %", "97.5 %"
    )?;
    for column in &summary.outputs {
        if let Some(s) = &column.statistics {
            writeln!(
                out,
                "{:<width$} {:>12.3} {:>10.3} {:>12.3} {:>12.3}",
                column.name, s.mean, s.std, s.p2_5, s.p97_5
            )?;
        }
    }
    for ellipse in &summary.ellipses {
        let body = ellipse
            .body
            .as_ref()
            .map(|b| format!("{b} "))
            .unwrap_or_default();
        writeln!(
            out,
            "{body}{} ellipse: centre ({:.1}, {:.1}) m, major axis {:.1} deg from east",
            ellipse.name, ellipse.center_m[0], ellipse.center_m[1], ellipse.orientation_deg
        )?;
        for (k, p) in ellipse.k_sigma_rocketpy.iter().zip(&ellipse.probability) {
            writeln!(
                out,
                "  {} sigma: semi-axes {:.1} x {:.1} m (k-sigma, {:.1} % if normal); {:.2} % region {:.1} x {:.1} m",
                k.sigma,
                k.semi_major_m,
                k.semi_minor_m,
                100.0 * k.normal_probability,
                100.0 * p.normal_probability,
                p.semi_major_m,
                p.semi_minor_m
            )?;
        }
    }
    Ok(())
}
