//! Repository rules: the crate layering of ARCHITECTURE.md, checked on `cargo metadata`.

use std::collections::BTreeSet;
use std::path::Path;
use std::process::Command;

use anyhow::{Context, Result, bail};

/// The dependency edges allowed between workspace packages (ARCHITECTURE.md, "Layers").
/// Each package may depend on the listed workspace packages and on no other.
pub const ALLOWED: &[(&str, &[&str])] = &[
    ("karman-math", &[]),
    ("karman-model", &["karman-math"]),
    ("karman-atmos", &["karman-math", "karman-model"]),
    ("karman-propulsion", &["karman-math", "karman-model"]),
    ("karman-airframe", &["karman-math", "karman-model"]),
    ("karman-dynamics", &["karman-math", "karman-model"]),
    ("karman-dispersion", &["karman-math"]),
    ("karman-script", &[]),
    (
        "karman-mission",
        &[
            "karman-math",
            "karman-model",
            "karman-atmos",
            "karman-propulsion",
            "karman-airframe",
            "karman-dynamics",
            "karman-dispersion",
            "karman-script",
        ],
    ),
    ("karman", &["karman-mission"]),
    ("karman-python", &["karman-mission"]),
    ("karman-validation", &[]),
    (
        "xtask",
        &["karman-mission", "karman-dispersion", "karman-validation"],
    ),
];

/// The crate of the validation flights: any crate's tests may use it (a dev-dependency),
/// outside [`ALLOWED`].
pub const TEST_DATA: &str = "karman-validation";

/// Every workspace-internal dependency edge `(from, to)` found in `cargo metadata` JSON, but
/// the dev-dependencies on [`TEST_DATA`].
pub fn workspace_edges(metadata: &serde_json::Value) -> Result<BTreeSet<(String, String)>> {
    let packages = metadata["packages"]
        .as_array()
        .context("metadata has no packages")?;
    let names: BTreeSet<&str> = packages.iter().filter_map(|p| p["name"].as_str()).collect();
    let mut edges = BTreeSet::new();
    for p in packages {
        let from = p["name"].as_str().context("package without a name")?;
        for d in p["dependencies"].as_array().into_iter().flatten() {
            let to = d["name"].as_str().context("dependency without a name")?;
            let test_data = to == TEST_DATA && d["kind"].as_str() == Some("dev");
            if names.contains(to) && !test_data {
                edges.insert((from.to_owned(), to.to_owned()));
            }
        }
    }
    Ok(edges)
}

/// The edges of `edges` that ALLOWED does not permit, and packages it does not know.
pub fn violations(edges: &BTreeSet<(String, String)>) -> Vec<String> {
    let mut out = Vec::new();
    for (from, to) in edges {
        match ALLOWED.iter().find(|(p, _)| p == from) {
            None => out.push(format!("{from} is not a known crate of ARCHITECTURE.md")),
            Some((_, allowed)) if !allowed.contains(&to.as_str()) => {
                out.push(format!("{from} must not depend on {to}"));
            }
            Some(_) => {}
        }
    }
    out
}

/// `cargo metadata --no-deps` of the workspace at `root`, as JSON.
fn metadata(root: &Path) -> Result<serde_json::Value> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    let out = Command::new(cargo)
        .args([
            "metadata",
            "--format-version",
            "1",
            "--no-deps",
            "--offline",
        ])
        .current_dir(root)
        .output()
        .context("could not run cargo metadata")?;
    if !out.status.success() {
        bail!(
            "cargo metadata failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    Ok(serde_json::from_slice(&out.stdout)?)
}

/// Fails on any workspace edge outside the layering.
pub fn check_layering(root: &Path) -> Result<()> {
    let bad = violations(&workspace_edges(&metadata(root)?)?);
    if !bad.is_empty() {
        bail!(
            "crate layering violated (see ARCHITECTURE.md):\n  {}",
            bad.join("\n  ")
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn workspace_follows_the_layering() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"))
            .parent()
            .expect("workspace root");
        check_layering(root).expect("layering");
    }

    #[test]
    fn every_crate_of_the_workspace_is_listed() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"))
            .parent()
            .expect("workspace root");
        let metadata = metadata(root).expect("cargo metadata");
        for p in metadata["packages"].as_array().expect("packages") {
            let name = p["name"].as_str().expect("name");
            assert!(
                ALLOWED.iter().any(|(n, _)| *n == name),
                "{name} missing from ALLOWED"
            );
        }
    }

    #[test]
    fn only_tests_may_use_the_validation_crate() {
        let metadata = serde_json::json!({"packages": [
            {"name": "karman-math", "dependencies": [{"name": TEST_DATA, "kind": "dev"}]},
            {"name": "karman-atmos", "dependencies": [{"name": TEST_DATA, "kind": null}]},
            {"name": TEST_DATA, "dependencies": []},
        ]});
        let edges = workspace_edges(&metadata).expect("edges");
        let bad = violations(&edges);
        assert_eq!(
            bad,
            ["karman-atmos must not depend on karman-validation"],
            "{edges:?}"
        );
    }

    #[test]
    fn a_forbidden_edge_is_reported() {
        let edges: BTreeSet<(String, String)> = [
            ("karman-atmos".to_owned(), "karman-math".to_owned()),
            ("karman-math".to_owned(), "karman-dynamics".to_owned()),
            ("karman-airframe".to_owned(), "karman-propulsion".to_owned()),
        ]
        .into();
        let bad = violations(&edges);
        assert_eq!(bad.len(), 2, "{bad:?}");
        assert!(
            bad.iter()
                .any(|m| m.contains("karman-math must not depend on karman-dynamics"))
        );
        assert!(
            bad.iter()
                .any(|m| m.contains("airframe must not depend on karman-propulsion"))
        );
    }
}
