//! `jkrbem simulate`: one scene's pull-off (one grid, several extrapolated, or the grids an
//! accuracy needs). The flags are the request schema's; the texts given become a typed
//! [`Request`] in the library, which runs it; this module only prints what comes back (and
//! sends a file asked as `-` to standard output).

use super::progress::Progress;
use super::stdout::{claim_stdout, is_stdout, write_stdout_bytes, Channel};
use super::{run_error, CliError};
use jkrbem::output::data::states_bytes;
use jkrbem::session::request::Request;
use jkrbem::session::simulate::{failure_error, simulate, Sink};
use std::path::PathBuf;

mod args;

pub use args::Args;

/// The accuracy of a bare `simulate` (relative): the adhesive force to 2 %.
pub use jkrbem::session::simulate::DEFAULT_ACCURACY;

/// What goes to standard output instead of a file (`-`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OnStdout {
    /// The states CSV (`--out -`).
    States,
    /// The summary JSON (`--summary -`).
    Summary,
}

impl Args {
    /// The typed request of these flags (checked against the schema).
    pub fn request(&self) -> Result<Request, CliError> {
        Request::from_texts(self.given.iter().map(|(n, t)| (*n, t.as_str()))).map_err(run_error)
    }
}

/// Which file of `request`, if any, goes to standard output; two may not.
fn stdout_claim(request: &Request) -> Result<Option<OnStdout>, CliError> {
    claim_stdout(&[
        (OnStdout::States, "--out", request.out.as_deref()),
        (OnStdout::Summary, "--summary", request.summary.as_deref()),
    ])
}

/// Where the states and the summary go: files, except what goes to standard output.
fn sink(request: &Request, on_stdout: Option<OnStdout>) -> Sink {
    let file = |p: &Option<PathBuf>| p.clone().filter(|p| !is_stdout(p));
    match on_stdout {
        Some(OnStdout::States) => Sink::OneRunReturned {
            summary: file(&request.summary),
        },
        _ => Sink::Files {
            out: request.out.clone(),
            summary: file(&request.summary),
        },
    }
}

/// Run `jkrbem simulate`.
pub fn run(args: Args) -> Result<(), CliError> {
    let typed = args.request()?;
    let on_stdout = stdout_claim(&typed)?;
    let request = typed
        .simulate_request(sink(&typed, on_stdout), None)
        .map_err(run_error)?;
    let progress = Progress::new();
    let done = simulate(&request, &progress).map_err(run_error)?;
    if let Some(plan) = &done.plan {
        errln!("jkrbem: {plan}");
    }
    // The results on standard output: the summary's text, or the file asked for there (then
    // the text goes to standard error). The warnings go to standard error after it.
    let text = Channel::beside(on_stdout.is_some());
    match on_stdout {
        Some(OnStdout::Summary) => write_stdout_bytes(done.summary.to_json().as_bytes()),
        Some(OnStdout::States) => {
            for run in &done.runs {
                write_stdout_bytes(&states_bytes(&run.states, run.onsets.name()));
            }
        }
        None => {}
    }
    text.print(&done.summary.to_text());
    for line in done.summary.warning_lines() {
        errln!("{line}");
    }
    for path in &done.states {
        text.line(&format!("states written to {}", path.display()));
    }
    for path in &done.field_files {
        text.line(&format!("fields written to {}", path.display()));
    }
    failure_error(done.failure).map_err(run_error)
}
