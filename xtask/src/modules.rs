//! Module circles: the sibling modules of a folder (the files beside its `mod.rs`) must not
//! use each other in a circle. An edge `a → b` is any `super::b::` path in `a` (in `use`
//! lines, groups `use super::{b::X, …}` included, and in code), or the folder's own
//! `crate::…::b::` path; comments are ignored. The parent (`mod.rs`) and the folder's
//! `tests.rs` are not siblings: they may use everything.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::Path;

use anyhow::{Context, Result, bail};

/// The folders (relative to the workspace root) whose sibling modules form no circle.
pub const ACYCLIC: &[&str] = &[
    "crates/dispersion/src",
    "crates/dynamics/src/equations",
    "crates/dynamics/src/flight",
    "crates/dynamics/src/integrator",
    "crates/mission/src/assemble",
    "crates/script/src",
];

/// The sibling modules each sibling of `dir` uses: `module → used modules`.
pub fn sibling_edges(dir: &Path) -> Result<BTreeMap<String, BTreeSet<String>>> {
    let mut sources = BTreeMap::new();
    for entry in fs::read_dir(dir).with_context(|| format!("reading {}", dir.display()))? {
        let path = entry?.path();
        let Some(stem) = path.file_stem().and_then(|s| s.to_str()) else {
            continue;
        };
        let module = stem.to_owned();
        if path.extension().is_some_and(|e| e == "rs") && module != "mod" && module != "tests" {
            let text =
                fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
            sources.insert(module, text);
        }
    }
    // The folder's own path from the crate root, e.g. `crate::flight::`.
    let own = dir
        .components()
        .rev()
        .take_while(|c| c.as_os_str() != "src")
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect::<Vec<_>>();
    let prefix = std::iter::once("crate".to_owned())
        .chain(own.into_iter().rev())
        .collect::<Vec<_>>()
        .join("::")
        + "::";
    let names: BTreeSet<String> = sources.keys().cloned().collect();
    let mut edges = BTreeMap::new();
    for (module, text) in &sources {
        let code = strip_comments(text);
        let mut used = BTreeSet::new();
        for start in ["super::".to_owned(), prefix.clone()] {
            for used_name in paths_after(&code, &start) {
                if names.contains(&used_name) && used_name != *module {
                    used.insert(used_name);
                }
            }
        }
        edges.insert(module.clone(), used);
    }
    Ok(edges)
}

/// The source without its `//` comments (doc comments included).
fn strip_comments(text: &str) -> String {
    text.lines()
        .map(|l| l.find("//").map_or(l, |i| &l[..i]))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The first path segments after every `start`: `start b::` gives `b`, and a group
/// `start {b::X, c::{Y, Z}, W}` gives `b`, `c` and `W`.
fn paths_after(code: &str, start: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find(start) {
        rest = &rest[i + start.len()..];
        if let Some(group) = rest.strip_prefix('{') {
            // The top-level items of the group.
            let mut depth = 0;
            let mut item = String::new();
            for c in group.chars() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        out.push(first_segment(&item));
                        item.clear();
                        continue;
                    }
                    _ => {}
                }
                if depth == 0 || c != '{' {
                    item.push(c);
                }
            }
            out.push(first_segment(&item));
        } else {
            out.push(first_segment(rest));
        }
    }
    out
}

/// The identifier at the start of `s` (after white space).
fn first_segment(s: &str) -> String {
    s.trim_start()
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect()
}

/// A circle of `edges`, as the modules along it (the first repeated at the end), if any.
pub fn find_circle(edges: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    /// Depth-first search; `path` holds the modules on the current path.
    fn visit(
        node: &str,
        edges: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(i) = path.iter().position(|p| p == node) {
            let mut circle = path[i..].to_vec();
            circle.push(node.to_owned());
            return Some(circle);
        }
        if done.contains(node) {
            return None;
        }
        path.push(node.to_owned());
        for next in edges.get(node).into_iter().flatten() {
            if let Some(circle) = visit(next, edges, path, done) {
                return Some(circle);
            }
        }
        path.pop();
        done.insert(node.to_owned());
        None
    }
    let mut done = BTreeSet::new();
    edges
        .keys()
        .find_map(|node| visit(node, edges, &mut Vec::new(), &mut done))
}

/// Fails when the sibling modules of an [`ACYCLIC`] folder use each other in a circle.
pub fn check_module_circles(root: &Path) -> Result<()> {
    let mut bad = Vec::new();
    for dir in ACYCLIC {
        if let Some(circle) = find_circle(&sibling_edges(&root.join(dir))?) {
            bad.push(format!("{dir}: {}", circle.join(" -> ")));
        }
    }
    if !bad.is_empty() {
        bail!("sibling modules in a circle:\n  {}", bad.join("\n  "));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn engine_modules_form_no_circle() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"))
            .parent()
            .expect("workspace root");
        check_module_circles(root).expect("no circle");
        // The engine's loop uses its parts; none of them uses it back.
        let edges = sibling_edges(&root.join("crates/dynamics/src/flight")).expect("edges");
        assert!(edges["run"].contains("schedule") && edges["run"].contains("instants"));
        assert!(
            edges.iter().all(|(_, used)| !used.contains("run")),
            "{edges:?}"
        );
    }

    #[test]
    fn a_circle_through_a_use_group_is_found() {
        let dir = std::env::temp_dir().join(format!("karman-modules-{}", std::process::id()));
        fs::create_dir_all(&dir).expect("temp dir");
        let files = [
            ("mod.rs", "mod a;\nmod b;\nmod c;\n"),
            ("a.rs", "use super::{c::Z, b::{X, Y}};\n"),
            (
                "b.rs",
                "// super::a::Nothing in a comment\nfn f() { crate::x::c::g(); }\n",
            ),
            ("c.rs", "pub fn g() { super::a::h() }\n"),
        ];
        for (name, text) in files {
            fs::write(dir.join(name), text).expect("write");
        }
        // The folder is read as module `x` of its crate only under a `src` folder; here
        // its `crate::` prefix is the temp path's, so b's edge comes from `super::` only.
        let edges = sibling_edges(&dir).expect("edges");
        assert_eq!(edges["a"], ["b", "c"].map(String::from).into());
        assert!(edges["b"].is_empty(), "{edges:?}");
        let circle = find_circle(&edges).expect("a -> c -> a");
        assert_eq!(circle, ["a", "c", "a"].map(String::from));
        fs::remove_dir_all(&dir).expect("clean up");
    }
}
