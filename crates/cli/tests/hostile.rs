//! The hostile-input suite: missions, trigger expressions, controller scripts, `.ork` designs,
//! thrust files, flight logs and Monte Carlo study folders written by a seeded generator
//! ([`generate`], reproducible: the same cases on every run), each run through the binary
//! under a wall-time bound ([`TIME_LIMIT`], killed past it) and a memory bound
//! ([`MEMORY_LIMIT_KIB`] of address space, `ulimit -v`). Every case must end without a crash
//! (no exit 101, no signal) or a hang; a refusal is exit 1 with a located message (the file,
//! and the key or line where there is one); what `check` accepts must fly (`check` catches
//! what the flight rejects); and a refused operation on a study leaves its files
//! byte-identical.

mod generate;

use generate::{Case, Expect};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// The wall time of one run of the binary before it counts as a hang and is killed.
const TIME_LIMIT: Duration = Duration::from_secs(20);

/// The address space of one run (1 GiB).
const MEMORY_LIMIT_KIB: u64 = 1 << 20;

/// How one bounded run ended.
#[derive(Debug)]
struct Outcome {
    /// The exit code (`None` when killed by a signal or for a hang).
    code: Option<i32>,
    /// The stderr text.
    stderr: String,
    /// Whether the run was killed at [`TIME_LIMIT`].
    hung: bool,
}

impl Outcome {
    /// A crash, a signal or a hang, described; `None` for an orderly exit (0, 1 or 2).
    fn disorder(&self) -> Option<String> {
        if self.hung {
            return Some(format!("no exit within {} s", TIME_LIMIT.as_secs()));
        }
        match self.code {
            Some(0..=2) if !self.stderr.contains("panicked at") => None,
            Some(code) => Some(format!("exit code {code}: {}", tail(&self.stderr))),
            None => Some(format!("killed by a signal: {}", tail(&self.stderr))),
        }
    }
}

/// The last 600 bytes of a message (a failure report stays readable).
fn tail(text: &str) -> &str {
    let mut start = text.len().saturating_sub(600);
    while !text.is_char_boundary(start) {
        start += 1;
    }
    &text[start..]
}

/// A command running `program` with its address space limited to [`MEMORY_LIMIT_KIB`]
/// (through the shell's `ulimit -v`, then `exec`: the child is the program itself).
fn limited(program: &str) -> Command {
    let mut command = Command::new("/bin/sh");
    command
        .arg("-c")
        .arg(format!(
            "ulimit -v {MEMORY_LIMIT_KIB} && exec \"$0\" \"$@\""
        ))
        .arg(program);
    command
}

/// Runs the binary with `args` in `dir`, bounded in time and memory.
fn bounded(args: &[String], dir: &Path) -> Outcome {
    static RUNS: AtomicUsize = AtomicUsize::new(0);
    let run = RUNS.fetch_add(1, Ordering::Relaxed);
    let err_path = dir.join(format!(".stderr-{}-{run}", std::process::id()));
    let err_file = std::fs::File::create(&err_path).expect("stderr file");
    let mut child = limited(env!("CARGO_BIN_EXE_karman"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(err_file)
        .spawn()
        .expect("the karman binary starts");
    let start = Instant::now();
    let (status, hung) = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break (Some(status), false);
        }
        if start.elapsed() > TIME_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            break (None, true);
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let stderr =
        String::from_utf8_lossy(&std::fs::read(&err_path).unwrap_or_default()).into_owned();
    let _ = std::fs::remove_file(&err_path);
    Outcome {
        code: status.and_then(|s| s.code()),
        stderr,
        hung,
    }
}

/// Whether a refusal's message names everything `located` lists.
fn unlocated<'a>(outcome: &Outcome, located: &'a [String]) -> Option<&'a String> {
    located
        .iter()
        .find(|l| !outcome.stderr.contains(l.as_str()))
}

