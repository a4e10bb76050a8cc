//! `karman tolerance STUDY_DIR [--output NAME]... [--coverage P] [--confidence C] [--json]`:
//! Wilks' distribution-free one-sided tolerance bounds of a Monte Carlo study's outputs ("99 %
//! of flights stay below X with 95 % confidence"), from the order statistics of its completed
//! samples (`karman_dispersion::tolerance`, whose documentation states the method).

use anyhow::Result;
use clap::Args;
use karman_mission::dispersion;
use std::io::Write;
use std::path::PathBuf;

/// Arguments of `karman tolerance`.
#[derive(Debug, Args)]
pub struct ToleranceArgs {
    /// The study's output directory (`karman montecarlo --out DIR`).
    #[arg(value_name = "STUDY_DIR")]
    pub dir: PathBuf,
    /// An output column (repeatable; default: every output).
    #[arg(long = "output", value_name = "NAME")]
    pub outputs: Vec<String>,
    /// The fraction of flights the bound covers.
    #[arg(long, value_name = "P", default_value_t = 0.99)]
    pub coverage: f64,
    /// The confidence of the bound.
    #[arg(long, value_name = "C", default_value_t = 0.95)]
    pub confidence: f64,
    /// Print one JSON array instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// Computes and prints the bounds.
pub fn run(args: &ToleranceArgs) -> Result<()> {
    let bounds = dispersion::tolerance(&args.dir, &args.outputs, args.coverage, args.confidence)?;
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&bounds)?)?;
        return Ok(());
    }
    writeln!(
        out,
        "Wilks one-sided tolerance bounds: {} % of flights within the bound with {} % confidence",
        100.0 * args.coverage,
        100.0 * args.confidence
    )?;
    let width = bounds.iter().map(|b| b.output.len()).fold(28, usize::max);
    writeln!(
        out,
        "{:<width$} {:>8} {:>16} {:>16} {:>6} {:>10}",
        "output", "samples", "below (upper)", "above (lower)", "rank", "confidence"
    )?;
    for b in &bounds {
        match (b.upper, b.lower, b.rank, b.achieved_confidence) {
            (Some(upper), Some(lower), Some(rank), Some(confidence)) => writeln!(
                out,
                "{:<width$} {:>8} {upper:>16.6} {lower:>16.6} {rank:>6} {:>9.4} %",
                b.output,
                b.samples,
                100.0 * confidence
            )?,
            _ => writeln!(
                out,
                "{:<width$} {:>8} needs at least {} completed samples",
                b.output, b.samples, b.samples_needed
            )?,
        }
    }
    writeln!(
        out,
        "method: the r-th largest (smallest) completed value for the largest r with P(B <= n - r) >= confidence, B ~ Binomial(n, coverage) (Wilks 1941)"
    )?;
    Ok(())
}
