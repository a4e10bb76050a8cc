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
    /// Stop once a condition holds, `QUANTITY.ci95 < VALUE` (repeatable: all must hold):
    /// QUANTITY an output (`apogee_agl_m`: the 95 % confidence half-width of its mean) or
    /// `landing.semi_major` / `landing.semi_minor` (of the 95.45 % landing ellipse's
    /// semi-axis); checked every --check-every samples, the sample count the cap. The study
    /// written is the study of the samples flown, as `--samples` of that many writes it.
    #[arg(long = "until", value_name = "CONDITION")]
    pub until: Vec<String>,
    /// The sampling design: `random` (the study) or `sobol` (Saltelli's design of
    /// (inputs + 2) x N flights, N = --samples; prints the first-order and total Sobol
    /// indices of every output and writes them to DIR/sobol.json; no study is written).
    #[arg(long, value_name = "DESIGN", default_value = "random", value_parser = ["random", "sobol"])]
    pub design: String,
    /// Samples between --until checks (the first check after this many).
    #[arg(long, value_name = "N", default_value_t = dispersion::convergence::DEFAULT_EVERY, requires = "until")]
    pub check_every: u64,
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
    if args.design == "sobol" {
        if !args.until.is_empty() || args.shard.is_some() {
            bail!("--design sobol takes neither --until nor --shard");
        }
        return sobol(&study, &options, &args.out);
    }
    let mut converged = None;
    let report = if args.until.is_empty() {
        dispersion::run(study.study(), &args.out, &options, |index, values| {
            study.fly(index, values)
        })?
    } else {
        let until = dispersion::convergence::Until {
            conditions: args
                .until
                .iter()
                .map(|text| dispersion::convergence::Condition::parse(text, study.study()))
                .collect::<Result<_, _>>()?,
            every: args.check_every,
        };
        let (report, stopped) = dispersion::convergence::run_converging(
            study.study(),
            &args.out,
            &options,
            &until,
            |index, values| study.fly(index, values),
        )?;
        converged = Some((until, stopped));
        report
    };
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
    if let Some((until, stopped)) = &converged {
        print_convergence(&mut out, until, stopped, study.study().samples)?;
    }
    if report.counts.completed == 0 {
        // The first failure's reason in the error itself (a study whose every sample fails
        // usually fails for one reason: a drawn value out of range, a mission the draws break).
        let first = report
            .summary
            .as_ref()
            .and_then(|s| s.failures.first())
            .map(|f| format!("; sample {} {}: {}", f.index, f.status, f.error))
            .unwrap_or_default();
        bail!(
            "no sample of shard {} completed its flight ({}){first}; see samples.csv in {}",
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

/// What `--until` did: the samples flown, why it stopped, each condition's half-width.
fn print_convergence(
    out: &mut impl Write,
    until: &dispersion::convergence::Until,
    stopped: &dispersion::convergence::Converged,
    cap: u64,
) -> Result<()> {
    if stopped.met {
        writeln!(
            out,
            "--until: every condition held at {} samples ({} checks, every {} samples; cap {cap})",
            stopped.samples, stopped.checks, until.every
        )?;
    } else {
        writeln!(
            out,
            "--until: the cap of {cap} samples was reached before every condition held ({} checks, every {} samples)",
            stopped.checks, until.every
        )?;
    }
    for (condition, width) in until.conditions.iter().zip(&stopped.widths) {
        let value = width.map_or_else(|| "too few values".to_owned(), |w| format!("{w:.6}"));
        let holds = width.is_some_and(|w| w < condition.threshold);
        writeln!(
            out,
            "  {}: {value} ({})",
            condition.text,
            if holds { "holds" } else { "does not hold" }
        )?;
    }
    writeln!(
        out,
        "  intervals: 95 % normal-approximation confidence half-width of the mean, 1.96 s/sqrt(n); \
         of a landing semi-axis a, 1.96 a/sqrt(2(n-1)) (delta method, normal sample covariance)"
    )?;
    Ok(())
}

/// `--design sobol`: Saltelli's design flown, the indices printed and written to
/// `out/sobol.json`.
fn sobol(study: &MonteCarlo, options: &RunOptions, out: &std::path::Path) -> Result<()> {
    let definition = study.study();
    let n = definition.samples;
    let started = std::time::Instant::now();
    let results = dispersion::sobol_study(definition, n, options, |index, values| {
        study.fly(index, values)
    })?;
    let flights = (definition.inputs.len() as u64 + 2) * n;
    let mut stdout = std::io::stdout().lock();
    writeln!(
        stdout,
        "Sobol indices (Saltelli's design): {flights} flights ({} inputs + 2) x {n}, seed {}, {:.1} s",
        definition.inputs.len(),
        definition.seed,
        started.elapsed().as_secs_f64()
    )?;
    let width = definition
        .inputs
        .iter()
        .map(|i| i.column().len())
        .fold(28, usize::max);
    let mut json = serde_json::Map::new();
    for (output, indices) in &results {
        match indices {
            Ok(s) => {
                writeln!(stdout, "{output}:")?;
                writeln!(
                    stdout,
                    "  {:<width$} {:>10} {:>10}",
                    "input", "first", "total"
                )?;
                for (i, name) in s.inputs.iter().enumerate() {
                    writeln!(
                        stdout,
                        "  {name:<width$} {:>10.4} {:>10.4}",
                        s.first[i], s.total[i]
                    )?;
                }
                json.insert(output.clone(), serde_json::to_value(s)?);
            }
            Err(reason) => {
                writeln!(stdout, "{output}: not computed: {reason}")?;
                json.insert(output.clone(), serde_json::json!({ "error": reason }));
            }
        }
    }
    std::fs::create_dir_all(out)?;
    let path = out.join("sobol.json");
    let mut text = serde_json::to_string_pretty(&json)?;
    text.push('\n');
    dispersion::files::write_atomic(&path, text.as_bytes())?;
    writeln!(stdout, "written to {}", path.display())?;
    Ok(())
}
