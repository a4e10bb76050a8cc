//! `karman`: the command-line interface of the karman rocket flight simulator.
//!
//! Every command that reads a mission takes the mission path and any number of
//! `--set PATH=VALUE` overrides ([`commands::MissionArgs`]). `main` returns an exit code:
//! 0 on success, 1 when the command fails (the whole error chain is printed to stderr), 2 for
//! usage errors (clap's own).

mod commands;
mod plot;

use clap::Parser;
use std::io::Write;
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
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(usage) => return usage_exit(&usage),
    };
    match commands::run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            // A closed stderr loses the message, not the exit code (`eprintln!` would panic).
            let _ = writeln!(std::io::stderr().lock(), "error: {error:#}");
            ExitCode::FAILURE
        }
    }
}

/// Prints clap's help, version or usage error and gives its exit code (0 for `--help`,
/// 2 for a usage error), or 1 when the text cannot be written (`karman --help > /dev/full`).
fn usage_exit(usage: &clap::Error) -> ExitCode {
    let written = usage.print().and_then(|()| std::io::stdout().flush());
    match written {
        Ok(()) => ExitCode::from(u8::try_from(usage.exit_code()).unwrap_or(2)),
        Err(error) => {
            let _ = writeln!(std::io::stderr().lock(), "error: cannot write: {error}");
            ExitCode::FAILURE
        }
    }
}
