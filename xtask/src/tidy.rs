//! Repository rules: the crate layering of ARCHITECTURE.md, checked on `cargo metadata`, and
//! the code's citations of the physics reference, checked against its headings.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

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
    ("karman-sensors", &["karman-math"]),
    (
        "karman-openrocket",
        &["karman-math", "karman-airframe", "karman-propulsion"],
    ),
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
            "karman-sensors",
            "karman-openrocket",
        ],
    ),
    ("karman-flightlog", &["karman-math"]),
    ("karman-fit", &["karman-mission", "karman-flightlog"]),
    (
        "karman",
        &[
            "karman-mission",
            "karman-flightlog",
            "karman-fit",
            "karman-openrocket",
        ],
    ),
    (
        "karman-python",
        &["karman-mission", "karman-flightlog", "karman-fit"],
    ),
    ("karman-web", &["karman-mission", "karman-openrocket"]),
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
    let out = crate::child_command(cargo)
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

/// The physics reference the code cites as `docs/physics.md §N.M`, from the workspace root.
pub const PHYSICS: &str = "docs/physics.md";

/// The folders whose files may cite [`PHYSICS`], from the workspace root.
const CITING: &[&str] = &["crates", "xtask"];

/// The kinds of file searched for citations (sources, docs, Python, manifests).
const CITING_EXTENSIONS: &[&str] = &["rs", "md", "py", "pyi", "toml"];

/// The section numbers of a Markdown text's headings: `## 7. Aerodynamics` gives `7`,
/// `### 7.5 Fin sets` gives `7.5`; headings that do not start with a number give none.
pub fn section_numbers(markdown: &str) -> BTreeSet<String> {
    markdown
        .lines()
        .filter_map(|line| {
            let title = line.trim_start_matches('#');
            if title.len() == line.len() || !title.starts_with(' ') {
                return None;
            }
            let (number, _) = number(title.trim_start())?;
            Some(number)
        })
        .collect()
}

/// One citation of the physics reference: the line it starts on, whether it names the file
/// as [`PHYSICS`] (not a bare `physics.md`), and the sections it cites (both ends of a range).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Citation {
    /// 1-based line of `physics.md` in the text.
    pub line: usize,
    /// Whether the file is named `docs/physics.md`.
    pub qualified: bool,
    /// The section numbers cited, in order.
    pub sections: Vec<String>,
}

/// A section number at the start of `s` (`7`, `7.5`, `15.3.1`; a trailing full stop is not
/// part of it) and the rest of `s`.
fn number(s: &str) -> Option<(String, &str)> {
    let digits = |s: &str| s.bytes().take_while(u8::is_ascii_digit).count();
    let mut end = digits(s);
    if end == 0 {
        return None;
    }
    while s[end..].starts_with('.') && digits(&s[end + 1..]) > 0 {
        end += 1 + digits(&s[end + 1..]);
    }
    Some((s[..end].to_owned(), &s[end..]))
}

/// `s` without the blanks, line breaks and comment leaders (`//`, `///`, `//!`, `#`) that a
/// citation may wrap across.
fn skip_gap(mut s: &str) -> &str {
    loop {
        s = s.trim_start_matches([' ', '\t']);
        let Some(rest) = s.strip_prefix('\n') else {
            return s;
        };
        let rest = rest.trim_start();
        s = ["//!", "///", "//", "#"]
            .iter()
            .find_map(|leader| rest.strip_prefix(leader))
            .unwrap_or(rest);
    }
}

/// Every citation `physics.md §A[, §B | –B | / §B | and §B]…` of `text`. A mention of the
/// file without a `§` after it is no citation.
pub fn citations(text: &str) -> Vec<Citation> {
    let mut out = Vec::new();
    for (at, _) in text.match_indices("physics.md") {
        let qualified = text[..at].ends_with("docs/");
        let mut rest = skip_gap(text[at + "physics.md".len()..].trim_start_matches('`'));
        let mut sections = Vec::new();
        while let Some(after) = rest.strip_prefix('§') {
            let Some((section, tail)) = number(after) else {
                break;
            };
            sections.push(section);
            rest = tail;
            // A further section: `, §B`, `/ §B`, `and §B`, or a range `–B` / `–§B`.
            let t = rest.trim_start();
            let (next, range) = if let Some(t) = t.strip_prefix(['–', '-']) {
                (skip_gap(t), true)
            } else if let Some(t) = [",", "/", "and "].iter().find_map(|s| t.strip_prefix(s)) {
                (skip_gap(t), false)
            } else {
                break;
            };
            if next.starts_with('§') {
                rest = next;
            } else if let Some((section, tail)) = number(next).filter(|_| range) {
                // A range's end without `§`; a list may go on after it.
                sections.push(section);
                match tail.trim_start().strip_prefix([',', '/']) {
                    Some(after) => rest = skip_gap(after),
                    None => break,
                }
            } else {
                break;
            }
        }
        if !sections.is_empty() {
            let line = text[..at].matches('\n').count() + 1;
            out.push(Citation {
                line,
                qualified,
                sections,
            });
        }
    }
    out
}

/// The files under `dir` (recursively, build output excluded) that may cite [`PHYSICS`].
fn citing_files(dir: &Path, out: &mut Vec<PathBuf>) -> Result<()> {
    for entry in std::fs::read_dir(dir).with_context(|| format!("reading {}", dir.display()))? {
        let path = entry?.path();
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if path.is_dir() {
            if name != "target" && !name.starts_with('.') {
                citing_files(&path, out)?;
            }
        } else if path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| CITING_EXTENSIONS.contains(&e))
        {
            out.push(path);
        }
    }
    Ok(())
}

