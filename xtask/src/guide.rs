//! `cargo xtask docs`: the user guide (mdBook, `docs/guide`) and the API documentation in one
//! folder, `target/docs` (`index.html` links both).
//!
//! The guide is built from a copy of `docs` in `target/docs/source` (the guide and the
//! reference pages beside it, which the guide's reference chapter includes with mdBook's
//! `{{#include}}`), to which the figures the chapters show are added first, drawn by karman
//! itself from the fixtures ([`FIGURES`]), so that a figure never drifts from what the program
//! draws, and the command-line reference, written from the help clap prints for every command
//! ([`cli_reference`]). The copy's links
//! are then checked (every relative link and image names a file of the book, every `#anchor`
//! a heading of its page) before mdBook renders it. mdBook comes from the crate registry, at
//! [`MDBOOK_VERSION`], installed once into `target/tools` (a few minutes of compilation on a
//! fresh machine). The commands of the chapters themselves are run, and their output
//! checked, by the CLI's test `crates/cli/tests/guide.rs`.

use std::fs;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

/// The mdBook release the guide is built with.
pub const MDBOOK_VERSION: &str = "0.5.4";

/// The figures of the guide: the folder under `src/figures` each goes to, and the karman
/// arguments that draw it there (`{out}` is that folder, paths relative to the repository).
const FIGURES: &[(&str, &[&str])] = &[
    (
        "first-flight",
        &["simulate", "fixtures/example.toml", "--out", "{out}"],
    ),
    (
        "frames",
        &[
            "inspect",
            "fixtures/example.toml",
            "--draw",
            "{out}/rocket.svg",
        ],
    ),
    (
        "dispersion",
        &[
            "montecarlo",
            "fixtures/example.toml",
            "--samples",
            "100",
            "--quiet",
            "--out",
            "{out}",
        ],
    ),
    (
        "after-the-flight",
        &[
            "compare",
            "fixtures/validation/prometheus_2022/mission.toml",
            "fixtures/validation/prometheus_2022/2022-06-24-serial-5115-flight-0001-TeleMetrum.csv",
            "--out",
            "{out}",
        ],
    ),
];

/// Where the generated command-line reference goes in the book (the chapter
/// `src/reference/cli.md` includes it).
const CLI_REFERENCE: &str = "src/reference/cli-generated.md";

/// How deep [`cli_reference`] follows subcommands (`karman weather fetch` is depth 2).
const MAX_COMMAND_DEPTH: usize = 3;

/// The command-line reference: the help of `karman` and of every subcommand, found from the
/// `Commands:` list of each help text (clap's layout), as Markdown sections.
fn cli_reference(karman: &Path) -> Result<String> {
    let mut out = String::new();
    let mut pending = vec![Vec::<String>::new()];
    while let Some(path) = pending.pop() {
        let mut args = path.clone();
        args.push("--help".to_owned());
        let output = crate::child_command(karman)
            .args(&args)
            .env("NO_COLOR", "1")
            .output()
            .with_context(|| format!("running {}", karman.display()))?;
        if !output.status.success() {
            bail!("`karman {}` failed", args.join(" "));
        }
        let help = String::from_utf8(output.stdout).context("karman's help is not UTF-8")?;
        let title = std::iter::once("karman".to_owned())
            .chain(path.iter().cloned())
            .collect::<Vec<_>>()
            .join(" ");
        out.push_str(&format!(
            "## `{title}`\n\n```text\n{}\n```\n\n",
            help.trim_end()
        ));
        if path.len() < MAX_COMMAND_DEPTH {
            // Pushed in reverse so that the sections come in the help's order.
            for command in subcommands(&help).into_iter().rev() {
                let mut next = path.clone();
                next.push(command);
                pending.push(next);
            }
        }
    }
    Ok(out)
}

