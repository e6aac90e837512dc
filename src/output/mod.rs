//! Outputs: state CSVs, run summaries for people and scripts, log–log and linear charts, and
//! the timings of `jkrbem bench`. Every file is written through [`file`](mod@file): never half-written,
//! never over a file that is not a regular one, and never over another run's.

pub mod batch_csv;
pub mod bench;
pub mod chart;
pub mod fields_npz;
pub mod file;
pub mod line_chart;
pub mod names;
pub mod pressure_chart;
#[cfg(feature = "gpu")]
pub mod profile;
pub mod provenance;
pub mod states_csv;
pub mod study_charts;
pub mod study_index;
pub mod summary;
pub mod sweep_charts;
pub mod sweep_csv;

use thiserror::Error;

/// " (FLAG)" when the flag that named a path is known, else nothing.
fn flag_note(flag: &Option<String>) -> String {
    flag.as_ref()
        .map_or_else(String::new, |f| format!(" ({f})"))
}

/// An output that could not be written. Every variant names the path, and the flag that set
/// it once the command line has added it ([`OutputError::with_flag`]).
#[derive(Debug, Error)]
pub enum OutputError {
    /// A file or folder could not be created or written.
    #[error("cannot write {path}{}: {source}", flag_note(flag))]
    Io {
        /// The path.
        path: String,
        /// The flag that named it.
        flag: Option<String>,
        /// The cause.
        source: std::io::Error,
    },
    /// A CSV record could not be written or read.
    #[error("cannot write CSV {path}{}: {source}", flag_note(flag))]
    Csv {
        /// The path.
        path: String,
        /// The flag that named it.
        flag: Option<String>,
        /// The cause.
        source: csv::Error,
    },
    /// A chart could not be drawn.
    #[error("cannot draw chart {path}{}: {reason}", flag_note(flag))]
    Chart {
        /// The path.
        path: String,
        /// The flag that named it.
        flag: Option<String>,
        /// What the plotting library said.
        reason: String,
    },
    /// Data could not be encoded in the file's format (e.g. a `.npz` archive).
    #[error("cannot encode {path}{}: {reason}", flag_note(flag))]
    Encode {
        /// The path.
        path: String,
        /// The flag that named it.
        flag: Option<String>,
        /// What the encoder said.
        reason: String,
    },
    /// The target may not be written (it is not a regular file, or two outputs clash).
    #[error("cannot write {path}{}: {reason}", flag_note(flag))]
    Refused {
        /// The path.
        path: String,
        /// The flag that named it.
        flag: Option<String>,
        /// Why.
        reason: String,
    },
    /// Another run holds the output's lock.
    #[error(
        "{path}{} is being written by another jkrbem run ({}, lock file {lock}): wait for it \
         to finish, or choose another output",
        flag_note(flag),
        pid.map_or_else(|| "process id unknown".to_string(), |p| format!("process {p}"))
    )]
    Locked {
        /// The output.
        path: String,
        /// The flag that named it.
        flag: Option<String>,
        /// The lock file.
        lock: String,
        /// The process that holds it, if its id could be read.
        pid: Option<u32>,
    },
}

impl OutputError {
    pub(crate) fn io(path: &std::path::Path, source: std::io::Error) -> Self {
        OutputError::Io {
            path: path.display().to_string(),
            flag: None,
            source,
        }
    }

    pub(crate) fn csv(path: &std::path::Path, source: csv::Error) -> Self {
        OutputError::Csv {
            path: path.display().to_string(),
            flag: None,
            source,
        }
    }

    /// The same error, saying which flag named the path (e.g. "--out", "--summary").
    pub fn with_flag(mut self, name: &str) -> Self {
        match &mut self {
            OutputError::Io { flag, .. }
            | OutputError::Csv { flag, .. }
            | OutputError::Chart { flag, .. }
            | OutputError::Encode { flag, .. }
            | OutputError::Refused { flag, .. }
            | OutputError::Locked { flag, .. } => {
                flag.get_or_insert_with(|| name.to_string());
            }
        }
        self
    }

    /// Whether the output was refused before anything was written (a target that is not a
    /// regular file, clashing outputs, or one held by another run), rather than failing.
    pub fn is_refusal(&self) -> bool {
        matches!(
            self,
            OutputError::Refused { .. } | OutputError::Locked { .. }
        )
    }
}
