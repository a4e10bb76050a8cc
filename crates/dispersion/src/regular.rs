//! Opening a study's files for reading: only regular files, so that a FIFO or a device put in
//! a study folder is an error naming the file instead of a blocked or endless read.

use std::fs::File;
use std::path::Path;

use crate::DispersionError;

/// Opens one of a study's files for reading, `Ok(None)` when it does not exist. Only a regular
/// file (or a link to one) is opened: a FIFO would block the run forever and a device such as
/// `/dev/zero` never ends, so anything else is an error naming the file.
pub(crate) fn open_regular(path: &Path) -> Result<Option<File>, DispersionError> {
    match std::fs::metadata(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(DispersionError::io(path)(e)),
        Ok(metadata) if !metadata.is_file() => {
            return Err(DispersionError::io(path)(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "not a regular file (a directory, FIFO, socket or device)",
            )));
        }
        Ok(_) => {}
    }
    File::open(path)
        .map(Some)
        .map_err(DispersionError::io(path))
}
