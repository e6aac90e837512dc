//! One module per subcommand, and the error type they share.

pub mod accuracy;
pub mod batch;
pub mod bench;
pub mod collect;
pub mod coverage;
pub mod crossed;
pub mod devices;
pub mod figures;
pub mod parse;
pub mod progress;
pub mod reference;
pub mod reproduce;
pub mod roughness;
pub mod simulate;
pub mod stdout;
pub mod study_backend;
pub mod sweep;
pub mod theory;

use std::fmt;
use std::process::ExitCode;

pub use stdout::{finish_stdout, write_stdout};

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

/// A request's error as the command's: a refusal is bad input, anything else a failed run.
pub fn run_error(e: jkrbem::session::RunError) -> CliError {
    if e.is_input() {
        CliError::Input(e.message)
    } else {
        CliError::Run(e.message)
    }
}

impl From<jkrbem::session::RunError> for CliError {
    fn from(e: jkrbem::session::RunError) -> Self {
        run_error(e)
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

/// Refuse a list flag with a repeated value, naming the flag and the value.
pub fn no_repeats<T: PartialEq + fmt::Display>(flag: &str, values: &[T]) -> Result<(), CliError> {
    for (i, v) in values.iter().enumerate() {
        if values[..i].contains(v) {
            return Err(input(format!(
                "{flag}: {v} is given more than once; each value may appear only once \
                 (a repeat would run the same work twice over the same files)"
            )));
        }
    }
    Ok(())
}

/// `--shard K/N` as (K, N) where given (sweep and batch alike).
pub fn shard(text: Option<&str>) -> Result<Option<(usize, usize)>, CliError> {
    text.map(jkrbem::output::sweep_csv::parse_shard)
        .transpose()
        .map_err(input)
}

/// Refuse a list flag with fewer than `min` or more than `max` values.
pub fn count_in(flag: &str, len: usize, min: usize, max: usize) -> Result<(), CliError> {
    if (min..=max).contains(&len) {
        Ok(())
    } else {
        Err(input(format!(
            "{flag}: {len} values given; give {min} to {max}"
        )))
    }
}

/// Ok if nothing failed, else the run's error listing `failures` (what failed: `what`).
pub fn failures(what: &str, failures: &[String], note: &str) -> Result<(), CliError> {
    if failures.is_empty() {
        Ok(())
    } else {
        Err(failed(format!(
            "{} of the {what} failed{note}:\n  {}",
            failures.len(),
            failures.join("\n  ")
        )))
    }
}

/// A batch's grid choice from `--grid` and `--accuracy`: the grid if given, else the accuracy
/// (default [`simulate::DEFAULT_ACCURACY`]).
pub fn grid_choice(
    grid: Option<usize>,
    accuracy: Option<f64>,
) -> jkrbem::session::pulloffs::GridChoice {
    use jkrbem::session::pulloffs::GridChoice;
    match grid {
        Some(nx) => GridChoice::Fixed(nx),
        None => GridChoice::Accuracy(accuracy.unwrap_or(simulate::DEFAULT_ACCURACY)),
    }
}
