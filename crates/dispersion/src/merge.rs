//! Merging the output directories of the shards of one study into the files a single run
//! makes.

use crate::error::DispersionError;
use crate::files::{self, SAMPLES_FILE, STUDY_FILE};
use crate::study::{Record, Shard};
use crate::summary::{Summary, summarize};
use std::fs::File;
use std::io::{BufRead, BufReader, BufWriter, Write as _};
use std::path::{Path, PathBuf};

/// The shards of a merge, in shard order: each one's study record and directory; the whole
/// study's record; the shard count.
type Shards<'a> = (Vec<(Record, &'a PathBuf)>, Record, u64);

/// The study record of each shard directory, checked to be shards of one study with every
/// shard number given once, in shard order; with the whole study's record and the shard
/// count.
fn shard_records(dirs: &[PathBuf]) -> Result<Shards<'_>, DispersionError> {
    let fail = |reason: String| Err(DispersionError::Merge { reason });
    let mut shards: Vec<(Record, &PathBuf)> = Vec::with_capacity(dirs.len());
    for dir in dirs {
        let record = Record::read(&dir.join(STUDY_FILE))?
            .ok_or_else(|| DispersionError::MissingStudy { dir: dir.clone() })?;
        shards.push((record, dir));
    }
    let Some((first, first_dir)) = shards.first().cloned() else {
        return fail("no shard directory given".to_owned());
    };
    let count = first.shard.count;
    let whole = Record::new(&first.study(), Shard::WHOLE);
    for (record, dir) in &shards {
        let fields = whole.differences(&Record::new(&record.study(), Shard::WHOLE));
        if !fields.is_empty() {
            return fail(format!(
                "{} and {} hold different studies (differ in: {})",
                first_dir.display(),
                dir.display(),
                fields.join(", ")
            ));
        }
        if record.shard.count != count {
            return fail(format!(
                "{} is shard {} but {} is shard {}",
                first_dir.display(),
                first.shard,
                dir.display(),
                record.shard
            ));
        }
    }
    shards.sort_by_key(|(record, _)| record.shard.number);
    for number in 1..=count {
        let given: Vec<&PathBuf> = shards
            .iter()
            .filter(|(r, _)| r.shard.number == number)
            .map(|(_, dir)| *dir)
            .collect();
        match given.as_slice() {
            [] => return fail(format!("shard {number}/{count} is missing")),
            [_] => {}
            [a, b, ..] => {
                return fail(format!(
                    "shard {number}/{count} is given twice ({} and {})",
                    a.display(),
                    b.display()
                ));
            }
        }
    }
    Ok((shards, whole, count))
}

/// Merges the complete shard directories `dirs` (every shard `K/N` of one study exactly
/// once, in any order) into `out`: `study.json` and `samples.csv` byte-identical to those of
/// an unsharded run, then the summary, KML and plots. Rows are streamed, so memory does not
/// grow with the number of samples. The shards must be of one study, data fingerprint
/// included (a shard flown on another weather file is refused, naming it); a shard still
/// being written (its lock held) and an `out` another run writes are refused.
pub fn merge(out: &Path, dirs: &[PathBuf]) -> Result<Summary, DispersionError> {
    let fail = |reason: String| Err(DispersionError::Merge { reason });
    // A mistyped shard is said to be missing as a folder, not as the study.json it lacks.
    for dir in dirs {
        if !dir.exists() {
            return fail(format!("{}: the folder does not exist", dir.display()));
        }
        if !dir.is_dir() {
            return fail(format!(
                "{}: not a folder (a shard's output directory, `montecarlo --out DIR`)",
                dir.display()
            ));
        }
    }
    // Each shard directory locked once (one given twice is reported below).
    let mut locks = Vec::with_capacity(dirs.len());
    let mut locked: Vec<PathBuf> = Vec::with_capacity(dirs.len());
    for dir in dirs {
        let canonical = dir.canonicalize().unwrap_or_else(|_| dir.clone());
        if !locked.contains(&canonical) {
            locks.push(files::lock(dir, false)?);
            locked.push(canonical);
        }
    }
    let (shards, whole, count) = shard_records(dirs)?;
    let mut readers = Vec::with_capacity(shards.len());
    for (record, dir) in &shards {
        let path = dir.join(SAMPLES_FILE);
        let scan = files::scan(&path, record)?;
        if !files::shard_is_complete(&scan, record) {
            return fail(format!(
                "{}: shard {} has {} of its {} samples; rerun its command to finish it",
                dir.display(),
                record.shard,
                scan.rows,
                record.shard.len(record.samples)
            ));
        }
        let mut reader = BufReader::new(File::open(&path).map_err(DispersionError::io(&path))?);
        // Skip the header, which the scan checked.
        reader
            .read_until(b'\n', &mut Vec::new())
            .map_err(DispersionError::io(&path))?;
        readers.push((reader, path));
    }
    for (_, dir) in &shards {
        let same = out
            .canonicalize()
            .ok()
            .zip(dir.canonicalize().ok())
            .is_some_and(|(a, b)| a == b);
        if same {
            return fail(format!(
                "the output directory {} is one of the shards",
                out.display()
            ));
        }
    }

    std::fs::create_dir_all(out).map_err(DispersionError::io(out))?;
    let mut out_lock = files::lock(out, true)?;
    files::remove_temporaries(out)?;
    if let Some(existing) = Record::read(&out.join(STUDY_FILE))? {
        let fields = whole.differences(&existing);
        if !fields.is_empty() {
            return Err(DispersionError::StudyMismatch {
                dir: out.to_owned(),
                fields,
            });
        }
    } else {
        // A folder that is not a study's: none of its files is replaced.
        if std::fs::symlink_metadata(out.join(SAMPLES_FILE)).is_ok() {
            return Err(DispersionError::MissingStudy {
                dir: out.to_owned(),
            });
        }
        if let Some(file) = files::foreign_output(out) {
            return Err(DispersionError::ForeignOutput {
                dir: out.to_owned(),
                file,
            });
        }
    }
    files::write_atomic(&out.join(STUDY_FILE), whole.to_json().as_bytes())?;
    let samples_path = out.join(SAMPLES_FILE);
    let temporary = files::temporary_path(&samples_path);
    let file = File::create(&temporary).map_err(DispersionError::io(&temporary))?;
    let mut writer = BufWriter::with_capacity(1 << 16, file);
    let header = crate::csv::header(&whole.study().columns());
    writer
        .write_all(header.as_bytes())
        .map_err(DispersionError::io(&temporary))?;
    let mut line = Vec::new();
    for index in 0..whole.samples {
        let slot = (index % count) as usize;
        let Some((reader, path)) = readers.get_mut(slot) else {
            return fail(format!("no shard for sample {index}"));
        };
        line.clear();
        reader
            .read_until(b'\n', &mut line)
            .map_err(DispersionError::io(path.as_path()))?;
        writer
            .write_all(&line)
            .map_err(DispersionError::io(&temporary))?;
    }
    writer.flush().map_err(DispersionError::io(&temporary))?;
    drop(writer);
    if let Err(error) = out_lock.check() {
        let _ = std::fs::remove_file(&temporary);
        return Err(error);
    }
    std::fs::rename(&temporary, &samples_path).map_err(DispersionError::io(&samples_path))?;
    let summary = summarize(out);
    drop(out_lock);
    drop(locks);
    summary
}
