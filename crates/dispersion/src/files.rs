//! The files of an output directory, its lock, atomic writes and the checked reading of
//! `samples.csv`.

use crate::csv::{self, Counts};
use crate::error::DispersionError;
use crate::regular::open_regular;
use crate::sampling::draw;
use crate::study::Record;
use std::fs::{File, OpenOptions};
use std::io::{BufRead, BufReader, Read as _, Write as _};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// The lock of an output directory: one run (or merge) writes a study at a time.
pub const LOCK_FILE: &str = "study.lock";
/// The study's identity (seed, samples, inputs, outputs, shard, fingerprint).
pub const STUDY_FILE: &str = "study.json";
/// One row per sample, in index order.
pub const SAMPLES_FILE: &str = "samples.csv";
/// Counts, statistics and ellipses.
pub const SUMMARY_FILE: &str = "summary.json";
/// Landing points and ellipses for Google Earth.
pub const KML_FILE: &str = "dispersion.kml";
/// Landing scatter with its ellipses.
pub const LANDING_PLOT_FILE: &str = "landing.svg";
/// Histogram of the chosen output (the apogee).
pub const HISTOGRAM_PLOT_FILE: &str = "apogee_histogram.svg";

/// What a scan of `samples.csv` found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Scan {
    /// Complete, valid rows (the first positions of the shard).
    pub rows: u64,
    /// Those rows by status.
    pub counts: Counts,
    /// Byte length of the header and those rows; anything after it is a partial line.
    pub valid_len: u64,
    /// Whether the header line is complete.
    pub has_header: bool,
    /// The first and the last complete row (the same row once when there is one): position,
    /// line number and text, for a resume to fly them again.
    pub ends: Vec<(u64, u64, String)>,
}

/// Why a first line that is not this study's header is refused: a byte-order mark or
/// Windows line endings (an editor or a copy rewrote the file; karman writes neither) are
/// said as such, anything else is another study's (or no) header.
fn foreign_header(line: &[u8]) -> String {
    if line.starts_with("\u{feff}".as_bytes()) {
        "the file starts with a byte-order mark (U+FEFF), which karman never writes: an \
         editor rewrote it; remove the mark to resume"
            .to_owned()
    } else if line.ends_with(b"\r\n") {
        "the file has Windows line endings (CRLF), which karman never writes: an editor or a \
         copy rewrote it; convert it back to LF line endings to resume"
            .to_owned()
    } else {
        "not the header of this study".to_owned()
    }
}

/// Bytes of one line of `samples.csv` beyond which the file is corrupt: a row is its index,
/// status, message and numbers, far below this; the bound keeps a file of gigabytes without a
/// line end (or a link to a device) from being read into memory whole.
const MAX_ROW_BYTES: u64 = 16 << 20;

/// Scans `samples.csv` of `record`: the header must be the study's and every complete row
/// must be the next sample of the shard with the inputs the study draws for it and a digest
/// that is the digest of its cells keyed by the study's fingerprint
/// ([`DispersionError::TamperedRow`] otherwise: an edited cell). A trailing
/// line without its newline (an interrupted write) is not counted. A missing file scans as
/// empty.
pub(crate) fn scan(path: &Path, record: &Record) -> Result<Scan, DispersionError> {
    let mut scan = Scan {
        rows: 0,
        counts: Counts::default(),
        valid_len: 0,
        has_header: false,
        ends: Vec::new(),
    };
    let Some(file) = open_regular(path)? else {
        return Ok(scan);
    };
    let study = record.study();
    let header = csv::header(&study.columns());
    let corrupt = |line: u64, reason: String| DispersionError::CorruptSamples {
        file: path.to_owned(),
        line,
        reason,
    };
    let mut reader = BufReader::new(file);
    let mut buffer = Vec::new();
    let mut line_number = 0u64;
    let shard_len = record.shard.len(record.samples);
    loop {
        buffer.clear();
        let n = (&mut reader)
            .take(MAX_ROW_BYTES + 1)
            .read_until(b'\n', &mut buffer)
            .map_err(DispersionError::io(path))?;
        if n as u64 > MAX_ROW_BYTES {
            return Err(corrupt(
                line_number + 1,
                format!("a line longer than {MAX_ROW_BYTES} bytes (no sample row is)"),
            ));
        }
        if n == 0 || buffer.last() != Some(&b'\n') {
            // End of file, or a partial last line.
            if !scan.has_header && !header.as_bytes().starts_with(&buffer) {
                return Err(corrupt(1, foreign_header(&buffer)));
            }
            return Ok(scan);
        }
        line_number += 1;
        let text = std::str::from_utf8(&buffer)
            .map_err(|_| corrupt(line_number, "not UTF-8 text".to_owned()))?;
        if !scan.has_header {
            if text != header {
                return Err(corrupt(1, foreign_header(&buffer)));
            }
            scan.has_header = true;
        } else {
            let row = csv::parse(
                text.trim_end_matches('\n'),
                study.inputs.len(),
                study.outputs.len(),
            )
            .map_err(|reason| corrupt(line_number, reason))?;
            if scan.rows >= shard_len {
                return Err(corrupt(
                    line_number,
                    format!(
                        "more rows than the {shard_len} samples of shard {}",
                        record.shard
                    ),
                ));
            }
            let expected = record.shard.index(scan.rows);
            if row.index != expected {
                return Err(corrupt(
                    line_number,
                    format!("sample {} where sample {expected} was expected", row.index),
                ));
            }
            let drawn = draw(record.seed, row.index, &study.inputs);
            let same = drawn
                .iter()
                .zip(&row.inputs)
                .all(|(a, b)| a.to_bits() == b.to_bits());
            if !same {
                return Err(corrupt(
                    line_number,
                    "its inputs are not the study's draws for this sample (written by another \
                     version or another study)"
                        .to_owned(),
                ));
            }
            let cells = text.trim_end_matches('\n');
            if let Err((stored, computed)) = csv::verify(cells, &record.fingerprint) {
                return Err(DispersionError::TamperedRow {
                    file: path.to_owned(),
                    line: line_number,
                    index: row.index,
                    stored,
                    computed,
                    detail: String::new(),
                    row: cells.to_owned(),
                });
            }
            scan.counts.add(&row.status);
            let kept = (scan.rows, line_number, text.to_owned());
            match scan.ends.len() {
                0 | 1 => scan.ends.push(kept),
                _ => scan.ends[1] = kept,
            }
            scan.rows += 1;
        }
        scan.valid_len += n as u64;
    }
}

