//! Data files given as bytes instead of read from disk.
//!
//! A [`FileSet`] maps file names to their bytes. While one is installed on a thread
//! ([`FileSet::with`]), [`read_data_file`](crate::read_data_file) and [`check_data_file`]
//! on that thread look files up in the set and never touch the file system; with none
//! installed (every program but the browser page) they read the file system as before.
//! This is how a mission parsed from text in a browser, which has no file system, finds its
//! thrust, drag and weather files: every reader of a data file goes through these two
//! functions.
//!
//! A path is looked up by its components with `.` dropped (`./a.csv` is `a.csv`, and
//! `data/../a.csv` stays as written); when no file has that path, by its file name alone
//! if exactly one file of the set has that name (a page is given files without their
//! folders). A path found in neither way is an [`std::io::ErrorKind::NotFound`] error that
//! says so.
//!
//! ```
//! use karman_math::files::FileSet;
//!
//! let mut files = FileSet::new();
//! files.insert("drag.csv", b"mach,cd\n0,0.5\n2,0.4\n".to_vec());
//! let curve = files.with(|| karman_math::read_curve("./drag.csv"))?;
//! assert_eq!(curve, [[0.0, 0.5], [2.0, 0.4]]);
//! assert!(files.with(|| karman_math::read_curve("lift.csv")).is_err());
//! # Ok::<(), karman_math::CsvError>(())
//! ```

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::io;
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

/// Files by name, each its bytes (module documentation).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct FileSet {
    files: Arc<BTreeMap<PathBuf, Arc<[u8]>>>,
}

thread_local! {
    /// The set installed on this thread by [`FileSet::with`], if any.
    static INSTALLED: RefCell<Option<FileSet>> = const { RefCell::new(None) };
}

/// `path` without its `.` components.
fn normal(path: &Path) -> PathBuf {
    path.components()
        .filter(|c| !matches!(c, Component::CurDir))
        .collect()
}

impl FileSet {
    /// An empty set.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds (or replaces) the file `name` with `bytes`.
    pub fn insert(&mut self, name: impl AsRef<Path>, bytes: Vec<u8>) {
        Arc::make_mut(&mut self.files).insert(normal(name.as_ref()), bytes.into());
    }

    /// The names of the files, in order.
    pub fn names(&self) -> impl Iterator<Item = &Path> {
        self.files.keys().map(PathBuf::as_path)
    }

    /// The bytes of the file at `path` (module documentation: by path, else by a unique file
    /// name).
    #[must_use]
    pub fn get(&self, path: &Path) -> Option<&[u8]> {
        if let Some(bytes) = self.files.get(&normal(path)) {
            return Some(bytes);
        }
        let name = path.file_name()?;
        let mut same = self
            .files
            .iter()
            .filter(|(key, _)| key.file_name() == Some(name));
        match (same.next(), same.next()) {
            (Some((_, bytes)), None) => Some(bytes),
            _ => None,
        }
    }

    /// Runs `f` with this set installed on the current thread (the one installed before is
    /// put back afterwards, also when `f` panics): the data files `f` reads come from the set.
    pub fn with<R>(&self, f: impl FnOnce() -> R) -> R {
        struct Restore(Option<FileSet>);
        impl Drop for Restore {
            fn drop(&mut self) {
                let previous = self.0.take();
                INSTALLED.with(|slot| *slot.borrow_mut() = previous);
            }
        }
        let previous = INSTALLED.with(|slot| slot.borrow_mut().replace(self.clone()));
        let _restore = Restore(previous);
        f()
    }

    /// The bytes of `path` as an I/O result: [`io::ErrorKind::NotFound`] when absent.
    fn read(&self, path: &Path) -> io::Result<Vec<u8>> {
        self.get(path).map(<[u8]>::to_vec).ok_or_else(|| {
            io::Error::new(
                io::ErrorKind::NotFound,
                format!(
                    "not among the given files ({})",
                    if self.files.is_empty() {
                        "none given".to_owned()
                    } else {
                        self.names()
                            .map(|n| n.display().to_string())
                            .collect::<Vec<_>>()
                            .join(", ")
                    }
                ),
            )
        })
    }
}

/// With a set installed on this thread, `Some` of what it holds at `path` (an
/// [`io::ErrorKind::NotFound`] error when nothing); with none, `None`: the caller reads the
/// file system as it would have. For readers that cannot go through
/// [`read_data_file`](crate::read_data_file) (a text read whole, without its checks).
pub fn installed_read(path: &Path) -> Option<io::Result<Vec<u8>>> {
    INSTALLED.with(|slot| slot.borrow().as_ref().map(|set| set.read(path)))
}

/// Whether the data file at `path` can be found: in the installed [`FileSet`] if there is
/// one, else on disk (the file system's metadata error as it is).
///
/// # Errors
/// The I/O error of a missing file.
pub fn check_data_file(path: &Path) -> io::Result<()> {
    match INSTALLED.with(|slot| slot.borrow().as_ref().map(|set| set.read(path).map(drop))) {
        Some(found) => found,
        None => std::fs::metadata(path).map(drop),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_are_found_by_components_then_by_a_unique_name() {
        let mut set = FileSet::new();
        set.insert("./a.csv", b"1".to_vec());
        set.insert("x/b.csv", b"2".to_vec());
        set.insert("y/b.csv", b"3".to_vec());
        assert_eq!(set.get(Path::new("a.csv")), Some(&b"1"[..]));
        assert_eq!(set.get(Path::new("./dir/a.csv")), Some(&b"1"[..]));
        assert_eq!(set.get(Path::new("./x/b.csv")), Some(&b"2"[..]));
        // Two files named b.csv: only the full path finds one.
        assert_eq!(set.get(Path::new("b.csv")), None);
        assert_eq!(set.get(Path::new("c.csv")), None);
    }

    #[test]
    fn an_installed_set_replaces_the_file_system_and_is_removed_afterwards() {
        let manifest = Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml");
        assert!(check_data_file(&manifest).is_ok());
        let set = FileSet::new();
        let inside = set.with(|| (check_data_file(&manifest), crate::read_data_file(&manifest)));
        assert_eq!(inside.0.unwrap_err().kind(), io::ErrorKind::NotFound);
        assert!(inside.1.unwrap_err().to_string().contains("none given"));
        assert!(check_data_file(&manifest).is_ok());
        let result = std::panic::catch_unwind(|| set.with(|| panic!("inside")));
        assert!(result.is_err());
        assert!(crate::read_data_file(&manifest).is_ok());
    }
}