/// Runs one case; `Err` describes how it failed.
fn run_case(case: &Case, dir: &Path) -> Result<(), String> {
    let first = bounded(&case.args, dir);
    if let Some(disorder) = first.disorder() {
        return Err(disorder);
    }
    let refused = |outcome: &Outcome, located: &[String]| -> Result<(), String> {
        if outcome.code != Some(1) {
            return Err(format!(
                "exit code {:?} for a refusal: {}",
                outcome.code,
                tail(&outcome.stderr)
            ));
        }
        match unlocated(outcome, located) {
            Some(missing) => Err(format!(
                "the message does not name `{missing}`: {}",
                tail(&outcome.stderr)
            )),
            None => Ok(()),
        }
    };
    match &case.expect {
        Expect::Either(located) => match first.code {
            Some(0) => Ok(()),
            _ => refused(&first, located),
        },
        Expect::Flies(located, fly) => {
            if first.code != Some(0) {
                return refused(&first, located);
            }
            let flight = bounded(fly, dir);
            if let Some(disorder) = flight.disorder() {
                return Err(format!("the flight after an ok check: {disorder}"));
            }
            if flight.code == Some(0) {
                Ok(())
            } else {
                Err(format!(
                    "`check` says ok and the flight fails: {}",
                    tail(&flight.stderr)
                ))
            }
        }
        Expect::Imports(located, check, forbidden) => {
            if first.code != Some(0) {
                return refused(&first, located);
            }
            let mission = std::fs::read_to_string(&check[1]).unwrap_or_default();
            if let Some(line) = mission.lines().find(|l| {
                forbidden
                    .iter()
                    .any(|f| l.trim_start().starts_with(f.as_str()))
            }) {
                return Err(format!(
                    "the imported mission holds an injected line: {line}"
                ));
            }
            let checked = bounded(check, dir);
            if let Some(disorder) = checked.disorder() {
                return Err(format!("`check` of the imported mission: {disorder}"));
            }
            if checked.code == Some(0) || forbidden.is_empty() {
                Ok(())
            } else {
                Err(format!(
                    "the imported mission does not check: {}",
                    tail(&checked.stderr)
                ))
            }
        }
    }
}

/// A fresh scratch folder of the suite.
fn fresh(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("karman-cli/hostile")
        .join(name);
    if dir.exists() {
        std::fs::remove_dir_all(&dir).expect("remove an old scratch folder");
    }
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// Runs every case of a class and fails with all the failures, each with its case name.
fn run_class(class: &str, make: fn(&Path) -> Vec<Case>) {
    let dir = fresh(class);
    let cases = make(&dir);
    assert!(cases.len() >= 10, "{class}: only {} cases", cases.len());
    let start = Instant::now();
    let failures: Vec<String> = cases
        .iter()
        .filter_map(|case| {
            run_case(case, &dir)
                .err()
                .map(|e| format!("{class} / {}: {e}", case.name))
        })
        .collect();
    eprintln!(
        "hostile {class}: {} cases in {:.1} s",
        cases.len(),
        start.elapsed().as_secs_f64()
    );
    assert!(
        failures.is_empty(),
        "{} of {} cases failed:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

#[test]
fn hostile_missions() {
    run_class("missions", generate::missions);
}

#[test]
fn hostile_trigger_expressions() {
    run_class("triggers", generate::triggers);
}

#[test]
fn hostile_controller_scripts() {
    run_class("scripts", generate::scripts);
}

#[test]
fn hostile_openrocket_designs() {
    run_class("ork", generate::designs);
}

#[test]
fn hostile_thrust_files() {
    run_class("thrust", generate::thrust_files);
}

#[test]
fn hostile_flight_logs() {
    run_class("logs", generate::flight_logs);
}

/// Every file of a folder (recursively) and its bytes; a symbolic link as its target and any
/// other file that is not regular (a FIFO a tamper made) as its kind, never opened.
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut files = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            let Ok(kind) = entry.file_type() else {
                continue;
            };
            if kind.is_dir() {
                stack.push(path);
            } else {
                let bytes = if kind.is_symlink() {
                    let target = std::fs::read_link(&path).unwrap_or_default();
                    format!("link to {}", target.display()).into_bytes()
                } else if kind.is_file() {
                    std::fs::read(&path).unwrap_or_default()
                } else {
                    format!("{kind:?}").into_bytes()
                };
                files.insert(path.strip_prefix(dir).unwrap_or(&path).to_path_buf(), bytes);
            }
        }
    }
    files
}

/// Copies the files of `from` into a new folder `to`.
fn copy_folder(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("study copy");
    for (name, bytes) in snapshot(from) {
        let path = to.join(name);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).expect("study copy");
        }
        std::fs::write(path, bytes).expect("study copy");
    }
}

