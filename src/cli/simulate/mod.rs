//! `jkrbem simulate`: one scene's pull-off (one grid, several extrapolated, or the grids an
//! accuracy needs). The flags are the request schema's; the texts given become a typed
//! [`Request`] in the library, which runs it; this module only prints what comes back.

use super::progress::Progress;
use super::{run_error, CliError};
use jkrbem::run::request::Request;
use jkrbem::run::simulate::{failure_error, simulate};

mod args;

pub use args::Args;

/// The accuracy of a bare `simulate` (relative): the adhesive force to 2 %.
pub use jkrbem::run::simulate::DEFAULT_ACCURACY;

impl Args {
    /// The typed request of these flags (checked against the schema).
    pub fn request(&self) -> Result<Request, CliError> {
        Request::from_texts(self.given.iter().map(|(n, t)| (*n, t.as_str()))).map_err(run_error)
    }
}

/// Run `jkrbem simulate`.
pub fn run(args: Args) -> Result<(), CliError> {
    let request = args
        .request()?
        .simulate_request(true, None)
        .map_err(run_error)?;
    let progress = Progress::new();
    let done = simulate(&request, &progress).map_err(run_error)?;
    if let Some(plan) = &done.plan {
        errln!("jkrbem: {plan}");
    }
    out!("{}", done.summary.to_text());
    for path in &done.states {
        outln!("states written to {}", path.display());
    }
    for path in &done.field_files {
        outln!("fields written to {}", path.display());
    }
    failure_error(done.failure).map_err(run_error)
}
