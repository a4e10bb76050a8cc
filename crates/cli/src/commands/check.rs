//! `karman check MISSION [--set PATH=VALUE]...`: load and validate a mission, then build and
//! check every model its flight needs (thrust and drag curves, soundings, weather grids, the
//! launch from the rail) exactly as `simulate` does before it integrates, call the air-brake
//! controller once as the flight's first call (its run-time errors are the flight's, located
//! in the script), and fly the nominal flight (seed 0) as `simulate` flies it: whatever that
//! flight rejects (a model the integrator cannot carry through, a controller error in a branch
//! the first call does not take, a rocket that never leaves the rail or never lands before
//! `max_time`) is check's error too, so that `ok` means the mission flies. A flight takes
//! milliseconds.

use super::MissionArgs;
use clap::Args;
use karman_mission::assemble::flight::{PreparedFlight, early_ending};
use karman_mission::assemble::scripts::{compile_controller, first_call};
use karman_mission::assemble::stages::{prepare_staged, simulate_staged};
use std::io::Write;

/// Arguments of `karman check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
}

/// Check's error for a nominal flight that ended early with `message` (the flight of `body`
/// in a multi-stage mission).
fn ended_early(file: &std::path::Path, body: Option<&str>, message: &str) -> anyhow::Error {
    let body = body.map_or_else(String::new, |b| format!("{b}: "));
    anyhow::anyhow!(
        "{}: the nominal flight (seed 0): {body}{message}",
        file.display()
    )
}

/// Prints the warnings (and a note when the air-brake controller runs interpreted rather
/// than compiled), then "ok" when the mission loads, validates, its models build and its
/// nominal flight (seed 0) flies as `simulate` flies it; otherwise the error (every problem,
/// each with `file:line:column`) goes back to `main`.
pub fn run(args: &CheckArgs) -> anyhow::Result<()> {
    let mission = args.mission.load()?;
    let script = if mission.spec.stages.is_empty() {
        // The models built once, as `simulate` builds them, then flown.
        let prepared = PreparedFlight::new(&mission)?;
        // The controller's first call, made as the flight makes it: its run-time errors
        // are the flight's, located in the script.
        if let Some(script) = prepared.script() {
            first_call(&mission, script, prepared.rocket(), prepared.environment())?;
        }
        super::print_warnings(&mission, prepared.warnings());
        let run = prepared.fly(&mission, 0)?;
        if let Some((_, message)) = early_ending(run.summary().termination, &run.settings) {
            return Err(ended_early(&mission.path, None, &message));
        }
        prepared.script().cloned()
    } else {
        super::print_warnings(&mission, &prepare_staged(&mission, 0)?);
        let run = simulate_staged(&mission, 0)?;
        for (i, body) in run.bodies.iter().enumerate() {
            if let Some((_, message)) = early_ending(run.summary(i).termination, &run.settings) {
                return Err(ended_early(&mission.path, Some(&body.name), &message));
            }
        }
        compile_controller(&mission)?
    };
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
