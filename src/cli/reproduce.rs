//! `jkrbem reproduce`: the whole study of physics §8 from one command — the sweep over R1/R2,
//! the fits, the crossed cylinders — with every chart as SVG and an index.html that shows
//! them. The work is [`jkrbem::studies::study`].

use super::parse::value;
use super::progress::Progress;
use super::{failures, run_error, CliError};
use jkrbem::params::JOBS;
use jkrbem::studies::study::{study, StudyRequest};
use std::path::PathBuf;

/// Arguments of `jkrbem reproduce`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output folder: sweep/, crossed/, the charts and index.html.
    #[arg(long, default_value = "jkrbem-out/reproduce")]
    pub out: PathBuf,
    /// One coarse grid per ratio (Nx 64 … 256; about 20 s on 2 CPU cores), each force
    /// corrected by the convergence law and the branch laws without uncertainties, instead
    /// of the full study: three grids per ratio (up to Nx 1024), every force and branch law
    /// extrapolated to Δx → 0 with its uncertainty (about 6 minutes on 2 CPU cores with
    /// --jobs 2).
    #[arg(long)]
    pub quick: bool,
    // The backend of every run, and its arithmetic.
    #[command(flatten)]
    pub backend: super::study_backend::StudyBackendArgs,
    /// Pull-offs run at the same time (1 to 256).
    #[arg(long, default_value_t = 1, value_parser = value::<usize>(JOBS))]
    pub jobs: usize,
    // The formats of the charts besides SVG (which index.html shows, and is always written).
    #[command(flatten)]
    pub figures: super::figures::FigureArgs,
}

/// Run `jkrbem reproduce`.
pub fn run(args: Args) -> Result<(), CliError> {
    super::stdout::not_stdout("--out", &args.out, "reproduce")?;
    let req = StudyRequest {
        out: args.out,
        quick: args.quick,
        backend: args.backend.request(),
        jobs: args.jobs,
        figures: args.figures.figure_format,
    };
    let done = study(&req, &Progress::new()).map_err(run_error)?;
    outln!(
        "report: {} ({} charts, {:.0} s)",
        done.index.display(),
        done.charts,
        done.wall_s
    );
    failures("parts", &done.failures, " (the report shows the rest)")
}
