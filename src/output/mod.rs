//! Outputs: state CSVs, run summaries for people and scripts, log–log and linear charts, and
//! the timings of `jkrbem bench`. Every file is written through [`file`](mod@file): never half-written,
//! never over a file that is not a regular one, and never over another run's.
//!
//! The charts are drawn (SVG, PDF, PNG) with the default-on `figures` feature. Without it every
//! chart's data is still computed, but a chart is not drawn, and writing one fails, naming it,
//! with [`figure::NOT_DRAWN`] (none of its files is written).

pub mod batch_csv;
pub mod bench;
pub mod chart;
pub mod data;
pub mod digest;
pub mod fields_npz;
pub mod figure;
pub mod figure_style;
pub mod file;
#[cfg(feature = "figures")]
pub mod legend;
pub mod line_chart;
pub mod names;
pub mod panels;
pub mod pressure_chart;
pub mod pressure_profile;
#[cfg(feature = "gpu")]
pub mod profile;
pub mod provenance;
#[cfg(feature = "figures")]
pub mod render;
pub mod roughness_npy;
pub mod series;
pub mod states_csv;
pub mod study_charts;
pub mod study_index;
pub mod summary;
pub mod sweep_charts;
pub mod sweep_csv;

use crate::params::Spec;
use thiserror::Error;

/// What named a path in a request: a parameter (shown as its marker, which each front end
/// words) or an argument of a command that is no parameter (`collect`'s `DIR`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NamedBy {
    /// A parameter, e.g. [`OUT`](crate::params::OUT).
    Param(&'static Spec),
    /// An argument, as the command names it.
    Argument(&'static str),
}

impl From<&'static Spec> for NamedBy {
    fn from(p: &'static Spec) -> Self {
        NamedBy::Param(p)
    }
}

impl NamedBy {
    /// The parameter, where a parameter (not an argument) names the output.
    pub fn spec(&self) -> Option<&'static Spec> {
        match self {
            NamedBy::Param(p) => Some(p),
            NamedBy::Argument(_) => None,
        }
    }
}

impl std::fmt::Display for NamedBy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NamedBy::Param(p) => p.fmt(f),
            NamedBy::Argument(a) => f.write_str(a),
        }
    }
}

/// " (PARAMETER)" when what named a path is known, else nothing.
fn param_note(param: &Option<NamedBy>) -> String {
    param.map_or_else(String::new, |p| format!(" ({p})"))
}

/// An output that could not be written. Every variant names the path, and the parameter that
/// set it once the request has added it ([`OutputError::with_param`]).
#[derive(Debug, Error)]
pub enum OutputError {
    /// A file or folder could not be created or written.
    #[error("cannot write {path}{}: {source}", param_note(param))]
    Io {
        /// The path.
        path: String,
        /// The parameter that named it.
        param: Option<NamedBy>,
        /// The cause.
        source: std::io::Error,
    },
    /// A CSV record could not be written or read.
    #[error("cannot write CSV {path}{}: {source}", param_note(param))]
    Csv {
        /// The path.
        path: String,
        /// The parameter that named it.
        param: Option<NamedBy>,
        /// The cause.
        source: csv::Error,
    },
    /// A chart could not be drawn.
    #[error("cannot draw chart {path}{}: {reason}", param_note(param))]
    Chart {
        /// The path.
        path: String,
        /// The parameter that named it.
        param: Option<NamedBy>,
        /// What the plotting library said.
        reason: String,
    },
    /// Data could not be encoded in the file's format (e.g. a `.npz` archive).
    #[error("cannot encode {path}{}: {reason}", param_note(param))]
    Encode {
        /// The path.
        path: String,
        /// The parameter that named it.
        param: Option<NamedBy>,
        /// What the encoder said.
        reason: String,
    },
    /// The target may not be written (it is not a regular file, or two outputs clash).
    #[error("cannot write {path}{}: {reason}", param_note(param))]
    Refused {
        /// The path.
        path: String,
        /// The parameter that named it.
        param: Option<NamedBy>,
        /// Why.
        reason: String,
    },
    /// Another run holds the output's lock.
    #[error(
        "{path}{} is being written by another jkrbem run ({}, lock file {lock}): wait for it \
         to finish, or choose another output",
        param_note(param),
        pid.map_or_else(|| "process id unknown".to_string(), |p| format!("process {p}"))
    )]
    Locked {
        /// The output.
        path: String,
        /// The parameter that named it.
        param: Option<NamedBy>,
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
            param: None,
            source,
        }
    }

    pub(crate) fn csv(path: &std::path::Path, source: csv::Error) -> Self {
        OutputError::Csv {
            path: path.display().to_string(),
            param: None,
            source,
        }
    }

    /// The same error, saying which parameter named the path (e.g. [`OUT`](crate::params::OUT),
    /// [`SUMMARY`](crate::params::SUMMARY)), unless one was said already.
    pub fn with_param(mut self, name: impl Into<NamedBy>) -> Self {
        let name = name.into();
        match &mut self {
            OutputError::Io { param, .. }
            | OutputError::Csv { param, .. }
            | OutputError::Chart { param, .. }
            | OutputError::Encode { param, .. }
            | OutputError::Refused { param, .. }
            | OutputError::Locked { param, .. } => {
                param.get_or_insert(name);
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