/// The subcommands a clap help text lists under `Commands:` (without `help`).
fn subcommands(help: &str) -> Vec<String> {
    help.lines()
        .skip_while(|l| l.trim() != "Commands:")
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        // A command's line is indented by two spaces; a wrapped description by more.
        .filter(|l| !l.starts_with("   "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .map(str::to_owned)
        .collect()
}

/// Builds the guide and the API documentation into `target/docs`.
pub fn build(root: &Path) -> Result<()> {
    let target = crate::target_dir(root);
    let docs = target.join("docs");
    let source = docs.join("source");
    if source.exists() {
        fs::remove_dir_all(&source).with_context(|| format!("removing {}", source.display()))?;
    }
    copy_tree(&root.join("docs"), &source)?;
    let book = source.join("guide");
    crate::cargo(root, &["build", "--package", "karman"])?;
    let karman = target.join("debug").join("karman");
    let cli = cli_reference(&karman)?;
    fs::write(book.join(CLI_REFERENCE), cli).with_context(|| format!("writing {CLI_REFERENCE}"))?;
    for (folder, args) in FIGURES {
        let out = book.join("src/figures").join(folder);
        fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
        let out_text = out.to_string_lossy();
        let args: Vec<String> = args.iter().map(|a| a.replace("{out}", &out_text)).collect();
        let output = crate::child_command(&karman)
            .args(&args)
            .current_dir(root)
            .output()
            .with_context(|| format!("running {}", karman.display()))?;
        if !output.status.success() {
            bail!(
                "`karman {}` failed: {}",
                args.join(" "),
                String::from_utf8_lossy(&output.stderr)
            );
        }
    }
    let broken = broken_links(&book.join("src"))?;
    if !broken.is_empty() {
        bail!(
            "{} broken link(s) in the guide:\n  {}",
            broken.len(),
            broken.join("\n  ")
        );
    }
    let mdbook = mdbook(root, &target)?;
    let html = docs.join("guide");
    let status = crate::child_command(&mdbook)
        .arg("build")
        .arg(&book)
        .arg("--dest-dir")
        .arg(&html)
        .status()
        .with_context(|| format!("running {}", mdbook.display()))?;
    if !status.success() {
        bail!("mdbook build failed ({status})");
    }
    crate::cargo_with(
        root,
        &["doc", "--workspace", "--no-deps"],
        &[("RUSTDOCFLAGS", "-D warnings")],
    )?;
    let api = docs.join("api");
    if api.exists() {
        fs::remove_dir_all(&api).with_context(|| format!("removing {}", api.display()))?;
    }
    copy_tree(&target.join("doc"), &api)?;
    fs::write(docs.join("index.html"), INDEX).context("writing the docs index")?;
    eprintln!(
        "xtask: the guide is in {}, the API documentation in {}",
        html.join("index.html").display(),
        api.join("karman_mission/index.html").display()
    );
    Ok(())
}

const INDEX: &str = "<!doctype html>\n<meta charset=\"utf-8\">\n<title>karman documentation</title>\n\
<h1>karman documentation</h1>\n<ul>\n<li><a href=\"guide/index.html\">The user guide</a></li>\n\
<li><a href=\"api/karman_mission/index.html\">The API documentation</a> (karman-mission and the \
crates below it)</li>\n</ul>\n";

/// The mdBook binary: `target/tools/bin/mdbook` at [`MDBOOK_VERSION`], installed from the
/// crate registry when missing or of another version.
fn mdbook(root: &Path, target: &Path) -> Result<PathBuf> {
    let tools = target.join("tools");
    let bin = tools.join("bin").join("mdbook");
    let current = crate::child_command(&bin)
        .arg("--version")
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned());
    if current.as_deref() != Some(&format!("mdbook v{MDBOOK_VERSION}")) {
        let tools = tools.to_string_lossy();
        crate::cargo(
            root,
            &[
                "install",
                "mdbook",
                "--locked",
                "--version",
                MDBOOK_VERSION,
                "--root",
                &tools,
            ],
        )?;
    }
    Ok(bin)
}

/// Copies the folder `from` to `to` (created), files and subfolders.
fn copy_tree(from: &Path, to: &Path) -> Result<()> {
    fs::create_dir_all(to).with_context(|| format!("creating {}", to.display()))?;
    for entry in fs::read_dir(from).with_context(|| format!("reading {}", from.display()))? {
        let entry = entry?;
        let path = entry.path();
        let dest = to.join(entry.file_name());
        if entry.file_type()?.is_dir() {
            copy_tree(&path, &dest)?;
        } else {
            fs::copy(&path, &dest)
                .with_context(|| format!("copying {} to {}", path.display(), dest.display()))?;
        }
    }
    Ok(())
}

/// Every broken link of the Markdown pages under `src`, as `page:line: link (why)`.
pub fn broken_links(src: &Path) -> Result<Vec<String>> {
    let mut pages = Vec::new();
    markdown_files(src, &mut pages)?;
    let mut broken = Vec::new();
    for page in &pages {
        let text =
            fs::read_to_string(page).with_context(|| format!("reading {}", page.display()))?;
        let name = page.strip_prefix(src).unwrap_or(page).display().to_string();
        let mut fenced = false;
        for (i, line) in text.lines().enumerate() {
            if line.trim_start().starts_with("```") {
                fenced = !fenced;
                continue;
            }
            if fenced {
                continue;
            }
            for link in links(line) {
                if let Some(why) = check_link(page, link)? {
                    broken.push(format!("{name}:{}: {link} ({why})", i + 1));
                }
            }
        }
    }
    Ok(broken)
}

fn markdown_files(dir: &Path, out: &mut Vec<PathBuf>) -> Result<()> {
    for entry in fs::read_dir(dir).with_context(|| format!("reading {}", dir.display()))? {
        let path = entry?.path();
        if path.is_dir() {
            markdown_files(&path, out)?;
        } else if path.extension().is_some_and(|e| e == "md") {
            out.push(path);
        }
    }
    out.sort();
    Ok(())
}

/// The targets of the inline links and images of one line of Markdown (`[text](target)`),
/// code spans left out.
fn links(line: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut in_code = false;
    let bytes = line.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'`' => in_code = !in_code,
            b']' if !in_code && bytes.get(i + 1) == Some(&b'(') => {
                let start = i + 2;
                if let Some(len) = line[start..].find(')') {
                    let target = line[start..start + len]
                        .split_whitespace()
                        .next()
                        .unwrap_or("");
                    out.push(target);
                    i = start + len;
                }
            }
            _ => {}
        }
        i += 1;
    }
    out
}

