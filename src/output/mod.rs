//! Outputs: state CSVs that are never half-written, and run summaries for people and scripts.

pub mod states_csv;
pub mod summary;

use thiserror::Error;

/// An output that could not be written.
#[derive(Debug, Error)]
pub enum OutputError {
    /// A file or folder could not be created or written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The path.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// A CSV record could not be written.
    #[error("cannot write CSV {path}: {source}")]
    Csv {
        /// The path.
        path: String,
        /// The cause.
        source: csv::Error,
    },
}

impl OutputError {
    pub(crate) fn io(path: &std::path::Path, source: std::io::Error) -> Self {
        OutputError::Io {
            path: path.display().to_string(),
            source,
        }
    }
}