/// Tampered copies of one small study, each resumed (`montecarlo` on it again) and merged:
/// no crash or hang, a refusal located in the study's files, and a refused operation leaves
/// every file of the folder as it was.
#[test]
fn hostile_study_folders() {
    let dir = fresh("studies");
    let mission = generate::example_mission(&dir);
    let base = dir.join("base");
    let study_args = |out: &Path| -> Vec<String> {
        [
            "montecarlo",
            mission.to_str().expect("UTF-8"),
            "--samples",
            "4",
            "--threads",
            "1",
            "--quiet",
            "--out",
            out.to_str().expect("UTF-8"),
        ]
        .map(str::to_owned)
        .to_vec()
    };
    let made = bounded(&study_args(&base), &dir);
    assert_eq!(made.code, Some(0), "the base study: {}", made.stderr);
    let start = Instant::now();
    let tampers = generate::study_tampers(&snapshot(&base));
    assert!(tampers.len() >= 10);
    let mut failures = Vec::new();
    for (index, tamper) in tampers.iter().enumerate() {
        let folder = dir.join(format!("case{index}"));
        copy_folder(&base, &folder);
        (tamper.apply)(&folder);
        let operations: [(&str, Vec<String>); 2] = [
            ("resume", study_args(&folder)),
            (
                "merge",
                vec![
                    "merge".to_owned(),
                    dir.join(format!("merged{index}")).display().to_string(),
                    folder.display().to_string(),
                ],
            ),
        ];
        for (operation, args) in operations {
            let before = snapshot(&folder);
            let outcome = bounded(&args, &dir);
            let fail = |e: String| format!("study / {} / {operation}: {e}", tamper.name);
            if let Some(disorder) = outcome.disorder() {
                failures.push(fail(disorder));
                continue;
            }
            if outcome.code == Some(0) {
                if !tamper.may_succeed {
                    failures.push(fail("accepted a tampered study".to_owned()));
                }
                continue;
            }
            if outcome.code != Some(1) {
                failures.push(fail(format!("exit code {:?}", outcome.code)));
            }
            let named = tamper
                .located
                .iter()
                .find(|l| !outcome.stderr.contains(l.as_str()));
            if let Some(missing) = named {
                failures.push(fail(format!(
                    "the message does not name `{missing}`: {}",
                    tail(&outcome.stderr)
                )));
            }
            if snapshot(&folder) != before {
                failures.push(fail(
                    "a refused operation changed the study's files".to_owned(),
                ));
            }
        }
    }
    // A merge of folders that do not exist, or that are files, names them.
    for (name, input) in [
        ("nonexistent", dir.join("no-such-study")),
        ("a file", mission.clone()),
    ] {
        let args = vec![
            "merge".to_owned(),
            dir.join("merged-bad").display().to_string(),
            input.display().to_string(),
        ];
        let outcome = bounded(&args, &dir);
        let shown = input.display().to_string();
        if outcome.code != Some(1) || !outcome.stderr.contains(&shown) {
            failures.push(format!(
                "study / merge of {name}: exit {:?}, {}",
                outcome.code,
                tail(&outcome.stderr)
            ));
        }
        if name == "nonexistent" && !outcome.stderr.contains("does not exist") {
            failures.push(format!(
                "study / merge of {name}: not said to not exist: {}",
                tail(&outcome.stderr)
            ));
        }
    }
    // A folder that is not a study's (no study.json) holding a file a study writes: a study
    // or a merge into it is refused, naming the file, and replaces nothing.
    for name in ["summary.json", "landing.svg", "samples.csv"] {
        let mine = dir.join(format!("mine-{name}"));
        std::fs::create_dir_all(&mine).expect("a folder of the user's");
        std::fs::write(mine.join(name), "the user's own file\n").expect("the user's file");
        let merge = vec![
            "merge".to_owned(),
            mine.display().to_string(),
            base.display().to_string(),
        ];
        for (operation, args) in [("montecarlo", study_args(&mine)), ("merge", merge)] {
            let outcome = bounded(&args, &dir);
            let kept = std::fs::read_to_string(mine.join(name)).unwrap_or_default();
            if outcome.code != Some(1)
                || !outcome.stderr.contains(name)
                || kept != "the user's own file\n"
            {
                failures.push(format!(
                    "study / {operation} into a folder holding the user's {name}: exit {:?}, \
                     file kept: {}, {}",
                    outcome.code,
                    kept == "the user's own file\n",
                    tail(&outcome.stderr)
                ));
            }
        }
    }
    eprintln!(
        "hostile studies: {} tampered folders in {:.1} s",
        tampers.len(),
        start.elapsed().as_secs_f64()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The runner itself: a hang and a crash are told from a refusal, the memory bound is set
/// on the child, and a run under it succeeds (it leaves room for the binary and its threads).
#[test]
fn the_bounds_are_enforced() {
    let dir = fresh("bounds");
    let sleeper = Outcome {
        code: None,
        stderr: String::new(),
        hung: true,
    };
    assert!(sleeper.disorder().is_some());
    let crashed = Outcome {
        code: Some(101),
        stderr: "thread 'main' panicked at".to_owned(),
        hung: false,
    };
    assert!(crashed.disorder().is_some());
    let refused = Outcome {
        code: Some(1),
        stderr: "error: x.toml:3:1: bad".to_owned(),
        hung: false,
    };
    assert!(refused.disorder().is_none());
    // `--version` runs within the bounds: the limit leaves room for the binary itself.
    let outcome = bounded(&["--version".to_owned()], &dir);
    assert_eq!(outcome.code, Some(0), "{}", outcome.stderr);
    // The limit is the child's own: a shell started the same way reports it.
    let shown = limited("/bin/sh")
        .args(["-c", "ulimit -v"])
        .output()
        .expect("a shell");
    assert_eq!(
        String::from_utf8_lossy(&shown.stdout).trim(),
        MEMORY_LIMIT_KIB.to_string()
    );
}
