//! Errors of the photometry readers, writers and tools.

use std::fmt;

/// A problem in a photometric file, located by file and 1-based line.
#[derive(Debug, Clone, PartialEq)]
pub struct ParseError {
    /// The file as named by the caller.
    pub file: String,
    /// 1-based line; 0 when the problem concerns the whole file.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

impl ParseError {
    /// A new error at `line` of `file`.
    pub fn new(file: &str, line: usize, message: impl Into<String>) -> Self {
        ParseError {
            file: file.to_string(),
            line,
            message: message.into(),
        }
    }
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            write!(f, "{}: {}", self.file, self.message)
        } else {
            write!(f, "{}: line {}: {}", self.file, self.line, self.message)
        }
    }
}

impl std::error::Error for ParseError {}

/// Any failure of the photometry module.
#[derive(Debug, thiserror::Error)]
pub enum PhotometryError {
    /// The file could not be read.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file's content is wrong.
    #[error(transparent)]
    Parse(#[from] ParseError),
    /// The request cannot be met with this data (a bad option, an impossible downsampling).
    #[error("{0}")]
    Invalid(String),
    /// A bad argument, named as the library names it (`shr`, `lamp_set`, `downsample`); a
    /// front end names its own parameter instead (the command line: `--shr`, …).
    #[error("{field} {value} {problem}")]
    Field {
        /// The argument.
        field: &'static str,
        /// Its value as given.
        value: String,
        /// What is wrong with it, and what would do.
        problem: String,
    },
    /// A diagram could not be drawn.
    #[error(transparent)]
    Draw(#[from] super::plot::DrawError),
}

impl PhotometryError {
    /// True when the error is the caller's input (a bad file or option), not a failure of
    /// the machine.
    pub fn is_bad_input(&self) -> bool {
        match self {
            PhotometryError::Io { source, .. } => crate::io::is_bad_input(source),
            PhotometryError::Parse(_)
            | PhotometryError::Invalid(_)
            | PhotometryError::Field { .. } => true,
            PhotometryError::Draw(_) => false,
        }
    }
}
