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
//! - `docs`: the user guide (mdBook, with figures karman draws from the fixtures and a link
//!   check) and the API documentation, into `target/docs` (`guide.rs`).
//! - `tidy`: repository rules that are not compiler checks (the crate layering of
//!   ARCHITECTURE.md, read from `cargo metadata`; every `docs/physics.md §N.M` citation
//!   naming a section of that file; no circle between the sibling modules of the folders
//!   `modules.rs` lists).
//! - `web`: the browser page (crates/web as WebAssembly, and `web/`) into `target/web/site`;
//!   `web-test`: that page driven by headless Chromium and compared with the CLI (`web.rs`),
//!   a step of `ci`.

mod bench;
mod guide;
mod modules;
mod python;
mod tidy;
mod validate;
mod web;

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
        Some("docs") => guide::build(&root),
        Some("web") => web::build(&root).map(drop),
        Some("web-test") => web::test(&root, args.iter().any(|a| a == "--native-timing")),
        _ => {
            eprintln!(
                "usage: cargo xtask <ci|validate [--data DIR]|validate --openrocket DIR|bench [FILTER]|docs|tidy|web|web-test [--native-timing]>"
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

/// Cargo's target directory: `CARGO_TARGET_DIR` when set (relative to `root`), else
/// `root/target`.
fn target_dir(root: &Path) -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .filter(|d| !d.is_empty())
        .map_or_else(|| root.join("target"), |d| root.join(d))
}

/// Runs `cargo` with `args` in `root`, failing on a non-zero exit.
fn cargo(root: &Path, args: &[&str]) -> Result<()> {
    cargo_with(root, args, &[])
}

/// A command for a child process of xtask, without the variables `cargo run` set for xtask
/// itself: its manifest and package figures describe the xtask crate, not the child's, and a
/// child cargo that inherited them would see a changed environment in every build script that
/// watches one (`CARGO_MANIFEST_DIR`), rebuilding what a plain `cargo build` had built.
/// `CARGO` (the path of the cargo that runs us) is kept.
pub(crate) fn child_command(program: impl AsRef<std::ffi::OsStr>) -> Command {
    let mut command = Command::new(program);
    for (key, _) in std::env::vars_os() {
        let key = key.to_string_lossy();
        if is_cargo_run_variable(&key) {
            command.env_remove(key.as_ref());
        }
    }
    command
}

/// Whether `key` is one of the variables cargo sets for the binary it runs (the cargo book,
/// "Environment variables Cargo sets for crates").
fn is_cargo_run_variable(key: &str) -> bool {
    key.starts_with("CARGO_PKG_")
        || matches!(
            key,
            "CARGO_MANIFEST_DIR"
                | "CARGO_MANIFEST_PATH"
                | "CARGO_CRATE_NAME"
                | "CARGO_BIN_NAME"
                | "CARGO_PRIMARY_PACKAGE"
        )
}

/// [`cargo`] with extra environment variables.
fn cargo_with(root: &Path, args: &[&str], envs: &[(&str, &str)]) -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    eprintln!("xtask: cargo {}", args.join(" "));
    let status = child_command(&cargo)
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

/// One step of `ci`: its name and what it runs.
type Step<'a> = (&'static str, Box<dyn Fn() -> Result<()> + 'a>);

/// Everything CI checks, step by step: each step is named when it starts and timed when it
/// ends; a failed step does not stop the later ones (a formatting slip should not hide a
/// failing test), and the run ends with one verdict line and fails if any step failed.
fn ci(root: &Path) -> Result<()> {
    // Property tests explore random cases when developers run `cargo test`; CI replays a
    // fixed seed (unless one is given) so that a landing never depends on the draw.
    let seed = std::env::var("PROPTEST_RNG_SEED").unwrap_or_else(|_| "20261123".to_owned());
    let steps: Vec<Step> = vec![
        (
            "format",
            Box::new(|| cargo(root, &["fmt", "--all", "--", "--check"])),
        ),
        (
            "clippy",
            Box::new(|| {
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
                )
            }),
        ),
        (
            "tidy",
            Box::new(|| {
                tidy::check_layering(root)?;
                tidy::check_citations(root)?;
                modules::check_module_circles(root)
            }),
        ),
        // The user guide and the API documentation build without broken links.
        ("docs", Box::new(|| guide::build(root))),
        // The network feature (`fetch`, on by default in the binary, so the workspace build
        // compiles and tests it) is tested against loopback servers only.
        (
            "tests",
            Box::new(|| {
                cargo_with(
                    root,
                    &["test", "--workspace"],
                    &[("PROPTEST_RNG_SEED", &seed)],
                )
            }),
        ),
        ("python", Box::new(|| python::test_package(root))),
        // The release validation run; with `CI` set an unavailable folder fails (as the
        // tests do).
        (
            "validation",
            Box::new(|| match karman_validation::locate() {
                Ok(_) => validate::run(root, &[]),
                Err(e) if karman_validation::in_ci() => {
                    bail!("{e} (CI is set: the validation must run)")
                }
                Err(e) => {
                    eprintln!("xtask: validation skipped: {e}");
                    Ok(())
                }
            }),
        ),
        // The browser page against the CLI (skipped without Chromium unless `CI` is set).
        ("web", Box::new(|| web::test(root, false))),
    ];
    let started = std::time::Instant::now();
    let total = steps.len();
    let mut failed = Vec::new();
    for (i, (name, step)) in steps.iter().enumerate() {
        eprintln!("xtask ci: [{}/{total}] {name} ...", i + 1);
        let t = std::time::Instant::now();
        let result = step();
        let secs = t.elapsed().as_secs_f64();
        match result {
            Ok(()) => eprintln!("xtask ci: [{}/{total}] {name} passed in {secs:.0} s", i + 1),
            Err(e) => {
                eprintln!(
                    "xtask ci: [{}/{total}] {name} FAILED in {secs:.0} s: {e:#}",
                    i + 1
                );
                failed.push(*name);
            }
        }
    }
    let verdict = format!(
        "{} passed, {} failed in {:.0} s",
        total - failed.len(),
        failed.len(),
        started.elapsed().as_secs_f64()
    );
    if failed.is_empty() {
        eprintln!("xtask ci: {verdict}");
        Ok(())
    } else {
        bail!("{verdict} (failed: {})", failed.join(", "))
    }
}
