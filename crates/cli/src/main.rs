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
    keep_freed_heap();
    let cli = Cli::parse();
    match commands::run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}

/// Keeps freed heap memory in the process instead of returning it to the kernel at every free.
///
/// glibc gives the top of its heap back (`brk`/`madvise`) whenever more than 128 KiB lie free
/// there. Each Monte Carlo sample builds and drops about half a megabyte of tables and
/// trajectory, so with the default every sample shrinks the heap and page-faults it back in:
/// about a tenth of a Monte Carlo run's time went to the kernel. A 4 MiB threshold keeps the
/// memory of one sample per thread in reserve (the peak resident size is unchanged).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[allow(unsafe_code)]
fn keep_freed_heap() {
    const TRIM_THRESHOLD: libc::c_int = 4 << 20;
    // SAFETY: `mallopt` only sets an allocator parameter (glibc serialises it with its own
    // lock); it takes no pointers and is called here before any other thread exists.
    unsafe {
        libc::mallopt(libc::M_TRIM_THRESHOLD, TRIM_THRESHOLD);
    }
}

/// Other allocators decide for themselves.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn keep_freed_heap() {}
