//! `karman solve MISSION --target OUTPUT=VALUE --vary PATH [--bounds LO,HI] [--tolerance T]
//! [--max-flights N] [--seed S] [--json]`: the value of one input that makes a summary output
//! reach a target (`--target apogee_agl_m=3048 --vary rocket.mass`), by Brent's bracketing
//! root finder (`karman_mission::solve`, whose documentation states the method), with the
//! flights it took and the `--set` that flies it.
//!
//! `--json` prints one object: `input`, `value`, `nominal`, `output`, `target`, `achieved`,
//! `bounds`, `flights`, `trials` (`[value, output]` pairs in the order flown) and `method`.

use super::MissionArgs;
use anyhow::{Result, bail};
use clap::Args;
use karman_mission::solve::{SolveOptions, solve};
use std::io::Write;

/// Arguments of `karman solve`.
#[derive(Debug, Args)]
pub struct SolveArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
    /// The summary output and its target, `OUTPUT=VALUE` (`apogee_agl_m=3048`).
    #[arg(long, value_name = "OUTPUT=VALUE")]
    pub target: String,
    /// The input to solve for, by dotted path (`rocket.mass`, `motor.total_impulse`).
    #[arg(long, value_name = "PATH")]
    pub vary: String,
    /// The bracket searched, `LO,HI` (default: the nominal value ∓ 50 %).
    #[arg(long, value_name = "LO,HI", allow_hyphen_values = true)]
    pub bounds: Option<String>,
    /// How close the output must come to the target, in its units.
    #[arg(long, value_name = "T", default_value_t = SolveOptions::new("", "", 0.0).tolerance)]
    pub tolerance: f64,
    /// Most flights.
    #[arg(long, value_name = "N", default_value_t = SolveOptions::new("", "", 0.0).max_flights)]
    pub max_flights: usize,
    /// Seed of the parachute-trigger noise of every flight.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Print one JSON object instead of the text report.
    #[arg(long)]
    pub json: bool,
}

/// Runs `karman solve`.
pub fn run(args: &SolveArgs) -> Result<()> {
    let Some((output, value)) = args.target.split_once('=') else {
        bail!(
            "--target {:?}: expected OUTPUT=VALUE (e.g. apogee_agl_m=3048)",
            args.target
        );
    };
    let Ok(target) = value.trim().parse::<f64>() else {
        bail!(
            "--target {:?}: {:?} is not a number",
            args.target,
            value.trim()
        );
    };
    let bounds = match &args.bounds {
        None => None,
        Some(text) => {
            let parts: Vec<&str> = text.split(',').map(str::trim).collect();
            let numbers: Vec<f64> = parts.iter().filter_map(|p| p.parse().ok()).collect();
            match numbers[..] {
                [low, high] if parts.len() == 2 => Some([low, high]),
                _ => bail!("--bounds {text:?}: expected two numbers LO,HI (e.g. 14,18)"),
            }
        }
    };
    let mission = args.mission.load()?;
    let options = SolveOptions {
        bounds,
        tolerance: args.tolerance,
        max_flights: args.max_flights,
        seed: args.seed,
        ..SolveOptions::new(&args.vary, output.trim(), target)
    };
    let solution = solve(&mission, &options)?;
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&solution)?)?;
        return Ok(());
    }
    writeln!(
        out,
        "{} = {} gives {} = {} (target {}, tolerance {}) in {} flights",
        solution.input,
        solution.value,
        solution.output,
        solution.achieved,
        solution.target,
        options.tolerance,
        solution.flights
    )?;
    writeln!(
        out,
        "nominal {} = {}; bounds [{}, {}]",
        solution.input, solution.nominal, solution.bounds[0], solution.bounds[1]
    )?;
    for (k, [x, y]) in solution.trials.iter().enumerate() {
        writeln!(
            out,
            "  flight {:>2}: {} = {x:<24} {} = {y}",
            k + 1,
            solution.input,
            solution.output
        )?;
    }
    writeln!(out, "method: {}", solution.method)?;
    writeln!(out, "fly it: --set {}={}", solution.input, solution.value)?;
    Ok(())
}
