//! `karman merge OUT DIR...`: join the output directories of every shard of one Monte Carlo
//! study into OUT, with exactly the files a single run makes. Exit code 1 when no sample of
//! the study completed its flight, as `karman montecarlo`.

use super::montecarlo::print_summary;
use anyhow::{Result, bail};
use clap::Args;
use karman_mission::dispersion::merge;
use std::io::Write;
use std::path::PathBuf;

/// Arguments of `karman merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// Output directory of the merged study.
    #[arg(value_name = "OUT")]
    pub out: PathBuf,
    /// The shard directories (`karman montecarlo --shard K/N --out DIR`), every shard once.
    #[arg(value_name = "DIR", required = true)]
    pub dirs: Vec<PathBuf>,
}

/// Merges the shards and prints the summary.
pub fn run(args: &MergeArgs) -> Result<()> {
    let summary = merge(&args.out, &args.dirs)?;
    let mut out = std::io::stdout().lock();
    print_summary(&mut out, &summary)?;
    writeln!(
        out,
        "seed {}; results in {}",
        summary.seed,
        args.out.display()
    )?;
    if summary.counts.completed == 0 {
        bail!(
            "no sample of the study completed its flight ({})",
            summary.counts
        );
    }
    Ok(())
}
