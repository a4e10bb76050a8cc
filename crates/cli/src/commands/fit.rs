//! `karman fit MISSION LOG --vary PATH... [-o FITTED.toml] [--json] [--max-flights N]`: the
//! factors on the chosen inputs' nominal values that make the simulation match the log best
//! in least squares over the phases those inputs act on (karman-fit, whose documentation
//! states the method), each with its uncertainty, the RMS before and after, and the mission
//! written with the fitted values as a commented copy.
//!
//! `--json` prints one object: `log`, `flights`, `converged`, `termination`,
//! `clock_offset_s` (`[value, std]` or null), `correlation_inflation`, `warnings`, `inputs` (each
//! `path`, `factor`, `factor_std`, and for a number `nominal`, `value`, `value_std`) and
//! `phases` (each `phase`, `unit`, `samples`, `rms_before`, `rms_after`): karman-fit's
//! `fit_json`, shared with the Python package's `Mission.fit()`.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Result, bail};
use clap::Args;
use karman_fit::{Fit, FitOptions, Nominal, fit, fit_json, write_fitted};

use super::MissionArgs;
use super::log::ReadArgs;

/// Arguments of `karman fit`.
#[derive(Debug, Args)]
pub struct FitArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
    /// The flight log.
    #[arg(value_name = "LOG")]
    pub log: PathBuf,
    #[command(flatten)]
    pub read: ReadArgs,
    /// An input to fit, as a dotted path (`rocket.power_off_drag`, `motor.total_impulse`,
    /// `rocket.parachutes.Main.cd_s`, `rocket.mass`); repeatable.
    #[arg(long = "vary", value_name = "PATH", required = true)]
    pub vary: Vec<String>,
    /// Most flights the fit may fly.
    #[arg(long, value_name = "N", default_value_t = FitOptions::default().max_flights)]
    pub max_flights: usize,
    /// Seed of the parachute-trigger pressure noise of every flight.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Write the mission with the fitted values here (a commented copy).
    #[arg(short = 'o', long = "out", value_name = "FITTED.toml")]
    pub output: Option<PathBuf>,
    /// Print one JSON object instead of the text report.
    #[arg(long)]
    pub json: bool,
}

/// Runs `karman fit`.
pub fn run(args: &FitArgs) -> Result<()> {
    if let Some(out) = &args.output
        && std::path::absolute(out).ok() == std::path::absolute(&args.mission.mission).ok()
    {
        bail!(
            "{}: the fitted copy would replace the mission itself; write it elsewhere",
            out.display()
        );
    }
    let log = args.read.read(&args.log)?;
    let mission = args.mission.load()?;
    let options = FitOptions {
        vary: args.vary.clone(),
        max_flights: args.max_flights,
        seed: args.seed,
    };
    let result = fit(&mission, &log, &options)?;
    let mut out = std::io::stdout().lock();
    if args.json {
        let json = fit_json(&args.log.display().to_string(), &result);
        writeln!(out, "{}", serde_json::to_string_pretty(&json)?)?;
    } else {
        write!(
            out,
            "{}",
            fit_text(&args.log.display().to_string(), &result)
        )?;
    }
    if let Some(path) = &args.output {
        write_fitted(&mission, &result, &args.log.display().to_string(), path)?;
        if !args.json {
            writeln!(out, "fitted mission written to {}", path.display())?;
        }
    }
    Ok(())
}

fn fit_text(log: &str, fit: &Fit) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = writeln!(s, "log:      {log}");
    let _ = writeln!(
        s,
        "fit:      {} after {} flights",
        fit.termination, fit.flights
    );
    for input in &fit.inputs {
        match (&input.nominal, input.value(), input.value_std()) {
            (Nominal::Number(nominal), Some(value), Some(std)) => {
                let _ = writeln!(
                    s,
                    "  {:<32} {value:.6} ± {std:.6} (nominal {nominal:.6}; factor {:.4} ± {:.4})",
                    input.path, input.factor, input.factor_std
                );
            }
            _ => {
                let _ = writeln!(
                    s,
                    "  {:<32} factor {:.4} ± {:.4} on the nominal",
                    input.path, input.factor, input.factor_std
                );
            }
        }
    }
    if let Some([offset, std]) = fit.clock_offset_s {
        let _ = writeln!(
            s,
            "  {:<32} {offset:+.3} ± {std:.3} s (the log's liftoff against the simulation's)",
            "log clock offset"
        );
    }
    for p in &fit.phases {
        let _ = writeln!(
            s,
            "  RMS {:<28} {:.2} -> {:.2} {} over {} samples",
            p.phase.to_string(),
            p.rms_before,
            p.rms_after,
            p.phase.unit(),
            p.samples
        );
    }
    if fit.correlation_inflation > 1.0 {
        let _ = writeln!(
            s,
            "  (uncertainties widened ×{:.2} in variance for correlated residuals)",
            fit.correlation_inflation
        );
    }
    for w in &fit.warnings {
        let _ = writeln!(s, "warning: {w}");
    }
    s
}
