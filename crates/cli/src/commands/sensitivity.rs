//! `karman sensitivity STUDY_DIR [--output NAME]... [--json] [--svg DIR]`: which varied input
//! causes the spread of each output of a finished (or interrupted) Monte Carlo study, from its
//! `samples.csv`: RocketPy 1.13's `SensitivityModel`, the linear regression variance
//! decomposition (docs/montecarlo.md, "Sensitivity"; `karman_dispersion::sensitivity`).
//!
//! The table gives, per output, each input's share of the variance, its mean and standard
//! deviation over the samples, the regression coefficient and the effect of one standard
//! deviation, then the unexplained part; `--json` prints the same as one object; `--svg DIR`
//! writes one bar chart per output, `DIR/sensitivity_<output>.svg`.

use anyhow::{Context, Result};
use clap::Args;
use karman_mission::dispersion::{self, OutputSensitivity};
use std::io::Write;
use std::path::PathBuf;

/// Arguments of `karman sensitivity`.
#[derive(Debug, Args)]
pub struct SensitivityArgs {
    /// The study's output directory (`karman montecarlo --out DIR`): its study.json names the
    /// varied inputs and the outputs, its samples.csv holds their values.
    #[arg(value_name = "STUDY_DIR")]
    pub dir: PathBuf,
    /// An output column to decompose (repeatable; default: every output that varies over
    /// the completed samples).
    #[arg(long = "output", value_name = "NAME")]
    pub outputs: Vec<String>,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Write a bar chart of each output's shares into this directory
    /// (`sensitivity_<output>.svg`).
    #[arg(long, value_name = "DIR")]
    pub svg: Option<PathBuf>,
}

/// Computes and prints the decomposition.
pub fn run(args: &SensitivityArgs) -> Result<()> {
    let result = dispersion::sensitivity(&args.dir, &args.outputs)?;
    if let Some(dir) = &args.svg {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        for output in &result.outputs {
            let name: String = output
                .output
                .chars()
                .map(|c| {
                    if c.is_ascii_alphanumeric() || c == '_' || c == '.' {
                        c
                    } else {
                        '_'
                    }
                })
                .collect();
            dispersion::sensitivity_bars(&dir.join(format!("sensitivity_{name}.svg")), output)?;
        }
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&result)?)?;
        return Ok(());
    }
    for output in &result.outputs {
        print_output(&mut out, output)?;
    }
    for skipped in &result.skipped {
        writeln!(
            out,
            "{}: not decomposed: {}",
            skipped.output, skipped.reason
        )?;
    }
    writeln!(out, "method: {}", result.method)?;
    Ok(())
}

fn print_output(out: &mut impl Write, s: &OutputSensitivity) -> std::io::Result<()> {
    writeln!(
        out,
        "{}: mean {}, std {} (linear model), {} samples",
        s.output,
        significant(s.mean),
        significant(s.std),
        s.samples
    )?;
    let width = s
        .inputs
        .iter()
        .map(|i| i.input.len())
        .chain([11])
        .max()
        .unwrap_or(11);
    writeln!(
        out,
        "  {:<width$}  {:>9}  {:>12}  {:>12}  {:>12}  {:>12}",
        "input", "share %", "mean", "std", "coefficient", "effect/std"
    )?;
    let mut order: Vec<usize> = (0..s.inputs.len()).collect();
    order.sort_by(|&a, &b| s.inputs[b].share.total_cmp(&s.inputs[a].share));
    for i in order.iter().map(|&k| &s.inputs[k]) {
        writeln!(
            out,
            "  {:<width$}  {:>9.4}  {:>12}  {:>12}  {:>12}  {:>12}",
            i.input,
            100.0 * i.share,
            significant(i.mean),
            significant(i.std),
            significant(i.coefficient),
            significant(i.effect_per_std)
        )?;
    }
    writeln!(
        out,
        "  {:<width$}  {:>9.4}",
        "unexplained",
        100.0 * s.unexplained
    )?;
    writeln!(out)
}

/// Six significant digits.
fn significant(value: f64) -> String {
    if value.abs() >= 1e-3 && value.abs() < 1e6 || value.abs() <= 0.0 {
        let digits = 5 - value.abs().log10().floor().clamp(-3.0, 5.0) as i32;
        format!("{value:.*}", usize::try_from(digits.max(0)).unwrap_or(0))
    } else {
        format!("{value:.5e}")
    }
}
