//! `karman`: the command-line interface of the karman rocket flight simulator.
//!
//! Every command that reads a mission takes the mission path and any number of
//! `--set PATH=VALUE` overrides ([`commands::MissionArgs`]). `main` returns an exit code:
//! 0 on success, 1 when the command fails (the whole error chain is printed to stderr), 2 for
//! usage errors (clap's own).

mod commands;
mod plot;

use clap::Parser;
use std::process::ExitCode;

/// A fast, scriptable 6-DOF rocket flight simulator.
#[derive(Debug, Parser)]
#[command(name = "karman", version, about, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: commands::Command,
}

fn main() -> ExitCode {
    karman_mission::allocator::keep_freed_heap();
    let cli = Cli::parse();
    match commands::run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}