/// Reads the parsed rows of a complete, already scanned `samples.csv`.
pub(crate) fn for_each_row(
    path: &Path,
    inputs: usize,
    outputs: usize,
    mut f: impl FnMut(csv::Row),
) -> Result<(), DispersionError> {
    let file = File::open(path).map_err(DispersionError::io(path))?;
    let mut lines = BufReader::new(file).lines();
    // The header.
    lines
        .next()
        .transpose()
        .map_err(DispersionError::io(path))?;
    for (number, line) in lines.enumerate() {
        let line = line.map_err(DispersionError::io(path))?;
        let row = csv::parse(&line, inputs, outputs).map_err(|reason| {
            DispersionError::CorruptSamples {
                file: path.to_owned(),
                line: number as u64 + 2,
                reason,
            }
        })?;
        f(row);
    }
    Ok(())
}

/// The shard of a record, checked against the study's size.
pub(crate) fn shard_is_complete(scan: &Scan, record: &Record) -> bool {
    scan.rows == record.shard.len(record.samples)
}

/// A temporary file name beside `path`, unique to this process and this call:
/// `.NAME.PID.N.tmp`. Two runs writing into one folder (two `simulate --out` of the same
/// folder) never share a temporary file, and each run removes only its own.
pub fn temporary_path(path: &Path) -> PathBuf {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let call = NEXT.fetch_add(1, Ordering::Relaxed);
    path.with_file_name(format!(".{name}.{}.{call}.tmp", std::process::id()))
}

/// Writes `bytes` to `path` atomically: into a temporary file beside it
/// ([`temporary_path`], created new), flushed to the disk, then renamed over `path`. A reader
/// sees the old file or the whole new one, never a part; on an error (a full disk) the
/// temporary file is removed, `path` is left as it was, and the error names `path`.
///
/// # Errors
/// [`DispersionError::Io`] naming `path`.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), DispersionError> {
    let temporary = temporary_path(path);
    let written = OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&temporary)
        .and_then(|mut file| file.write_all(bytes).and_then(|()| file.sync_all()))
        .and_then(|()| std::fs::rename(&temporary, path));
    written.map_err(|e| {
        let _ = std::fs::remove_file(&temporary);
        DispersionError::io(path)(e)
    })
}

/// The files a study writes into its output directory, each through a temporary file
/// ([`temporary_path`]) that a killed run may leave behind.
const WRITTEN: [&str; 6] = [
    STUDY_FILE,
    SAMPLES_FILE,
    SUMMARY_FILE,
    KML_FILE,
    LANDING_PLOT_FILE,
    HISTOGRAM_PLOT_FILE,
];

/// The first output file of a study (other than `study.json` and `samples.csv`, which the
/// caller checks) that already exists in `dir`: in a folder without `study.json` such a file
/// is not a study's, and writing the study there would replace it.
pub(crate) fn foreign_output(dir: &Path) -> Option<&'static str> {
    WRITTEN[2..]
        .iter()
        .copied()
        .find(|name| std::fs::symlink_metadata(dir.join(name)).is_ok())
}

