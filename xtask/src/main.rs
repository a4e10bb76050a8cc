//! Project automation for karman, run as `cargo xtask <command>` (alias in
//! `.cargo/config.toml`, after matklad's cargo-xtask pattern).
//!
//! - `ci`: everything CI checks — formatting, clippy with warnings denied, the whole test
//!   suite, the Python package built into a fresh virtual environment with its pytest suite
//!   (`python.rs`), and the validation run on the repository's `fixtures/validation` (a
//!   missing or incomplete folder is skipped with a message, and fails when `CI` is set).
//! - `validate [--data DIR]`: fly every validation mission in release and compare with
//!   RocketPy 1.13 and the measured flights, and the OpenRocket designs of
//!   `fixtures/openrocket` with OpenRocket's stored flights; `validate --openrocket DIR`: the
//!   OpenRocket comparison alone, on the designs of another folder (see `validate.rs`).
//! - `bench [FILTER]`: run the criterion benchmarks and print their medians.
//! - `tidy`: repository rules that are not compiler checks (the crate layering of
//!   ARCHITECTURE.md, read from `cargo metadata`; every `docs/physics.md §N.M` citation
//!   naming a section of that file; no circle between the sibling modules of the folders
//!   `modules.rs` lists).

mod bench;
mod modules;
mod python;
mod tidy;
mod validate;

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

use anyhow::{Context, Result, bail};

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("xtask: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let root = workspace_root();
    match args.first().map(String::as_str) {
        Some("ci") => ci(&root),
        Some("tidy") => tidy::check_layering(&root)
            .and_then(|()| tidy::check_citations(&root))
            .and_then(|()| modules::check_module_circles(&root)),
        Some("validate") => validate::run(&root, &args[1..]),
        Some("bench") => bench::run(&root, &args[1..]),
        _ => {
            eprintln!(
                "usage: cargo xtask <ci|validate [--data DIR]|validate --openrocket DIR|bench [FILTER]|tidy>"
            );
            bail!("unknown or missing command {:?}", args.first())
        }
    }
}

/// The workspace root: the parent of this crate's manifest directory.
fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

/// Runs `cargo` with `args` in `root`, failing on a non-zero exit.
fn cargo(root: &Path, args: &[&str]) -> Result<()> {
    cargo_with(root, args, &[])
}

/// [`cargo`] with extra environment variables.
fn cargo_with(root: &Path, args: &[&str], envs: &[(&str, &str)]) -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    eprintln!("xtask: cargo {}", args.join(" "));
    let status = Command::new(&cargo)
        .args(args)
        .envs(envs.iter().copied())
        .current_dir(root)
        .status()
        .with_context(|| format!("could not run {cargo}"))?;
    if !status.success() {
        bail!("`cargo {}` failed ({status})", args.join(" "));
    }
    Ok(())
}

fn ci(root: &Path) -> Result<()> {
    cargo(root, &["fmt", "--all", "--", "--check"])?;
    cargo(
        root,
        &[
            "clippy",
            "--workspace",
            "--all-targets",
            "--",
            "-D",
            "warnings",
        ],
    )?;
    tidy::check_layering(root)?;
    tidy::check_citations(root)?;
    modules::check_module_circles(root)?;
    // The API documentation builds without broken links.
    cargo_with(
        root,
        &["doc", "--workspace", "--no-deps"],
        &[("RUSTDOCFLAGS", "-D warnings")],
    )?;
    // Property tests explore random cases when developers run `cargo test`; CI replays a
    // fixed seed (unless one is given) so that a landing never depends on the draw.
    let seed = std::env::var("PROPTEST_RNG_SEED").unwrap_or_else(|_| "20261123".to_owned());
    cargo_with(
        root,
        &["test", "--workspace"],
        &[("PROPTEST_RNG_SEED", &seed)],
    )?;
    // The network feature (`fetch`, on by default in the binary, so the workspace build above
    // compiled and tested it) is tested against loopback servers only.
    python::test_package(root)?;
    // The release validation run; with `CI` set an unavailable folder fails (as the tests do).
    match karman_validation::locate() {
        Ok(_) => validate::run(root, &[])?,
        Err(e) if karman_validation::in_ci() => bail!("{e} (CI is set: the validation must run)"),
        Err(e) => eprintln!("xtask: validation skipped: {e}"),
    }
    Ok(())
}
