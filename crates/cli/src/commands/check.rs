//! `karman check MISSION [--set PATH=VALUE]...`: load and validate a mission.

use super::MissionArgs;
use clap::Args;
use std::io::Write;

/// Arguments of `karman check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
}

/// Prints "ok" when the mission loads and validates; otherwise the error (every problem,
/// each with `file:line:column`) goes back to `main`.
pub fn run(args: &CheckArgs) -> anyhow::Result<()> {
    args.mission.load()?;
    // A closed stdout is an error to report, not a panic (as `println!` would).
    writeln!(std::io::stdout().lock(), "ok")?;
    Ok(())
}