/// Whether `name` is a temporary file [`write_atomic`] (or a merge) makes for one of the
/// files a study writes: `.NAME.PID.N.tmp`.
fn is_temporary(name: &str) -> bool {
    let Some(middle) = name
        .strip_prefix('.')
        .and_then(|rest| rest.strip_suffix(".tmp"))
    else {
        return false;
    };
    WRITTEN.iter().any(|file| {
        middle
            .strip_prefix(file)
            .and_then(|rest| rest.strip_prefix('.'))
            .and_then(|rest| rest.split_once('.'))
            .is_some_and(|(pid, call)| {
                let digits = |t: &str| !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit());
                digits(pid) && digits(call)
            })
    })
}

/// Removes the temporary files of killed runs from `dir` (a run holding its lock: no other
/// run is writing there), saying so on stderr; returns them. Only the temporary files of a
/// study's own files are removed, never another file.
pub(crate) fn remove_temporaries(dir: &Path) -> Result<Vec<PathBuf>, DispersionError> {
    let mut removed = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(DispersionError::io(dir))? {
        let entry = entry.map_err(DispersionError::io(dir))?;
        let is_file = entry.file_type().is_ok_and(|t| t.is_file());
        if is_file && is_temporary(&entry.file_name().to_string_lossy()) {
            let path = entry.path();
            std::fs::remove_file(&path).map_err(DispersionError::io(&path))?;
            eprintln!(
                "karman: removed {}, a temporary file left by an interrupted run",
                path.display()
            );
            removed.push(path);
        }
    }
    removed.sort();
    Ok(removed)
}

/// What identifies a file, to see that the lock file under its name is still the one locked.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Identity(u64, u64);

impl Identity {
    #[cfg(unix)]
    fn of(metadata: &std::fs::Metadata) -> Self {
        use std::os::unix::fs::MetadataExt as _;
        Identity(metadata.dev(), metadata.ino())
    }

    #[cfg(not(unix))]
    fn of(metadata: &std::fs::Metadata) -> Self {
        let created = metadata
            .created()
            .ok()
            .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
            .unwrap_or_default();
        Identity(created.as_secs(), u64::from(created.subsec_nanos()))
    }
}

/// An exclusive lock on an output directory, held while the value lives. The operating
/// system releases it when the process ends, however it ends (a killed run leaves no stale
/// lock).
///
/// Two locks are taken: on Unix the directory itself (through a descriptor of the directory,
/// which no one can remove from under the run while it holds it: deleting `study.lock` does
/// not let a second run in), and on every system the lock file [`LOCK_FILE`] (the lock of
/// earlier versions). [`DirLock::check`] sees whether the lock file is still the one locked,
/// and puts it back when it was removed.
#[derive(Debug)]
pub(crate) struct DirLock {
    dir: PathBuf,
    /// The directory's descriptor, locked (Unix).
    _directory: Option<File>,
    /// The lock file, locked, and its identity.
    file: Option<(File, Identity)>,
}

impl DirLock {
    /// Checks that the lock file is still the file locked (before each write). When it was
    /// removed or replaced: with the directory itself locked (Unix) no run of this version
    /// got in, so a new lock file is created and locked in its place (for earlier versions,
    /// which lock only the file); [`DispersionError::LockLost`] when that new file is
    /// already locked by someone else, or where the directory cannot be locked, so that a
    /// second writer that got in is noticed at the next write and the run stops.
    pub(crate) fn check(&mut self) -> Result<(), DispersionError> {
        let Some((_, identity)) = &self.file else {
            return Ok(());
        };
        let path = self.dir.join(LOCK_FILE);
        let now = std::fs::metadata(&path).map(|m| Identity::of(&m));
        if now.as_ref().ok() == Some(identity) {
            return Ok(());
        }
        let lost = || DispersionError::LockLost {
            dir: self.dir.clone(),
        };
        if self._directory.is_none() {
            return Err(lost());
        }
        let file = OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&path)
            .map_err(DispersionError::io(&path))?;
        match try_lock(&file, &self.dir, &path) {
            Ok(()) => {}
            Err(DispersionError::Locked { .. }) => return Err(lost()),
            Err(other) => return Err(other),
        }
        let identity = Identity::of(&file.metadata().map_err(DispersionError::io(&path))?);
        self.file = Some((file, identity));
        Ok(())
    }
}

/// Takes `file`'s lock; `Locked` when another run holds it.
#[cfg(not(target_arch = "wasm32"))]
fn try_lock(file: &File, dir: &Path, path: &Path) -> Result<(), DispersionError> {
    match fs4::FileExt::try_lock(file) {
        Ok(()) => Ok(()),
        Err(fs4::TryLockError::WouldBlock) => Err(DispersionError::Locked {
            dir: dir.to_owned(),
        }),
        Err(fs4::TryLockError::Error(e)) => Err(DispersionError::io(path)(e)),
    }
}

