//! `karman check MISSION [--set PATH=VALUE]...`: load and validate a mission, then build and
//! check every model its flight needs (thrust and drag curves, soundings, weather grids, the
//! launch from the rail) exactly as `simulate` does before it integrates, and call the
//! air-brake controller once as the flight's first call (its run-time errors are the
//! flight's).

use super::MissionArgs;
use clap::Args;
use karman_mission::assemble::preflight::prepare;
use karman_mission::assemble::scripts::{compile_controller, first_call};
use karman_mission::assemble::stages::prepare_staged;
use std::io::Write;

/// Arguments of `karman check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
}

/// Prints the warnings (and a note when the air-brake controller runs interpreted rather
/// than compiled), then "ok" when the mission loads, validates and its models build;
/// otherwise the error (every problem, each with `file:line:column`) goes back to `main`.
pub fn run(args: &CheckArgs) -> anyhow::Result<()> {
    let mission = args.mission.load()?;
    let (warnings, script) = if mission.spec.stages.is_empty() {
        let models = prepare(&mission, 0)?;
        let script = compile_controller(&mission)?;
        // The controller's first call, made as the flight makes it: its run-time errors
        // are the flight's.
        if let Some(script) = &script {
            first_call(&mission, script, &models.rocket, &models.environment)?;
        }
        (models.warnings, script)
    } else {
        (prepare_staged(&mission, 0)?, compile_controller(&mission)?)
    };
    super::print_warnings(&mission, &warnings);
    // A controller outside the compiled subset is no error: its calls run in Rhai's
    // interpreter, with the same results, slower.
    if let Some(script) = script
        && let Some(reason) = script.interpreted_because()
    {
        let _ = writeln!(
            std::io::stderr().lock(),
            "{}: note: rocket.air_brakes.controller: its calls run in Rhai's interpreter \
             (same results, slower); outside the compiled subset: {reason}",
            mission.path.display()
        );
    }
    // A closed stdout is an error to report, not a panic (as `println!` would).
    writeln!(std::io::stdout().lock(), "ok")?;
    Ok(())
}
