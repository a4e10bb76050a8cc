//! The reader's entry points: the document of a `.ork` file (zip archive or plain XML, with
//! the hostile-input limits), its errors, and [`import`] (read, parse, write the mission).

use std::path::{Path, PathBuf};

use thiserror::Error;

use crate::design::Design;

/// Errors of the `.ork` reader; each names the file and, where there is one, the component.
#[derive(Debug, Error)]
pub enum OrkError {
    /// The file cannot be read.
    #[error("{}: cannot read: {error}", file.display())]
    Read {
        /// The design file.
        file: PathBuf,
        /// The I/O error.
        error: std::io::Error,
    },
    /// Not a zip archive holding an OpenRocket document, nor OpenRocket XML.
    #[error("{}: not an OpenRocket design: {reason}", file.display())]
    Container {
        /// The design file.
        file: PathBuf,
        /// What was found instead.
        reason: String,
    },
    /// The XML is malformed.
    #[error("{}: XML error: {message}", file.display())]
    Xml {
        /// The design file.
        file: PathBuf,
        /// The parser's message (with line and column).
        message: String,
    },
    /// A format version this reader does not know.
    #[error("{}: OpenRocket file format version {version:?} is not supported (1.0 to 1.10 are)", file.display())]
    Version {
        /// The design file.
        file: PathBuf,
        /// The `version` attribute.
        version: String,
    },
    /// A value is missing, not a number, or not finite/positive where it must be.
    #[error("{}: component `{component}`: <{element}> {problem}", file.display())]
    Value {
        /// The design file.
        file: PathBuf,
        /// The component's name.
        component: String,
        /// The element.
        element: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A component or configuration karman cannot fly yet.
    #[error("{}: component `{component}`: {what} is not supported yet", file.display())]
    Unsupported {
        /// The design file.
        file: PathBuf,
        /// The component's name.
        component: String,
        /// What.
        what: String,
    },
    /// No simulation of that name, or none at all.
    #[error("{}: no simulation named {name:?} (the file has: {available})", file.display())]
    Simulation {
        /// The design file.
        file: PathBuf,
        /// The requested name.
        name: String,
        /// The names the file has.
        available: String,
    },
    /// The chosen simulation's motor has no thrust curve among the given files and folders.
    #[error("{}: no thrust curve for motor {manufacturer} {designation} in {searched} (give one with --motor)", file.display())]
    Motor {
        /// The design file.
        file: PathBuf,
        /// Motor manufacturer.
        manufacturer: String,
        /// Motor designation.
        designation: String,
        /// Where it was looked for.
        searched: String,
    },
}

/// What `import` was asked for.
#[derive(Debug, Clone, Default)]
pub struct ImportOptions {
    /// The simulation whose motor and launch conditions to take (default: the first).
    pub simulation: Option<String>,
    /// Thrust-curve files, or folders searched for `.eng` files, for the motor (the design's
    /// folder is always searched last).
    pub motors: Vec<PathBuf>,
    /// Where the mission will be written: the thrust-curve path is made relative to its
    /// folder.
    pub output_dir: Option<PathBuf>,
}

/// An imported design.
#[derive(Debug, Clone)]
pub struct Imported {
    /// The mission file's text (commented TOML).
    pub mission: String,
    /// What was mapped approximately or left out.
    pub warnings: Vec<String>,
}

/// Reads the OpenRocket document of `file`: the `.ork` entry of a zip archive, or the file
/// itself when it is XML.
///
/// # Errors
/// [`OrkError::Read`]; [`OrkError::Container`] also for a file that is not a regular file
/// or a document larger than [`MAX_DOCUMENT_BYTES`] (decompressed).
pub fn read_document(file: &Path) -> Result<String, OrkError> {
    use std::io::Read;
    let read_error = |error| OrkError::Read {
        file: file.to_owned(),
        error,
    };
    // Only a regular file: a FIFO would block forever and `/dev/zero` never ends.
    let meta = std::fs::metadata(file).map_err(read_error)?;
    if !meta.is_file() {
        return Err(OrkError::Container {
            file: file.to_owned(),
            reason: "not a regular file".to_owned(),
        });
    }
    let mut bytes = Vec::new();
    std::fs::File::open(file)
        .and_then(|f| f.take(MAX_DOCUMENT_BYTES + 1).read_to_end(&mut bytes))
        .map_err(read_error)?;
    if bytes.len() as u64 > MAX_DOCUMENT_BYTES {
        return Err(too_large(file, "the file"));
    }
    document_text(file, &bytes)
}

/// The largest design document read, compressed or not, in bytes (64 MiB; OpenRocket's
/// example designs are tens of kilobytes, the largest with decals a few megabytes): a zip
/// bomb stops here instead of filling memory.
pub const MAX_DOCUMENT_BYTES: u64 = 64 << 20;

fn too_large(file: &Path, what: &str) -> OrkError {
    OrkError::Container {
        file: file.to_owned(),
        reason: format!(
            "{what} is larger than {} MiB, far beyond any design",
            MAX_DOCUMENT_BYTES >> 20
        ),
    }
}

/// The document text of `.ork` bytes (see [`read_document`]).
///
/// # Errors
/// [`OrkError::Container`].
pub fn document_text(file: &Path, bytes: &[u8]) -> Result<String, OrkError> {
    let container = |reason: String| OrkError::Container {
        file: file.to_owned(),
        reason,
    };
    if bytes.starts_with(b"PK") {
        use std::io::Read;
        let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes))
            .map_err(|e| container(format!("a broken zip archive ({e})")))?;
        let names: Vec<String> = archive.file_names().map(str::to_owned).collect();
        let Some(name) = names
            .iter()
            .find(|n| n.ends_with(".ork") || n.ends_with(".xml") || n.ends_with(".rkt"))
        else {
            return Err(container(format!(
                "a zip archive without an .ork document (it holds {})",
                names.join(", ")
            )));
        };
        let mut entry = archive
            .by_name(name)
            .map_err(|e| container(format!("cannot open {name} in the archive ({e})")))?;
        let mut raw = Vec::new();
        (&mut entry)
            .take(MAX_DOCUMENT_BYTES + 1)
            .read_to_end(&mut raw)
            .map_err(|e| container(format!("cannot read {name} in the archive ({e})")))?;
        if raw.len() as u64 > MAX_DOCUMENT_BYTES {
            return Err(too_large(file, &format!("{name} decompressed")));
        }
        String::from_utf8(raw)
            .map_err(|e| container(format!("{name} in the archive is not UTF-8 text ({e})")))
    } else if bytes.starts_with(&[0x1f, 0x8b]) {
        Err(container(
            "a gzip-compressed document (OpenRocket before 15.03); open and save it in a \
             current OpenRocket"
                .to_owned(),
        ))
    } else {
        let text = std::str::from_utf8(bytes)
            .map_err(|_| container("neither a zip archive nor UTF-8 XML text".to_owned()))?;
        if !text.trim_start().starts_with('<') {
            return Err(container("neither a zip archive nor XML".to_owned()));
        }
        Ok(text.to_owned())
    }
}

/// Imports `file` as a mission.
///
/// # Errors
/// [`OrkError`] naming the file and the component.
pub fn import(file: &Path, options: &ImportOptions) -> Result<Imported, OrkError> {
    let text = read_document(file)?;
    let design = Design::parse(file, &text)?;
    crate::write::mission(file, &design, options)
}

/// [`import`] of a design given as `bytes` (what `file`, which names it in messages, holds),
/// for a program without files (the browser page): its motor files are then found among
/// `options.motors` through an installed `karman_math::files::FileSet`.
///
/// # Errors
/// As [`import`]; [`OrkError::Container`] for more than [`MAX_DOCUMENT_BYTES`].
pub fn import_bytes(
    file: &Path,
    bytes: &[u8],
    options: &ImportOptions,
) -> Result<Imported, OrkError> {
    if bytes.len() as u64 > MAX_DOCUMENT_BYTES {
        return Err(too_large(file, "the file"));
    }
    let text = document_text(file, bytes)?;
    let design = Design::parse(file, &text)?;
    crate::write::mission(file, &design, options)
}
