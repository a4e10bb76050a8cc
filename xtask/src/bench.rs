//! `cargo xtask bench [FILTER]`: run every criterion benchmark of the workspace in release and
//! print one line per benchmark with its median time (and, where the benchmark declares a
//! throughput in elements, the rate and the time per element: right-hand-side evaluations of
//! a flight, flights of a Monte Carlo run; in bytes, MB/s and the time per byte: a flight
//! log read), read from criterion's
//! `target/criterion/**/new/estimates.json` written by this run (older files, of benchmarks
//! since renamed or removed, are left out). Speed targets live here, never in timed tests.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use serde_json::Value;

/// Runs the benchmarks (optionally only those matching `filter`) and prints the medians.
pub fn run(root: &Path, args: &[String]) -> Result<()> {
    let mut cargo_args = vec!["bench", "--workspace", "--benches", "--"];
    if let Some(filter) = args.first() {
        cargo_args.push(filter);
    }
    // File times have a coarse resolution on some systems: a second of slack.
    let started = std::time::SystemTime::now() - std::time::Duration::from_secs(1);
    crate::cargo(root, &cargo_args)?;
    let dir = crate::target_dir(root).join("criterion");
    let mut found = Vec::new();
    collect(&dir, &mut found)?;
    found.retain(|path| {
        std::fs::metadata(path)
            .and_then(|m| m.modified())
            .is_ok_and(|modified| modified >= started)
    });
    found.sort();
    println!(
        "{:<42} {:>14} {:>18} {:>14}",
        "benchmark", "median", "throughput", "per element"
    );
    for path in found {
        let text = std::fs::read_to_string(&path)?;
        let v: Value = serde_json::from_str(&text).with_context(|| path.display().to_string())?;
        let Some(ns) = v["median"]["point_estimate"].as_f64() else {
            continue;
        };
        let name = path
            .strip_prefix(&dir)
            .ok()
            .and_then(|p| p.parent()?.parent())
            .map_or_else(String::new, |p| p.display().to_string());
        // Elements per second where the bench declares a throughput (criterion's
        // benchmark.json beside the estimates).
        let throughput = std::fs::read_to_string(path.with_file_name("benchmark.json"))
            .ok()
            .and_then(|t| serde_json::from_str::<Value>(&t).ok())
            .map(|b| b["throughput"].clone());
        let elements = throughput.as_ref().and_then(|t| t["Elements"].as_f64());
        let bytes = throughput.as_ref().and_then(|t| t["Bytes"].as_f64());
        let (rate, each) = match (elements, bytes) {
            (Some(n), _) => (format!("{:.0} /s", n / (ns * 1e-9)), human(ns / n)),
            (None, Some(n)) => (
                format!("{:.1} MB/s", n / (ns * 1e-9) / 1e6),
                format!("{} /B", human(ns / n)),
            ),
            (None, None) => (String::new(), String::new()),
        };
        println!("{name:<42} {:>14} {rate:>18} {each:>14}", human(ns));
    }
    Ok(())
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) -> Result<()> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            collect(&p, out)?;
        } else if p.ends_with("new/estimates.json") {
            out.push(p);
        }
    }
    Ok(())
}

/// A duration in ns printed with a sensible unit.
fn human(ns: f64) -> String {
    match ns {
        n if n < 1e3 => format!("{n:.2} ns"),
        n if n < 1e6 => format!("{:.2} µs", n / 1e3),
        n if n < 1e9 => format!("{:.3} ms", n / 1e6),
        n => format!("{:.3} s", n / 1e9),
    }
}

#[cfg(test)]
mod tests {
    use super::human;

    #[test]
    fn units() {
        assert_eq!(human(12.345), "12.35 ns");
        assert_eq!(human(2_500.0), "2.50 µs");
        assert_eq!(human(310_000.0), "310.00 µs");
        assert_eq!(human(4.5e7), "45.000 ms");
    }
}
