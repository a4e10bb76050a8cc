//! The user guide's blocks run (docs/guide/src): every command the guide shows is run, and the
//! output it shows is checked, so that the guide cannot drift from the program.
//!
//! The rules the chapters are written to:
//! - A ` ```console ` block is run. Each line starting with `$ ` is a command, run by `sh` in the
//!   chapter's working folder with the `karman` binary first on `PATH`; the lines after it, up
//!   to the next command, are output it must print: each, with runs of white space made one,
//!   must be a line of its standard output or error, in order (`...` stands for lines left
//!   out; the working folder's path is shown as `$PWD`). The command must succeed, unless the
//!   block is ` ```console,exit=N `.
//! - A ` ```toml,file=NAME ` block is written to `NAME` in the working folder before the
//!   commands after it run (` ```toml,file=NAME,append ` adds it to the end of the file, so
//!   that a chapter builds a mission part by part); any other ` ```toml ` block is a fragment
//!   and must parse as TOML. A ` ```rhai,file=NAME ` block (a controller script) is written
//!   the same way; other ` ```rhai ` blocks are shown only.
//! - A ` ```sh ` block is not run: it may hold only commands the test cannot run here (`cargo`,
//!   `pip`, `git`, `python3 -m venv`, `source`), so no `karman` command hides in one.
//! - A ` ```python ` block is run by the Python package's tests
//!   (`crates/python/tests/test_guide.py`), where its `assert`s state the figures.
//!
//! Each chapter has a working folder of its own, holding a link `fixtures` to the repository's
//! fixtures: the guide's paths are the repository's.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The guide's chapters, in SUMMARY.md's order.
fn chapters() -> Vec<PathBuf> {
    let src = guide_src();
    let summary = std::fs::read_to_string(src.join("SUMMARY.md")).expect("SUMMARY.md");
    summary
        .lines()
        .filter_map(|line| {
            let start = line.find("](")? + 2;
            let end = start + line[start..].find(')')?;
            Some(src.join(&line[start..end]))
        })
        .collect()
}

fn guide_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/guide/src")
}

/// One fenced block: its info string, its first line's number and its lines.
struct Block {
    info: String,
    line: usize,
    lines: Vec<String>,
}

fn blocks(text: &str) -> Vec<Block> {
    let mut out = Vec::new();
    let mut open: Option<Block> = None;
    for (i, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        if let Some(rest) = trimmed.strip_prefix("```") {
            match open.take() {
                Some(block) => out.push(block),
                None => {
                    open = Some(Block {
                        info: rest.trim().to_owned(),
                        line: i + 1,
                        lines: Vec::new(),
                    });
                }
            }
        } else if let Some(block) = &mut open {
            block.lines.push(line.to_owned());
        }
    }
    assert!(open.is_none(), "a block is not closed");
    out
}

/// The words of `line` joined by single spaces.
fn squeeze(line: &str) -> String {
    line.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Runs `command` in `dir`; checks its exit code and that `expected` appear in order.
fn run(chapter: &str, line: usize, dir: &Path, command: &str, expected: &[String], exit: i32) {
    let bin = Path::new(env!("CARGO_BIN_EXE_karman"))
        .parent()
        .expect("the binary's folder")
        .to_owned();
    let path = std::env::join_paths(std::iter::once(bin).chain(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    )))
    .expect("PATH");
    let output = Command::new("sh")
        .arg("-c")
        .arg(command)
        .current_dir(dir)
        .env("PATH", path)
        .env("NO_COLOR", "1")
        .output()
        .expect("sh runs");
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    let place = format!("{chapter}:{line}: `{command}`");
    assert!(
        !stderr.contains("panicked at"),
        "{place} panicked: {stderr}"
    );
    assert_eq!(
        output.status.code(),
        Some(exit),
        "{place} exited {:?}\nstdout:\n{stdout}\nstderr:\n{stderr}",
        output.status.code()
    );
    // The working folder is shown as `$PWD`, as the commands that name it write it.
    let folder = dir.display().to_string();
    let printed: Vec<String> = stdout
        .lines()
        .chain(stderr.lines())
        .map(|l| squeeze(&l.replace(&folder, "$PWD")))
        .collect();
    let mut at = 0;
    for want in expected
        .iter()
        .map(|l| squeeze(l))
        .filter(|l| !l.is_empty() && l != "...")
    {
        match printed[at..].iter().position(|p| *p == want) {
            Some(i) => at += i + 1,
            None => panic!(
                "{place}: the guide shows the line\n  {want}\nwhich the command does not print \
                 (after the lines already matched); it printed:\n{}",
                printed.join("\n")
            ),
        }
    }
}

