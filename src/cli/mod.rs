//! One module per subcommand, and the error type they share.

pub mod accuracy;
pub mod bench;
pub mod collect;
pub mod crossed;
pub mod devices;
pub mod extrapolate;
pub mod reproduce;
pub mod simulate;
pub mod sweep;
pub mod theory;

use std::fmt;
use std::process::ExitCode;

/// A command's failure: bad input (exit 2, nothing was done) or a failed run (exit 1).
#[derive(Debug)]
pub enum CliError {
    /// The arguments were refused before any work.
    Input(String),
    /// The work started and failed.
    Run(String),
}

impl CliError {
    /// The process exit code for this error.
    pub fn exit_code(&self) -> ExitCode {
        match self {
            CliError::Input(_) => ExitCode::from(2),
            CliError::Run(_) => ExitCode::from(1),
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Input(m) | CliError::Run(m) => f.write_str(m),
        }
    }
}

/// Bad input, from any layer's error.
pub fn input(e: impl fmt::Display) -> CliError {
    CliError::Input(e.to_string())
}

/// A failed run, from any layer's error.
pub fn failed(e: impl fmt::Display) -> CliError {
    CliError::Run(e.to_string())
}
