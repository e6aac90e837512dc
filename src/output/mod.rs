//! Outputs: state CSVs that are never half-written, run summaries for people and scripts,
//! log–log charts, and the timings of `jkrbem bench`.

pub mod bench;
pub mod chart;
pub mod line_chart;
pub mod profile;
pub mod states_csv;
pub mod study_charts;
pub mod summary;
pub mod sweep_charts;
pub mod sweep_csv;

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
    /// A chart could not be drawn.
    #[error("cannot draw chart {path}: {reason}")]
    Chart {
        /// The path.
        path: String,
        /// What the plotting library said.
        reason: String,
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
