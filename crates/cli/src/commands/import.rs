//! `karman import DESIGN.ork -o MISSION.toml`: an OpenRocket design as a commented mission
//! (karman-openrocket), its motor's thrust curve found by designation.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use karman_openrocket::{ImportOptions, import};

/// Arguments of `karman import`.
#[derive(Debug, Args)]
pub struct ImportArgs {
    /// The OpenRocket design (`.ork`: zip archive or plain XML).
    #[arg(value_name = "DESIGN")]
    pub design: PathBuf,
    /// The stored simulation whose motor and launch conditions to use (default: the first).
    #[arg(long, value_name = "NAME")]
    pub simulation: Option<String>,
    /// A thrust-curve file (.eng), or a folder of them, searched for the motor by designation
    /// (repeatable; the design's folder is searched last).
    #[arg(long = "motor", value_name = "FILE|DIR")]
    pub motors: Vec<PathBuf>,
    /// Where to write the mission.
    #[arg(
        short = 'o',
        long = "out",
        alias = "output",
        value_name = "MISSION.toml"
    )]
    pub output: PathBuf,
}

/// Reads the design and writes the mission.
///
/// Refused before anything is read: a `--motor` path that does not exist (a typo would
/// otherwise only show as a motor not found), and an output that is the design itself
/// (`import X.ork -o X.ork` would replace the design with its mission).
pub fn run(args: &ImportArgs) -> Result<()> {
    for motor in &args.motors {
        if !motor.exists() {
            bail!("--motor {}: no such file or folder", motor.display());
        }
    }
    let same = |a: &std::path::Path, b: &std::path::Path| matches!((a.canonicalize(), b.canonicalize()), (Ok(a), Ok(b)) if a == b);
    if same(&args.design, &args.output) {
        bail!(
            "-o {}: that is the design being imported; name another file for the mission",
            args.output.display()
        );
    }
    let options = ImportOptions {
        simulation: args.simulation.clone(),
        motors: args.motors.clone(),
        output_dir: args.output.parent().map(|p| {
            if p.as_os_str().is_empty() {
                PathBuf::from(".")
            } else {
                p.to_path_buf()
            }
        }),
    };
    let imported = import(&args.design, &options)?;
    std::fs::write(&args.output, &imported.mission)
        .with_context(|| format!("cannot write {}", args.output.display()))?;
    let mut err = std::io::stderr().lock();
    for warning in &imported.warnings {
        let _ = writeln!(err, "{}: warning: {warning}", args.design.display());
    }
    Ok(())
}
