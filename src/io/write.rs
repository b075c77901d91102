//! Writing output files whole or not at all, and the one error every output path returns.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::outputs::{self, OutputCheck, OutputError};

/// Why an output file was not written. Each variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// The path is refused before anything is written (an input, twice, not a file).
    #[error(transparent)]
    Refused(#[from] OutputError),
    /// The path names no file (it ends in `..` or is empty).
    #[error("{}: not a file path", path.display())]
    NotAFilePath {
        /// The path as given.
        path: PathBuf,
    },
    /// The file system refused: `action` is "writing", "creating", "reading" or "moving".
    #[error("{action} {}: {source}", path.display())]
    Io {
        /// What was being done.
        action: &'static str,
        /// The file or folder.
        path: PathBuf,
        /// The system's error.
        #[source]
        source: std::io::Error,
    },
    /// The content could not be encoded in the file's format.
    #[error("encoding {}: {why}", path.display())]
    Encode {
        /// The file.
        path: PathBuf,
        /// The encoder's message.
        why: String,
    },
    /// An image path whose extension names no format goniolight writes.
    #[error("{}: unknown image extension (use .png or .exr)", path.display())]
    UnknownExtension {
        /// The file.
        path: PathBuf,
    },
}

impl WriteError {
    /// A file-system error while `action` (`"writing"`, `"creating"` …) `path`.
    pub fn io(action: &'static str, path: &Path, source: std::io::Error) -> WriteError {
        WriteError::Io {
            action,
            path: path.to_path_buf(),
            source,
        }
    }

    /// An encoder's error for `path`.
    pub fn encode(path: &Path, why: impl std::fmt::Display) -> WriteError {
        WriteError::Encode {
            path: path.to_path_buf(),
            why: why.to_string(),
        }
    }
}

/// Creates `dir` and its parents (an existing folder is fine).
pub fn create_dir(dir: &Path) -> Result<(), WriteError> {
    std::fs::create_dir_all(dir).map_err(|e| WriteError::io("creating", dir, e))
}

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename, so a
/// failure never leaves a half-written output behind.
///
/// A path that exists and is not a regular file (a FIFO, a device, a folder) is refused:
/// the rename would replace the node itself (as root, `/dev/null`).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    let mut check = OutputCheck::new();
    check.output(path);
    check.check()?;
    let tmp = outputs::temporary_beside(path, "tmp").map_err(|_| WriteError::NotAFilePath {
        path: path.to_path_buf(),
    })?;
    let result = (|| -> std::io::Result<()> {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    outputs::finished(&tmp);
    result.map_err(|e| WriteError::io("writing", path, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_write_names_the_file_and_the_cause() {
        let dir = std::env::temp_dir().join("goniolight-write-test-missing/deeper");
        let path = dir.join("out.csv");
        let e = write_atomic(&path, b"x").unwrap_err();
        assert!(
            matches!(
                e,
                WriteError::Io {
                    action: "writing",
                    ..
                }
            ),
            "{e:?}"
        );
        let text = e.to_string();
        assert!(
            text.starts_with("writing ") && text.contains("out.csv"),
            "{text}"
        );
        assert!(!path.exists());
    }

    #[test]
    fn a_folder_is_refused_before_anything_is_written() {
        let dir = std::env::temp_dir();
        let e = write_atomic(&dir, b"x").unwrap_err();
        assert!(
            matches!(e, WriteError::Refused(OutputError::NotAFile { .. })),
            "{e:?}"
        );
    }
}