/// Writes a block's `body` to `file` in `dir`, or adds it to the file's end when `append`.
fn write_block(dir: &Path, file: &str, body: &str, append: bool) -> std::io::Result<()> {
    let path = dir.join(file);
    let mut text = if append {
        std::fs::read_to_string(&path)?
    } else {
        String::new()
    };
    text.push_str(body);
    text.push('\n');
    std::fs::write(&path, text)
}

/// Commands a ` ```sh ` block may hold (not run by the test).
const NOT_RUN: [&str; 5] = ["cargo ", "pip ", "git ", "python3 -m venv", "source "];

fn check_chapter(path: &Path) {
    let name = path
        .strip_prefix(guide_src())
        .unwrap_or(path)
        .display()
        .to_string();
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{name}: {e}"));
    let dir = tempfile::tempdir().expect("a scratch folder");
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures");
    std::os::unix::fs::symlink(&fixtures, dir.path().join("fixtures")).expect("link");
    for block in blocks(&text) {
        let mut words = block.info.split(',');
        let language = words.next().unwrap_or("").trim();
        let attribute = |key: &str| {
            block
                .info
                .split(',')
                .find_map(|w| w.trim().strip_prefix(key)?.strip_prefix('='))
                .map(str::to_owned)
        };
        match language {
            "console" => {
                let exit = attribute("exit").map_or(0, |e| e.parse().expect("exit=N"));
                let mut current: Option<(usize, String, Vec<String>)> = None;
                for (i, line) in block.lines.iter().enumerate() {
                    if let Some(command) = line.strip_prefix("$ ") {
                        if let Some((at, command, expected)) = current.take() {
                            run(&name, at, dir.path(), &command, &expected, 0);
                        }
                        current = Some((block.line + 1 + i, command.to_owned(), Vec::new()));
                    } else if let Some((_, _, expected)) = &mut current {
                        expected.push(line.clone());
                    } else {
                        panic!("{name}:{}: output before any command", block.line + 1 + i);
                    }
                }
                // The block's exit code is its last command's.
                let (at, command, expected) =
                    current.unwrap_or_else(|| panic!("{name}:{}: no command", block.line));
                run(&name, at, dir.path(), &command, &expected, exit);
            }
            "toml" | "rhai" => {
                let body = block.lines.join("\n");
                match attribute("file") {
                    Some(file) => {
                        let append = block.info.split(',').any(|w| w.trim() == "append");
                        write_block(dir.path(), &file, &body, append)
                            .unwrap_or_else(|e| panic!("{name}:{}: {file}: {e}", block.line));
                    }
                    None if language == "toml" => {
                        if let Err(e) = body.parse::<toml::Table>() {
                            panic!(
                                "{name}:{}: the TOML fragment does not parse: {e}",
                                block.line
                            );
                        }
                    }
                    None => {}
                }
            }
            "sh" => {
                for line in &block.lines {
                    let line = line.trim();
                    assert!(
                        line.is_empty()
                            || line.starts_with('#')
                            || NOT_RUN.iter().any(|c| line.starts_with(c)),
                        "{name}:{}: `{line}` would not be run: show it in a console block",
                        block.line
                    );
                }
            }
            _ => {}
        }
    }
}

#[test]
fn every_block_of_the_guide_runs_and_prints_what_it_shows() {
    let chapters = chapters();
    assert!(chapters.len() >= 3, "{chapters:?}");
    for chapter in &chapters {
        check_chapter(chapter);
    }
}
