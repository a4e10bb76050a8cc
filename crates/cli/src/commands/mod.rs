//! The subcommands, one file each, and the arguments they share.

mod check;
mod compare;
mod fit;
mod import;
mod inspect;
mod log;
mod merge;
mod montecarlo;
mod safety;
mod sensitivity;
mod sil;
mod simulate;
mod solve;
mod sweep;
mod tolerance;
mod weather;

use clap::{Args, Subcommand};
use karman_mission::Override;
use std::io::Write;
use std::path::PathBuf;

/// The subcommands of `karman`.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Load and validate a mission file; print "ok" or every problem with its location.
    Check(check::CheckArgs),
    /// Read an OpenRocket design (.ork) into a commented mission file: geometry, masses,
    /// recovery, the launch conditions and motor of one of its simulations, drag estimated.
    Import(import::ImportArgs),
    /// Build the environment, motor and rocket of a mission and show them (tables, JSON,
    /// SVG plots, a drawing of the rocket).
    Inspect(inspect::InspectArgs),
    /// Fly a mission: summary (table or JSON); --out writes trajectory.csv, KML and plots.
    Simulate(simulate::SimulateArgs),
    /// Monte Carlo dispersion: fly the mission with the inputs of its `[dispersion]` table
    /// drawn at random; statistics, apogee and landing ellipses (resumable, shardable).
    Montecarlo(montecarlo::MonteCarloArgs),
    /// Join the output directories of the shards of one Monte Carlo study.
    Merge(merge::MergeArgs),
    /// Which varied input causes the spread of each output of a Monte Carlo study: each
    /// input's share of the variance and the unexplained part (RocketPy's SensitivityModel,
    /// a linear regression on the study's samples).
    Sensitivity(sensitivity::SensitivityArgs),
    /// Wilks' distribution-free tolerance bounds of a Monte Carlo study's outputs: "99 % of
    /// flights stay below X with 95 % confidence", from the order statistics of its samples.
    Tolerance(tolerance::ToleranceArgs),
    /// Range-safety report of the nominal flight: rail-exit speed, thrust-to-weight and
    /// stability, Mach and dynamic pressure, fin flutter margin (NACA TN 4197), landing
    /// energy, descent rate and drift, each pass / warn / fail against a threshold.
    Safety(safety::SafetyArgs),
    /// Find the value of one input that makes a summary output reach a target
    /// (`--target apogee_agl_m=3048 --vary rocket.mass`): a bracketing root finder (Brent),
    /// the flights it took and the `--set` that flies it.
    Solve(solve::SolveArgs),
    /// Fly the mission with one input set to each of several values: a table of summaries
    /// and one SVG per chosen series with the variants overlaid.
    Sweep(sweep::SweepArgs),
    /// Altimeter and flight-computer logs: `show` reads one (format detected from its
    /// content) and prints liftoff, apogee, velocity, events and warnings.
    Log(log::LogArgs),
    /// Fly the mission and set flight logs against it: apogee, velocity, ascent RMS, descent
    /// rates, landing; --out writes comparison.json and overlay plots.
    Compare(compare::CompareArgs),
    /// Fit inputs of the mission (a drag scale, the impulse, a parachute's cd_s, the mass) to
    /// a flight log by least squares; -o writes the mission with the fitted values.
    Fit(fit::FitArgs),
    /// Launch-day weather: download a forecast or sounding once (`fetch`), print and plot
    /// the profile a weather file gives (`show`).
    Weather(weather::WeatherArgs),
    /// Software in the loop: fly the mission with its air brakes driven by an outside program
    /// (flight software) that reads a line of state and sensors per controller call on its
    /// input and answers the level on its output.
    Sil(sil::SilArgs),
}

/// The mission file and its `--set` overrides, shared by every command that reads a mission.
#[derive(Debug, Args)]
pub struct MissionArgs {
    /// The mission file (TOML).
    #[arg(value_name = "MISSION")]
    pub mission: PathBuf,
    /// Override one input before validation: a dotted path and a TOML value, e.g.
    /// `--set flight.inclination=84` or `--set environment.atmosphere.model='"standard"'`.
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub overrides: Vec<Override>,
}

impl MissionArgs {
    /// Loads and validates the mission with its overrides.
    pub fn load(&self) -> Result<karman_mission::Mission, karman_mission::MissionError> {
        karman_mission::load(&self.mission, &self.overrides)
    }
}

/// `--fetch`: download the weather file the mission's `source` names before loading it.
#[derive(Debug, Args)]
pub struct FetchFlag {
    /// Download the weather file the mission's `[environment.atmosphere] source` names into
    /// its `file` first (with FILE.provenance.json beside it), then fly on it.
    #[cfg(feature = "fetch")]
    #[arg(long)]
    pub fetch: bool,
}

impl FetchFlag {
    /// Downloads the mission's weather file when `--fetch` was given, reporting on stderr.
    pub fn run(&self, mission: &MissionArgs) -> anyhow::Result<()> {
        #[cfg(feature = "fetch")]
        if self.fetch {
            let fetched = karman_mission::weather::fetch_source(
                &mission.mission,
                &mission.overrides,
                &weather::fetcher()?,
            )?;
            eprintln!(
                "{}: downloaded {} bytes from {}",
                fetched.path.display(),
                fetched.download.bytes.len(),
                fetched.download.request
            );
        }
        #[cfg(not(feature = "fetch"))]
        let _ = mission;
        Ok(())
    }
}

/// Prints each warning of a mission's models on stderr as `MISSION: warning: ...` (a closed
/// stderr loses them silently: they are also in `--json` and summary.json).
pub fn print_warnings(mission: &karman_mission::Mission, warnings: &[String]) {
    let mut err = std::io::stderr().lock();
    for warning in warnings {
        let _ = writeln!(err, "{}: warning: {warning}", mission.path.display());
    }
}

/// Runs one command.
pub fn run(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Check(args) => check::run(&args),
        Command::Import(args) => import::run(&args),
        Command::Inspect(args) => inspect::run(&args),
        Command::Simulate(args) => simulate::run(&args),
        Command::Sil(args) => sil::run(&args),
        Command::Montecarlo(args) => montecarlo::run(&args),
        Command::Merge(args) => merge::run(&args),
        Command::Sensitivity(args) => sensitivity::run(&args),
        Command::Tolerance(args) => tolerance::run(&args),
        Command::Sweep(args) => sweep::run(&args),
        Command::Solve(args) => solve::run(&args),
        Command::Safety(args) => safety::run(&args),
        Command::Weather(args) => weather::run(&args),
        Command::Log(args) => log::run(&args),
        Command::Compare(args) => compare::run(&args),
        Command::Fit(args) => fit::run(&args),
    }
}