/// WebAssembly in a browser has no files to lock (nor any output directory: the page flies
/// samples with [`crate::sample_lines`]).
#[cfg(target_arch = "wasm32")]
fn try_lock(_file: &File, _dir: &Path, _path: &Path) -> Result<(), DispersionError> {
    Ok(())
}

/// Locks the output directory `dir` ([`DirLock`]: the directory itself on Unix, and its
/// [`LOCK_FILE`], created when `create`); `Locked` when another run holds it. `create` false:
/// a directory without a lock file is not touched (its lock file not created).
pub(crate) fn lock(dir: &Path, create: bool) -> Result<DirLock, DispersionError> {
    #[cfg(unix)]
    let directory = {
        let handle = File::open(dir).map_err(DispersionError::io(dir))?;
        try_lock(&handle, dir, dir)?;
        Some(handle)
    };
    #[cfg(not(unix))]
    let directory = None;
    let path = dir.join(LOCK_FILE);
    // An existing lock file must be a regular file: opening a FIFO blocks.
    if std::fs::symlink_metadata(&path).is_ok() {
        open_regular(&path)?;
    }
    let file = if create {
        OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&path)
    } else {
        match File::open(&path) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                return Ok(DirLock {
                    dir: dir.to_owned(),
                    _directory: directory,
                    file: None,
                });
            }
            other => other,
        }
    }
    .map_err(DispersionError::io(&path))?;
    try_lock(&file, dir, &path)?;
    let identity = Identity::of(&file.metadata().map_err(DispersionError::io(&path))?);
    Ok(DirLock {
        dir: dir.to_owned(),
        _directory: directory,
        file: Some((file, identity)),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rewritten_header_says_how_it_was_rewritten() {
        let bom = foreign_header("\u{feff}index,status\n".as_bytes());
        assert!(bom.contains("byte-order mark"), "{bom}");
        let crlf = foreign_header(b"index,status\r\n");
        assert!(crlf.contains("Windows line endings (CRLF)"), "{crlf}");
        assert_eq!(foreign_header(b"a,b\n"), "not the header of this study");
    }

    #[test]
    fn temporary_files_are_recognised() {
        let made = temporary_path(&PathBuf::from("dir").join(SAMPLES_FILE));
        let name = made
            .file_name()
            .expect("name")
            .to_string_lossy()
            .into_owned();
        assert!(is_temporary(&name), "{name}");
        assert!(is_temporary(".summary.json.12.0.tmp"));
        for other in [
            "samples.csv",
            ".samples.csv.tmp",
            ".samples.csv.12.tmp",
            ".notes.txt.12.0.tmp",
            ".samples.csv.x.0.tmp",
            ".samples.csv.1.0.tmp.bak",
        ] {
            assert!(!is_temporary(other), "{other}");
        }
    }

    #[test]
    fn a_replaced_lock_file_is_noticed() {
        let tmp = tempfile::tempdir().expect("temporary directory");
        let path = tmp.path().join(LOCK_FILE);
        let mut lock = lock(tmp.path(), true).expect("lock");
        lock.check().expect("held");
        std::fs::remove_file(&path).expect("remove");
        if cfg!(unix) {
            // The directory is still locked: the lock file is put back, locked.
            lock.check().expect("put back");
            let file = File::open(&path).expect("a lock file again");
            assert!(matches!(
                fs4::FileExt::try_lock(&file),
                Err(fs4::TryLockError::WouldBlock)
            ));
        } else {
            assert!(matches!(
                lock.check(),
                Err(DispersionError::LockLost { .. })
            ));
        }
        // Replaced by a file someone else locks (an earlier version that got in): stop.
        std::fs::remove_file(&path).expect("remove");
        let other = File::create(&path).expect("another lock file");
        fs4::FileExt::try_lock(&other).expect("the other writer's lock");
        assert!(matches!(
            lock.check(),
            Err(DispersionError::LockLost { .. })
        ));
    }

    #[cfg(unix)]
    #[test]
    fn the_directory_stays_locked_without_its_lock_file() {
        let tmp = tempfile::tempdir().expect("temporary directory");
        let held = lock(tmp.path(), true).expect("lock");
        std::fs::remove_file(tmp.path().join(LOCK_FILE)).expect("remove");
        let second = lock(tmp.path(), true);
        assert!(
            matches!(second, Err(DispersionError::Locked { .. })),
            "{second:?}"
        );
        assert!(
            !tmp.path().join(LOCK_FILE).exists(),
            "the refused run created nothing"
        );
        drop(held);
        lock(tmp.path(), true).expect("free again");
    }
}
