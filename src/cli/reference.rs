//! `jkrbem reference`: the table of converged adhesive forces per R1/R2 that the convergence law
//! is fitted to. Parses the flags; the work is [`jkrbem::studies::reference`].

use super::parse::value;
use super::progress::Progress;
use super::{run_error, CliError};
use jkrbem::backend::select::BackendKind;
use jkrbem::params::{FIRST_GRID, MAX_GRID, PHASES, RATIOS, TARGET};
use jkrbem::session::open::BackendRequest;
use jkrbem::studies::reference::{reference, ReferenceRequest, REFERENCE_RATIOS};
use std::path::PathBuf;

/// Arguments of `jkrbem reference`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Ratios R1/R2, comma-separated, each in [1, 1000] [default: 1, 1.5, 2, 3, 5, 7, 10, 15,
    /// 20, 25, 35, 50].
    #[arg(long, value_delimiter = ',', value_parser = value::<f64>(RATIOS))]
    pub ratios: Vec<f64>,
    /// The relative uncertainty wanted of each |min F̄| at Δx → 0 (a percentage in [0.1, 50],
    /// the unit required). Each ratio's grids double (at least three) until it is reached, or
    /// --max-grid or the memory is.
    #[arg(long, default_value = "0.3%", value_parser = value::<f64>(TARGET))]
    pub target: f64,
    /// Nx of the finest grid a ratio's ladder may use (a power of two from 32 to 65536). Every
    /// ratio's ladder is checked before any work: from its first grid, at least three grids
    /// must fit below this and in the memory available, else the request is refused (exit
    /// code 2) naming the --max-grid or --first-grid that would.
    #[arg(long, default_value_t = 2048, value_parser = value::<usize>(MAX_GRID))]
    pub max_grid: usize,
    /// Nx of the first (coarsest) grid of every ladder (a power of two, at least 32) [default:
    /// the grid a 5 % --accuracy plan takes for the ratio, about 20–40 elements across the
    /// contact's minor axis at the minimum]. A coarser start gives a slender ratio its three
    /// grids below --max-grid.
    #[arg(long, value_parser = value::<usize>(FIRST_GRID))]
    pub first_grid: Option<usize>,
    /// Runs per grid (1 to 8), each at another domain margin (0.08, 0.13, 0.18, …, relative to
    /// the initial contact's half-axes): where the contact's edge falls between element
    /// centres (the grid phase) differs from run to run, so the fit averages its scatter
    /// instead of taking one sample of it per grid.
    #[arg(long, default_value_t = 1, value_parser = value::<usize>(PHASES))]
    pub phases: usize,
    /// Backend: `auto` (a hardware GPU if present, else the CPU), `cpu` or `gpu`.
    #[arg(long, value_enum, default_value_t = BackendKind::Auto)]
    pub backend: BackendKind,
    /// The table (CSV); the one compiled into `--accuracy` is the repository's
    /// `data/reference/adhesive-force.csv` (copy a new table there and rebuild). Every run's
    /// states and summary go beside the table in `<stem>-runs/`, the summary recording the
    /// run's settings. A later job reuses a run found there only where it finished with a force
    /// minimum, records the same settings (grid, margin, steps, CG tolerances, …), ran on the
    /// backend asked for (cpu: f64; gpu: f32; auto: either) and its states reproduce its
    /// summary; any other is run again (and replaced), saying why.
    #[arg(long, default_value = "jkrbem-out/reference/adhesive-force.csv")]
    pub out: PathBuf,
}

/// Run `jkrbem reference`.
pub fn run(args: Args) -> Result<(), CliError> {
    super::stdout::not_stdout("--out", &args.out, "reference")?;
    let ratios = if args.ratios.is_empty() {
        REFERENCE_RATIOS.to_vec()
    } else {
        args.ratios.clone()
    };
    let command = std::iter::once("jkrbem".to_string())
        .chain(std::env::args().skip(1))
        .collect::<Vec<_>>()
        .join(" ");
    let req = ReferenceRequest {
        ratios,
        target: args.target,
        max_grid: args.max_grid,
        first_grid: args.first_grid,
        phases: args.phases,
        backend: BackendRequest {
            kind: args.backend,
            ..BackendRequest::default()
        },
        out: args.out,
        command,
    };
    let done = reference(&req, &Progress::new()).map_err(run_error)?;
    outln!("ratio   |min F̄| at Δx → 0      k      grids");
    for r in &done.rows {
        let f = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.5}"));
        outln!(
            "{:<7} {} ± {}{}  {}  {}",
            r.ratio,
            f(r.f_ad_bar),
            f(r.f_ad_bar_uncertainty),
            if r.target_met {
                ""
            } else {
                " (target not met)"
            },
            r.k.map_or("—".into(), |k| format!("{k:.2}")),
            r.grids
        );
    }
    outln!("written {}", done.path.display());
    if let Some(law) = done.law {
        let (sd_slender, sd_round) = law.sd();
        outln!(
            "the convergence law fitted to this table: k = {:.3} (± {:.3}) + {:.3} (± {:.3}) / \
             (R1/R2) (one standard deviation; compiled into --accuracy once the table is copied to \
             data/reference/adhesive-force.csv and jkrbem rebuilt)",
            law.k_slender,
            sd_slender,
            law.k_round,
            sd_round
        );
    }
    Ok(())
}