/// Why the link `target` of `page` is broken, or `None`.
fn check_link(page: &Path, target: &str) -> Result<Option<String>> {
    if target.is_empty() {
        return Ok(Some("empty target".into()));
    }
    if target.contains("://") || target.starts_with("mailto:") {
        return Ok(None);
    }
    let (file, anchor) = match target.split_once('#') {
        Some((file, anchor)) => (file, Some(anchor)),
        None => (target, None),
    };
    let dir = page.parent().unwrap_or(Path::new("."));
    let resolved = if file.is_empty() {
        page.to_path_buf()
    } else {
        dir.join(file)
    };
    if !resolved.is_file() {
        return Ok(Some("no such file in the book".into()));
    }
    if let Some(anchor) = anchor
        && resolved.extension().is_some_and(|e| e == "md")
    {
        let text = fs::read_to_string(&resolved)
            .with_context(|| format!("reading {}", resolved.display()))?;
        let found = text
            .lines()
            .filter_map(|l| l.strip_prefix('#'))
            .map(|h| heading_id(h.trim_start_matches('#')))
            .any(|id| id == anchor);
        if !found {
            return Ok(Some(format!("no heading with the id `{anchor}`")));
        }
    }
    Ok(None)
}

/// mdBook's id of a heading: lower case, alphanumerics, `-` and `_` kept, spaces to `-`,
/// everything else dropped.
fn heading_id(heading: &str) -> String {
    heading
        .trim()
        .chars()
        .filter_map(|c| {
            if c.is_alphanumeric() || c == '-' || c == '_' {
                Some(c.to_lowercase().next().unwrap_or(c))
            } else if c == ' ' {
                Some('-')
            } else {
                None
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn links_are_found_outside_code_spans() {
        assert_eq!(
            links("see [a](a.md), ![b](f/b.svg \"title\") and `[c](c.md)`"),
            ["a.md", "f/b.svg"]
        );
    }

    #[test]
    fn subcommands_are_read_from_the_commands_list() {
        let help = "Usage: karman <COMMAND>\n\nCommands:\n  check   Load a mission\n  \
                    weather  Weather\n          more text\n  help    Print\n\nOptions:\n  -h\n";
        assert_eq!(subcommands(help), ["check", "weather"]);
        assert!(subcommands("Usage: karman check <MISSION>\n\nOptions:\n  -h\n").is_empty());
    }

    #[test]
    fn heading_ids_follow_mdbook() {
        assert_eq!(
            heading_id(" Install and a first flight"),
            "install-and-a-first-flight"
        );
        assert_eq!(
            heading_id("After the flight: your altimeter's log"),
            "after-the-flight-your-altimeters-log"
        );
    }

    #[test]
    fn a_link_to_a_missing_page_or_heading_is_broken() {
        let dir = std::env::temp_dir().join(format!("karman-guide-links-{}", std::process::id()));
        fs::create_dir_all(&dir).expect("dir");
        fs::write(dir.join("a.md"), "# Title\n\n## A part\n").expect("a");
        fs::write(
            dir.join("b.md"),
            "[ok](a.md) [ok](a.md#a-part) [no](c.md) [no](a.md#other) [web](https://x.org)\n",
        )
        .expect("b");
        let broken = broken_links(&dir).expect("reads");
        fs::remove_dir_all(&dir).ok();
        assert_eq!(broken.len(), 2, "{broken:?}");
        assert!(broken[0].starts_with("b.md:1: c.md"), "{broken:?}");
        assert!(broken[1].contains("a.md#other"), "{broken:?}");
    }
}