/// Every citation under `root`'s [`CITING`] folders that does not name [`PHYSICS`] or names a
/// section its headings do not have, as `file:line: problem`.
///
/// # Errors
/// When the reference or a folder cannot be read.
pub fn citation_errors(root: &Path) -> Result<Vec<String>> {
    let reference = std::fs::read_to_string(root.join(PHYSICS))
        .with_context(|| format!("reading {PHYSICS}"))?;
    let sections = section_numbers(&reference);
    let mut files = Vec::new();
    for dir in CITING {
        citing_files(&root.join(dir), &mut files)?;
    }
    files.sort();
    let mut errors = Vec::new();
    for file in files {
        let Ok(text) = std::fs::read_to_string(&file) else {
            continue;
        };
        let shown = file
            .strip_prefix(root)
            .unwrap_or(&file)
            .display()
            .to_string();
        for c in citations(&text) {
            if !c.qualified {
                errors.push(format!(
                    "{shown}:{}: cite the physics reference as `{PHYSICS} §…`",
                    c.line
                ));
            }
            for s in c.sections.iter().filter(|s| !sections.contains(*s)) {
                errors.push(format!("{shown}:{}: {PHYSICS} has no section {s}", c.line));
            }
        }
    }
    Ok(errors)
}

/// Fails on any citation [`citation_errors`] reports.
///
/// # Errors
/// The list of bad citations, or a file that cannot be read.
pub fn check_citations(root: &Path) -> Result<()> {
    let bad = citation_errors(root)?;
    if !bad.is_empty() {
        bail!(
            "citations of {PHYSICS} that name no section of it:\n  {}",
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
        let root = &crate::workspace_root();
        check_layering(root).expect("layering");
    }

    #[test]
    fn every_crate_of_the_workspace_is_listed() {
        let root = &crate::workspace_root();
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

    #[test]
    fn every_physics_citation_names_a_section() {
        let root = &crate::workspace_root();
        let bad = citation_errors(root).expect("citations read");
        assert!(bad.is_empty(), "bad citations:\n  {}", bad.join("\n  "));
    }

    #[test]
    fn headings_give_their_section_numbers() {
        let doc = "# Title\n## 0. Notation\n## 7. Aerodynamics\n### 7.5 Fin sets\n\
                   ### 15.3 Liquid motor **[RP]**\n#no heading\n## References\n";
        let got: Vec<String> = section_numbers(doc).into_iter().collect();
        assert_eq!(got, ["0", "15.3", "7", "7.5"]);
    }

    #[test]
    fn citations_are_read_with_their_lists_and_ranges() {
        // The file's name is split so that this test's text is not itself a citation.
        let (file, bare) = (
            format!("docs/{}.md", "physics"),
            format!("{}.md", "physics"),
        );
        let text = format!(
            "/// a ({file} §5.3–§5.5, §8.4 / §12.2) b\n\
             //! c {file} §15.3–15.4, §7\n\
             /// d {bare} §4.1 item 6 and §13\n\
             /// e `{file}` §2.5, §5, §7,\n/// §8.4), f\n\
             /// g {file}\n/// §9.1 step 4, §9.2. h {file} follows\n"
        );
        let got = citations(&text);
        let secs = |c: &Citation| c.sections.join(" ");
        // A mention without `§` (h) is no citation.
        assert_eq!(got.len(), 5, "{got:?}");
        assert_eq!((got[0].line, secs(&got[0])), (1, "5.3 5.5 8.4 12.2".into()));
        assert_eq!(secs(&got[1]), "15.3 15.4 7");
        assert_eq!((got[2].qualified, secs(&got[2])), (false, "4.1".into()));
        assert!(got[3].qualified, "a backquoted name still names the file");
        assert_eq!(secs(&got[3]), "2.5 5 7 8.4");
        assert_eq!((got[4].line, secs(&got[4])), (6, "9.1".into()));
    }

    #[test]
    fn a_citation_of_a_missing_section_is_reported() {
        let dir = std::env::temp_dir().join(format!("karman-tidy-{}", std::process::id()));
        let src = dir.join("crates/demo/src");
        std::fs::create_dir_all(&src).expect("temporary folders");
        std::fs::create_dir_all(dir.join("xtask")).expect("temporary folders");
        std::fs::create_dir_all(dir.join("docs")).expect("temporary folders");
        std::fs::write(dir.join(PHYSICS), "## 4. Environment\n### 4.1 ISA\n").expect("write");
        let (file, bare) = (
            format!("docs/{}.md", "physics"),
            format!("{}.md", "physics"),
        );
        std::fs::write(
            src.join("lib.rs"),
            format!("//! ISA ({file} §4.1), gravity ({file} §4.3).\n//! {bare} §4\n"),
        )
        .expect("write");
        let bad = citation_errors(&dir).expect("citations read");
        std::fs::remove_dir_all(&dir).ok();
        assert_eq!(
            bad,
            [
                format!("crates/demo/src/lib.rs:1: {PHYSICS} has no section 4.3"),
                format!("crates/demo/src/lib.rs:2: cite the physics reference as `{PHYSICS} §…`"),
            ]
        );
    }
}
