//! The Python package's CI step: a fresh virtual environment in `target/venv`, the build and
//! test requirements from the package index, the package built from `crates/python` (maturin,
//! the `wheel` profile), and its pytest suite, which also runs the examples. Any non-zero
//! pytest exit fails CI, including 5 ("no tests collected").

use std::ffi::OsStr;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result, bail};

/// What the tests need from the package index: the build backend, the runner, numpy, and
/// RocketPy 1.13 for the adapter's parity tests (it brings matplotlib, so the examples draw
/// their figures headless).
const REQUIREMENTS: &[&str] = &["maturin>=1.9.4,<2", "pytest", "numpy", "rocketpy==1.13.0"];

/// Runs `program args...` in `root`, failing on a non-zero exit.
fn run(root: &Path, program: &Path, args: &[&str], envs: &[(&str, &OsStr)]) -> Result<()> {
    eprintln!("xtask: {} {}", program.display(), args.join(" "));
    let status = crate::child_command(program)
        .args(args)
        .envs(envs.iter().copied())
        .current_dir(root)
        .status()
        .with_context(|| format!("could not run {}", program.display()))?;
    if !status.success() {
        bail!(
            "`{} {}` failed ({status})",
            program.display(),
            args.join(" ")
        );
    }
    Ok(())
}

/// Builds the package into a fresh `target/venv` and runs its pytest suite.
pub fn test_package(root: &Path) -> Result<()> {
    let started = Instant::now();
    let venv = crate::target_dir(root).join("venv");
    let python3 = std::env::var_os("PYTHON").unwrap_or_else(|| "python3".into());
    run(
        root,
        Path::new(&python3),
        &["-m", "venv", "--clear", &venv.to_string_lossy()],
        &[],
    )?;
    let bin = venv.join("bin");
    let python = bin.join("python");
    // The environment's own `bin` first on PATH, as `activate` would do: maturin's build hook
    // runs `maturin` by name, and pytest's subprocesses find the environment's tools.
    let path = std::env::join_paths(
        std::iter::once(bin.clone()).chain(
            std::env::var_os("PATH")
                .map(|p| std::env::split_paths(&p).collect::<Vec<_>>())
                .unwrap_or_default(),
        ),
    )
    .context("the virtual environment's path cannot go on PATH")?;
    let venv_env: [(&str, &OsStr); 2] = [
        ("PATH", path.as_os_str()),
        ("VIRTUAL_ENV", venv.as_os_str()),
    ];
    let mut install = vec!["-m", "pip", "install", "--quiet", "--upgrade"];
    install.extend_from_slice(REQUIREMENTS);
    run(root, &python, &install, &venv_env)?;
    let requirements = started.elapsed();
    // The backend is already in the environment: no isolated build environment to fill.
    run(
        root,
        &python,
        &[
            "-m",
            "pip",
            "install",
            "--quiet",
            "--no-build-isolation",
            "./crates/python",
        ],
        &venv_env,
    )?;
    let built = started.elapsed();
    // The command-line binary for the tests that compare the package's files with its own.
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    run(
        root,
        Path::new(&cargo),
        &["build", "--quiet", "--package", "karman"],
        &[],
    )?;
    let cli = crate::target_dir(root).join("debug").join("karman");
    run(
        root,
        &python,
        &["-m", "pytest", "-q", "crates/python/tests"],
        &[
            venv_env[0],
            venv_env[1],
            ("KARMAN_CLI", cli.as_os_str()),
            ("MPLBACKEND", OsStr::new("Agg")),
        ],
    )?;
    eprintln!(
        "xtask: Python package: requirements {:.0} s, build {:.0} s, tests {:.0} s",
        requirements.as_secs_f64(),
        (built - requirements).as_secs_f64(),
        (started.elapsed() - built).as_secs_f64()
    );
    Ok(())
}
